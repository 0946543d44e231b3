//! The slave surface of `kratos-3d` read back: the candidate faces' nodes on sphere 1 (their MDPA
//! ids, points and weights) and the faces as the triangles of fem-3d's surface-field layout.
//!
//! Weights ω_j = ∫ L_j dA, L_j node j's linear hat on the faces (fem-3d's contact rule, the one
//! [`crate::surface3d`] measures with): on a triangle a third of its area at each corner
//! (exact); on a 4-node quadrangle the bilinear shape function's integral over the bilinear
//! surface by the 2 × 2 Gauss rule (exact on a planar quadrangle, whose area element is then
//! linear in ξ and η; on the slightly warped faces of the sphere a rule of the order of Kratos'
//! own mortar integration). The quadrangles are split along their diagonal 0–2 into two triangles
//! for the surface-field layout (p varies linearly on each: the layout's rule).

use super::linear::LinearBody;
use super::results::SlaveNodes;
use super::vector::{cross, dot, sub};

/// The 2-point Gauss abscissae on [−1, 1] (weights 1).
const GAUSS2: [f64; 2] = [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8];
/// The quadrangle's corners' reference coordinates (ξ, η).
const QUAD: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// ∫ N_j dA at each corner of the bilinear quadrangle `p` (2 × 2 Gauss).
pub fn quad_weights(p: &[[f64; 3]; 4]) -> [f64; 4] {
    let mut weights = [0.0; 4];
    for xi in GAUSS2 {
        for eta in GAUSS2 {
            let (mut dxi, mut deta) = ([0.0; 3], [0.0; 3]);
            for (c, x) in QUAD.iter().zip(p) {
                let (a, b) = (c[0] * (1.0 + c[1] * eta) / 4.0, c[1] * (1.0 + c[0] * xi) / 4.0);
                for i in 0..3 {
                    dxi[i] += a * x[i];
                    deta[i] += b * x[i];
                }
            }
            let n = cross(dxi, deta);
            let area = dot(n, n).sqrt();
            for (w, c) in weights.iter_mut().zip(&QUAD) {
                *w += area * (1.0 + c[0] * xi) * (1.0 + c[1] * eta) / 4.0;
            }
        }
    }
    weights
}

/// ∫ L_j dA at each corner of the triangle `p`: a third of its area.
fn triangle_weights(p: &[[f64; 3]; 3]) -> [f64; 3] {
    let n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    [0.5 * dot(n, n).sqrt() / 3.0; 3]
}

/// The corners' weights of one face (3 or 4 nodes).
fn face_weights(points: &[[f64; 3]]) -> Vec<f64> {
    match points {
        [a, b, c] => triangle_weights(&[*a, *b, *c]).to_vec(),
        [a, b, c, d] => quad_weights(&[*a, *b, *c, *d]).to_vec(),
        _ => vec![0.0; points.len()],
    }
}

/// A face as triangles: itself, or a quadrangle's two halves along its diagonal 0–2.
fn triangles_of(face: &[usize]) -> Vec<[usize; 3]> {
    match face {
        [a, b, c] => vec![[*a, *b, *c]],
        [a, b, c, d] => vec![[*a, *b, *c], [*a, *c, *d]],
        _ => Vec::new(),
    }
}

/// The slave nodes of the candidate `faces` of `body` (MDPA ids, points, weights) and the faces
/// as triangles of those nodes' indices.
pub fn slave_nodes(body: &LinearBody, faces: &[Vec<usize>]) -> (SlaveNodes, Vec<[usize; 3]>) {
    let skin = LinearBody::nodes_of(faces);
    let mut weights = vec![0.0; skin.len()];
    let local = |n: usize| skin.binary_search(&n).unwrap_or(0);
    let mut triangles = Vec::new();
    for face in faces {
        let points: Vec<[f64; 3]> = face.iter().map(|&n| body.nodes[n]).collect();
        for (&n, w) in face.iter().zip(face_weights(&points)) {
            weights[local(n)] += w;
        }
        let face: Vec<usize> = face.iter().map(|&n| local(n)).collect();
        triangles.extend(triangles_of(&face));
    }
    let slaves = SlaveNodes {
        ids: skin.iter().map(|n| n + 1).collect(),
        points: skin.iter().map(|&n| body.nodes[n]).collect(),
        weights,
    };
    (slaves, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requirement: a planar quadrangle's corner weights are its shape functions' integrals
    /// (exact by hand below) and the split gives its two triangles. Tolerance 1e-15: round-off of
    /// a few operations on numbers of order 1 (the 2 × 2 rule is exact on a planar quadrangle).
    #[test]
    fn a_quadrangles_weights_are_its_shape_functions_integrals_and_it_splits_in_two() {
        // A unit square: a quarter of its area at each corner.
        let square = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        for w in quad_weights(&square) {
            assert!((w - 0.25).abs() < 1e-15, "{w}");
        }
        // A trapezium with sides 2 (y = 0) and 1 (y = 1), area 3/2: x_ξ = (3 − η)/4, y_η = 1/2,
        // dA = (3 − η)/8 dξ dη; ∫ N_0 dA = ∫∫ (1 − ξ)(1 − η)/4 · (3 − η)/8 = 5/12 (corner 1
        // alike), ∫ N_2 dA = ∫∫ (1 + ξ)(1 + η)/4 · (3 − η)/8 = 1/3 (corner 3 alike).
        let trapezium = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.5, 1.0, 0.0], [0.5, 1.0, 0.0]];
        let w = quad_weights(&trapezium);
        let exact = [5.0 / 12.0, 5.0 / 12.0, 1.0 / 3.0, 1.0 / 3.0];
        for (a, b) in w.iter().zip(exact) {
            assert!((a - b).abs() < 1e-15, "{w:?}");
        }
        assert_eq!(triangles_of(&[4, 5, 6, 7]), vec![[4, 5, 6], [4, 6, 7]]);
        assert_eq!(triangles_of(&[4, 5, 6]), vec![[4, 5, 6]]);
    }
}
