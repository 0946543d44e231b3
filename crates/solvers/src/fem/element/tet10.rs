//! The quadratic tetrahedron (10 nodes, isoparametric) of 3D linear elasticity.
//!
//! Node order (gmsh's type 11): corners 0–3 at reference points (0,0,0), (1,0,0), (0,1,0),
//! (0,0,1), then the midside nodes of edges 0–1, 1–2, 2–0, 3–0, 3–2, 3–1 ([`EDGES`]). In
//! barycentric coordinates L₀ = 1 − ξ − η − ζ, L₁ = ξ, L₂ = η, L₃ = ζ the shape functions are
//! L_i (2 L_i − 1) at corner i and 4 L_i L_j at the midside of edge i–j.
//!
//! With u = Σ_j N_j u_j, the strain energy ½ ∫ (λ (div u)² + 2μ ε:ε) dV gives the 3 × 3 block
//! of nodes i, j (components a, b):
//!
//! ```text
//! K_ia,jb = ∫ ( λ ∂_a N_i ∂_b N_j + μ ∂_b N_i ∂_a N_j + μ δ_ab ∇N_i · ∇N_j ) dV
//! ```
//! A straight-sided element has a constant Jacobian and linear gradients, so the integrand is
//! quadratic and the 4-point rule is exact; a curved one (midside nodes off their edges' middles,
//! as gmsh places them on the sphere) gets the 14-point degree-5 rule.

use super::tri6::Lame;
use spherecontact_model::quadrature::{self, Point3};

/// Node coordinates of one element [m].
pub type Coords = [[f64; 3]; 10];

/// The corners of each edge, in the order of the midside nodes 4–9.
pub const EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];

/// The ten nodes in VTK's order (ParaView's `VTK_QUADRATIC_TETRA`, type 24): the same corners,
/// edges 0–1, 1–2, 2–0, 0–3, 1–3, 2–3: gmsh's midside nodes 8 and 9 swapped.
pub const VTK_ORDER: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// Reference coordinates of the ten nodes.
pub const NODES: [[f64; 3]; 10] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.0, 0.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.0],
    [0.0, 0.0, 0.5],
    [0.0, 0.5, 0.5],
    [0.5, 0.0, 0.5],
];

/// Shape functions and their reference gradients ∂N/∂(ξ, η, ζ) at `at`.
pub fn shape(at: [f64; 3]) -> ([f64; 10], [[f64; 3]; 10]) {
    let l = [1.0 - at[0] - at[1] - at[2], at[0], at[1], at[2]];
    let grad_l = [
        [-1.0, -1.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let mut n = [0.0; 10];
    let mut dn = [[0.0; 3]; 10];
    for i in 0..4 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
        dn[i] = grad_l[i].map(|g| (4.0 * l[i] - 1.0) * g);
    }
    for (k, &[i, j]) in EDGES.iter().enumerate() {
        n[4 + k] = 4.0 * l[i] * l[j];
        dn[4 + k] = std::array::from_fn(|a| 4.0 * (l[j] * grad_l[i][a] + l[i] * grad_l[j][a]));
    }
    (n, dn)
}

/// The map from reference to physical coordinates at one point.
pub struct Mapped {
    /// Shape function values.
    pub n: [f64; 10],
    /// Gradients ∂N/∂(x, y, z).
    pub grad: [[f64; 3]; 10],
    /// Jacobian determinant (positive for a positively oriented element).
    pub det: f64,
}

impl Mapped {
    /// The physical point Σ N_i x_i.
    pub fn point(&self, x: &Coords) -> [f64; 3] {
        std::array::from_fn(|a| (0..10).map(|i| self.n[i] * x[i][a]).sum())
    }
}

/// Maps reference point `at` of the element with nodes `x`; `None` if it is inverted or
/// degenerate there.
pub fn map(x: &Coords, at: [f64; 3]) -> Option<Mapped> {
    let (n, dn) = shape(at);
    let (grad, det) = super::physical_gradients(x, &dn)?;
    Some(Mapped { n, grad, det })
}

/// True if every midside node lies at the middle of its edge (to round-off of the element's
/// size): then the Jacobian is constant.
pub fn is_straight(x: &Coords) -> bool {
    let size = EDGES
        .iter()
        .map(|&[i, j]| (0..3).map(|a| (x[i][a] - x[j][a]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    EDGES
        .iter()
        .enumerate()
        .all(|(k, &[i, j])| (0..3).all(|a| (x[4 + k][a] - 0.5 * (x[i][a] + x[j][a])).abs() <= 1e-12 * size))
}

/// The rule that integrates this element's stiffness: exact on straight elements.
pub fn stiffness_rule(x: &Coords) -> Vec<Point3> {
    if is_straight(x) {
        quadrature::tetrahedron_degree2()
    } else {
        quadrature::tetrahedron_degree5()
    }
}

/// The 30 × 30 element stiffness (DOFs u_x0, u_y0, u_z0, u_x1, …) [N/m]; `None` if the element
/// is inverted somewhere.
pub fn stiffness(x: &Coords, lame: Lame) -> Option<Box<[[f64; 30]; 30]>> {
    let mut k = Box::new([[0.0; 30]; 30]);
    for p in stiffness_rule(x) {
        let m = map(x, p.at)?;
        let w = m.det * p.weight;
        for i in 0..10 {
            let gi = m.grad[i];
            for j in 0..10 {
                let gj = m.grad[j];
                let dot = w * lame.mu * (gi[0] * gj[0] + gi[1] * gj[1] + gi[2] * gj[2]);
                for a in 0..3 {
                    for b in 0..3 {
                        k[3 * i + a][3 * j + b] +=
                            w * (lame.lambda * gi[a] * gj[b] + lame.mu * gi[b] * gj[a]);
                    }
                    k[3 * i + a][3 * j + a] += dot;
                }
            }
        }
    }
    Some(k)
}

/// Strain (ε_xx, ε_yy, ε_zz, γ_yz, γ_xz, γ_xy) at reference point `at` from nodal displacements.
pub fn strain(x: &Coords, u: &[[f64; 3]; 10], at: [f64; 3]) -> Option<[f64; 6]> {
    let m = map(x, at)?;
    let mut g = [[0.0; 3]; 3]; // g[a][b] = ∂u_a/∂x_b
    for (ui, gi) in u.iter().zip(&m.grad) {
        for a in 0..3 {
            for b in 0..3 {
                g[a][b] += ui[a] * gi[b];
            }
        }
    }
    Some([
        g[0][0],
        g[1][1],
        g[2][2],
        g[1][2] + g[2][1],
        g[0][2] + g[2][0],
        g[0][1] + g[1][0],
    ])
}

/// Stress (σ_xx, σ_yy, σ_zz, τ_yz, τ_xz, τ_xy) [Pa] from the strain of [`strain`].
pub fn stress(lame: Lame, e: [f64; 6]) -> [f64; 6] {
    let volumetric = lame.lambda * (e[0] + e[1] + e[2]);
    std::array::from_fn(|k| {
        if k < 3 {
            volumetric + 2.0 * lame.mu * e[k]
        } else {
            lame.mu * e[k]
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A curved element: the reference element with its midside nodes pushed off their edges.
    fn curved() -> Coords {
        let mut x = NODES;
        x[4][2] -= 0.05;
        x[8][0] += 0.04;
        x
    }

    #[test]
    fn shape_functions_interpolate_and_sum_to_one() {
        for (i, at) in NODES.iter().enumerate() {
            let (n, dn) = shape(*at);
            for (j, nj) in n.iter().enumerate() {
                assert!((nj - f64::from(u8::from(i == j))).abs() < 1e-15);
            }
            for a in 0..3 {
                assert!(dn.iter().map(|d| d[a]).sum::<f64>().abs() < 1e-14);
            }
        }
        // Midside nodes sit on their edges.
        for (k, &[i, j]) in EDGES.iter().enumerate() {
            let middle: [f64; 3] = std::array::from_fn(|a| 0.5 * (NODES[i][a] + NODES[j][a]));
            assert_eq!(NODES[4 + k], middle);
        }
    }

    #[test]
    fn reference_gradients_match_finite_differences() {
        let at = [0.21, 0.17, 0.33];
        let (_, dn) = shape(at);
        let h = 1e-6;
        for b in 0..3 {
            let (mut up, mut down) = (at, at);
            up[b] += h;
            down[b] -= h;
            let (nu, nd) = (shape(up).0, shape(down).0);
            for i in 0..10 {
                assert!(((nu[i] - nd[i]) / (2.0 * h) - dn[i][b]).abs() < 1e-8);
            }
        }
    }

    #[test]
    fn stiffness_is_symmetric_with_six_rigid_body_modes() {
        let lame = Lame { lambda: 1.5, mu: 1.0 };
        for x in [NODES, curved()] {
            assert_eq!(is_straight(&x), x == NODES);
            let k = stiffness(&x, lame).unwrap();
            for a in 0..30 {
                for b in 0..30 {
                    assert!((k[a][b] - k[b][a]).abs() < 1e-13);
                }
            }
            // Translations and infinitesimal rotations: K u = 0.
            type Mode = Box<dyn Fn([f64; 3]) -> [f64; 3]>;
            let modes: Vec<Mode> = vec![
                Box::new(|_| [1.0, 0.0, 0.0]),
                Box::new(|_| [0.0, 1.0, 0.0]),
                Box::new(|_| [0.0, 0.0, 1.0]),
                Box::new(|p| [-p[1], p[0], 0.0]),
                Box::new(|p| [0.0, -p[2], p[1]]),
                Box::new(|p| [p[2], 0.0, -p[0]]),
            ];
            for mode in &modes {
                let u: Vec<f64> = x.iter().flat_map(|&p| mode(p)).collect();
                for row in k.iter() {
                    let f: f64 = row.iter().zip(&u).map(|(a, b)| a * b).sum();
                    assert!(f.abs() < 1e-13, "rigid mode loads the element: {f}");
                }
            }
        }
    }

    #[test]
    fn an_inverted_element_is_refused() {
        let mut x = NODES;
        x.swap(1, 2);
        x.swap(4, 6);
        x.swap(8, 9);
        assert!(stiffness(&x, Lame { lambda: 1.0, mu: 1.0 }).is_none());
    }

    #[test]
    fn vtk_order_swaps_the_last_two_edges() {
        // VTK edge 4 = 1–3 and edge 5 = 2–3 are gmsh's midsides 9 (3–1) and 8 (3–2).
        assert_eq!(EDGES[VTK_ORDER[8] - 4], [3, 1]);
        assert_eq!(EDGES[VTK_ORDER[9] - 4], [3, 2]);
    }
}
