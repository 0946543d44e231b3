//! The external decks along frictional paths: history, Coulomb's bound, agreement with MDR within
//! the finite body's measured offset and with each other, flagged iterations, mesh convergence.
//!
//! Tests that need gmsh, FreeFEM, dolfinx and meshio print why they skip where those are absent
//! (install them with `scripts/setup.sh`). Run: `cargo test --test suite external_friction::`; the
//! heavy walk: `cargo test --release --test suite external_friction::the_decks_walk -- --ignored`.

use spherecontact::external::axisym::AxisymSolver;
use spherecontact::external::fenicsx::Fenicsx;
use spherecontact::external::freefem::FreeFem;
use spherecontact::history::Quantity;
use spherecontact::solver;

use crate::common;
use common::decks::{at_resolution, frictional_scene, tools_present};

/// Both decks walk a frictional path with history: Q against MDR within the finite body's
/// measured offset, against each other within what their geometry (curved against straight
/// edges) explains, Coulomb's bound on the fields, the stick zone shrinking under load and
/// reset by the reversal, and the same run twice gives the same numbers within round-off. At
/// pole size c/20 (a third of the default's cost).
///
/// History of a fault this test caught: the decks once chose their grip from the path (rigid when
/// it shifts) while the mesh's far-face tag came from the scene's `[domain]` grip; this scene,
/// built from the axially gripped normal case, got a mesh tagged 2 and decks that held tag 4,
/// i.e. nothing: singular stiffnesses whose factorisations (MUMPS pivots, a Cholesky "not
/// positive definite") and capped increments varied from run to run. The decks now take the
/// grip from the scene, as the mesh does, and refuse a shift under the axial grip.
#[test]
#[ignore = "heavy: four deck runs (each deck twice); .ci/run runs it"]
fn the_decks_walk_a_frictional_path_with_history() {
    if !tools_present("the_decks_walk_a_frictional_path_with_history") {
        return;
    }
    let scene = frictional_scene();
    let h = scene.max_contact_radius() / 20.0;
    let mdr = solver::run(spherecontact::registry::by_name("mdr").unwrap().as_ref(), &scene).unwrap();
    let peak = mdr.peak(Quantity::TangentialForce);
    let mut histories = Vec::new();
    for deck in [at_resolution(FreeFem, h), at_resolution(Fenicsx, h)] {
        let history = solver::run(deck.as_ref(), &scene).unwrap();
        assert_eq!(history.metadata.extra["fourier_modes"], serde_json::json!([0, 1]));
        assert_eq!(history.metadata.extra["grip"], "rigid");
        assert_eq!(history.metadata.extra["capped_steps"], serde_json::json!([]));
        let q: Vec<f64> = history
            .steps
            .iter()
            .map(|r| r.tangential_force.unwrap())
            .collect();
        // Loading: Q rises; after the reversal at step 10 it falls.
        assert!(q[4..=10].windows(2).all(|w| w[1] > w[0]), "{q:?}");
        assert!(q[10..].windows(2).all(|w| w[1] < w[0]), "{q:?}");
        // Against exact MD on the half-space: the gripped hemisphere is ≈ 4 % softer in shear,
        // which puts Q 2.4 % below MD in partial slip and up to 3 % of the peak after a
        // reversal (measured on the paper path, docs/external-decks.md); 4 % of the peak.
        for (row, reference) in history.steps.iter().zip(&mdr.steps) {
            let error = (row.tangential_force.unwrap() - reference.tangential_force.unwrap()).abs() / peak;
            assert!(error < 4e-2, "{}: step {} Q error {error}", deck.name(), row.step);
        }
        // The stick zone: the whole contact before the shift, shrinking while Q rises.
        let stick: Vec<f64> = history
            .steps
            .iter()
            .map(|r| r.stick_radius.unwrap_or(0.0))
            .collect();
        assert_eq!(stick[4], history.steps[4].contact_radius.unwrap());
        assert!(
            stick[5..=10].windows(2).all(|w| w[1] <= w[0]) && stick[10] < 0.8 * stick[4],
            "{stick:?}"
        );
        assert!(
            stick[11] > stick[10],
            "the reversal sticks the contact again: {stick:?}"
        );
        // Fields at positions: |q_x| <= μ p everywhere, = μ p on slipping nodes in contact.
        let field = history.field_at(2).unwrap();
        let traction = field.traction.as_ref().unwrap();
        let sticking = field.stick.as_ref().unwrap();
        for ((q, p), &stuck) in traction.iter().zip(&field.pressure).zip(sticking) {
            let bound = scene.friction * p;
            assert!(
                q[0].abs() <= bound * (1.0 + 1e-9) + 1.0,
                "q {} > μp {bound}",
                q[0]
            );
            if *p > 0.0 && !stuck {
                assert!(
                    (q[0].abs() - bound).abs() <= 1e-9 * bound + 1.0,
                    "slip: q {} μp {bound}",
                    q[0]
                );
            }
        }
        // Reproducible: the same deck on the same scene gives the same Q within round-off.
        // Tolerance 1e-12 of the peak: dolfinx reruns are bit-identical (one BLAS thread);
        // FreeFEM's MUMPS_seq differs in the last bits (≈ 1e-14 relative, measured); the fault
        // this guards against (an unheld far face) moved Q by whole percents.
        let again = solver::run(deck.as_ref(), &scene).unwrap();
        for (a, b) in history.steps.iter().zip(&again.steps) {
            let (qa, qb) = (a.tangential_force.unwrap(), b.tangential_force.unwrap());
            assert!(
                (qa - qb).abs() <= 1e-12 * peak,
                "{}: step {}: {qa} then {qb}",
                deck.name(),
                a.step
            );
        }
        histories.push(history);
    }
    // Same model, mesh and increments; straight (FreeFEM) against curved (dolfinx) edges:
    // measured 4e-5 of the peak on the paper path at c/40; 5e-4 of the peak.
    for (a, b) in histories[0].steps.iter().zip(&histories[1].steps) {
        let error = (a.tangential_force.unwrap() - b.tangential_force.unwrap()).abs() / peak;
        assert!(
            error < 5e-4,
            "step {}: decks differ by {error} of the peak",
            a.step
        );
    }
}

/// A step whose contact iteration hits the cap is flagged in the metadata, not hidden and not a
/// failure: with a cap of one iteration, every step that needs a second is flagged.
#[test]
#[ignore = "heavy: a FreeFEM deck with its iterations capped; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn capped_iterations_are_flagged() {
    if !tools_present("capped_iterations_are_flagged") {
        return;
    }
    let scene = frictional_scene();
    let mut deck = AxisymSolver::new(FreeFem);
    deck.options.resolution = Some(scene.max_contact_radius() / 10.0);
    deck.options.max_iterations = Some(1);
    let history = solver::run(&deck, &scene).unwrap();
    let capped = history.metadata.extra["capped_steps"].as_array().unwrap();
    assert!(!capped.is_empty(), "{:?}", history.metadata.extra);
    assert!(
        history
            .metadata
            .warnings
            .iter()
            .any(|w| w.contains("hit its cap")),
        "{:?}",
        history.metadata.warnings
    );
}

/// Mesh convergence of Q along the frictional path: dolfinx on the pole sizes c/10 … c/80; the
/// largest change of Q between successive meshes (relative to the peak |Q|, over every step)
/// falls at least as h^1.5 (measured 1.9e-3, 4.4e-4, 1.3e-4: rates 2.2 and 1.7), so the mesh part
/// at the default c/40 is about 1.3e-4 of the peak. Heavy (≈ 2 min): `cargo test --release
/// --test suite external_friction:: -- --ignored`.
#[test]
#[ignore]
fn the_tangential_force_converges_on_the_mesh_ladder() {
    if !tools_present("the_tangential_force_converges_on_the_mesh_ladder") {
        return;
    }
    let scene = frictional_scene();
    let c = scene.max_contact_radius();
    let runs: Vec<Vec<f64>> = [10.0, 20.0, 40.0, 80.0]
        .iter()
        .map(|n| {
            let history = solver::run(at_resolution(Fenicsx, c / n).as_ref(), &scene).unwrap();
            history
                .steps
                .iter()
                .map(|r| r.tangential_force.unwrap())
                .collect()
        })
        .collect();
    let peak = runs[3].iter().fold(0.0_f64, |m, q| m.max(q.abs()));
    let changes: Vec<f64> = runs
        .windows(2)
        .map(|w| {
            w[0].iter()
                .zip(&w[1])
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
                / peak
        })
        .collect();
    eprintln!("largest change of Q between c/10, c/20, c/40, c/80 (of the peak): {changes:?}");
    for pair in changes.windows(2) {
        assert!(pair[1] < 0.5 * pair[0], "Q converges slower than h: {changes:?}");
    }
    assert!(
        changes[2] < 1e-3,
        "mesh part at c/40 above 0.1 % of the peak: {changes:?}"
    );
}
