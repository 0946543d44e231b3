//! Verification of the 10-node tetrahedron: patch test, and a manufactured 3D solution
//! converging at the asserted rates. Run: `cargo test --test suite fem3d_element::`.

use crate::solid_common;

use faer::Mat;
use spherecontact::fem::assembly::Dofs;
use spherecontact::fem::element::tet10;
use spherecontact::fem::element::tri6::Lame;
use spherecontact::fem::factor::{Factor, Ordering};
use spherecontact::fem::mesh::solid::SolidMesh;
use spherecontact::fem::solid3d::system;
use spherecontact::quadrature;

type Field = dyn Fn([f64; 3]) -> [f64; 3];

fn lame() -> Lame {
    Lame { lambda: 1.5, mu: 1.0 }
}

fn on_boundary(x: [f64; 3]) -> bool {
    x.iter().any(|&c| c.abs() < 1e-12 || (c - 1.0).abs() < 1e-12)
}

/// Solves K u = f on the unit cube with u = `exact` on the whole boundary; `force` is the body
/// force. Returns nodal displacements.
fn solve(mesh: &SolidMesh, exact: &Field, force: &Field) -> Vec<[f64; 3]> {
    let fixed: Vec<bool> = mesh.nodes.iter().flat_map(|&x| [on_boundary(x); 3]).collect();
    let dofs = Dofs::from_fixed(&fixed);
    let sys = system::assemble(mesh, lame(), dofs.clone()).unwrap();
    // u = û + v: û the nodal interpolant of the exact field, v = 0 on the boundary,
    // K_ff v = f − K û.
    let lifted: Vec<[f64; 3]> = mesh.nodes.iter().map(|&x| exact(x)).collect();
    let mut rhs = Mat::<f64>::zeros(dofs.count(), 1);
    for (e, t) in mesh.tetrahedra.iter().enumerate() {
        let x = mesh.coords(e);
        for p in quadrature::tetrahedron_degree5() {
            let m = tet10::map(&x, p.at).unwrap();
            let f = force(m.point(&x));
            for (&node, &n) in t.iter().zip(&m.n) {
                for (a, f_a) in f.iter().enumerate() {
                    if let Some(d) = dofs.free(3 * node + a) {
                        rhs[(d, 0)] += n * f_a * m.det * p.weight;
                    }
                }
            }
        }
        let k = tet10::stiffness(&x, lame()).unwrap();
        let ue: Vec<f64> = t.iter().flat_map(|&n| lifted[n]).collect();
        for (p, row) in k.iter().enumerate() {
            if let Some(d) = dofs.free(3 * t[p / 3] + p % 3) {
                rhs[(d, 0)] -= row.iter().zip(&ue).map(|(a, b)| a * b).sum::<f64>();
            }
        }
    }
    Factor::new(&sys.stiffness, Ordering::Amd)
        .unwrap()
        .solve_in_place(rhs.as_mut());
    (0..mesh.nodes.len())
        .map(|n| std::array::from_fn(|a| lifted[n][a] + dofs.free(3 * n + a).map_or(0.0, |d| rhs[(d, 0)])))
        .collect()
}

/// L2 and energy-norm errors against the exact field and its strain.
fn errors(
    mesh: &SolidMesh,
    u: &[[f64; 3]],
    exact: &Field,
    strain: &dyn Fn([f64; 3]) -> [f64; 6],
) -> (f64, f64) {
    let (mut l2, mut energy) = (0.0, 0.0);
    for (e, t) in mesh.tetrahedra.iter().enumerate() {
        let x = mesh.coords(e);
        let ue = t.map(|n| u[n]);
        for p in quadrature::tetrahedron_degree5() {
            let m = tet10::map(&x, p.at).unwrap();
            let point = m.point(&x);
            let uh: [f64; 3] = std::array::from_fn(|a| (0..10).map(|i| m.n[i] * ue[i][a]).sum());
            let w = m.det * p.weight;
            let ex = exact(point);
            l2 += w * (0..3).map(|a| (uh[a] - ex[a]).powi(2)).sum::<f64>();
            let eh = tet10::strain(&x, &ue, p.at).unwrap();
            let ee = strain(point);
            let de: [f64; 6] = std::array::from_fn(|k| eh[k] - ee[k]);
            let ds = tet10::stress(lame(), de);
            energy += w * (0..6).map(|k| de[k] * ds[k]).sum::<f64>();
        }
    }
    (l2.sqrt(), energy.sqrt())
}

#[test]
fn patch_test_reproduces_a_linear_field_exactly() {
    // A general linear field: constant strain, div σ = 0 without body force. A distorted patch
    // of straight-sided elements must reproduce it at every node to round-off.
    let exact = |x: [f64; 3]| {
        [
            1e-3 * (2.0 * x[0] - x[1] + 0.5 * x[2]) + 1e-4,
            1e-3 * (0.3 * x[0] + 1.5 * x[1] - 2.0 * x[2]),
            1e-3 * (-x[0] + 0.7 * x[1] - 3.0 * x[2]) - 2e-4,
        ]
    };
    let mesh = solid_common::block(3, [1.0; 3], true);
    let u = solve(&mesh, &exact, &|_| [0.0; 3]);
    for (x, uh) in mesh.nodes.iter().zip(&u) {
        let e = exact(*x);
        for a in 0..3 {
            assert!((uh[a] - e[a]).abs() < 1e-15, "{x:?}: {uh:?} against {e:?}");
        }
    }
}

#[test]
fn manufactured_solution_converges_at_the_optimal_rates() {
    // u = (x³ + y³, z³, x³): strain (3x², 0, 0, γ_yz = 3z², γ_xz = 3x², γ_xy = 3y²),
    // tr ε = 3x², σ = λ tr ε I + 2μ ε, and the body force f = −div σ is
    // f_x = −((6λ + 12μ) x + 6μ y), f_y = −6μ z, f_z = −6μ x.
    let l = lame();
    let exact = |x: [f64; 3]| [x[0].powi(3) + x[1].powi(3), x[2].powi(3), x[0].powi(3)];
    let strain = |x: [f64; 3]| {
        let [a, b, c] = x.map(|v| 3.0 * v * v);
        [a, 0.0, 0.0, c, a, b]
    };
    let force = move |x: [f64; 3]| {
        [
            -((6.0 * l.lambda + 12.0 * l.mu) * x[0] + 6.0 * l.mu * x[1]),
            -6.0 * l.mu * x[2],
            -6.0 * l.mu * x[0],
        ]
    };
    let results: Vec<(f64, f64)> = [2, 4, 8]
        .iter()
        .map(|&n| {
            let mesh = solid_common::block(n, [1.0; 3], false);
            let u = solve(&mesh, &exact, &force);
            errors(&mesh, &u, &exact, &strain)
        })
        .collect();
    eprintln!("(L2, energy) errors at n = 2, 4, 8: {results:?}");
    for w in results.windows(2) {
        let rate_l2 = (w[0].0 / w[1].0).log2();
        let rate_energy = (w[0].1 / w[1].1).log2();
        // Quadratic elements: O(h³) in L2 and O(h²) in energy (Ciarlet 1978, Thm 3.2.2); the
        // margin 0.2 covers the pre-asymptotic range of these coarse meshes.
        assert!(rate_l2 > 2.8, "L2 rate {rate_l2:.3} ({results:?})");
        assert!(rate_energy > 1.8, "energy rate {rate_energy:.3} ({results:?})");
    }
}
