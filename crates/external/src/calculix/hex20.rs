//! The geometry of CalculiX's 20-node brick (C3D20, C3D20R) and of its 8-node faces: node order,
//! serendipity shape functions, the Jacobian at the Gauss points, volume and face area, and the
//! permutation from gmsh's node order.
//!
//! Node order (CalculiX's, Abaqus's): corners 1–4 on the face ζ = −1, counter-clockwise about
//! +ζ, 5–8 above them on ζ = +1; midside nodes 9–12 on the edges 1–2, 2–3, 3–4, 4–1, 13–16
//! on 5–6, 6–7, 7–8, 8–5, 17–20 on 1–5, 2–6, 3–7, 4–8 (the CalculiX manual, "C3D20"). gmsh
//! numbers the corners alike but the midside nodes edge by edge from the lower corner: 0–1, 0–3,
//! 0–4, 1–2, 1–5, 2–3, 2–6, 3–7, 4–5, 4–7, 5–6, 6–7 (gmsh's reference manual, "Node ordering",
//! 20-node hexahedron); [`GMSH_TO_CCX`] maps one to the other and the tests derive it again from
//! the reference coordinates. The 8-node quadrangle has the same order in both (corners, then
//! the edges 1–2, 2–3, 3–4, 4–1).

/// Corners and edges of the brick in CalculiX's order, as reference coordinates (ξ, η, ζ).
pub const NODES: [[f64; 3]; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, -1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// CalculiX's node k is gmsh's node `GMSH_TO_CCX[k]` (0-based).
pub const GMSH_TO_CCX: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
];

/// The brick's faces (CalculiX's S1–S6) as 8-node quadrangles of its nodes, corners then edges,
/// in the manual's order (1-2-3-4, 5-8-7-6, 1-5-6-2, 2-6-7-3, 3-7-8-4, 4-8-5-1: their
/// right-hand normal points into the element).
pub const FACES: [[usize; 8]; 6] = [
    [0, 1, 2, 3, 8, 9, 10, 11],
    [4, 7, 6, 5, 15, 14, 13, 12],
    [0, 4, 5, 1, 16, 12, 17, 8],
    [1, 5, 6, 2, 17, 13, 18, 9],
    [2, 6, 7, 3, 18, 14, 19, 10],
    [3, 7, 4, 0, 19, 15, 16, 11],
];

/// The 8-node quadrangle's nodes as reference coordinates (ξ, η).
pub const QUAD_NODES: [[f64; 2]; 8] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];

/// The 3-point Gauss rule on [−1, 1]: points and weights.
const GAUSS3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

/// The serendipity shape function of the node at `node` (coordinates ±1 or 0, at most one 0)
/// and its gradient at `x`, in D = 2 or 3 dimensions.
pub fn serendipity<const D: usize>(node: [f64; D], x: [f64; D]) -> (f64, [f64; D]) {
    let factor = |j: usize| 1.0 + x[j] * node[j];
    let product_without =
        |skip: &[usize]| -> f64 { (0..D).filter(|j| !skip.contains(j)).map(factor).product() };
    let mut gradient = [0.0; D];
    match (0..D).find(|&k| node[k] == 0.0) {
        None => {
            let scale = 0.5_f64.powi(D as i32);
            let sum = (0..D).map(|j| x[j] * node[j]).sum::<f64>() - (D as f64 - 1.0);
            let all = product_without(&[]);
            for (m, g) in gradient.iter_mut().enumerate() {
                *g = scale * node[m] * (product_without(&[m]) * sum + all);
            }
            (scale * all * sum, gradient)
        }
        Some(k) => {
            let scale = 0.5_f64.powi(D as i32 - 1);
            let bubble = 1.0 - x[k] * x[k];
            for (m, g) in gradient.iter_mut().enumerate() {
                *g = if m == k {
                    -2.0 * x[k] * scale * product_without(&[k])
                } else {
                    scale * bubble * node[m] * product_without(&[k, m])
                };
            }
            (scale * bubble * product_without(&[k]), gradient)
        }
    }
}

/// The reference gradients ∂N/∂ξ of the 20 shape functions at `xi`.
fn reference_gradients(xi: [f64; 3]) -> [[f64; 3]; 20] {
    NODES.map(|node| serendipity(node, xi).1)
}

/// The determinant of the brick's Jacobian ∂x/∂ξ at `xi` for nodes at `coords`.
pub fn jacobian(coords: &[[f64; 3]; 20], xi: [f64; 3]) -> f64 {
    let j = spherecontact_solvers::fem::element::jacobian(coords, &reference_gradients(xi));
    j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
        + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
}

/// The physical gradients ∂N/∂x of the 20 shape functions at `xi` and the Jacobian's
/// determinant; `None` where the brick is folded (det J ≤ 0).
pub fn gradients(coords: &[[f64; 3]; 20], xi: [f64; 3]) -> Option<([[f64; 3]; 20], f64)> {
    spherecontact_solvers::fem::element::physical_gradients(coords, &reference_gradients(xi))
}

/// The 8 Gauss points of the reduced rule (C3D20R's, 2 × 2 × 2 at ±1/√3) with their weights.
pub fn reduced_gauss_points() -> impl Iterator<Item = ([f64; 3], f64)> {
    let g = 1.0 / 3.0_f64.sqrt();
    (0..8).map(move |k| {
        (
            [k & 1, (k >> 1) & 1, (k >> 2) & 1].map(|bit| if bit == 0 { -g } else { g }),
            1.0,
        )
    })
}

/// The 27 Gauss points of the full rule (C3D20's) with their weights.
pub fn gauss_points() -> impl Iterator<Item = ([f64; 3], f64)> {
    GAUSS3.into_iter().flat_map(|(a, wa)| {
        GAUSS3
            .into_iter()
            .flat_map(move |(b, wb)| GAUSS3.into_iter().map(move |(c, wc)| ([a, b, c], wa * wb * wc)))
    })
}

/// The Jacobian's determinant at each of the 27 Gauss points.
pub fn jacobians(coords: &[[f64; 3]; 20]) -> impl Iterator<Item = f64> + '_ {
    gauss_points().map(|(xi, _)| jacobian(coords, xi))
}

/// The element's volume by the 27-point rule (exact for the brick's own polynomial map up to
/// the rule's degree: straight bricks exactly, curved ones to the rule's accuracy).
pub fn volume(coords: &[[f64; 3]; 20]) -> f64 {
    gauss_points().map(|(xi, w)| w * jacobian(coords, xi)).sum()
}

/// The surface element |∂x/∂ξ × ∂x/∂η| of an 8-node quadrangle at each point of the 3 × 3
/// rule, with the point and its weight.
fn quad_points(coords: &[[f64; 3]; 8]) -> impl Iterator<Item = ([f64; 2], f64)> + '_ {
    GAUSS3.into_iter().flat_map(move |(a, wa)| {
        GAUSS3.into_iter().map(move |(b, wb)| {
            let (mut ta, mut tb) = ([0.0; 3], [0.0; 3]);
            for (node, x) in QUAD_NODES.iter().zip(coords) {
                let (_, g) = serendipity(*node, [a, b]);
                for d in 0..3 {
                    ta[d] += x[d] * g[0];
                    tb[d] += x[d] * g[1];
                }
            }
            let n = [
                ta[1] * tb[2] - ta[2] * tb[1],
                ta[2] * tb[0] - ta[0] * tb[2],
                ta[0] * tb[1] - ta[1] * tb[0],
            ];
            ([a, b], wa * wb * n.iter().map(|v| v * v).sum::<f64>().sqrt())
        })
    })
}

/// The area of an 8-node quadrangle by the 3 × 3 rule.
pub fn quad_area(coords: &[[f64; 3]; 8]) -> f64 {
    quad_points(coords).map(|(_, da)| da).sum()
}

/// The integrals over an 8-node quadrangle of its four corners' bilinear hats
/// ¼ (1 ± ξ)(1 ± η) (3 × 3 rule): they sum to its area.
pub fn quad_corner_weights(coords: &[[f64; 3]; 8]) -> [f64; 4] {
    let mut weights = [0.0; 4];
    for ([a, b], da) in quad_points(coords) {
        for (w, [xa, xb]) in weights.iter_mut().zip(&QUAD_NODES[..4]) {
            *w += 0.25 * (1.0 + a * xa) * (1.0 + b * xb) * da;
        }
    }
    weights
}

/// The node permutation that mirrors the brick in the plane ξ = η (node k goes to the node at
/// (η, ξ, ζ)): it turns an inverted element (negative Jacobian) into a valid one.
pub fn mirror() -> [usize; 20] {
    std::array::from_fn(|k| {
        let [a, b, c] = NODES[k];
        NODES
            .iter()
            .position(|n| *n == [b, a, c])
            .expect("the reference brick is symmetric in ξ = η")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// gmsh's 20-node hexahedron, its nodes in gmsh's order (the reference manual's figure).
    const GMSH_NODES: [[f64; 3]; 20] = [
        [-1.0, -1.0, -1.0],
        [1.0, -1.0, -1.0],
        [1.0, 1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, 1.0],
        [0.0, -1.0, -1.0],
        [-1.0, 0.0, -1.0],
        [-1.0, -1.0, 0.0],
        [1.0, 0.0, -1.0],
        [1.0, -1.0, 0.0],
        [0.0, 1.0, -1.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [0.0, -1.0, 1.0],
        [-1.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
    ];

    #[test]
    fn the_permutation_is_derived_from_both_orders() {
        let derived: [usize; 20] =
            std::array::from_fn(|k| GMSH_NODES.iter().position(|n| *n == NODES[k]).unwrap());
        assert_eq!(derived, GMSH_TO_CCX);
        // CalculiX's midside nodes lie on the edges its manual names (1-based pairs).
        let edges = [
            (1, 2),
            (2, 3),
            (3, 4),
            (4, 1),
            (5, 6),
            (6, 7),
            (7, 8),
            (8, 5),
            (1, 5),
            (2, 6),
            (3, 7),
            (4, 8),
        ];
        for (k, (a, b)) in edges.into_iter().enumerate() {
            let mid: Vec<f64> = (0..3)
                .map(|d| 0.5 * (NODES[a - 1][d] + NODES[b - 1][d]))
                .collect();
            assert_eq!(NODES[8 + k].to_vec(), mid, "node {}", 9 + k);
        }
    }

    #[test]
    fn shape_functions_are_a_partition_of_unity_and_interpolate() {
        let x = [0.3, -0.7, 0.45];
        let (sum, grad) = NODES.iter().fold((0.0, [0.0; 3]), |(s, g), n| {
            let (v, d) = serendipity(*n, x);
            (s + v, [g[0] + d[0], g[1] + d[1], g[2] + d[2]])
        });
        assert!((sum - 1.0).abs() < 1e-14 && grad.iter().all(|g| g.abs() < 1e-14));
        for (i, ni) in NODES.iter().enumerate() {
            for (j, nj) in NODES.iter().enumerate() {
                let v = serendipity(*ni, *nj).0;
                assert!(
                    (v - f64::from(u8::from(i == j))).abs() < 1e-14,
                    "N{i} at node {j}: {v}"
                );
            }
        }
        // The gradient against central differences (2nd order: 1e-6 steps leave ~1e-10).
        for n in NODES {
            let g = serendipity(n, x).1;
            for d in 0..3 {
                let (mut a, mut b) = (x, x);
                a[d] += 1e-6;
                b[d] -= 1e-6;
                let fd = (serendipity(n, a).0 - serendipity(n, b).0) / 2e-6;
                assert!((fd - g[d]).abs() < 1e-8, "{n:?} d{d}: {fd} vs {}", g[d]);
            }
        }
    }

    #[test]
    fn a_box_has_its_volume_faces_and_a_constant_jacobian() {
        // The box [0, 2] × [0, 3] × [0, 5]: J = 1 · 1.5 · 2.5 everywhere.
        let coords = NODES.map(|[a, b, c]| [1.0 + a, 1.5 * (1.0 + b), 2.5 * (1.0 + c)]);
        assert!(jacobians(&coords).all(|j| (j - 3.75).abs() < 1e-12));
        assert!((volume(&coords) - 30.0).abs() < 1e-12);
        let areas: Vec<f64> = FACES.iter().map(|f| quad_area(&f.map(|n| coords[n]))).collect();
        for (area, exact) in areas.iter().zip([6.0, 6.0, 10.0, 15.0, 10.0, 15.0]) {
            assert!((area - exact).abs() < 1e-12, "{areas:?}");
        }
        // A rectangle's corner hats each integrate to a quarter of it.
        for (f, area) in FACES.iter().zip(&areas) {
            let w = quad_corner_weights(&f.map(|n| coords[n]));
            assert!(
                w.iter().all(|w| (w - area / 4.0).abs() < 1e-12),
                "{w:?} of {area}"
            );
        }
    }

    /// Requirement: the physical gradients make the brick's nodal forces under a uniform stress
    /// the resultants of the stress on its faces: the forces of a face's nodes sum to σ n times
    /// its area, on the full rule (C3D20's 27 points) and on the reduced one (C3D20R's 8), and
    /// all forces sum to zero. Reference: σ_xx · 15 on the faces x = 0, 2 of the box
    /// [0, 2] × [0, 3] × [0, 5] under u = (ε x, 0, 0), σ_yy · 10 on y = 0, 3; tolerance 1e-12 of
    /// the resultant, round-off (both rules integrate the box's gradients exactly).
    #[test]
    fn a_uniform_stress_loads_a_boxs_faces_with_their_resultants_on_both_rules() {
        use spherecontact_solvers::fem::element::internal_force::{internal_forces, GradientPoint};
        use spherecontact_solvers::fem::element::tri6::Lame;
        let coords = NODES.map(|[a, b, c]| [1.0 + a, 1.5 * (1.0 + b), 2.5 * (1.0 + c)]);
        let lame = Lame { lambda: 2.0, mu: 1.5 };
        let epsilon = 1e-3;
        let u: Vec<[f64; 3]> = coords.iter().map(|x| [epsilon * x[0], 0.0, 0.0]).collect();
        let (sxx, syy) = ((lame.lambda + 2.0 * lame.mu) * epsilon, lame.lambda * epsilon);
        for rule in [
            gauss_points().collect::<Vec<_>>(),
            reduced_gauss_points().collect(),
        ] {
            let points: Vec<GradientPoint> = rule
                .iter()
                .map(|&(xi, w)| {
                    let (grad, det) = gradients(&coords, xi).unwrap();
                    GradientPoint {
                        grad: grad.to_vec(),
                        volume: w * det,
                    }
                })
                .collect();
            let f = internal_forces(&points, &u, lame);
            let on = |axis: usize, side: f64, component: usize| -> f64 {
                (0..20)
                    .filter(|&k| NODES[k][axis] == side)
                    .map(|k| f[k][component])
                    .sum()
            };
            for (got, want) in [
                (on(0, 1.0, 0), 15.0 * sxx),
                (on(0, -1.0, 0), -15.0 * sxx),
                (on(1, 1.0, 1), 10.0 * syy),
                (on(1, -1.0, 1), -10.0 * syy),
            ] {
                assert!(
                    (got - want).abs() <= 1e-12 * want.abs(),
                    "{got} against {want} ({} points)",
                    rule.len()
                );
            }
            let total: f64 = f.iter().flatten().map(|v| v.abs()).fold(0.0, f64::max);
            let sum: [f64; 3] = std::array::from_fn(|a| f.iter().map(|fi| fi[a]).sum());
            assert!(sum.iter().all(|s| s.abs() <= 1e-12 * total), "{sum:?}");
        }
    }

    #[test]
    fn faces_are_the_manuals_and_the_mirror_turns_an_element_round() {
        let centroid = |f: [usize; 8]| -> Vec<f64> {
            (0..3)
                .map(|d| f.iter().map(|&n| NODES[n][d]).sum::<f64>() / 8.0)
                .collect()
        };
        for face in FACES {
            let [a, b, _, d] = [face[0], face[1], face[2], face[3]].map(|n| NODES[n]);
            let (u, v) = (
                [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                [d[0] - a[0], d[1] - a[1], d[2] - a[2]],
            );
            let normal = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let outward: f64 = centroid(face).iter().zip(normal).map(|(c, n)| c * n).sum();
            assert!(outward < 0.0, "{face:?}");
        }
        let mirrored = mirror().map(|k| NODES[k]);
        assert!(jacobians(&mirrored).all(|j| (j + 1.0).abs() < 1e-12));
        assert_eq!(mirror().map(|k| mirror()[k]), std::array::from_fn(|k| k));
    }
}
