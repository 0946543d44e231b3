//! The elimination order of a body's stiffness with three DOFs a node (the 3D solid's (u_x, u_y,
//! u_z), the Fourier mode n = 1's (A, B, W)): a fill-reducing order of the body's interior with
//! the contact candidate nodes' DOFs last.
//!
//! Putting the contact DOFs last makes the trailing block of the Cholesky factor the factor of
//! their Schur complement (see [`crate::fem::factor::Factor::trailing_block`]): the condensed
//! compliance then costs one dense triangular solve in the contact DOFs' dimension instead of
//! one solve through the whole factor per contact DOF. The contact patch then plays the part of
//! a last separator.
//!
//! The interior is ordered on the node graph (three times smaller than the DOF graph; each
//! node's DOFs stay together, which makes the factor's supernodes larger), then expanded to
//! DOFs, by one of:
//! - [`NodeOrder::MinimumDegree`]: faer's approximate minimum degree (Amestoy, Davis & Duff 1996);
//! - [`NodeOrder::NestedDissection`]: geometric nested dissection (George 1973; the coordinate
//!   bisection of Heath & Raghavan 1995): split the nodes at the median of their widest
//!   coordinate, take as separator the nodes of the larger half that touch the other half,
//!   order both halves recursively and the separator last; parts below [`LEAF`] nodes by
//!   minimum degree. On a 3D mesh it leaves markedly less fill than minimum degree
//!   (`examples/fem3d_timing.rs` measures both).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMat;

use crate::fem::assembly::Dofs;

/// The fill-reducing order of the interior nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeOrder {
    /// Approximate minimum degree.
    MinimumDegree,
    /// Geometric nested dissection with minimum-degree leaves.
    NestedDissection,
}

/// Parts of at most this many nodes are ordered by minimum degree rather than dissected.
pub const LEAF: usize = 256;

/// A DOF order with a trailing block.
#[derive(Clone, Debug)]
pub struct ContactLast {
    /// forward[k] = the free DOF eliminated k-th.
    pub forward: Vec<usize>,
    /// The trailing DOFs, as (index into the candidate list, component 0 … 2 of the node), in
    /// elimination order: position k of the trailing block is `trailing[k]`.
    pub trailing: Vec<(usize, usize)>,
    /// Their free DOF indices (the last entries of `forward`).
    pub trailing_dofs: Vec<usize>,
}

/// The node graph of a mesh of `count` nodes and `elements`: the sorted neighbours of every node
/// (nodes sharing an element), itself included.
pub fn node_graph<const K: usize>(count: usize, elements: &[[usize; K]]) -> Vec<Vec<usize>> {
    let mut graph = vec![Vec::new(); count];
    for e in elements {
        for &a in e {
            graph[a].extend_from_slice(e);
        }
    }
    for list in &mut graph {
        list.sort_unstable();
        list.dedup();
    }
    graph
}

/// The order of the nodes of `graph` (coordinates `points`) that are not `candidates` by `how`,
/// expanded to their free DOFs, followed by the candidates' free DOFs (node by node, in the
/// candidates' order).
pub fn contact_last(
    graph: &[Vec<usize>],
    points: &[[f64; 3]],
    dofs: &Dofs,
    candidates: &[usize],
    how: NodeOrder,
) -> Result<ContactLast, String> {
    let mut is_candidate = vec![false; graph.len()];
    candidates.iter().for_each(|&n| is_candidate[n] = true);
    let has_free = |n: usize| (0..3).any(|a| dofs.free(3 * n + a).is_some());
    let interior: Vec<usize> = (0..graph.len())
        .filter(|&n| !is_candidate[n] && has_free(n))
        .collect();
    let mut local = vec![usize::MAX; graph.len()];
    let order = match how {
        NodeOrder::MinimumDegree => {
            // Ordered with the candidates present (their adjacency shapes the fill), which are
            // then taken out to go last.
            let all: Vec<usize> = (0..graph.len()).filter(|&n| has_free(n)).collect();
            let mut order = minimum_degree(graph, &all, &mut local)?;
            order.retain(|&n| !is_candidate[n]);
            order
        }
        NodeOrder::NestedDissection => {
            let mut order = Vec::with_capacity(interior.len());
            let mut side = vec![0u8; graph.len()];
            dissect(graph, points, interior, &mut side, &mut local, &mut order)?;
            order
        }
    };
    let mut forward = Vec::with_capacity(dofs.count());
    for &n in &order {
        forward.extend((0..3).filter_map(|a| dofs.free(3 * n + a)));
    }
    let (mut trailing, mut trailing_dofs) = (Vec::new(), Vec::new());
    for (j, &n) in candidates.iter().enumerate() {
        for a in 0..3 {
            if let Some(d) = dofs.free(3 * n + a) {
                trailing.push((j, a));
                trailing_dofs.push(d);
            }
        }
    }
    forward.extend(&trailing_dofs);
    Ok(ContactLast {
        forward,
        trailing,
        trailing_dofs,
    })
}

/// Appends the nested-dissection order of `nodes` to `order`. `side` (all zero on entry and
/// exit) and `local` (all `usize::MAX`) are work arrays over the whole graph.
fn dissect(
    graph: &[Vec<usize>],
    points: &[[f64; 3]],
    mut nodes: Vec<usize>,
    side: &mut [u8],
    local: &mut [usize],
    order: &mut Vec<usize>,
) -> Result<(), String> {
    if nodes.len() <= LEAF {
        order.extend(minimum_degree(graph, &nodes, local)?);
        return Ok(());
    }
    let spread = |a: usize| {
        let (lo, hi) = nodes
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &n| {
                (lo.min(points[n][a]), hi.max(points[n][a]))
            });
        hi - lo
    };
    let axis = (0..3)
        .max_by(|&a, &b| spread(a).total_cmp(&spread(b)))
        .unwrap_or(0);
    let half = nodes.len() / 2;
    nodes.select_nth_unstable_by(half, |&a, &b| points[a][axis].total_cmp(&points[b][axis]));
    let right = nodes.split_off(half);
    let left = nodes;
    left.iter().for_each(|&n| side[n] = 1);
    right.iter().for_each(|&n| side[n] = 2);
    let touches = |n: usize, other: u8| graph[n].iter().any(|&m| side[m] == other);
    let (mut kept, mut separator) = (Vec::with_capacity(right.len()), Vec::new());
    for &n in &right {
        if touches(n, 1) {
            separator.push(n);
        } else {
            kept.push(n);
        }
    }
    left.iter().chain(&right).for_each(|&n| side[n] = 0);
    dissect(graph, points, left, side, local, order)?;
    dissect(graph, points, kept, side, local, order)?;
    order.extend(minimum_degree(graph, &separator, local)?);
    Ok(())
}

/// faer's approximate minimum degree order of the subgraph induced by `nodes`, as node indices.
/// `local` (all `usize::MAX` on entry and exit) is a work array over the whole graph.
fn minimum_degree(graph: &[Vec<usize>], nodes: &[usize], local: &mut [usize]) -> Result<Vec<usize>, String> {
    let k = nodes.len();
    if k == 0 {
        return Ok(Vec::new());
    }
    nodes.iter().enumerate().for_each(|(i, &n)| local[n] = i);
    let mut col_ptr = Vec::with_capacity(k + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for &n in nodes {
        let start = row_idx.len();
        row_idx.extend(graph[n].iter().map(|&m| local[m]).filter(|&i| i != usize::MAX));
        row_idx[start..].sort_unstable();
        col_ptr.push(row_idx.len());
    }
    nodes.iter().for_each(|&n| local[n] = usize::MAX);
    let nnz = row_idx.len();
    let pattern = SymbolicSparseColMat::new_checked(k, k, col_ptr, None, row_idx);
    let (mut perm, mut inverse) = (vec![0usize; k], vec![0usize; k]);
    let mut buffer = MemBuffer::try_new(amd::order_scratch::<usize>(k, nnz))
        .map_err(|e| format!("minimum degree workspace: {e}"))?;
    amd::order(
        &mut perm,
        &mut inverse,
        pattern.as_ref(),
        amd::Control::default(),
        MemStack::new(&mut buffer),
    )
    .map_err(|e| format!("minimum degree ordering: {e}"))?;
    Ok(perm.into_iter().map(|i| nodes[i]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path graph 0 – 1 – … – (n−1) on the x axis.
    fn path(n: usize) -> (Vec<Vec<usize>>, Vec<[f64; 3]>) {
        let graph = (0..n)
            .map(|i| (i.saturating_sub(1)..(i + 2).min(n)).collect())
            .collect();
        let points = (0..n).map(|i| [i as f64, 0.0, 0.0]).collect();
        (graph, points)
    }

    #[test]
    fn both_orders_are_permutations_with_the_candidates_last() {
        let (graph, points) = path(1000);
        let dofs = Dofs::from_fixed(&vec![false; 3000]);
        for how in [NodeOrder::MinimumDegree, NodeOrder::NestedDissection] {
            let order = contact_last(&graph, &points, &dofs, &[500, 7], how).unwrap();
            let mut sorted = order.forward.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..3000).collect::<Vec<_>>(), "{how:?}");
            assert_eq!(&order.forward[2994..], &[1500, 1501, 1502, 21, 22, 23]);
            assert_eq!(order.trailing[3], (1, 0));
        }
    }

    #[test]
    fn a_dissected_path_puts_its_middle_last() {
        // The first cut of a path at its median leaves one separator node, eliminated last.
        let (graph, points) = path(4 * LEAF);
        let dofs = Dofs::from_fixed(&vec![false; 12 * LEAF]);
        let order = contact_last(&graph, &points, &dofs, &[], NodeOrder::NestedDissection).unwrap();
        let last = order.forward[order.forward.len() - 1] / 3;
        assert_eq!(last, 2 * LEAF);
    }
}
