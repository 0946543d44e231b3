//! Verification of the axisymmetric 6-node element: patch test and manufactured-solution
//! convergence with asserted rates. Run: `cargo test --test fem_element`.

use faer::Mat;
use spherecontact::fem::assembly::{assemble_with, Dofs};
use spherecontact::fem::element::tri6::{self, Integration, Lame};
use spherecontact::fem::factor::{Factor, Ordering};
use spherecontact::fem::mesh::meridian::Mesh;
use spherecontact::fem::quadrature;
use std::f64::consts::PI;

/// A uniform mesh of n × n squares, each cut into two 6-node triangles, on [r0, r0 + 1] × [0, 1].
/// With `distort`, interior corner nodes are shifted by up to 0.2 of a cell (a distorted patch).
fn square(n: usize, r0: f64, distort: bool) -> Mesh {
    let m = 2 * n + 1; // nodes per side, midsides included
    let h = 1.0 / (m - 1) as f64;
    let id = |i: usize, j: usize| i * m + j;
    let mut nodes: Vec<[f64; 2]> = (0..m * m)
        .map(|k| [r0 + (k / m) as f64 * h, (k % m) as f64 * h])
        .collect();
    if distort {
        for i in (2..m - 1).step_by(2) {
            for j in (2..m - 1).step_by(2) {
                let s = ((i * 7 + j * 13) % 5) as f64 / 4.0 - 0.5; // in [−0.5, 0.5]
                nodes[id(i, j)][0] += 0.4 * s * 2.0 * h;
                nodes[id(i, j)][1] -= 0.3 * s * 2.0 * h;
            }
        }
        // Midsides back to the middle of their (now straight) edges.
        for i in 0..m {
            for j in 0..m {
                if i % 2 == 1 || j % 2 == 1 {
                    let (a, b) = match (i % 2, j % 2) {
                        (1, 0) => (id(i - 1, j), id(i + 1, j)),
                        (0, 1) => (id(i, j - 1), id(i, j + 1)),
                        _ => (id(i - 1, j + 1), id(i + 1, j - 1)),
                    };
                    nodes[id(i, j)] = [
                        0.5 * (nodes[a][0] + nodes[b][0]),
                        0.5 * (nodes[a][1] + nodes[b][1]),
                    ];
                }
            }
        }
    }
    let mut triangles = Vec::new();
    for i in (0..m - 1).step_by(2) {
        for j in (0..m - 1).step_by(2) {
            let (a, b, c, d) = (id(i, j), id(i + 2, j), id(i + 2, j + 2), id(i, j + 2));
            let centre = id(i + 1, j + 1);
            triangles.push([a, b, d, id(i + 1, j), centre, id(i, j + 1)]);
            triangles.push([b, c, d, id(i + 2, j + 1), id(i + 1, j + 2), centre]);
        }
    }
    Mesh {
        nodes,
        triangles,
        ..Mesh::default()
    }
}

fn on_boundary(x: [f64; 2], r0: f64) -> bool {
    let eps = 1e-12;
    (r0 > 0.0 && x[0] < r0 + eps) || x[0] > r0 + 1.0 - eps || x[1] < eps || x[1] > 1.0 - eps
}

/// Solves K u = f with u = `exact` on the boundary (and u_r = 0 on the axis when r0 = 0);
/// `force` is the body force. Returns nodal displacements.
fn solve(
    mesh: &Mesh,
    lame: Lame,
    r0: f64,
    exact: &dyn Fn([f64; 2]) -> [f64; 2],
    force: &dyn Fn([f64; 2]) -> [f64; 2],
) -> Vec<[f64; 2]> {
    let n = mesh.nodes.len();
    let mut fixed = vec![false; 2 * n];
    for (k, &x) in mesh.nodes.iter().enumerate() {
        if on_boundary(x, r0) {
            fixed[2 * k] = true;
            fixed[2 * k + 1] = true;
        }
        if x[0] == 0.0 {
            fixed[2 * k] = true;
        }
    }
    let dofs = Dofs::from_fixed(&fixed);
    let system = assemble_with(mesh, lame, Integration::Full, dofs.clone()).unwrap();
    // u = û + v: û the nodal interpolant of the exact field, v = 0 on fixed DOFs, K_ff v = f − K û.
    let lifted: Vec<[f64; 2]> = mesh.nodes.iter().map(|&x| exact(x)).collect();
    let mut rhs = Mat::<f64>::zeros(dofs.count(), 1);
    for t in &mesh.triangles {
        let x = t.map(|k| mesh.nodes[k]);
        let k = tri6::stiffness(&x, lame, Integration::Full).unwrap();
        let ue: Vec<f64> = t.iter().flat_map(|&k| lifted[k]).collect();
        for p in quadrature::triangle_degree4() {
            let m = tri6::map(&x, p.at).unwrap();
            let point = [0, 1].map(|a| (0..6).map(|i| m.n[i] * x[i][a]).sum::<f64>());
            let f = force(point);
            for (&node, &n) in t.iter().zip(&m.n) {
                for (a, &f_a) in f.iter().enumerate() {
                    if let Some(d) = dofs.free(2 * node + a) {
                        rhs[(d, 0)] += 2.0 * PI * n * f_a * m.r * m.det * p.weight;
                    }
                }
            }
        }
        for a in 0..12 {
            if let Some(d) = dofs.free(2 * t[a / 2] + a % 2) {
                rhs[(d, 0)] -= (0..12).map(|b| k[a][b] * ue[b]).sum::<f64>();
            }
        }
    }
    Factor::new(&system.stiffness, Ordering::Amd)
        .unwrap()
        .solve_in_place(rhs.as_mut());
    (0..n)
        .map(|k| [0, 1].map(|a| lifted[k][a] + dofs.free(2 * k + a).map_or(0.0, |d| rhs[(d, 0)])))
        .collect()
}

/// L2 and energy-norm errors against the exact field and its strain.
fn errors(
    mesh: &Mesh,
    lame: Lame,
    u: &[[f64; 2]],
    exact: &dyn Fn([f64; 2]) -> [f64; 2],
    strain: &dyn Fn([f64; 2]) -> [f64; 4],
) -> (f64, f64) {
    let (mut l2, mut energy) = (0.0, 0.0);
    for t in &mesh.triangles {
        let x = t.map(|k| mesh.nodes[k]);
        let ue = t.map(|k| u[k]);
        for p in quadrature::triangle_degree4() {
            let m = tri6::map(&x, p.at).unwrap();
            let point = [0, 1].map(|a| (0..6).map(|i| m.n[i] * x[i][a]).sum::<f64>());
            let uh = [0, 1].map(|a| (0..6).map(|i| m.n[i] * ue[i][a]).sum::<f64>());
            let ex = exact(point);
            let w = 2.0 * PI * m.r * m.det * p.weight;
            l2 += w * ((uh[0] - ex[0]).powi(2) + (uh[1] - ex[1]).powi(2));
            let eh = tri6::strain(&x, &ue, p.at).unwrap();
            let e = strain(point);
            let de: [f64; 4] = std::array::from_fn(|k| eh[k] - e[k]);
            let ds = lame.stress(de);
            energy += w * (0..4).map(|k| de[k] * ds[k]).sum::<f64>();
        }
    }
    (l2.sqrt(), energy.sqrt())
}

fn lame() -> Lame {
    Lame { lambda: 1.5, mu: 1.0 }
}

#[test]
fn patch_test_reproduces_a_linear_field_exactly() {
    // u = (a r, b z + c): constant strain (a, b, a, 0), σ_rr = σ_θθ, so div σ = 0 with no body
    // force. A distorted patch of straight-sided elements must reproduce it to round-off.
    let exact = |x: [f64; 2]| [2e-3 * x[0], -3e-3 * x[1] + 1e-3];
    for r0 in [0.0, 0.5] {
        let mesh = square(3, r0, true);
        let u = solve(&mesh, lame(), r0, &exact, &|_| [0.0, 0.0]);
        for (x, uh) in mesh.nodes.iter().zip(&u) {
            let e = exact(*x);
            assert!(
                (uh[0] - e[0]).abs() < 1e-13 && (uh[1] - e[1]).abs() < 1e-13,
                "r0 {r0}: {x:?}"
            );
        }
    }
}

#[test]
fn manufactured_solution_converges_at_the_optimal_rates() {
    // u_r = r z², u_z = r² z (u_r = 0 on the axis). Strain (z², r², z², 4rz); with
    // tr ε = 2z² + r²: σ_rr = σ_θθ = λ tr + 2μ z², σ_zz = λ tr + 2μ r², τ = 4μ r z, and the body
    // force f = −div σ is f_r = −(∂σ_rr/∂r + ∂τ/∂z + (σ_rr − σ_θθ)/r) = −(2λ + 4μ) r,
    // f_z = −(∂τ/∂r + ∂σ_zz/∂z + τ/r) = −(4λ + 8μ) z.
    let l = lame();
    let exact = |x: [f64; 2]| [x[0] * x[1] * x[1], x[0] * x[0] * x[1]];
    let strain = |x: [f64; 2]| [x[1] * x[1], x[0] * x[0], x[1] * x[1], 4.0 * x[0] * x[1]];
    let force = move |x: [f64; 2]| {
        [
            -(2.0 * l.lambda + 4.0 * l.mu) * x[0],
            -(4.0 * l.lambda + 8.0 * l.mu) * x[1],
        ]
    };
    let results: Vec<(f64, f64)> = [4, 8, 16]
        .iter()
        .map(|&n| {
            let mesh = square(n, 0.0, false);
            let u = solve(&mesh, l, 0.0, &exact, &force);
            errors(&mesh, l, &u, &exact, &strain)
        })
        .collect();
    for w in results.windows(2) {
        let rate_l2 = (w[0].0 / w[1].0).log2();
        let rate_energy = (w[0].1 / w[1].1).log2();
        // Quadratic elements: O(h³) in L2 and O(h²) in energy (Ciarlet 1978, Thm 3.2.2); the
        // margin 0.2 covers the pre-asymptotic range of these coarse meshes.
        assert!(rate_l2 > 2.8, "L2 rate {rate_l2} ({results:?})");
        assert!(rate_energy > 1.8, "energy rate {rate_energy} ({results:?})");
        println!("rates: L2 {rate_l2:.3}, energy {rate_energy:.3}");
    }
}
