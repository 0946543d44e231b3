//! Element kinds.
//!
//! | module | element |
//! |---|---|
//! | [`tri6`] | 6-node triangle of the meridian plane, axisymmetric (Fourier mode n = 0), r-weighted stiffness |
//! | [`tri6_n1`] | the same triangle in the Fourier mode n = 1 (a shift along x of an axisymmetric body) |
//! | [`tet10`] | 10-node tetrahedron of 3D elasticity (gmsh's node order), its stiffness and strain |
//! | [`face6`] | the 6-node triangular face of a tetrahedron and its contact rule (sub-triangulated pressure) |
//!
//! [`internal_force`]: the nodal forces ∫ σ ∇N_i dV of any 3D element from its displacements.

pub mod face6;
pub mod internal_force;
pub mod tet10;
pub mod tri6;
pub mod tri6_n1;

use tri6::{Coords, Integration, Lame};

/// The Jacobian J_ab = ∂x_a/∂ξ_b = Σ_i x_i,a ∂N_i/∂ξ_b of an isoparametric element of dimension
/// D from its nodes `x` and its shape functions' reference gradients `dn` (one row a node).
pub fn jacobian<const D: usize>(x: &[[f64; D]], dn: &[[f64; D]]) -> [[f64; D]; D] {
    let mut j = [[0.0; D]; D];
    for (xi, dni) in x.iter().zip(dn) {
        for (row, xa) in j.iter_mut().zip(xi) {
            for (entry, db) in row.iter_mut().zip(dni) {
                *entry += xa * db;
            }
        }
    }
    j
}

/// The physical gradients ∇_x N = J⁻ᵀ ∇_ξ N of a 3D isoparametric element's shape functions
/// from their reference gradients `dn` (one row a node) and its nodes `x`, and det J; `None`
/// where the element is inverted or degenerate (det J ≤ 0 or not a number).
///
/// J⁻¹ from the cofactors: (J⁻¹)_ba = cof(J)_ab / det J.
pub fn physical_gradients<const N: usize>(
    x: &[[f64; 3]; N],
    dn: &[[f64; 3]; N],
) -> Option<([[f64; 3]; N], f64)> {
    let j = jacobian(x, dn);
    let cof = |a: usize, b: usize| {
        let (r0, r1) = ((a + 1) % 3, (a + 2) % 3);
        let (c0, c1) = ((b + 1) % 3, (b + 2) % 3);
        j[r0][c0] * j[r1][c1] - j[r0][c1] * j[r1][c0]
    };
    let cofactor: [[f64; 3]; 3] = std::array::from_fn(|a| std::array::from_fn(|b| cof(a, b)));
    let det: f64 = (0..3).map(|b| j[0][b] * cofactor[0][b]).sum();
    if det.is_nan() || det <= 0.0 {
        return None;
    }
    let grad = dn.map(|d| std::array::from_fn(|a| (0..3).map(|b| cofactor[a][b] * d[b]).sum::<f64>() / det));
    Some((grad, det))
}

/// A Fourier mode of the 6-node meridian triangle, as the assembly sees it.
pub trait Mode {
    /// Displacement components per node (their amplitudes are the DOFs, node-major).
    const COMPONENTS: usize;

    /// The element stiffness, (6 C)² row-major with DOFs node-major (node 0's components,
    /// node 1's, …); `None` if the element is inverted or degenerate.
    fn stiffness(x: &Coords, lame: Lame, integration: Integration) -> Option<Vec<f64>>;
}
