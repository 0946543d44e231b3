//! The 6-node triangular face of a 10-node tetrahedron, and the contact rule on it.
//!
//! Node order (gmsh's type 9): corners 0, 1, 2, then the midside nodes of edges 0–1, 1–2, 2–0;
//! the shape functions N_k are those of [`super::tri6::shape`], the geometry is the quadratic
//! (curved) face x(ξ, η) = Σ N_k x_k.
//!
//! Why a rule of its own: the consistent load of a uniform pressure, p ∫ N_k dA, is zero at the
//! corners of a flat 6-node triangle (∫ N_corner = 0) and can be negative for a pressure that
//! rises away from a corner (∫ N₁ L₂ dA = −A/60). Node-wise contact conditions (a force ≥ 0 per
//! node) on those forces would open corner nodes inside the contact and give no pressure there.
//!
//! The rule: the contact pressure is interpolated piecewise linearly on the face's
//! sub-triangulation into four 3-node triangles (corner–midside–midside three times and the
//! middle one), p_h = Σ_j p_j φ_j, φ_j the hat of node j on the sub-triangles (the dual-mortar
//! choice of Popp, Gee & Wall 2010 for quadratic faces). Its work on the displacement gives
//!
//! ```text
//! nodal forces f_k = Σ_j D_jk p_j,   weighted gaps g̃_j = Σ_k D_jk g_k,   D_jk = ∫ φ_j N_k dA
//! ```
//! and since Σ_k N_k = 1 the row sums w_j = Σ_k D_jk = ∫ φ_j dA are positive (A/12 at a corner,
//! A/4 at a midside node of a flat face). Scaling rows by w_j gives the averaging operator
//! A_jk = D_jk / w_j (rows summing to one): nodal force-like multipliers λ_j = w_j p_j act on the
//! body as Aᵀ λ and see the averaged gap (A g)_j; a uniform pressure (all p_j = p) gives exactly
//! the consistent load p ∫ N_k dA, so a uniform-pressure state is reproduced node by node
//! (the patch test in `tests/fem3d_surface.rs`).

use super::tri6;
use spherecontact_model::quadrature;

/// Node coordinates of one face [m].
pub type Coords = [[f64; 3]; 6];

/// The four sub-triangles, as local node indices, each counter-clockwise in (ξ, η).
pub const SUB_TRIANGLES: [[usize; 3]; 4] = [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]];

/// The surface point and its area element |∂x/∂ξ × ∂x/∂η| at reference point `at`.
pub fn map(x: &Coords, at: [f64; 2]) -> ([f64; 3], f64) {
    let (n, dn) = tri6::shape(at);
    let mut point = [0.0; 3];
    let (mut dxi, mut deta) = ([0.0; 3], [0.0; 3]);
    for k in 0..6 {
        for a in 0..3 {
            point[a] += n[k] * x[k][a];
            dxi[a] += dn[k][0] * x[k][a];
            deta[a] += dn[k][1] * x[k][a];
        }
    }
    let cross = [
        dxi[1] * deta[2] - dxi[2] * deta[1],
        dxi[2] * deta[0] - dxi[0] * deta[2],
        dxi[0] * deta[1] - dxi[1] * deta[0],
    ];
    (
        point,
        (cross[0].powi(2) + cross[1].powi(2) + cross[2].powi(2)).sqrt(),
    )
}

/// The coupling D_jk = ∫ φ_j N_k dA of one face (row j: the sub-triangulation hat of node j;
/// column k: the quadratic shape function of node k). Integrated with the 6-point degree-4 rule
/// on each sub-triangle: exact on a flat face (degree 3), to the rule's accuracy on a curved one.
pub fn coupling(x: &Coords) -> [[f64; 6]; 6] {
    let mut d = [[0.0; 6]; 6];
    for sub in SUB_TRIANGLES {
        let v = sub.map(|k| tri6::NODES[k]);
        for p in quadrature::triangle_degree4() {
            // The sub-triangle's own barycentric coordinates are the values of its three hats.
            let hat = [1.0 - p.at[0] - p.at[1], p.at[0], p.at[1]];
            let at = [0, 1].map(|a| (0..3).map(|i| hat[i] * v[i][a]).sum::<f64>());
            let (_, area) = map(x, at);
            // Each sub-triangle covers a quarter of the reference triangle.
            let w = 0.25 * p.weight * area;
            let (n, _) = tri6::shape(at);
            for (i, &j) in sub.iter().enumerate() {
                for k in 0..6 {
                    d[j][k] += w * hat[i] * n[k];
                }
            }
        }
    }
    d
}

/// The coupling D_jk = ∫ L_j N_k dA of one face for multipliers at its corners only (row j:
/// the linear hat L_j of corner j on the whole face; column k: the quadratic shape function of
/// node k). Rows sum to ∫ L_j dA = A/3 on a flat face; a uniform pressure Σ_j p L_j = p gives the
/// consistent load p ∫ N_k dA exactly. Integrated like [`coupling`] (degree 3 on a flat face).
pub fn corner_coupling(x: &Coords) -> [[f64; 6]; 3] {
    let mut d = [[0.0; 6]; 3];
    for p in quadrature::triangle_degree4() {
        let hat = [1.0 - p.at[0] - p.at[1], p.at[0], p.at[1]];
        let (_, area) = map(x, p.at);
        let (n, _) = tri6::shape(p.at);
        for (j, row) in d.iter_mut().enumerate() {
            for k in 0..6 {
                row[k] += p.weight * area * hat[j] * n[k];
            }
        }
    }
    d
}

/// The area of a face.
pub fn area(x: &Coords) -> f64 {
    quadrature::triangle_degree4()
        .iter()
        .map(|p| p.weight * map(x, p.at).1)
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat face in the plane z = 0 with straight edges (midsides at the middles).
    fn flat() -> Coords {
        let c = [[0.0, 0.0, 0.0], [2.0, 0.3, 0.0], [0.4, 1.5, 0.0]];
        let mid = |i: usize, j: usize| std::array::from_fn(|a| 0.5 * (c[i][a] + c[j][a]));
        [c[0], c[1], c[2], mid(0, 1), mid(1, 2), mid(2, 0)]
    }

    #[test]
    fn the_sub_triangulation_weights_are_positive_where_the_consistent_ones_vanish() {
        let x = flat();
        let a = area(&x);
        assert!((a - 0.5 * (2.0 * 1.5 - 0.3 * 0.4)).abs() < 1e-14);
        let d = coupling(&x);
        for (j, row) in d.iter().enumerate() {
            let w: f64 = row.iter().sum();
            let expected = if j < 3 { a / 12.0 } else { a / 4.0 };
            assert!((w - expected).abs() < 1e-14, "node {j}: ∫φ = {w}");
            let consistent: f64 = d.iter().map(|r| r[j]).sum();
            let expected = if j < 3 { 0.0 } else { a / 3.0 };
            assert!(
                (consistent - expected).abs() < 1e-14,
                "node {j}: ∫N = {consistent}"
            );
        }
    }

    #[test]
    fn the_corner_hats_give_the_consistent_load_of_a_uniform_pressure() {
        let x = flat();
        let a = area(&x);
        let d = corner_coupling(&x);
        for (j, row) in d.iter().enumerate() {
            let w: f64 = row.iter().sum();
            assert!((w - a / 3.0).abs() < 1e-14, "corner {j}: ∫L = {w}");
        }
        for k in 0..6 {
            let consistent: f64 = d.iter().map(|r| r[k]).sum();
            let expected = if k < 3 { 0.0 } else { a / 3.0 };
            assert!(
                (consistent - expected).abs() < 1e-14,
                "node {k}: ∫N = {consistent}"
            );
        }
    }

    #[test]
    fn a_curved_face_has_more_area_than_its_chords() {
        let mut x = flat();
        x[3][2] = 0.2; // lift the midside node of edge 0–1
        let d = coupling(&x);
        let total: f64 = d.iter().flatten().sum();
        // Two quadratures (24 and 6 points) of the same non-polynomial area element.
        assert!(
            (total - area(&x)).abs() < 1e-4 * area(&x),
            "{total} against {}",
            area(&x)
        );
        assert!(area(&x) > area(&flat()));
        assert!(d.iter().all(|row| row.iter().sum::<f64>() > 0.0));
    }
}
