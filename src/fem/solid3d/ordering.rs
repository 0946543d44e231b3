//! The elimination order of the 3D stiffness: a fill-reducing order of the body's interior with
//! the contact candidate nodes' DOFs last.
//!
//! Putting the contact DOFs last makes the trailing block of the Cholesky factor the factor of
//! their Schur complement (see [`crate::fem::factor::Factor::trailing_block`]): the condensed
//! compliance then costs one dense triangular inversion of that block instead of one solve
//! through the whole factor per contact DOF. Eliminating the interior first is what a nested
//! dissection would do with the contact patch as the last separator, so the fill of the rest is
//! hardly changed (measured by `examples/fem3d_timing.rs`).
//!
//! The order is computed on the node graph (three times smaller than the DOF graph, and it
//! keeps each node's DOFs together, which makes the factor's supernodes larger) by faer's
//! approximate minimum degree, then expanded to DOFs.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMat;

use crate::fem::assembly::Dofs;

/// A DOF order with a trailing block.
#[derive(Clone, Debug)]
pub struct ContactLast {
    /// forward[k] = the free DOF eliminated k-th.
    pub forward: Vec<usize>,
    /// The trailing DOFs, as (index into the candidate list, component 0 = x, 1 = y, 2 = z), in
    /// elimination order: position k of the trailing block is `trailing[k]`.
    pub trailing: Vec<(usize, usize)>,
    /// Their free DOF indices (the last entries of `forward`).
    pub trailing_dofs: Vec<usize>,
}

/// The minimum-degree order of the nodes of `graph` that are not `candidates`, expanded to their
/// free DOFs, followed by the candidates' free DOFs (node by node, in the candidates' order).
pub fn contact_last(graph: &[Vec<usize>], dofs: &Dofs, candidates: &[usize]) -> Result<ContactLast, String> {
    let mut is_candidate = vec![false; graph.len()];
    candidates.iter().for_each(|&n| is_candidate[n] = true);
    let has_free = |n: usize| (0..3).any(|a| dofs.free(3 * n + a).is_some());
    let interior: Vec<usize> = (0..graph.len())
        .filter(|&n| !is_candidate[n] && has_free(n))
        .collect();
    let order = minimum_degree(graph, &interior)?;
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

/// faer's approximate minimum degree order of the subgraph induced by `nodes`, as node indices.
fn minimum_degree(graph: &[Vec<usize>], nodes: &[usize]) -> Result<Vec<usize>, String> {
    let k = nodes.len();
    let mut local = vec![usize::MAX; graph.len()];
    nodes.iter().enumerate().for_each(|(i, &n)| local[n] = i);
    let mut col_ptr = Vec::with_capacity(k + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for &n in nodes {
        // The neighbour lists are sorted and `local` is increasing along `nodes`.
        row_idx.extend(graph[n].iter().map(|&m| local[m]).filter(|&i| i != usize::MAX));
        col_ptr.push(row_idx.len());
    }
    let nnz = row_idx.len();
    let pattern = SymbolicSparseColMat::new_checked(k, k, col_ptr, None, row_idx);
    let (mut perm, mut inverse) = (vec![0usize; k], vec![0usize; k]);
    let mut buffer = MemBuffer::try_new(amd::order_scratch::<usize>(k, nnz))
        .map_err(|e| format!("minimum degree workspace: {e:?}"))?;
    amd::order(
        &mut perm,
        &mut inverse,
        pattern.as_ref(),
        amd::Control::default(),
        MemStack::new(&mut buffer),
    )
    .map_err(|e| format!("minimum degree ordering: {e:?}"))?;
    Ok(perm.into_iter().map(|i| nodes[i]).collect())
}
