//! The 6-node meridian triangle in the Fourier mode n = 1: a body of revolution under a load
//! along x (a tangential shift of the contact), with the displacement
//!
//! ```text
//! u_r = U(r, z) cos θ,   u_θ = −V(r, z) sin θ,   u_z = W(r, z) cos θ
//! ```
//! (θ from the x axis). The DOFs per node are A = (U + V)/2, B = (U − V)/2 and W: then
//! u_x = A + B cos 2θ and u_y = B sin 2θ, so A is the θ-mean of u_x (the rigid shift of a ring)
//! and B its distortion. The strain amplitudes (cos θ for the first four, −sin θ for the shears
//! with θ) are (Zienkiewicz & Taylor 2000, vol. 1, §9.3, in these variables)
//!
//! ```text
//! ε_rr = U,r = A,r + B,r          ε_zz = W,z          ε_θθ = (U − V)/r = 2B/r
//! γ_rz = U,z + W,r = A,z + B,z + W,r
//! γ_rθ = V,r + (U − V)/r = A,r − B,r + 2B/r
//! γ_θz = V,z + W/r = A,z − B,z + W/r
//! K_e  = π ∫ Bᵀ D B r dA            (∫ cos²θ dθ = ∫ sin²θ dθ = π)
//! ```
//! Axis regularity: a smooth Cartesian field has W = O(r) and B = O(r²) at r = 0, so B = W = 0
//! on the axis (equivalently U = V); A is free there. With these DOFs a rigid translation along
//! x is A = const, B = W = 0 (no strain), and a rotation about y is A = ωz, B = 0, W = −ωr.
//!
//! Loads: a surface traction with amplitudes t_r = T_r cos θ, t_θ = −T_θ sin θ does the virtual
//! work π ∫ ((T_r + T_θ) δA + (T_r − T_θ) δB) r ds; a traction along x (T_r = T_θ = T, no q_y)
//! loads A alone with the nodal force 2π ∫ T N_i r ds, the same ring weights as a pressure in the
//! mode n = 0 ([`super::tri6::edge_weights`]), and the x-forces of the A DOFs add up to the total
//! force along x.

use std::f64::consts::PI;

use super::tri6::{self, Coords, Integration, Lame, Mapped};

/// Components per node: A, B, W.
pub const COMPONENTS: usize = 3;

/// Strain rows of node i, columns (A, B, W), rows (ε_rr, ε_zz, ε_θθ, γ_rz, γ_rθ, γ_θz).
fn b_rows(m: &Mapped, i: usize) -> [[f64; 3]; 6] {
    let [nr, nz] = m.grad[i];
    let over_r = m.n[i] / m.r;
    [
        [nr, nr, 0.0],
        [0.0, 0.0, nz],
        [0.0, 2.0 * over_r, 0.0],
        [nz, nz, nr],
        [nr, -nr + 2.0 * over_r, 0.0],
        [nz, -nz, over_r],
    ]
}

/// The 18 × 18 element stiffness, row-major (DOFs A0, B0, W0, A1, …); `None` if the element is
/// inverted.
pub fn stiffness(x: &Coords, lame: Lame, integration: Integration) -> Option<Vec<f64>> {
    tri6::integrate(x, lame, integration, PI, b_rows)
}

/// The Fourier mode n = 1: A, B, W per node.
pub struct FourierOne;

impl super::Mode for FourierOne {
    const COMPONENTS: usize = COMPONENTS;

    fn stiffness(x: &Coords, lame: Lame, integration: Integration) -> Option<Vec<f64>> {
        stiffness(x, lame, integration)
    }
}

/// Strain amplitudes (ε_rr, ε_zz, ε_θθ, γ_rz, γ_rθ, γ_θz) at reference point `at` from nodal
/// (A, B, W) `u`. On the axis the terms B/r and W/r take their limits ∂B/∂r and ∂W/∂r, since
/// B = W = 0 there.
pub fn strain(x: &Coords, u: &[[f64; 3]; 6], at: [f64; 2]) -> Option<[f64; 6]> {
    let m = tri6::map(x, at)?;
    let mut grad = [[0.0; 2]; 3]; // ∂(A, B, W)/∂(r, z)
    let mut value = [0.0; 3];
    for ((g, &n), ui) in m.grad.iter().zip(&m.n).zip(u) {
        for c in 0..3 {
            grad[c][0] += g[0] * ui[c];
            grad[c][1] += g[1] * ui[c];
            value[c] += n * ui[c];
        }
    }
    let size = x.iter().map(|p| p[0].abs() + p[1].abs()).fold(0.0, f64::max);
    let on_axis = m.r <= 1e-12 * size;
    let [b_r, w_r] = if on_axis {
        [grad[1][0], grad[2][0]]
    } else {
        [value[1] / m.r, value[2] / m.r]
    };
    let ([a_r, a_z], [b_dr, b_dz], [w_dr, w_dz]) = (grad[0], grad[1], grad[2]);
    Some([
        a_r + b_dr,
        w_dz,
        2.0 * b_r,
        a_z + b_dz + w_dr,
        a_r - b_dr + 2.0 * b_r,
        a_z - b_dz + w_r,
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A curved-free, well-shaped element off the axis.
    fn element() -> Coords {
        let c = [[1.0, 0.0], [2.0, 0.2], [1.3, 1.0]];
        let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        [
            c[0],
            c[1],
            c[2],
            mid(c[0], c[1]),
            mid(c[1], c[2]),
            mid(c[2], c[0]),
        ]
    }

    fn lame() -> Lame {
        Lame { lambda: 1.5, mu: 1.0 }
    }

    #[test]
    fn rigid_motions_are_in_the_kernel_and_the_matrix_is_symmetric() {
        let x = element();
        let k = stiffness(&x, lame(), Integration::Full).unwrap();
        // Translation along x: A = 1; rotation about y by ω = 1: A = z, B = 0, W = −r.
        let translation: Vec<f64> = (0..6).flat_map(|_| [1.0, 0.0, 0.0]).collect();
        let rotation: Vec<f64> = x.iter().flat_map(|p| [p[1], 0.0, -p[0]]).collect();
        let scale = k.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for mode in [translation, rotation] {
            for row in k.chunks(18) {
                let f: f64 = row.iter().zip(&mode).map(|(a, b)| a * b).sum();
                // Round-off of the quadrature sums relative to the largest entry.
                assert!(f.abs() < 1e-13 * scale, "K · rigid motion = {f}");
            }
        }
        for i in 0..18 {
            for j in 0..18 {
                assert!((k[i * 18 + j] - k[j * 18 + i]).abs() < 1e-14 * scale);
            }
        }
    }

    #[test]
    fn strain_of_a_rigid_motion_vanishes_also_on_the_axis() {
        // An element with an edge on the axis: the limits B/r → ∂B/∂r, W/r → ∂W/∂r are used there.
        // The reference triangle itself: its edge ξ = 0 lies on the axis.
        let x = tri6::NODES;
        let u = x.map(|p| [0.3 + 2.0 * p[1], 0.0, -2.0 * p[0]]);
        for at in tri6::NODES {
            let e = strain(&x, &u, at).unwrap();
            assert!(e.iter().all(|v| v.abs() < 1e-14), "{e:?} at {at:?}");
        }
    }
}
