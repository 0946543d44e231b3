//! # spherecontact-impact: impact runs
//!
//! **Job.** Running the impact benchmarks: every law and DEM code of an impact case over its sweep, beside the exact reference, and the case's checks on their outcomes.
//!
//! **May depend on.** `spherecontact-model`, `spherecontact-system`, `spherecontact-reference` (the impact dynamics), `spherecontact-external` (LAMMPS, YADE and LIGGGHTS), `spherecontact-check`, `spherecontact-case`.
//!
//! **Offers.** `ImpactRun`, `run::run_case`, and the DEM codes' impact adapters.
//!
//! Dynamic impact of two spheres (or a sphere on a rigid flat): the DEM benchmarks of Chung &
//! Ooi (2011, Granular Matter 13:643–656), with the exact quasi-static reference.
//!
//! An impact case (`kind = "impact"`, `cases/impact/`) describes bodies with density, initial
//! velocities and spins, friction, an optional prescribed restitution and a sweep of one initial
//! condition ([`case`]). Each solver is a contact law ([`law`]) integrated with the rigid-body
//! dynamics of both bodies ([`integrator`]); `mdr` — MDR's spring bed, exact Mindlin–Deresiewicz
//! for any oblique history of elastically similar bodies — makes the integration the exact
//! quasi-static theory of oblique impact; the DEM laws of [`spherecontact_reference`] run in its place.
//! The outcome of each impact ([`outcome`]) is written per solver ([`files`]) and judged by the
//! case's checks ([`judge`]): Hertz's closed forms of normal impact ([`closed_form`]) and the
//! exact reference.
//!
//! **Why not the [`spherecontact_model::solver::Solver`] trait.** A `Solver` maps a scene's prescribed path
//! (δn, δt at every step) to forces: the motion is the input. In an impact the motion is the
//! output — the path is not known before the forces are — and the result is not a history of
//! the path's steps but the rebound (restitutions, spins, angles) of each sweep point. A contact
//! law that answers one increment at a time ([`law::ContactLaw`]) is what both need: MDR's bed
//! and the DEM laws' incremental updates are reused as they are (not copied) through it.
//!
//! docs/impact.md holds the conventions, the damping law and the measured convergence.

// The exact impact dynamics live in the reference crate (spherecontact-reference, `impact`);
// the impact runs and their users name them from here.
pub use spherecontact_reference::impact::problem as case;
pub use spherecontact_reference::impact::{closed_form, integrator, law, outcome};
mod budget;
pub mod code_readback;
pub mod code_rule;
pub mod code_run;
pub mod cost;
#[cfg(test)]
mod cross_check;
pub mod files;
pub mod judge;
pub mod kratos;
pub mod lammps;
pub mod liggghts;
pub mod own_run;
pub mod own_scene;
pub mod placement;
pub mod run;
pub mod solver_run;
mod tally;
pub mod yade;

pub use case::ImpactCase;

/// A case run: its solvers' runs and its checks' outcomes.
#[derive(Debug)]
pub struct ImpactRun {
    /// The case.
    pub case: ImpactCase,
    /// Every solver in every variant.
    pub runs: Vec<solver_run::SolverRun>,
    /// The checks' outcomes, in the case's order.
    pub outcomes: Vec<judge::CheckOutcome>,
}

impl ImpactRun {
    /// Runs every solver the case and its checks need, and judges the checks.
    pub fn of(case: ImpactCase) -> Self {
        let runs = run::run_case(&case, &case.required_solvers());
        Self::judged(case, runs)
    }

    /// The case judged on `runs` (a shard's: the checks whose solvers all ran).
    pub fn judged(case: ImpactCase, runs: Vec<solver_run::SolverRun>) -> Self {
        let outcomes = judge::judge(&case, &runs);
        Self { case, runs, outcomes }
    }

    /// True when no check fails the run (NOOK, DRIFT) and every available solver ran at every
    /// sweep point (a DEM code not installed makes its checks N/A, as `verify` treats every
    /// missing solver; `--require-external` fails on N/A).
    pub fn passed(&self) -> bool {
        let solved = self
            .runs
            .iter()
            .filter(|r| r.unavailable.is_none())
            .all(|r| r.points.iter().all(|(_, o)| o.is_ok()));
        solved && !self.outcomes.iter().any(|o| o.verdict.fails_run())
    }

    /// True when a solver could not run at all (a DEM code not installed): `verify
    /// --require-external` counts that as a failure.
    pub fn lacks_a_solver(&self) -> bool {
        self.runs.iter().any(|r| r.unavailable.is_some())
    }

    /// The block `verify` prints: a row per check, and each failed sweep point.
    pub fn block(&self) -> String {
        let file = self.case.file.display().to_string();
        let mut text = format!(
            "== {} ({})\n",
            self.case.name,
            spherecontact_system::text::one_line(&file)
        );
        for run in &self.runs {
            if let Some(why) = &run.unavailable {
                text.push_str(&format!(
                    "N/A   {} ({}): not available: {why}\n",
                    run.solver,
                    run.variant.name()
                ));
                continue;
            }
            for (at, result) in &run.points {
                if let Err(e) = result {
                    let (first, more) = spherecontact_system::text::row_lines(e);
                    text.push_str(&format!(
                        "SOLVER {} ({}) at {}: {first}{more}\n",
                        run.solver,
                        run.variant.name(),
                        spherecontact_model::number::format_value(*at),
                    ));
                }
            }
        }
        for outcome in &self.outcomes {
            text.push_str(&judge::outcome_row(&self.case.name, outcome));
            text.push('\n');
        }
        text
    }

    /// The case's judged checks as the verification job lists them ([`spherecontact_check::judged`]).
    pub fn suite(&self) -> spherecontact_check::judged::Suite {
        let rows = self
            .outcomes
            .iter()
            .enumerate()
            .map(|(i, outcome)| spherecontact_check::judged::Row {
                title: format!("{i:02} {}", outcome.check.key()),
                verdict: outcome.verdict,
                text: judge::outcome_row(&self.case.name, outcome),
            })
            .collect();
        spherecontact_check::judged::Suite {
            name: self.case.name.clone(),
            block: self.block(),
            rows,
            passed: self.passed(),
            no_baseline: None,
        }
    }
}
