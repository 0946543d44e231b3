//! Verification of the 6-node meridian element in the Fourier modes n = 0 (axisymmetric) and
//! n = 1 (a shift along x): patch tests (exact reproduction of strain-free and constant-strain
//! fields on a distorted patch) and manufactured-solution convergence with asserted rates, through
//! the shared assembly. Run: `cargo test --test suite fem_element::`.

use faer::Mat;
use spherecontact::fem::assembly::{assemble_with, Dofs};
use spherecontact::fem::element::tri6::{self, Integration, Lame};
use spherecontact::fem::element::{tri6_n1, Mode};
use spherecontact::fem::factor::{Factor, Ordering};
use spherecontact::fem::mesh::meridian::Mesh;
use spherecontact::quadrature;
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

/// A Fourier mode as the tests drive it: its ring factor, the components fixed on the axis and
/// its strain.
trait Tested<const C: usize, const S: usize>: Mode {
    /// ∫ (angular factor)² dθ: 2π for n = 0, π for n = 1.
    const RING: f64;
    /// Components fixed on the axis (u_r for n = 0; B, W for n = 1).
    const ON_AXIS: &'static [usize];
    fn strain(x: &tri6::Coords, u: &[[f64; C]; 6], at: [f64; 2]) -> Option<[f64; S]>;
}

impl Tested<2, 4> for tri6::Axisymmetric {
    const RING: f64 = 2.0 * PI;
    const ON_AXIS: &'static [usize] = &[0];
    fn strain(x: &tri6::Coords, u: &[[f64; 2]; 6], at: [f64; 2]) -> Option<[f64; 4]> {
        tri6::strain(x, u, at)
    }
}

impl Tested<3, 6> for tri6_n1::FourierOne {
    const RING: f64 = PI;
    const ON_AXIS: &'static [usize] = &[1, 2];
    fn strain(x: &tri6::Coords, u: &[[f64; 3]; 6], at: [f64; 2]) -> Option<[f64; 6]> {
        tri6_n1::strain(x, u, at)
    }
}

/// The point of reference coordinates `at` in element `x`, and the map there.
fn point(x: &tri6::Coords, at: [f64; 2]) -> ([f64; 2], tri6::Mapped) {
    let m = tri6::map(x, at).unwrap();
    let p = [0, 1].map(|a| (0..6).map(|i| m.n[i] * x[i][a]).sum::<f64>());
    (p, m)
}

/// Solves K u = f in mode `M` with u = `exact` on the boundary (and the mode's axis components
/// zero on the axis when r0 = 0); `force` holds the body-force amplitudes conjugate to the DOFs.
fn solve<M: Tested<C, S>, const C: usize, const S: usize>(
    mesh: &Mesh,
    lame: Lame,
    r0: f64,
    exact: &dyn Fn([f64; 2]) -> [f64; C],
    force: &dyn Fn([f64; 2]) -> [f64; C],
) -> Vec<[f64; C]> {
    let n = mesh.nodes.len();
    let mut fixed = vec![false; C * n];
    for (k, &x) in mesh.nodes.iter().enumerate() {
        if on_boundary(x, r0) {
            fixed[C * k..C * (k + 1)].fill(true);
        }
        if x[0] == 0.0 {
            M::ON_AXIS.iter().for_each(|&a| fixed[C * k + a] = true);
        }
    }
    let dofs = Dofs::from_fixed(&fixed);
    let system = assemble_with::<M>(mesh, lame, Integration::Full, dofs.clone(), 0).unwrap();
    // u = û + v: û the nodal interpolant of the exact field, v = 0 on fixed DOFs, K_ff v = f − K û.
    let lifted: Vec<[f64; C]> = mesh.nodes.iter().map(|&x| exact(x)).collect();
    let mut rhs = Mat::<f64>::zeros(dofs.count(), 1);
    for t in &mesh.triangles {
        let x = t.map(|k| mesh.nodes[k]);
        let k = M::stiffness(&x, lame, Integration::Full).unwrap();
        let ue: Vec<f64> = t.iter().flat_map(|&k| lifted[k]).collect();
        for p in quadrature::triangle_degree4() {
            let (at, m) = point(&x, p.at);
            let f = force(at);
            for (&node, &n) in t.iter().zip(&m.n) {
                for (a, &f_a) in f.iter().enumerate() {
                    if let Some(d) = dofs.free(C * node + a) {
                        rhs[(d, 0)] += M::RING * n * f_a * m.r * m.det * p.weight;
                    }
                }
            }
        }
        for (a, row) in k.chunks_exact(6 * C).enumerate() {
            if let Some(d) = dofs.free(C * t[a / C] + a % C) {
                rhs[(d, 0)] -= row.iter().zip(&ue).map(|(k, u)| k * u).sum::<f64>();
            }
        }
    }
    Factor::new(&system.stiffness, Ordering::Amd)
        .unwrap()
        .solve_in_place(rhs.as_mut());
    (0..n)
        .map(|k| std::array::from_fn(|a| lifted[k][a] + dofs.free(C * k + a).map_or(0.0, |d| rhs[(d, 0)])))
        .collect()
}

/// L2 and energy-norm errors against the exact field and its strain.
fn errors<M: Tested<C, S>, const C: usize, const S: usize>(
    mesh: &Mesh,
    lame: Lame,
    u: &[[f64; C]],
    exact: &dyn Fn([f64; 2]) -> [f64; C],
    strain: &dyn Fn([f64; 2]) -> [f64; S],
) -> (f64, f64) {
    let (mut l2, mut energy) = (0.0, 0.0);
    for t in &mesh.triangles {
        let x = t.map(|k| mesh.nodes[k]);
        let ue = t.map(|k| u[k]);
        for p in quadrature::triangle_degree4() {
            let (at, m) = point(&x, p.at);
            let uh: [f64; C] = std::array::from_fn(|a| (0..6).map(|i| m.n[i] * ue[i][a]).sum());
            let ex = exact(at);
            let w = M::RING * m.r * m.det * p.weight;
            l2 += w * (0..C).map(|a| (uh[a] - ex[a]).powi(2)).sum::<f64>();
            let eh = M::strain(&x, &ue, p.at).unwrap();
            let e = strain(at);
            let de: [f64; S] = std::array::from_fn(|k| eh[k] - e[k]);
            let ds = lame.stress_of(de);
            energy += w * (0..S).map(|k| de[k] * ds[k]).sum::<f64>();
        }
    }
    (l2.sqrt(), energy.sqrt())
}

fn lame() -> Lame {
    Lame { lambda: 1.5, mu: 1.0 }
}

/// The patch test: a field in the element's space with zero body force, imposed on the boundary
/// of a distorted patch, is reproduced at every node to round-off, with its exact strain.
fn patch_test<M: Tested<C, S>, const C: usize, const S: usize>(
    exact: &dyn Fn([f64; 2]) -> [f64; C],
    strain: [f64; S],
) {
    for r0 in [0.0, 0.5] {
        let mesh = square(3, r0, true);
        let u = solve::<M, C, S>(&mesh, lame(), r0, exact, &|_| [0.0; C]);
        for (x, uh) in mesh.nodes.iter().zip(&u) {
            let e = exact(*x);
            assert!((0..C).all(|a| (uh[a] - e[a]).abs() < 1e-13), "r0 {r0}: {x:?}");
        }
        let (l2, energy) = errors::<M, C, S>(&mesh, lame(), &u, exact, &|_| strain);
        assert!(l2 < 1e-13 && energy < 1e-12, "r0 {r0}: errors {l2:e}, {energy:e}");
    }
}

#[test]
fn patch_test_reproduces_a_linear_field_exactly() {
    // u = (a r, b z + c): constant strain (a, b, a, 0), σ_rr = σ_θθ, so div σ = 0 with no body
    // force. A distorted patch of straight-sided elements must reproduce it to round-off.
    let exact = |x: [f64; 2]| [2e-3 * x[0], -3e-3 * x[1] + 1e-3];
    patch_test::<tri6::Axisymmetric, 2, 4>(&exact, [2e-3, -3e-3, 2e-3, 0.0]);
}

#[test]
fn fourier_one_rigid_motions_give_no_strain() {
    // The n = 1 patch test: a translation along x (A = 1e-3) and a rotation about y by ω
    // (A = ω z, B = 0, W = −ω r) are strain-free; reproduced exactly, with zero strain, on a
    // distorted patch, on and off the axis.
    let omega = 2e-3;
    patch_test::<tri6_n1::FourierOne, 3, 6>(&|_| [1e-3, 0.0, 0.0], [0.0; 6]);
    patch_test::<tri6_n1::FourierOne, 3, 6>(&|x| [omega * x[1], 0.0, -omega * x[0]], [0.0; 6]);
}

#[test]
fn fourier_one_patch_test_reproduces_a_constant_shear() {
    // u = (a z, 0, b x): A = a z, B = 0, W = b r; the only strains are γ_rz = γ_θz = a + b
    // (amplitudes), a constant stress with no body force.
    let (a, b) = (2e-3, -5e-4);
    patch_test::<tri6_n1::FourierOne, 3, 6>(
        &|x| [a * x[1], 0.0, b * x[0]],
        [0.0, 0.0, 0.0, a + b, 0.0, a + b],
    );
}

/// Rates of the L2 and energy errors of a manufactured solution on meshes of 4, 8, 16 cells a
/// side, each asserted: O(h³) in L2 and O(h²) in energy for quadratic elements (Ciarlet 1978,
/// Thm 3.2.2); the margin 0.2 covers the pre-asymptotic range of these coarse meshes.
fn assert_optimal_rates<M: Tested<C, S>, const C: usize, const S: usize>(
    exact: &dyn Fn([f64; 2]) -> [f64; C],
    strain: &dyn Fn([f64; 2]) -> [f64; S],
    force: &dyn Fn([f64; 2]) -> [f64; C],
) {
    let results: Vec<(f64, f64)> = [4, 8, 16]
        .iter()
        .map(|&n| {
            let mesh = square(n, 0.0, false);
            let u = solve::<M, C, S>(&mesh, lame(), 0.0, exact, force);
            errors::<M, C, S>(&mesh, lame(), &u, exact, strain)
        })
        .collect();
    for w in results.windows(2) {
        let rate_l2 = (w[0].0 / w[1].0).log2();
        let rate_energy = (w[0].1 / w[1].1).log2();
        assert!(rate_l2 > 2.8, "L2 rate {rate_l2} ({results:?})");
        assert!(rate_energy > 1.8, "energy rate {rate_energy} ({results:?})");
        println!("rates: L2 {rate_l2:.3}, energy {rate_energy:.3}");
    }
}

#[test]
fn manufactured_solution_converges_at_the_optimal_rates() {
    // u_r = r z², u_z = r² z (u_r = 0 on the axis). Strain (z², r², z², 4rz); with
    // tr ε = 2z² + r²: σ_rr = σ_θθ = λ tr + 2μ z², σ_zz = λ tr + 2μ r², τ = 4μ r z, and the body
    // force f = −div σ is f_r = −(∂σ_rr/∂r + ∂τ/∂z + (σ_rr − σ_θθ)/r) = −(2λ + 4μ) r,
    // f_z = −(∂τ/∂r + ∂σ_zz/∂z + τ/r) = −(4λ + 8μ) z.
    let l = lame();
    assert_optimal_rates::<tri6::Axisymmetric, 2, 4>(
        &|x| [x[0] * x[1] * x[1], x[0] * x[0] * x[1]],
        &|x| [x[1] * x[1], x[0] * x[0], x[1] * x[1], 4.0 * x[0] * x[1]],
        &|x| {
            [
                -(2.0 * l.lambda + 4.0 * l.mu) * x[0],
                -(4.0 * l.lambda + 8.0 * l.mu) * x[1],
            ]
        },
    );
}

#[test]
fn fourier_one_manufactured_solution_converges_at_the_optimal_rates() {
    // A = r²z² + z³, B = r²z², W = r z³: regular on the axis (B = O(r²), W = O(r)); the Cartesian
    // field is u_x = z²(2x² + z), u_y = 2xyz², u_z = x z³. With U = A + B, V = A − B the strain
    // amplitudes are ε_rr = U,r = 4rz², ε_zz = W,z = 3rz², ε_θθ = (U − V)/r = 2rz²,
    // γ_rz = U,z + W,r = 4r²z + 3z² + z³, γ_rθ = V,r + (U − V)/r = 2rz², γ_θz = V,z + W/r = 3z² + z³.
    // Equilibrium of the amplitudes (σ_rθ = −S_rθ sin θ, σ_θz = −S_θz sin θ):
    // F_r = −(S_rr,r − S_rθ/r + S_rz,z + (S_rr − S_θθ)/r), F_θ = −(S_rθ,r + S_θθ/r + S_θz,z + 2S_rθ/r),
    // F_z = −(S_rz,r − S_θz/r + S_zz,z + S_rz/r); the loads conjugate to (A, B, W) are
    // (F_r + F_θ, F_r − F_θ, F_z) = (−18λz² − 4μr² − 26μz² − 12μz, −4μr², −(18λ + 24μ) r z)
    // (derived symbolically and checked against −div σ of the Cartesian field).
    let l = lame();
    let (lambda, mu) = (l.lambda, l.mu);
    assert_optimal_rates::<tri6_n1::FourierOne, 3, 6>(
        &|x| {
            let (r, z) = (x[0], x[1]);
            [r * r * z * z + z.powi(3), r * r * z * z, r * z.powi(3)]
        },
        &|x| {
            let (r, z) = (x[0], x[1]);
            [
                4.0 * r * z * z,
                3.0 * r * z * z,
                2.0 * r * z * z,
                4.0 * r * r * z + 3.0 * z * z + z.powi(3),
                2.0 * r * z * z,
                3.0 * z * z + z.powi(3),
            ]
        },
        &|x| {
            let (r, z) = (x[0], x[1]);
            [
                -18.0 * lambda * z * z - 4.0 * mu * r * r - 26.0 * mu * z * z - 12.0 * mu * z,
                -4.0 * mu * r * r,
                -(18.0 * lambda + 24.0 * mu) * r * z,
            ]
        },
    );
}
