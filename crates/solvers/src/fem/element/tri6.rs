//! The quadratic axisymmetric triangle (6 nodes, isoparametric) of linear elasticity.
//!
//! Meridian coordinates x = (r, z); the displacement (u_r, u_z) does not depend on the hoop
//! angle θ. The strains are (Zienkiewicz & Taylor 2000, vol. 1, §6.2)
//!
//! ```text
//! ε = (ε_rr, ε_zz, ε_θθ, γ_rz) = (∂u_r/∂r, ∂u_z/∂z, u_r/r, ∂u_r/∂z + ∂u_z/∂r)
//! σ = D ε,   D = λ m mᵀ + μ diag(2, 2, 2, 1),   m = (1, 1, 1, 0)
//! K_e = 2π ∫ Bᵀ D B r dA
//! ```
//! so that nodal forces are whole-ring forces in newtons. Node order: corners 0, 1, 2
//! counter-clockwise, then the midside nodes of edges 0–1, 1–2, 2–0 (gmsh's order).
//!
//! Near ν = ½ the term λ m mᵀ locks a displacement element (the discrete divergence constraint
//! is too strong); [`Integration::SelectiveReduced`] integrates it with the 3-point rule only
//! (Hughes 1987, §4.5; Malkus & Hughes 1978), which relieves the constraint.

use spherecontact_model::pair::Material;
use spherecontact_model::quadrature::{self, Point};
use std::f64::consts::PI;

/// Node coordinates (r, z) of one element.
pub type Coords = [[f64; 2]; 6];

/// How the element stiffness is integrated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integration {
    /// Everything with the 6-point, degree-4 rule.
    Full,
    /// The μ part with the 6-point rule, the λ (volumetric) part with the 3-point rule.
    SelectiveReduced,
}

/// Lamé constants of an isotropic material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lame {
    /// λ = Eν / ((1 + ν)(1 − 2ν)) [Pa].
    pub lambda: f64,
    /// μ = G = E / (2(1 + ν)) [Pa].
    pub mu: f64,
}

impl Lame {
    /// The Lamé constants of `material`.
    pub fn of(material: &Material) -> Self {
        let (e, nu) = (material.young, material.poisson);
        Self {
            lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            mu: material.shear_modulus(),
        }
    }

    /// Stress (σ_rr, σ_zz, σ_θθ, τ_rz) from strain (ε_rr, ε_zz, ε_θθ, γ_rz).
    pub fn stress(&self, strain: [f64; 4]) -> [f64; 4] {
        self.stress_of(strain)
    }

    /// Stress from strain of any length S ≥ 3: three normal strains, then engineering shears
    /// (σ_k = λ tr ε + 2μ ε_k for k < 3, τ = μ γ beyond).
    pub fn stress_of<const S: usize>(&self, strain: [f64; S]) -> [f64; S] {
        let trace = strain[0] + strain[1] + strain[2];
        std::array::from_fn(|k| {
            if k < 3 {
                self.lambda * trace + 2.0 * self.mu * strain[k]
            } else {
                self.mu * strain[k]
            }
        })
    }
}

/// Shape functions of the 6-node triangle and their reference gradients at (ξ, η).
pub fn shape(at: [f64; 2]) -> ([f64; 6], [[f64; 2]; 6]) {
    let (xi, eta) = (at[0], at[1]);
    let l1 = 1.0 - xi - eta;
    let n = [
        l1 * (2.0 * l1 - 1.0),
        xi * (2.0 * xi - 1.0),
        eta * (2.0 * eta - 1.0),
        4.0 * l1 * xi,
        4.0 * xi * eta,
        4.0 * eta * l1,
    ];
    let dn = [
        [1.0 - 4.0 * l1, 1.0 - 4.0 * l1],
        [4.0 * xi - 1.0, 0.0],
        [0.0, 4.0 * eta - 1.0],
        [4.0 * (l1 - xi), -4.0 * xi],
        [4.0 * eta, 4.0 * xi],
        [-4.0 * eta, 4.0 * (l1 - eta)],
    ];
    (n, dn)
}

/// The map from reference to meridian coordinates at one point.
pub struct Mapped {
    /// Shape function values.
    pub n: [f64; 6],
    /// Gradients ∂N/∂(r, z).
    pub grad: [[f64; 2]; 6],
    /// Radius r of the point.
    pub r: f64,
    /// Jacobian determinant (positive for a counter-clockwise element).
    pub det: f64,
}

/// Maps reference point `at` of the element with nodes `x`; `None` if the element is inverted
/// or degenerate there.
pub fn map(x: &Coords, at: [f64; 2]) -> Option<Mapped> {
    let (n, dn) = shape(at);
    let j = super::jacobian(x, &dn); // j[a][b] = ∂x_a/∂ξ_b
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if det.is_nan() || det <= 0.0 {
        return None;
    }
    // ∇_x N = J⁻ᵀ ∇_ξ N.
    let grad = dn.map(|d| {
        [
            (j[1][1] * d[0] - j[1][0] * d[1]) / det,
            (-j[0][1] * d[0] + j[0][0] * d[1]) / det,
        ]
    });
    let r = x.iter().zip(&n).map(|(xi, ni)| xi[0] * ni).sum();
    Some(Mapped { n, grad, r, det })
}

/// Strain rows of node i: B_i = [[N,r 0] [0 N,z] [N/r 0] [N,z N,r]], as columns (u_r, u_z).
fn b_rows(m: &Mapped, i: usize) -> [[f64; 2]; 4] {
    let [nr, nz] = m.grad[i];
    [[nr, 0.0], [0.0, nz], [m.n[i] / m.r, 0.0], [nz, nr]]
}

/// Adds `ring` ∫ Bᵀ D B r dA over `rule` to the element matrix `k` ((6C)², row-major, DOFs
/// node-major), with D = λ_part m mᵀ + μ_part diag(2, 2, 2, 1, …) and B_i = `rows(m, i)`: S strains
/// (three normal, then engineering shears) by C displacement components of node i. `ring` is the
/// θ-integral of the mode's angular factors squared: 2π for n = 0, π for n = 1.
pub(crate) fn add_stiffness<const C: usize, const S: usize>(
    k: &mut [f64],
    x: &Coords,
    rule: &[Point],
    d: Lame,
    ring: f64,
    rows: impl Fn(&Mapped, usize) -> [[f64; C]; S],
) -> Option<()> {
    let size = 6 * C;
    for p in rule {
        let m = map(x, p.at)?;
        let scale = ring * m.r * m.det * p.weight;
        let b: [[[f64; C]; S]; 6] = std::array::from_fn(|i| rows(&m, i));
        for i in 0..6 {
            for a in 0..C {
                let col_i: [f64; S] = std::array::from_fn(|s| b[i][s][a]);
                let db = d.stress_of(col_i);
                for (j, b_j) in b.iter().enumerate() {
                    for c in 0..C {
                        let v: f64 = (0..S).map(|s| b_j[s][c] * db[s]).sum();
                        k[(C * i + a) * size + C * j + c] += scale * v;
                    }
                }
            }
        }
    }
    Some(())
}

/// Integrates an element matrix of any Fourier mode: everything with the 6-point rule, or the
/// volumetric (λ) part with the 3-point rule only ([`Integration::SelectiveReduced`]).
pub(crate) fn integrate<const C: usize, const S: usize>(
    x: &Coords,
    lame: Lame,
    integration: Integration,
    ring: f64,
    rows: impl Fn(&Mapped, usize) -> [[f64; C]; S] + Copy,
) -> Option<Vec<f64>> {
    let mut k = vec![0.0; 36 * C * C];
    match integration {
        Integration::Full => add_stiffness(&mut k, x, &quadrature::triangle_degree4(), lame, ring, rows)?,
        Integration::SelectiveReduced => {
            let shear = Lame { lambda: 0.0, ..lame };
            let volumetric = Lame { mu: 0.0, ..lame };
            add_stiffness(&mut k, x, &quadrature::triangle_degree4(), shear, ring, rows)?;
            add_stiffness(&mut k, x, &quadrature::triangle_degree2(), volumetric, ring, rows)?;
        }
    }
    Some(k)
}

/// The 12 × 12 element stiffness, row-major (DOFs u_r0, u_z0, u_r1, …); `None` if the element
/// is inverted.
pub fn stiffness(x: &Coords, lame: Lame, integration: Integration) -> Option<Vec<f64>> {
    integrate(x, lame, integration, 2.0 * PI, b_rows)
}

/// The axisymmetric mode n = 0: u_r and u_z per node.
pub struct Axisymmetric;

impl super::Mode for Axisymmetric {
    const COMPONENTS: usize = 2;

    fn stiffness(x: &Coords, lame: Lame, integration: Integration) -> Option<Vec<f64>> {
        stiffness(x, lame, integration)
    }
}

/// Strain at reference point `at` from nodal displacements `u`. On the axis (r = 0) the hoop
/// strain u_r/r takes its limit ∂u_r/∂r, since u_r = 0 there.
pub fn strain(x: &Coords, u: &[[f64; 2]; 6], at: [f64; 2]) -> Option<[f64; 4]> {
    let m = map(x, at)?;
    let mut e = [0.0; 4];
    let mut ur = 0.0;
    for ((&[nr, nz], &n), ui) in m.grad.iter().zip(&m.n).zip(u) {
        e[0] += nr * ui[0];
        e[1] += nz * ui[1];
        e[3] += nz * ui[0] + nr * ui[1];
        ur += n * ui[0];
    }
    let size = x.iter().map(|p| p[0].abs() + p[1].abs()).fold(0.0, f64::max);
    e[2] = if m.r > 1e-12 * size { ur / m.r } else { e[0] };
    Some(e)
}

/// Reference coordinates of the six nodes.
pub const NODES: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];

/// Ring weights w_i = 2π ∫ N_i r ds of a quadratic edge with nodes (start, middle, end):
/// the force a unit pressure puts on each node. Zero for a node on the axis.
pub fn edge_weights(start: [f64; 2], middle: [f64; 2], end: [f64; 2]) -> [f64; 3] {
    let mut w = [0.0; 3];
    for p in quadrature::line_gauss3() {
        let s = p.at[0];
        let n = [
            (1.0 - s) * (1.0 - 2.0 * s),
            4.0 * s * (1.0 - s),
            s * (2.0 * s - 1.0),
        ];
        let dn = [4.0 * s - 3.0, 4.0 - 8.0 * s, 4.0 * s - 1.0];
        let pts = [start, middle, end];
        let point = |f: &[f64; 3], a: usize| (0..3).map(|i| f[i] * pts[i][a]).sum::<f64>();
        let r = point(&n, 0);
        let ds = point(&dn, 0).hypot(point(&dn, 1));
        for i in 0..3 {
            w[i] += 2.0 * PI * n[i] * r * ds * p.weight;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_functions_are_a_partition_of_unity_and_interpolate() {
        for (i, at) in NODES.iter().enumerate() {
            let (n, dn) = shape(*at);
            for (j, nj) in n.iter().enumerate() {
                assert!((nj - f64::from(u8::from(i == j))).abs() < 1e-15);
            }
            let sum: [f64; 2] = [0, 1].map(|a| dn.iter().map(|d| d[a]).sum());
            assert!(sum[0].abs() < 1e-14 && sum[1].abs() < 1e-14);
        }
    }

    #[test]
    fn edge_weights_sum_to_the_ring_area() {
        // A straight edge from r = 1 to r = 3 at z = 0: 2π ∫ r dr = 8π.
        let w = edge_weights([1.0, 0.0], [2.0, 0.0], [3.0, 0.0]);
        assert!((w.iter().sum::<f64>() - 8.0 * PI).abs() < 1e-12);
        assert!(edge_weights([0.0, 0.0], [1.0, 0.0], [2.0, 0.0])[0].abs() < 1e-15);
    }
}
