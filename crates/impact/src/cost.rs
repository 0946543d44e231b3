//! The wall-time model of an impact run, to announce a long sweep before it starts and to cost it
//! in a verification plan (`plan` (spherecontact-verify)): integration steps × springs × sweep points ×
//! variants for the harness's own laws, a start-up and a cost a step for the DEM codes (one
//! process a sweep, [`super::code_run::Code::estimated_seconds`]).
//!
//! An impact takes about `steps` integration steps (h = t_c / `steps`, the contact lasting one
//! Hertz duration t_c when elastic, a little less when damped: [`super::budget::STEP_BUDGET`] bounds
//! it at four). Each step costs the integrator and the law; MDR's bed walks the springs in
//! contact, a prefix of the bed that grows and shrinks with the contact (about 70 % of the bed
//! on average over an impact, folded into [`MDR_SPRING_STEP`]).
//!
//! The constants were measured in a release build on the shared 2-core development machine at a
//! load of about 9 (`cargo run --release --example impact_estimate`, with `--steps 20000` and
//! `--springs 40000` or `400000` for the fit; docs/impact.md "Estimate and progress"), against
//! both the wall time and the CPU time of each run, which differed by a factor of about 2.5 at
//! that load; each is set between the two. Checked on the shipped cases at loads about 5 and 3.5: wall
//! / estimate 0.36–1.96 for every run above a millisecond, CPU / estimate 0.19–0.95 (an idle
//! machine runs faster than the estimate). The model leaves out what varies from point to point
//! (stick and slip, the damped rebound's shorter contact, the cache once a large bed no longer
//! fits), so it is coarse: within the factor of about 3 that [`spherecontact_model::progress`] states.

use super::case::ImpactCase;
use super::code_rule;
use super::code_run::Code;
use spherecontact_reference::impact::own_solver::Source;

/// One integration step with a DEM law (the integrator, the law's increment, the damping) [s]:
/// measured 4e-8 to 8e-8 of CPU and 4e-8 to 2.5e-7 of wall time a step (thornton, walton-braun,
/// hertz-mindlin-spring, md-incremental over the shipped sweeps, at 2000 and 20 000 steps a
/// contact; the shortest runs, 0.1 ms, the noisiest).
pub const LAW_STEP: f64 = 1.0e-7;

/// One spring of MDR's bed over one integration step [s]: measured 1.6e-9 to 2.3e-9 of CPU and
/// 3.9e-9 to 6.1e-9 of wall time (`mdr`, `mdr-lammps`, `mdr-yade` over the shipped sweeps at 4000
/// springs; test 4 at 20 000 steps and at 40 000 springs, test 1 at 400 000 springs: linear in
/// both, the largest bed 30 % dearer a spring).
pub const MDR_SPRING_STEP: f64 = 3.0e-9;

/// A case's own program over one variant's sweep [s]: unknown beforehand (it is the user's);
/// the plan needs a cost to balance shards by until a baseline records the measured one.
pub const OWN_PROGRAM_SECONDS: f64 = 1.0;

/// The integration steps of one impact of `case`.
fn steps_per_point(case: &ImpactCase) -> f64 {
    case.steps as f64
}

/// The sweep points of a run of `case` (one solver): every point in every variant.
pub fn points(case: &ImpactCase) -> usize {
    case.points().len() * case.variants().len()
}

/// The expected wall time of `solver` over `case`'s sweep in one variant [s].
fn sweep_seconds(case: &ImpactCase, solver: &str) -> f64 {
    let steps = steps_per_point(case) * case.points().len() as f64;
    if let Some(own) = case.own_solver(solver) {
        return match own.source {
            Source::Stored { .. } => 0.0,
            Source::Command { .. } => OWN_PROGRAM_SECONDS,
        };
    }
    match Code::named(solver) {
        Some(code) => code.estimated_seconds(steps),
        None if code_rule::is_reference(solver) => (LAW_STEP + MDR_SPRING_STEP * case.springs as f64) * steps,
        None => LAW_STEP * steps,
    }
}

/// The expected wall time of `solver` over `case`'s sweep in every variant [s]: what `verify`'s
/// plan costs the run at when no baseline records it, and what is announced before it runs.
pub fn seconds(case: &ImpactCase, solver: &str) -> f64 {
    sweep_seconds(case, solver) * case.variants().len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_reference::impact::problem::{Sweep, SweepVariable};

    fn case(name: &str) -> ImpactCase {
        spherecontact_case::load_impact(
            &spherecontact_model::fixtures::repository().join(format!("cases/impact/{name}.toml")),
        )
        .unwrap()
    }

    /// `case` with `count` incident angles.
    fn swept(mut case: ImpactCase, count: usize) -> ImpactCase {
        let values = (0..count).map(|i| 0.01 + 1.5 * i as f64 / count as f64).collect();
        case.sweep = Some(Sweep {
            variable: SweepVariable::IncidentAngle,
            values,
            body2_spin: spherecontact_reference::impact::problem::Body2Spin::Kept,
        });
        case
    }

    /// Requirement: the estimate of an impact run grows with its size, integration steps ×
    /// springs × sweep points × variants (reference values of the model's constants).
    #[test]
    fn the_estimate_grows_with_the_sweep_the_steps_the_springs_and_the_variants() {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        // Test 4: 17 angles, 2000 steps, 4000 springs, e = 0.98 (two variants): 0.82 s (measured
        // 0.43 to 0.67 s of CPU, 1.1 to 1.7 s of wall time at load 9).
        let four = case("chung-ooi-4");
        let mdr = (1e-7 + 3e-9 * 4000.0) * 2000.0 * 17.0 * 2.0;
        assert!(close(seconds(&four, "mdr"), mdr), "{}", seconds(&four, "mdr"));
        assert!(close(mdr, 0.8228), "{mdr}");
        assert!(close(seconds(&four, "thornton"), 1e-7 * 2000.0 * 34.0));
        assert_eq!(points(&four), 34);
        // A 200-angle damped sweep at the finest steps and springs a case may ask for: 33 h
        // (issue 42 measured about 20 h; 10 h elastic).
        let mut heavy = swept(four.clone(), 200);
        (heavy.steps, heavy.springs) = (100_000, 1_000_000);
        let hours = seconds(&heavy, "mdr") / 3600.0;
        assert!(close(hours, (1e-7 + 3e-3) * 1e5 * 400.0 / 3600.0), "{hours}");
        assert!((33.0..34.0).contains(&hours), "{hours}");
        // Linear in each factor.
        assert!(close(seconds(&swept(four.clone(), 170), "mdr"), 10.0 * mdr));
        let mut elastic = four.clone();
        elastic.restitution = 1.0;
        assert!(close(seconds(&elastic, "mdr"), mdr / 2.0));
        assert_eq!(points(&elastic), 17);
    }

    /// Requirement: a DEM code's run is one process a sweep: its start-up once a variant, and its
    /// cost a step over every point (reference values of the constants).
    #[test]
    fn a_dem_codes_run_costs_a_start_up_a_variant_and_its_steps() {
        let four = case("chung-ooi-4");
        let lammps = Code::named("lammps-mindlin").unwrap();
        for (solver, code, start_up, step) in [
            ("lammps-mindlin", lammps, 0.6, 4e-5),
            ("yade-mindlin", Code::Yade, 3.0, 4e-5),
        ] {
            // Two variants, 17 points of 2000 steps each.
            let want = 2.0 * (start_up + step * 34_000.0);
            assert!((seconds(&four, solver) - want).abs() < 1e-12, "{solver}");
            assert_eq!(seconds(&four, solver), 2.0 * code.estimated_seconds(34_000.0));
            let ten = seconds(&swept(four.clone(), 170), solver);
            assert!(
                (ten - 2.0 * (start_up + step * 340_000.0)).abs() < 1e-9,
                "{solver}"
            );
        }
    }
}
