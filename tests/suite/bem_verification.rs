//! Verification of the `bem` solver against Hertz, Cattaneo–Mindlin and MDR, and its hard cases.
//!
//! Default runs use grids up to 64² (a few seconds in the dev profile). The grid sweeps are
//! `#[ignore]`d: `cargo test --release --test suite bem_verification:: -- --ignored --nocapture`.

use std::path::Path;

use spherecontact::analytic::cattaneo_mindlin::CattaneoMindlin;
use spherecontact::analytic::mdr::Mdr;
use spherecontact::case::Case;
use spherecontact::history::History;
use spherecontact::scene::Scene;
use spherecontact::solver::{SolveError, Solver};

use spherecontact::bem::solver::PositionFields;
use spherecontact::bem::Bem;

/// The paper's spheres (R 0.1 m, E 70 GPa, ν 0.3, μ 0.2) along a path in µm.
fn scene(delta_n: &[f64], delta_t: &[f64], substeps: usize, extra: &str) -> Scene {
    let list = |v: &[f64]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", ");
    let text = format!(
        "friction = 0.2\nsolvers = [\"hertz\"]\n{extra}\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
         [path]\nunit = \"um\"\ndelta_n = [{}]\ndelta_t = [{}]\nsubsteps = {substeps}\n",
        list(delta_n),
        list(delta_t)
    );
    Case::parse(Path::new("test.toml"), &text)
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}

fn solve(n: usize, scene: &Scene) -> (History, Vec<PositionFields>) {
    Bem::with_grid(n)
        .solve_with_fields(scene)
        .unwrap_or_else(|e| panic!("bem on {n}²: {e}"))
}

/// The least-squares slope of log(error) against log(h): the observed convergence rate.
fn rate(h: &[f64], error: &[f64]) -> f64 {
    let points: Vec<(f64, f64)> = h.iter().zip(error).map(|(h, e)| (h.ln(), e.abs().ln())).collect();
    spherecontact::fit::Line::fit(&points)
        .expect("a ladder of distinct sizes")
        .slope
}

#[test]
fn hertz_force_pressure_and_radius_converge_with_panel_size() {
    let scene = scene(&[0.0, 17.0], &[0.0, 0.0], 1, "");
    let hertz = scene.hertz();
    let (p, p0, c) = (
        hertz.force(17e-6),
        hertz.peak_pressure(17e-6),
        hertz.contact_radius(17e-6),
    );
    let (mut h, mut ep, mut ep0, mut ec) = (vec![], vec![], vec![], vec![]);
    for n in [16, 32, 64] {
        let (history, fields) = solve(n, &scene);
        let row = history.at_position(1).expect("position 1");
        h.push(fields[1].snapshot.grid.h / c);
        ep.push(row.normal_force.unwrap() / p - 1.0);
        ep0.push(row.peak_pressure.unwrap() / p0 - 1.0);
        ec.push(row.contact_radius.unwrap() / c - 1.0);
    }
    let (rp, rp0, rc) = (rate(&h, &ep), rate(&h, &ep0), rate(&h, &ec));
    let show = |v: &[f64]| {
        v.iter()
            .map(|e| format!("{e:+.2e}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    eprintln!("h/c {}\nP err {} rate {rp:.2}", show(&h), show(&ep));
    eprintln!(
        "p0 err {} rate {rp0:.2}\nc err {} rate {rc:.2}",
        show(&ep0),
        show(&ec)
    );
    // Rates: constant-traction collocation is second order where p is smooth (p0: the centre
    // panel); P loses some to the √ edge of the Hertz pressure (measured 1.5).
    assert!(rp > 1.3, "P rate {rp}");
    assert!(rp0 > 1.7, "p0 rate {rp0}");
    // The contact radius from the p² edge fit has no clean asymptotic rate (its error changes
    // sign: +7e-4, −3e-4, +1e-4, +1.5e-4 from 32² to 256², bem_timing); it is bounded instead.
    assert!(ec[1..].iter().all(|e| e.abs() < 1e-3), "c errors {ec:?}");
    // At 64² (h = c/29): the errors the case files' tolerances build on.
    assert!(ep[2].abs() < 2e-4 && ep0[2].abs() < 2e-4);
}

#[test]
fn cattaneo_mindlin_force_stick_radius_and_masing_unloading() {
    // Constant δn = 17 µm; δt to 2 µm (partial slip, Q/μP ≈ 0.63), back to −1 µm (Masing).
    let scene = scene(&[0.0, 17.0, 17.0, 17.0], &[0.0, 0.0, 2.0, -1.0], 8, "");
    let reference = CattaneoMindlin.solve(&scene).expect("closed form");
    let (history, _) = solve(64, &scene);
    let mu_p = 0.2 * scene.hertz().force(17e-6);
    for (row, expected) in history.steps.iter().zip(&reference.steps).skip(8) {
        let q = row.tangential_force.unwrap();
        let q_ref = expected.tangential_force.unwrap();
        // Tolerance 0.3 % of μP: the 64² discretisation (Q/μP error 5e-4 at 2 µm, bem_timing)
        // plus the increment-wise convergence tolerance.
        assert!(
            (q - q_ref).abs() < 3e-3 * mu_p,
            "step {}: Q {q} vs {q_ref}",
            row.step
        );
        // Stick radius against c (1 − shed/μP)^{1/3} from C–M: 64² resolves it to about one
        // panel (h = c/29), so 1.5 h on c.
        let (cs, cs_ref) = (row.stick_radius.unwrap(), expected.stick_radius.unwrap());
        let h = 2.0 * 1.1 * scene.max_contact_radius() / 63.0;
        assert!(
            (cs - cs_ref).abs() < 1.5 * h,
            "step {}: stick {cs} vs {cs_ref}",
            row.step
        );
    }
}

#[test]
fn cattaneo_is_reproduced_exactly_when_poisson_is_zero() {
    // With ν = 0 the Cerruti cross term ν XY/ρ³ vanishes and Cattaneo–Mindlin is the exact
    // partial-slip solution; with ν = 0.3 BEM stays +4.2e-4 above it from 64² to 512²
    // (bem_timing), the known approximation of Mindlin's solution (q_y = 0, circular stick zone).
    let mut scene = scene(&[17.0, 17.0], &[0.0, 2.0], 1, "");
    scene.pair.body1.material.poisson = 0.0;
    scene.pair.body2.material.poisson = 0.0;
    let q_ref = CattaneoMindlin.solve(&scene).expect("closed form").steps[1]
        .tangential_force
        .unwrap();
    let errors: Vec<f64> = [32, 64]
        .iter()
        .map(|&n| (solve(n, &scene).0.steps[1].tangential_force.unwrap() / q_ref - 1.0).abs())
        .collect();
    // Measured 5.8e-5 at 64² (1.3e-5 at 128²): discretisation only.
    assert!(errors[1] < 1e-4 && errors[1] < errors[0], "{errors:?}");
}

#[test]
fn slip_zone_carries_mu_p_and_stick_zone_is_the_central_disc() {
    let scene = scene(&[0.0, 17.0, 17.0], &[0.0, 0.0, 2.0], 4, "");
    let (history, fields) = solve(64, &scene);
    let s = &fields[2].snapshot;
    let row = history.at_position(2).unwrap();
    let c = row.contact_radius.unwrap();
    let cs = c * (1.0 - row.tangential_force.unwrap() / (0.2 * row.normal_force.unwrap())).cbrt();
    let h = s.grid.h;
    let (mut slip_checked, mut stick_checked) = (0, 0);
    for k in 0..s.grid.len() {
        let [x, y] = s.grid.centre(k);
        let r = x.hypot(y);
        let q = s.traction_magnitude(k);
        if r > cs + 2.0 * h && r < c - 2.0 * h {
            // Cattaneo's annulus, two panels clear of both boundaries: slip at the Coulomb bound.
            assert!(!s.stick[k], "panel at r = {r} should slip");
            assert!((q - 0.2 * s.pressure[k]).abs() <= 1e-12 * s.pressure[k]);
            slip_checked += 1;
        } else if r < cs - 2.0 * h {
            assert!(
                s.stick[k] && q < 0.2 * s.pressure[k],
                "panel at r = {r} should stick"
            );
            stick_checked += 1;
        }
    }
    assert!(slip_checked > 100 && stick_checked > 100);
    // The stick zone's semi-axes from its panels' second moments: Cattaneo's c_s within half a
    // panel.
    let [ax, ay] = s.stick_zone().expect("a stick zone").semi_axes;
    eprintln!("c_s {cs:.4e}, semi-axes {ax:.4e} {ay:.4e}, h {h:.3e}");
    assert!((ax - cs).abs() < 0.5 * h && (ay - cs).abs() < 0.5 * h);
}

#[test]
fn paper_path_tangential_force_follows_mdr_at_every_position() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/paper-fig7.toml");
    let mut scene = Case::load(&file).expect("paper case").scene;
    scene.path = spherecontact::path::LoadingPath::try_new(scene.path.positions().to_vec(), vec![10; 11])
        .expect("path");
    let mdr = Mdr::default().solve(&scene).expect("mdr");
    let (history, fields) = solve(64, &scene);
    let peak = mdr
        .steps
        .iter()
        .filter_map(|r| r.tangential_force)
        .fold(0.0, |m: f64, q| m.max(q.abs()));
    for (b, m) in history.at_positions().zip(mdr.at_positions()) {
        let error = (b.tangential_force.unwrap() - m.tangential_force.unwrap()).abs() / peak;
        // The 2 % of the peak |Ft| (64² measured 7e-4).
        assert!(error < 0.02, "position {:?}: {error}", b.position);
    }
    assert_eq!(history.fields.len(), 12);
    assert_eq!(fields[5].snapshot.grid.len(), 64 * 64);
    let field = &history.fields[5];
    assert_eq!(field.points.len(), 64 * 64);
    assert!(field.traction.is_some() && field.stick.is_some());
}

#[test]
fn a_window_smaller_than_the_contact_is_a_clear_error() {
    let scene = scene(&[0.0, 17.0], &[0.0, 0.0], 2, "");
    let bem = Bem {
        window: 0.8,
        ..Bem::with_grid(16)
    };
    match bem.solve(&scene) {
        Err(SolveError::Failed(message)) => assert!(message.contains("edge of the window")),
        other => panic!("expected a window error, got {other:?}"),
    }
}

#[test]
fn a_coarse_grid_warns() {
    let scene = scene(&[0.0, 17.0], &[0.0, 0.0], 1, "");
    // 8² over ±2 c: h = 0.57 c, 3.5 panels across the contact.
    let coarse = Bem {
        window: 2.0,
        ..Bem::with_grid(8)
    };
    let history = coarse.solve(&scene).expect("a coarse grid still solves");
    assert!(history.metadata.warnings.iter().any(|w| w.contains("too coarse")));
    let (history, _) = solve(16, &scene);
    assert!(history.metadata.warnings.is_empty());
}

#[test]
fn zero_friction_gives_no_tangential_force() {
    let text_scene = scene(&[0.0, 17.0, 17.0], &[0.0, 0.0, 2.0], 2, "");
    let scene = Scene {
        friction: 0.0,
        ..text_scene
    };
    let (history, _) = solve(16, &scene);
    for row in &history.steps {
        assert_eq!(row.tangential_force, Some(0.0));
    }
    assert_eq!(history.at_position(2).unwrap().stick_radius, Some(0.0));
}

#[test]
fn separation_and_recontact_start_afresh() {
    // Loaded and sheared, separated (gap of 1 µm), re-contacted and sheared from the origin again.
    let scene = scene(
        &[0.0, 17.0, 17.0, -1.0, 17.0, 17.0],
        &[0.0, 0.0, 2.0, 2.0, 2.0, 4.0],
        4,
        "",
    );
    let (history, _) = solve(32, &scene);
    let separated = history.at_position(3).unwrap();
    assert_eq!(separated.normal_force, Some(0.0));
    assert_eq!(separated.tangential_force, Some(0.0));
    let mdr = Mdr::default().solve(&scene).expect("mdr");
    let again = history.at_position(5).unwrap().tangential_force.unwrap();
    let reference = mdr.at_position(5).unwrap().tangential_force.unwrap();
    // 32² (h = c/14): 1 % of the force.
    assert!(
        (again - reference).abs() < 0.01 * reference,
        "{again} vs {reference}"
    );
}

#[test]
fn reversal_at_every_step_follows_mdr() {
    let delta_t: Vec<f64> = (0..12)
        .map(|k| if k < 2 { 0.0 } else { 0.5 * (k % 2) as f64 })
        .collect();
    let mut delta_n = vec![17.0; 12];
    delta_n[0] = 0.0;
    let scene = scene(&delta_n, &delta_t, 1, "");
    let (history, _) = solve(32, &scene);
    let mdr = Mdr::default().solve(&scene).expect("mdr");
    let peak = mdr
        .steps
        .iter()
        .filter_map(|r| r.tangential_force)
        .fold(0.0, f64::max);
    for (b, m) in history.steps.iter().zip(&mdr.steps) {
        let error = (b.tangential_force.unwrap() - m.tangential_force.unwrap()).abs();
        // 32²: 2 % of the peak, the bound for the path.
        assert!(error < 0.02 * peak, "step {}: {error}", b.step);
    }
}

#[test]
fn dissimilar_materials_warn_about_the_neglected_coupling() {
    let scene = scene(
        &[0.0, 17.0],
        &[0.0, 1.0],
        1,
        "[body2]\nradius = 0.1\nyoung = 210e9\npoisson = 0.29\n",
    );
    let (history, _) = solve(16, &scene);
    assert!(history.metadata.warnings.iter().any(|w| w.contains("coupling")));
}

/// The stick zone's departure from axisymmetry at the paper's position 5 (δn = 17 µm, δt = 3 µm
/// after 1 µm and 2 µm), on grids 64², 128², 256²: semi-axes along x (the loading direction) and
/// y from the stick zone's second moments. Run: `cargo test --release --test suite bem_verification::stick_zone_axisymmetry -- --ignored --nocapture`.
#[test]
#[ignore]
fn stick_zone_axisymmetry() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/paper-fig7.toml");
    let mut scene = Case::load(&file).expect("paper case").scene;
    let positions = scene.path.positions()[..6].to_vec();
    scene.path = spherecontact::path::LoadingPath::try_new(positions, vec![20; 5]).expect("path");
    let mut axes = Vec::new();
    for n in [64, 128, 256] {
        let (history, fields) = solve(n, &scene);
        let s = &fields[5].snapshot;
        let [wx, wy] = s.stick_zone().expect("a stick zone").semi_axes;
        let c = history.at_position(5).unwrap().contact_radius.unwrap();
        eprintln!(
            "{n}²: h = {:.3e} m, stick semi-axes x {wx:.5e} m, y {wy:.5e} m, (a_y − a_x)/c = {:+.1e}, \
             stick radius {:.4e} m",
            s.grid.h,
            (wy - wx) / c,
            history.at_position(5).unwrap().stick_radius.unwrap()
        );
        axes.push((wx / c, wy / c));
    }
    // Converged: 128² and 256² agree to 1e-3 c on both semi-axes (measured 2e-4 and 1e-4 c), and
    // no departure from a disc is resolved: (a_y − a_x)/c = +3.3e-4 at 128², −1e-5 at 256²,
    // at the level of the solver tolerances (the sign changed when they were changed).
    let [(_, _), (x1, y1), (x2, y2)] = axes[..] else {
        unreachable!()
    };
    assert!((x1 - x2).abs() < 1e-3 && (y1 - y2).abs() < 1e-3);
    assert!((y1 - x1).abs() < 1e-3 && (y2 - x2).abs() < 1e-3);
}
