//! `fem-3d` with Coulomb friction: the hard cases of a path (μ = 0, gross sliding at once,
//! reversal at every increment, separation and re-contact while sliding, a pole element coarser
//! than the contact, bodies it does not model) on a coarse mesh (pole size c_max/4, a few
//! seconds each), and the paper's Figure 11–12 claim measured against the BEM (heavy, ignored).
//!
//! The Q accuracy along the paper path and on Cattaneo's shift is checked by the shipped cases
//! (cases/paper-fig7.toml, cases/fem-3d-cattaneo.toml: `spherecontact verify`).

mod common;

use common::{identical_spheres, paper_scene_with_path};
use spherecontact::external::toolchain::{Tool, Toolchain};
use spherecontact::fem::FemSolid3d;
use spherecontact::history::History;
use spherecontact::report::claims::study;
use spherecontact::scene::Scene;
use spherecontact::solver::{self, SolveError, Solver};

fn gmsh_missing(test: &str) -> bool {
    let missing = Toolchain::default().require(Tool::Gmsh).is_err();
    if missing {
        eprintln!("{test}: gmsh is not installed, fem-3d is not available: nothing to run");
    }
    missing
}

/// fem-3d at pole size c_max/`divisions`.
fn fem3d(scene: &Scene, divisions: f64) -> History {
    let solver = FemSolid3d::with_pole_size(scene.max_contact_radius() / divisions);
    solver::run(&solver, scene).unwrap_or_else(|e| panic!("fem-3d: {e}"))
}

/// The coarse mesh of the light tests: the contact spans about four elements at its largest.
const COARSE: f64 = 4.0;
/// The mesh of the reversal test, whose Q is checked against the corrected reference: with the
/// multipliers at the corners, c_max/4 leaves 2.9 % of the peak (about four multiplier points
/// along the contact radius), c_max/6 1.1 %, c_max/8 0.22 %.
const REVERSAL_MESH: f64 = 8.0;

#[test]
fn bodies_it_does_not_model_are_not_applicable_with_the_reason() {
    let mut scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 1.0)], 1);
    scene.pair.body2 = identical_spheres(0.1, 210e9, 0.29).body1;
    match FemSolid3d::default().solve(&scene) {
        Err(SolveError::NotApplicable(why)) => assert!(why.contains("dissimilar"), "{why}"),
        other => panic!("dissimilar bodies were answered: {other:?}"),
    }
    let mut axial = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 1.0)], 1);
    axial.domain.grip = spherecontact::domain::Grip::Axial;
    match FemSolid3d::default().solve(&axial) {
        Err(SolveError::NotApplicable(why)) => assert!(why.contains("axial grip"), "{why}"),
        other => panic!("a shifted axial grip was answered: {other:?}"),
    }
}

#[test]
fn zero_friction_gives_zero_tangential_force_exactly() {
    if gmsh_missing("zero_friction_gives_zero_tangential_force_exactly") {
        return;
    }
    let mut scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 2.0), (12.0, -1.0)], 2);
    scene.friction = 0.0;
    let history = fem3d(&scene, COARSE);
    assert!(history.steps.iter().all(|r| r.tangential_force == Some(0.0)));
    assert!(history.steps[2].normal_force.unwrap() > 0.0);
    // Every point in contact slips freely: the traction field is zero, no point sticks.
    let field = history.fields.last().expect("fields at the positions");
    assert!(field.traction.as_ref().unwrap().iter().all(|q| *q == [0.0, 0.0]));
    assert!(field.stick.as_ref().unwrap().iter().all(|&s| !s));
}

#[test]
fn gross_sliding_at_once_carries_mu_p() {
    if gmsh_missing("gross_sliding_at_once_carries_mu_p") {
        return;
    }
    // 6 µm in one increment at δn = 17 µm: past Cattaneo's sliding shift (4.1 µm).
    let scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 6.0)], 1);
    let history = fem3d(&scene, COARSE);
    let row = &history.steps[2];
    let (p, q) = (row.normal_force.unwrap(), row.tangential_force.unwrap());
    let ratio = q / (scene.friction * p);
    eprintln!(
        "gross sliding: Q/μP = {ratio:.6}, stick radius {:?}",
        row.stick_radius
    );
    // Every point slips with |q| = μp; q_x = μp cos θ with θ the slip's angle from x, which
    // the transverse compliance turns by a few per cent of a radian at most (cos ≥ 0.999);
    // measured Q/μP = 0.99987.
    assert!(ratio <= 1.0 + 1e-9 && ratio > 0.999, "Q/μP = {ratio}");
    assert_eq!(row.stick_radius, Some(0.0));
}

#[test]
fn reversal_at_every_increment_stays_on_the_masing_branches() {
    if gmsh_missing("reversal_at_every_increment_stays_on_the_masing_branches") {
        return;
    }
    // δt alternates ±0.5 µm at δn = 17 µm: every increment reverses the slip.
    let positions: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
        .chain(std::iter::once((17.0, 0.0)))
        .chain((0..8).map(|k| (17.0, if k % 2 == 0 { 0.5 } else { -0.5 })))
        .collect();
    let scene = paper_scene_with_path(&positions, 1);
    let history = fem3d(&scene, REVERSAL_MESH);
    let reference = common::solve("mdr-domain", &scene);
    let peak = reference.peak(spherecontact::history::Quantity::TangentialForce);
    let mut worst: f64 = 0.0;
    for (a, b) in history.steps.iter().zip(&reference.steps) {
        let (q, p) = (a.tangential_force.unwrap(), a.normal_force.unwrap());
        assert!(q.abs() <= scene.friction * p * (1.0 + 1e-9));
        worst = worst.max((q - b.tangential_force.unwrap()).abs() / peak);
    }
    eprintln!(
        "reversal every increment: worst |Q − Q_mdr-domain| = {:.3} % of the peak",
        100.0 * worst
    );
    // Each reversal after the first retraces the same branch (Masing): Q alternates between
    // two values, the same at every repetition to the engine's tolerance.
    let q: Vec<f64> = history
        .steps
        .iter()
        .map(|r| r.tangential_force.unwrap())
        .collect();
    for k in 4..q.len() {
        assert!(
            (q[k] - q[k - 2]).abs() < 1e-4 * peak,
            "step {k}: {} then {}",
            q[k - 2],
            q[k]
        );
    }
    // c_max/8 against the corrected reference: the mesh error of a contact eight elements wide,
    // measured 2.2e-3 of the peak; 1e-2 is the bound at the default mesh.
    assert!(worst < 1e-2, "{worst}");
}

#[test]
fn separation_and_recontact_while_sliding_start_from_rest() {
    if gmsh_missing("separation_and_recontact_while_sliding_start_from_rest") {
        return;
    }
    // Loaded and sheared, the gap opens while sliding, and closes again 2 µm further on.
    let path = [(0.0, 0.0), (17.0, 0.0), (17.0, 2.0), (-1.0, 3.0), (17.0, 5.0)];
    let scene = paper_scene_with_path(&path, 1);
    let history = fem3d(&scene, COARSE);
    let open = &history.steps[3];
    assert_eq!((open.normal_force, open.tangential_force), (Some(0.0), Some(0.0)));
    // The memory is cleared: the re-contact is the contact of a fresh pair loaded to 17 µm while
    // shifted by 2 µm in one increment.
    let fresh = fem3d(&paper_scene_with_path(&[(0.0, 0.0), (17.0, 2.0)], 1), COARSE);
    let (again, new) = (&history.steps[4], &fresh.steps[1]);
    let q = again.tangential_force.unwrap();
    assert!(q > 0.0);
    // The same mesh (gmsh is deterministic for one geometry) and the same increment.
    assert!(
        (q - new.tangential_force.unwrap()).abs() <= 1e-9 * q,
        "{q} against {:?}",
        new.tangential_force
    );
    assert!((again.normal_force.unwrap() - new.normal_force.unwrap()).abs() <= 1e-9 * q.abs().max(1.0));
}

#[test]
fn a_pole_element_coarser_than_the_contact_is_warned_about_with_friction() {
    if gmsh_missing("a_pole_element_coarser_than_the_contact_is_warned_about_with_friction") {
        return;
    }
    let scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 1.0)], 1);
    let history = fem3d(&scene, 1.0 / 0.7);
    let warnings = history.metadata.warnings.join("\n");
    assert!(warnings.contains("P, Q, c and p0 are unreliable"), "{warnings}");
    assert!(history.steps[2].tangential_force.is_some());
}

/// The paper's Figure 11–12 claim at position 5 (δn = 17 µm after the shifts 1, 2, 3 µm):
/// q_y against q_x, its sign over the quadrants and the stick semi-axes, fem-3d against the BEM,
/// measured by the reports' own measures (`report::claims::measure`); c_max/6 printed for the
/// trend. Heavy (fem-3d along five segments, three times, about 3 min): `cargo test --release --test fem3d_friction -- --ignored --nocapture`.
#[test]
#[ignore]
fn transverse_traction_and_stick_zone_at_position_five_against_the_bem() {
    if gmsh_missing("transverse_traction_and_stick_zone_at_position_five_against_the_bem") {
        return;
    }
    let path = [
        (0.0, 0.0),
        (10.0, 0.0),
        (14.0, 1.0),
        (17.0, 1.0),
        (17.0, 2.0),
        (17.0, 3.0),
    ];
    let mu = 0.2;
    let measure = |h: &History, label: &str| {
        let (m, c) = study::measure(h, 5, mu, None).expect("a map at position 5");
        let q: Vec<f64> = m.quadrants.iter().map(|s| s.total).collect();
        eprintln!(
            "{label}: max|q_y|/max|q_x| = {:.4}, ∫q_y over the quadrants {:+.3e} {:+.3e} {:+.3e} {:+.3e} N, \
             stick semi-axes x/y {:?} µm, c {:.1} µm, spacing c/{:.0}",
            m.qy_max / m.qx_max,
            q[0],
            q[1],
            q[2],
            q[3],
            m.stick_axes.map(|a| a.map(|v| (1e6 * v).round())),
            1e6 * c,
            c / m.spacing
        );
        m
    };
    // In the mesh (c_max/6, /10) and in the increments (10, 20 a segment).
    let mut runs = Vec::new();
    for (divisions, substeps) in [(6.0, 10), (10.0, 10), (10.0, 20)] {
        let scene = paper_scene_with_path(&path, substeps);
        let bem = measure(
            &common::solve("bem", &scene),
            &format!("bem, {substeps} increments a segment"),
        );
        let label = format!("fem-3d c_max/{divisions}, {substeps} increments a segment");
        let solid = measure(&fem3d(&scene, divisions), &label);
        runs.push((bem, solid));
    }
    // Asserted at the default mesh c_max/10.
    for (bem, solid) in &runs[1..] {
        // The same sign pattern: q_y odd in x and in y in both (neighbouring quadrants opposite,
        // within 10 % of the largest: the BEM's grid and fem-3d's mesh are not symmetric in x),
        // and the same sign in the first quadrant.
        assert!(bem.is_odd_in_x_and_y(0.1) && solid.is_odd_in_x_and_y(0.1));
        assert!(bem.quadrants[0].total * solid.quadrants[0].total > 0.0);
        // The magnitude: ∫ q_y dA over the first quadrant within 10 % of the BEM's (measured
        // 3.6–4.4 % with the corner multipliers: panels c/29 against points c/10 apart, each
        // resolving the stick edge, where q_y changes sign, to about one sample). The ratio of
        // the maxima max|q_y|/max|q_x| is printed, not asserted: fem-3d's is 0.056–0.066 against
        // the BEM's 0.049–0.050, a one-point peak at the stick edge (a point that has just
        // begun to slip, its slip direction set by a small increment); averaged over squares of
        // side c/5 the two agree within 6 % (0.0445–0.0455 against 0.0429–0.0441:
        // `examples/fem3d_transverse.rs`). With multipliers at every node of the quadratic faces
        // (the former rule) the multipliers oscillated from node to node and the ratio was 0.155.
        let (qb, qs) = (bem.quadrants[0].total, solid.quadrants[0].total);
        assert!((qs / qb - 1.0).abs() < 0.1, "fem-3d {qs} N, bem {qb} N");
        // The stick semi-axes within one fem-3d element (c_max/10 ≈ 92 µm) of the BEM's.
        let (a, b) = (bem.stick_axes.unwrap(), solid.stick_axes.unwrap());
        assert!(
            (a[0] - b[0]).abs() < 9.2e-5 && (a[1] - b[1]).abs() < 9.2e-5,
            "{a:?} {b:?}"
        );
    }
}

/// Q on Cattaneo's shift (δn = 17 µm, δt 0 → 5 µm, 10 increments) against mdr-domain under
/// refinement of the pole size, c_max/4, /6, /10, /14. Heavy (c/14: 2.5 GB, about a minute):
/// `cargo test --release --test fem3d_friction -- --ignored --nocapture`.
#[test]
#[ignore]
fn tangential_force_converges_under_refinement() {
    if gmsh_missing("tangential_force_converges_under_refinement") {
        return;
    }
    let mut scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 5.0)], 10);
    scene.path =
        spherecontact::path::LoadingPath::try_new(scene.path.positions().to_vec(), vec![2, 10]).unwrap();
    let reference = common::solve("mdr-domain", &scene);
    let peak = reference.peak(spherecontact::history::Quantity::TangentialForce);
    let errors: Vec<f64> = [4.0, 6.0, 10.0, 14.0]
        .into_iter()
        .map(|divisions| {
            let history = fem3d(&scene, divisions);
            let worst = history
                .steps
                .iter()
                .zip(&reference.steps)
                .map(|(a, b)| (a.tangential_force.unwrap() - b.tangential_force.unwrap()).abs() / peak)
                .fold(0.0, f64::max);
            eprintln!(
                "c/{divisions}: worst |Q − Q_mdr-domain| = {:.4} % of the peak",
                100.0 * worst
            );
            worst
        })
        .collect();
    // The error falls at every refinement, towards the reference's own first-order remainder
    // (about 1.1e-3 of the peak, which fem-axisym also leaves at c_max/40): measured 0.52 %,
    // 0.19 %, 0.10 %, 0.096 % at c_max/4, /6, /10, /14 with the corner multipliers.
    assert!(errors.windows(2).all(|e| e[1] < e[0]), "{errors:?}");
    assert!(errors[2] < 3e-3, "{errors:?}");
}
