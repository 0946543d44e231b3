//! Global stiffness of one body in one Fourier mode, assembled once, with its Dirichlet
//! conditions eliminated.
//!
//! The same mechanism serves every mode ([`Mode`]: n = 0 with (u_r, u_z) per node, n = 1 with
//! (A, B, W)); what differs is the element matrix and which DOFs are fixed:
//!
//! - n = 0 ([`Dofs::axisymmetric`]): u_r on the axis (symmetry); on the far boundary u_z (the
//!   axial grip: displaced rigidly along the axis, free radially) or u_r and u_z (the rigid grip);
//! - n = 1 ([`Dofs::fourier_one`]): B and W on the axis (regularity), A, B and W on the far
//!   boundary (a rigid grip, shifted along x).
//!
//! A rigid translation along the loaded direction (z for n = 0, x for n = 1) is an exact,
//! stress-free solution that satisfies these conditions, so the displacement is u = Δ e + u₀, with
//! u₀ zero on the far boundary and driven by the contact forces alone: only u₀ needs the
//! stiffness, and the far boundary's displacement Δ enters the contact problem as a shift.

use faer::sparse::{SparseColMat, Triplet};

use super::element::tri6::{Integration, Lame};
use super::element::tri6_n1;
use super::element::Mode;
use super::mesh::meridian::{Mesh, MeshError};
use spherecontact_model::domain::Grip;

/// The numbering of free DOFs (node n, component a: full DOF C n + a, C components per node).
#[derive(Clone, Debug)]
pub struct Dofs {
    free: Vec<Option<usize>>,
    count: usize,
}

impl Dofs {
    /// Mode n = 0: u_r on the axis; u_z on the far boundary, and u_r too under a rigid grip.
    pub fn axisymmetric(mesh: &Mesh, grip: Grip) -> Self {
        let mut fixed = vec![false; 2 * mesh.nodes.len()];
        for &n in &mesh.axis {
            fixed[2 * n] = true;
        }
        for &n in &mesh.far {
            fixed[2 * n + 1] = true;
            fixed[2 * n] |= grip == Grip::Rigid;
        }
        Self::from_fixed(&fixed)
    }

    /// Mode n = 1: B and W on the axis, every component on the far boundary.
    pub fn fourier_one(mesh: &Mesh) -> Self {
        let c = tri6_n1::COMPONENTS;
        let mut fixed = vec![false; c * mesh.nodes.len()];
        for &n in &mesh.axis {
            fixed[c * n + 1] = true;
            fixed[c * n + 2] = true;
        }
        for &n in &mesh.far {
            fixed[c * n..c * (n + 1)].fill(true);
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

/// The assembled system of one body in one mode.
pub struct System {
    /// The DOF numbering.
    pub dofs: Dofs,
    /// The free–free stiffness K_ff, lower triangle only [N/m].
    pub stiffness: SparseColMat<usize, f64>,
    /// The row that turns u₀ (free DOFs) into the force carried by the far boundary along the
    /// loaded direction: F_reaction = −Σ_{far loaded DOFs} (K u), as (free DOF, coefficient) pairs.
    pub reaction: Vec<(usize, f64)>,
}

/// Assembles the mode n = 0 stiffness of `mesh` with the contact problem's boundary conditions
/// ([`Dofs::axisymmetric`]); the reaction is the far boundary's force along z.
pub fn assemble(mesh: &Mesh, lame: Lame, integration: Integration, grip: Grip) -> Result<System, MeshError> {
    use super::element::tri6::Axisymmetric;
    assemble_with::<Axisymmetric>(mesh, lame, integration, Dofs::axisymmetric(mesh, grip), 1)
}

/// Assembles the mode n = 1 stiffness of `mesh` ([`Dofs::fourier_one`]); the reaction is the far
/// boundary's force along x (its A DOFs).
pub fn assemble_fourier_one(mesh: &Mesh, lame: Lame, integration: Integration) -> Result<System, MeshError> {
    use super::element::tri6_n1::FourierOne;
    assemble_with::<FourierOne>(mesh, lame, integration, Dofs::fourier_one(mesh), 0)
}

/// Assembles the stiffness of mode `M` of `mesh` on the free DOFs of `dofs`; the reaction row
/// sums component `loaded` over the far boundary's fixed DOFs.
pub fn assemble_with<M: Mode>(
    mesh: &Mesh,
    lame: Lame,
    integration: Integration,
    dofs: Dofs,
    loaded: usize,
) -> Result<System, MeshError> {
    let c = M::COMPONENTS;
    let size = 6 * c;
    let mut far_loaded = vec![false; c * mesh.nodes.len()];
    for &n in &mesh.far {
        far_loaded[c * n + loaded] = true;
    }
    let mut triplets = Vec::with_capacity(mesh.triangles.len() * size * (size + 1) / 2);
    let mut reaction = vec![0.0; dofs.count()];
    for (e, t) in mesh.triangles.iter().enumerate() {
        let x = t.map(|n| mesh.nodes[n]);
        let k = M::stiffness(&x, lame, integration).ok_or(MeshError::Inverted(e))?;
        let global = |a: usize| c * t[a / c] + a % c;
        for (a, k_a) in k.chunks_exact(size).enumerate() {
            for (b, &k_ab) in k_a.iter().enumerate() {
                let (row, col) = (global(a), global(b));
                match (dofs.free(row), dofs.free(col)) {
                    (Some(i), Some(j)) if i >= j => triplets.push(Triplet::new(i, j, k_ab)),
                    (None, Some(j)) if far_loaded[row] => reaction[j] -= k_ab,
                    _ => {}
                }
            }
        }
    }
    let n = dofs.count();
    let stiffness = SparseColMat::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| MeshError::Parameters(format!("sparse assembly: {e}")))?;
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
