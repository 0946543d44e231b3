//! Global stiffness of one body, assembled once, with its Dirichlet conditions eliminated.
//!
//! Fixed DOFs: u_r on the axis (symmetry) and u_z on the far boundary (displaced rigidly along
//! the axis, free to slide radially: the loading of the FreeFEM and dolfinx decks, so that the
//! same mesh gives the same model in every code). A rigid translation along z is an exact, stress-free solution that satisfies both,
//! so the displacement is u = −Δ e_z + u₀, with u₀ zero on the far boundary and driven by the
//! contact forces alone: only u₀ needs the stiffness, and the far boundary's displacement Δ enters
//! the contact problem as a shift of the gap.

use faer::sparse::{SparseColMat, Triplet};

use super::element::tri6::{self, Integration, Lame};
use super::mesh::meridian::{Mesh, MeshError};

/// The numbering of free DOFs (node n: u_r = 2n, u_z = 2n + 1 in the full numbering).
#[derive(Clone, Debug)]
pub struct Dofs {
    free: Vec<Option<usize>>,
    count: usize,
}

impl Dofs {
    /// Fixes u_r on the axis and u_z on the far boundary of `mesh`.
    pub fn of(mesh: &Mesh) -> Self {
        let mut fixed = vec![false; 2 * mesh.nodes.len()];
        for &n in &mesh.axis {
            fixed[2 * n] = true;
        }
        for &n in &mesh.far {
            fixed[2 * n + 1] = true;
        }
        Self::from_fixed(&fixed)
    }

    /// Numbers the DOFs not flagged in `fixed` (one flag per full DOF).
    pub fn from_fixed(fixed: &[bool]) -> Self {
        let mut count = 0;
        let free = fixed
            .iter()
            .map(|&f| {
                (!f).then(|| {
                    count += 1;
                    count - 1
                })
            })
            .collect();
        Self { free, count }
    }

    /// The free index of full DOF `dof`, if free.
    pub fn free(&self, dof: usize) -> Option<usize> {
        self.free[dof]
    }

    /// The number of free DOFs.
    pub fn count(&self) -> usize {
        self.count
    }
}

/// The assembled system of one body.
pub struct System {
    /// The DOF numbering.
    pub dofs: Dofs,
    /// The free–free stiffness K_ff, lower triangle only [N/m].
    pub stiffness: SparseColMat<usize, f64>,
    /// The row that turns u₀ (free DOFs) into the normal force carried by the far boundary:
    /// P_reaction = −Σ_{far z-DOFs} (K u)_z, as (free DOF, coefficient) pairs.
    pub reaction: Vec<(usize, f64)>,
}

/// Assembles the stiffness of `mesh` for a material with Lamé constants `lame`, with the
/// contact problem's boundary conditions ([`Dofs::of`]).
pub fn assemble(mesh: &Mesh, lame: Lame, integration: Integration) -> Result<System, MeshError> {
    assemble_with(mesh, lame, integration, Dofs::of(mesh))
}

/// Assembles the stiffness of `mesh` on the free DOFs of `dofs`.
pub fn assemble_with(
    mesh: &Mesh,
    lame: Lame,
    integration: Integration,
    dofs: Dofs,
) -> Result<System, MeshError> {
    let mut far_z = vec![false; 2 * mesh.nodes.len()];
    for &n in &mesh.far {
        far_z[2 * n + 1] = true;
    }
    let mut triplets = Vec::with_capacity(mesh.triangles.len() * 78);
    let mut reaction = vec![0.0; dofs.count()];
    for (e, t) in mesh.triangles.iter().enumerate() {
        let x = t.map(|n| mesh.nodes[n]);
        let k = tri6::stiffness(&x, lame, integration).ok_or(MeshError::Inverted(e))?;
        let global = |a: usize| 2 * t[a / 2] + a % 2;
        for (a, k_a) in k.iter().enumerate() {
            for (b, &k_ab) in k_a.iter().enumerate() {
                let (row, col) = (global(a), global(b));
                match (dofs.free(row), dofs.free(col)) {
                    (Some(i), Some(j)) if i >= j => triplets.push(Triplet::new(i, j, k_ab)),
                    (None, Some(j)) if far_z[row] => reaction[j] -= k_ab,
                    _ => {}
                }
            }
        }
    }
    let n = dofs.count();
    let stiffness = SparseColMat::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| MeshError::Parameters(format!("sparse assembly: {e:?}")))?;
    let reaction = reaction
        .into_iter()
        .enumerate()
        .filter(|(_, v)| *v != 0.0)
        .collect();
    Ok(System {
        dofs,
        stiffness,
        reaction,
    })
}
