//! The internal nodal forces of a 3D element of linear elasticity from its nodal displacements.
//!
//! For u = Σ_j N_j u_j, the virtual work of the stress on a virtual displacement N_i δu gives
//! node i's force
//!
//! ```text
//! f_i = ∫ σ ∇N_i dV ≈ Σ_p w_p det J_p σ(ξ_p) ∇_x N_i(ξ_p),
//! σ = λ tr(ε) I + 2μ ε,   ε = sym(∇u),   ∇u = Σ_j u_j ⊗ ∇_x N_j,
//! ```
//!
//! which is K u for the element stiffness integrated on the same rule (the tests check it
//! against [`super::tet10::stiffness`]). Summed over a body's elements at a node, it is the force
//! the rest of the world exerts on the body there, for a displacement solution in equilibrium:
//! how `ccx-3d` recovers the contact's nodal forces from CalculiX's displacements
//! (`calculix::nodal_forces` (spherecontact-external)). Generic over the element: it needs only the shape
//! functions' physical gradients at the rule's points.

use super::tri6::Lame;

/// One integration point of an element: the shape functions' physical gradients ∇_x N_i (one
/// row a node) and the point's weight times the Jacobian's determinant, w det J [m³].
#[derive(Clone, Debug, PartialEq)]
pub struct GradientPoint {
    /// ∇_x N_i [1/m], one row a node.
    pub grad: Vec<[f64; 3]>,
    /// w det J [m³].
    pub volume: f64,
}

/// The nodal forces f_i [N] of an element integrated on `points`, under the nodal displacements
/// `u` [m] (one row a node, in the order of the points' gradients).
pub fn internal_forces(points: &[GradientPoint], u: &[[f64; 3]], lame: Lame) -> Vec<[f64; 3]> {
    let mut f = vec![[0.0; 3]; u.len()];
    for point in points {
        let sigma = stress(lame, &displacement_gradient(&point.grad, u));
        for (fi, gi) in f.iter_mut().zip(&point.grad) {
            for (a, fa) in fi.iter_mut().enumerate() {
                *fa += point.volume * (0..3).map(|b| sigma[a][b] * gi[b]).sum::<f64>();
            }
        }
    }
    f
}

/// ∇u, g[a][b] = ∂u_a/∂x_b = Σ_j u_j,a ∂N_j/∂x_b.
fn displacement_gradient(grad: &[[f64; 3]], u: &[[f64; 3]]) -> [[f64; 3]; 3] {
    let mut g = [[0.0; 3]; 3];
    for (uj, gj) in u.iter().zip(grad) {
        for (row, ua) in g.iter_mut().zip(uj) {
            for (entry, gb) in row.iter_mut().zip(gj) {
                *entry += ua * gb;
            }
        }
    }
    g
}

/// Hooke's law σ = λ tr(ε) I + 2μ ε with ε = (∇u + ∇uᵀ)/2.
fn stress(lame: Lame, g: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let trace = g[0][0] + g[1][1] + g[2][2];
    std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            let volumetric = if a == b { lame.lambda * trace } else { 0.0 };
            volumetric + lame.mu * (g[a][b] + g[b][a])
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::element::tet10::{self, Coords};

    const LAME: Lame = Lame {
        lambda: 40.4e9,
        mu: 26.9e9,
    };

    /// A curved quadratic tetrahedron of millimetre size: its midside nodes off their edges.
    fn curved() -> Coords {
        let mut x = tet10::NODES.map(|p| p.map(|v| 1e-3 * v));
        x[4][2] -= 5e-5;
        x[8][0] += 4e-5;
        x
    }

    /// The element's gradient points on its stiffness rule.
    fn points(x: &Coords) -> Vec<GradientPoint> {
        tet10::stiffness_rule(x)
            .into_iter()
            .map(|p| {
                let m = tet10::map(x, p.at).unwrap();
                GradientPoint {
                    grad: m.grad.to_vec(),
                    volume: p.weight * m.det,
                }
            })
            .collect()
    }

    /// Requirement: the forces are K u for the stiffness assembled independently (its 30 × 30
    /// matrix, [`tet10::stiffness`]) on the same rule, for an arbitrary displacement. Reference:
    /// that product; tolerance 1e-12 of the largest force, the round-off of two sums of a few
    /// hundred terms.
    #[test]
    fn the_forces_are_the_stiffness_times_the_displacements() {
        let x = curved();
        let u: Vec<[f64; 3]> = (0..10)
            .map(|i| {
                [
                    1e-6 * (i as f64).sin(),
                    2e-6 * (0.7 * i as f64).cos(),
                    -1e-6 * (i as f64) / 9.0,
                ]
            })
            .collect();
        let f = internal_forces(&points(&x), &u, LAME);
        let k = tet10::stiffness(&x, LAME).unwrap();
        let flat: Vec<f64> = u.iter().flatten().copied().collect();
        let largest = f.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(
            largest > 1.0,
            "a displacement of a few µm over a millimetre strains: {largest} N"
        );
        for (row, fi) in k.iter().zip(f.iter().flatten()) {
            let ku: f64 = row.iter().zip(&flat).map(|(kij, uj)| kij * uj).sum();
            assert!((ku - fi).abs() <= 1e-12 * largest, "K u = {ku}, f = {fi}");
        }
    }

    /// Requirement: a rigid motion (a translation and an infinitesimal rotation) strains nothing,
    /// so no node carries a force. Reference: 0, `abs_zero` 1e-9 N against forces of order 1 N
    /// for a strain of 1e-3 (the rotation's size), the round-off of the gradients' sums.
    #[test]
    fn a_rigid_motion_carries_no_force() {
        let x = curved();
        let (t, w) = ([3e-6, -1e-6, 2e-6], [1e-3, 2e-3, -1.5e-3]);
        let u: Vec<[f64; 3]> = x
            .iter()
            .map(|p| {
                let cross = [
                    w[1] * p[2] - w[2] * p[1],
                    w[2] * p[0] - w[0] * p[2],
                    w[0] * p[1] - w[1] * p[0],
                ];
                std::array::from_fn(|a| t[a] + cross[a])
            })
            .collect();
        for fi in internal_forces(&points(&x), &u, LAME) {
            assert!(fi.iter().all(|v| v.abs() < 1e-9), "{fi:?}");
        }
    }
}
