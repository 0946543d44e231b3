//! The stiffness of one 3D body, assembled once on its free DOFs, with the far face gripped.
//!
//! DOFs: u_x, u_y, u_z of every node (full index 3 n + a). Fixed: every component of the far
//! face's nodes (the rigid grip: they follow the imposed approach and shift exactly; or u_z only,
//! [`Grip::Axial`]), and u_y on the symmetry plane y = 0. A rigid translation of the whole body is an exact, stress-free
//! solution that satisfies the grip and, for translations in x and z, the symmetry condition;
//! so u = t + u₀ with t the far face's translation and u₀ zero on the far face, driven by the
//! contact forces alone. Only u₀ needs the stiffness; t enters the contact problem as a shift of
//! the gap (normal) and of the slip (tangential).
//!
//! K_ff is assembled straight into compressed columns on the node graph's pattern (its lower
//! triangle: all that the Cholesky factorisation reads), so memory stays at the matrix's own
//! size rather than a list of element triplets ten times larger.

use faer::sparse::{SparseColMat, SymbolicSparseColMat};

use crate::fem::assembly::Dofs;
use crate::fem::element::tet10;
use crate::fem::element::tri6::Lame;
use crate::fem::mesh::solid::{SolidMesh, SolidMeshError};

/// The assembled system of one body.
pub struct System {
    /// The DOF numbering.
    pub dofs: Dofs,
    /// K_ff, lower triangle [N/m].
    pub stiffness: SparseColMat<usize, f64>,
    /// Rows turning u₀ (free DOFs) into the force the far face carries along x and z:
    /// F_a = −Σ_{far DOFs of component a} (K u₀), for a = x (index 0) and z (index 1).
    pub reaction: [Vec<f64>; 2],
    /// The node graph: the sorted neighbours of each node (itself included).
    pub graph: Vec<Vec<usize>>,
}

/// How the far face is held.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Grip {
    /// Every displacement component of the far face follows the imposed approach and shift.
    #[default]
    Rigid,
    /// Only u_z of the far face is imposed; it is free in its plane (frictionless scenes only).
    /// u_x is held at one far-face node against the rigid translation along x, which u_z and the
    /// symmetry plane leave free; no force along x acts on a frictionless body, so that node
    /// carries no reaction.
    Axial,
}

/// The fixed DOFs of the gripped body: the far face's gripped components, u_y on the symmetry
/// plane.
pub fn fixed_dofs(mesh: &SolidMesh, grip: Grip) -> Vec<bool> {
    let mut fixed = vec![false; 3 * mesh.nodes.len()];
    let far = SolidMesh::nodes_of(&mesh.far);
    for &n in &far {
        match grip {
            Grip::Rigid => fixed[3 * n..3 * n + 3].fill(true),
            Grip::Axial => fixed[3 * n + 2] = true,
        }
    }
    if let (Grip::Axial, Some(&n)) = (grip, far.first()) {
        fixed[3 * n] = true;
    }
    for n in SolidMesh::nodes_of(&mesh.symmetry) {
        fixed[3 * n + 1] = true;
    }
    fixed
}

/// The sorted neighbours of every node (nodes sharing an element), itself included.
pub fn node_graph(mesh: &SolidMesh) -> Vec<Vec<usize>> {
    crate::fem::ordering::node_graph(mesh.nodes.len(), &mesh.tetrahedra)
}

/// Assembles K_ff of `mesh` for Lamé constants `lame` on the free DOFs of `dofs`.
pub fn assemble(mesh: &SolidMesh, lame: Lame, dofs: Dofs) -> Result<System, SolidMeshError> {
    let graph = node_graph(mesh);
    let pattern = lower_pattern(&graph, &dofs);
    let mut values = vec![0.0; pattern.row_idx().len()];
    let n = dofs.count();
    let mut reaction = [vec![0.0; n], vec![0.0; n]];
    let far: Vec<bool> = {
        let mut far = vec![false; mesh.nodes.len()];
        SolidMesh::nodes_of(&mesh.far)
            .into_iter()
            .for_each(|k| far[k] = true);
        far
    };
    let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
    for (e, t) in mesh.tetrahedra.iter().enumerate() {
        let k = tet10::stiffness(&mesh.coords(e), lame).ok_or(SolidMeshError::Inverted(e))?;
        let global = |p: usize| 3 * t[p / 3] + p % 3;
        for (p, k_p) in k.iter().enumerate() {
            let row = global(p);
            for (q, &k_pq) in k_p.iter().enumerate() {
                let col = global(q);
                match (dofs.free(row), dofs.free(col)) {
                    (Some(i), Some(j)) if i >= j => {
                        let rows = &row_idx[col_ptr[j]..col_ptr[j + 1]];
                        let at = rows
                            .binary_search(&i)
                            .expect("the pattern holds every element pair");
                        values[col_ptr[j] + at] += k_pq;
                    }
                    (None, Some(j)) if far[t[p / 3]] && p % 3 != 1 => {
                        reaction[(p % 3) / 2][j] -= k_pq;
                    }
                    _ => {}
                }
            }
        }
    }
    Ok(System {
        dofs,
        stiffness: SparseColMat::new(pattern, values),
        reaction,
        graph,
    })
}

/// The lower-triangle pattern of K_ff: column j (free DOF of node n) holds the free DOFs i ≥ j
/// of n's neighbours. `Dofs` numbers node by node in order, so the rows come out sorted.
fn lower_pattern(graph: &[Vec<usize>], dofs: &Dofs) -> SymbolicSparseColMat<usize> {
    let n = dofs.count();
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for (node, neighbours) in graph.iter().enumerate() {
        for a in 0..3 {
            let Some(j) = dofs.free(3 * node + a) else {
                continue;
            };
            for &m in neighbours {
                for b in 0..3 {
                    if let Some(i) = dofs.free(3 * m + b).filter(|&i| i >= j) {
                        row_idx.push(i);
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
    }
    SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx)
}
