//! Requirements every solver that produces a tangential force must meet, whatever its model
//! (MDR, Cattaneo–Mindlin, every DEM law in the registry — new laws are picked up automatically):
//! - Coulomb: |Q| ≤ μP at every step;
//! - μ = 0 gives Q = 0;
//! - an open gap gives zero force and clears the history: a contact made again without tangential
//!   motion carries no tangential force;
//! - nothing panics or gives NaN on any shipped case (hard cases included).
//!
//! These run the in-crate solvers ([`registry::in_crate`]): the decks and the real DEM codes meet
//! the same requirements in tests/external_friction.rs and tests/dem_codes.rs, and every shipped
//! case with every solver runs in CI's `verify --require-external` step, which fails on any
//! solver failure.

use crate::common;

use common::{all_case_files, paper_scene_with_path, paper_scene_with_substeps, root};
use spherecontact::case::Case;
use spherecontact::history::History;
use spherecontact::registry;
use spherecontact::scene::Scene;
use spherecontact::solver::{self, SolveError, Solver};

/// Runs every registered solver that gives a tangential force on `scene`; skips those that do
/// not apply to it (Cattaneo–Mindlin under a varying load) or are not installed.
fn tangential_histories(scene: &Scene) -> Vec<(String, History)> {
    registry::in_crate()
        .iter()
        .filter_map(|s| match solver::run(s.as_ref(), scene) {
            Ok(h) if h.steps.iter().any(|r| r.tangential_force.is_some()) => Some((s.name().to_owned(), h)),
            Ok(_) | Err(SolveError::NotApplicable(_)) | Err(SolveError::Unavailable(_)) => None,
            Err(e) => panic!("{}: {e}", s.name()),
        })
        .collect()
}

fn assert_coulomb(scene: &Scene) {
    let histories = tangential_histories(scene);
    assert!(histories.len() >= 2, "at least MDR and one law must run");
    for (name, history) in histories {
        for row in &history.steps {
            let (p, q) = (row.normal_force.unwrap(), row.tangential_force.unwrap());
            // Tolerance: one rounding of μP (the cap is applied as a clamp to ±μP).
            assert!(
                q.abs() <= scene.friction * p * (1.0 + 1e-12),
                "{name} step {}: |Q| = {q} > μP = {}",
                row.step,
                scene.friction * p
            );
        }
    }
}

#[test]
fn coulomb_bound_holds_on_the_paper_path() {
    assert_coulomb(&paper_scene_with_substeps(50));
}

#[test]
fn coulomb_bound_holds_with_reversal_at_every_step() {
    let zigzag: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
        .chain((0..60).map(|k| {
            (
                12.0 + 0.1 * k as f64,
                if k % 2 == 0 { 0.3 } else { -0.2 } * (1.0 + k as f64 / 10.0),
            )
        }))
        .collect();
    assert_coulomb(&paper_scene_with_path(&zigzag, 1));
}

#[test]
fn frictionless_contact_carries_no_tangential_force() {
    let mut scene = paper_scene_with_substeps(20);
    scene.friction = 0.0;
    for (name, history) in tangential_histories(&scene) {
        assert!(
            history.steps.iter().all(|r| r.tangential_force == Some(0.0)),
            "{name}: Q ≠ 0 with μ = 0"
        );
    }
}

#[test]
fn separation_gives_zero_force_and_clears_history() {
    // Partial slip at 10 µm, separation while δt still moves, a gap, then re-contact at fixed δt:
    // with the history cleared, Q must be exactly zero on re-contact.
    let path = [
        (0.0, 0.0),
        (10.0, 0.0),
        (10.0, 1.5),
        (0.0, 3.0),
        (-2.0, 3.5),
        (10.0, 3.5),
    ];
    let scene = paper_scene_with_path(&path, 40);
    for (name, history) in tangential_histories(&scene) {
        for k in [3, 4] {
            let row = history.at_position(k).unwrap();
            assert_eq!(
                (row.normal_force, row.tangential_force),
                (Some(0.0), Some(0.0)),
                "{name} at position {k}"
            );
        }
        let recontact = history.at_position(5).unwrap();
        assert!(recontact.normal_force.unwrap() > 0.0);
        assert_eq!(
            recontact.tangential_force,
            Some(0.0),
            "{name} kept history across separation"
        );
        let slipping = history.at_position(2).unwrap().tangential_force.unwrap();
        assert!(slipping > 0.0, "{name}: no tangential force in partial slip");
    }
}

#[test]
#[ignore = "heavy: every law on every shipped case, 12 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn every_solver_runs_every_shipped_case_without_failure() {
    // solver::run rejects non-finite values, so this also asserts "no NaN anywhere".
    for file in all_case_files() {
        let case = Case::load(&file).unwrap_or_else(|e| panic!("{e}"));
        for name in case.solvers.iter().filter(|s| registry::is_in_crate(s)) {
            let solver: Box<dyn Solver> = case.solver(name).unwrap();
            match solver::run(solver.as_ref(), &case.scene) {
                Ok(_) | Err(SolveError::Unavailable(_)) => {}
                Err(e) => panic!(
                    "{} on {}: {e}",
                    name,
                    file.strip_prefix(root()).unwrap().display()
                ),
            }
        }
    }
}
