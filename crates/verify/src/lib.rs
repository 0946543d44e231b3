//! # spherecontact-verify: the verification job
//!
//! **Job.** Cases run and judged: the plan (what runs, on how many cores), the schedule, baselines (non-regression on every value), shards, run files, merge, Slurm, and the check table they print.
//!
//! **May depend on.** Every crate below it; nothing of the reports.
//!
//! **Offers.** `run_case`, `judge`, `plan`, `schedule`, `baseline`, `runfile`, `merge`, `slurm`.
//!
//! Running cases: every solver a case needs, once each, then every check on their histories.

pub mod baseline;
pub mod bench;
pub mod merge;
pub mod plan;
pub mod runfile;
pub mod schedule;
pub mod slurm;

pub mod table;

use spherecontact_case::Case;
use spherecontact_check::{Histories, Outcome};
use spherecontact_model::history::History;
use spherecontact_model::solver;
use spherecontact_model::solver::SolveError;

/// A case after its solvers ran and its checks were judged.
#[derive(Debug)]
pub struct CaseRun {
    /// The case.
    pub case: Case,
    /// What the scene and the solvers warned about.
    pub warnings: Vec<String>,
    /// Each solver's history, or why it has none.
    pub histories: Histories,
    /// Each check's outcome, in the case's order.
    pub outcomes: Vec<Outcome>,
}

impl CaseRun {
    /// True when no check fails the run (NOOK, DRIFT, or FIXED?: a known failure that passes)
    /// and every solver the case needs either ran or is not installed.
    pub fn passed(&self) -> bool {
        let solvers_ran = self
            .histories
            .values()
            .all(|r| matches!(r, Ok(_) | Err(SolveError::Unavailable(_))));
        solvers_ran && !self.outcomes.iter().any(|o| o.verdict.fails_run())
    }
}

/// Runs every solver the case needs and judges its checks. A solver that fails does not stop
/// the others; the checks that need it are NOOK (or N/A when it is not installed). The solvers
/// run one after another, each long run announced and metered on stderr ([`spherecontact_model::progress`]);
/// `crate::schedule::run_cases` runs them concurrently.
pub fn run_case(case: Case) -> CaseRun {
    let results = case
        .required_solvers()
        .into_iter()
        .map(|name| {
            let result = run_solver(&case, &name);
            (name, result)
        })
        .collect();
    judge(case, results)
}

/// Runs the case's solver called `name` (a long run announced and metered on stderr,
/// [`spherecontact_model::progress`]).
pub fn run_solver(case: &Case, name: &str) -> Result<History, SolveError> {
    match case.solver(name) {
        Some(s) => solver::run_reported(s.as_ref(), &case.scene, &format!("{} {name}", case.name())),
        None => Err(SolveError::Unavailable(format!(
            "no solver `{name}` in this build"
        ))),
    }
}

/// Judges the case's checks on its solvers' `results` (in the case's order). A check that needs
/// a solver not among them is left out: a shard judges only the checks whose solvers it ran
/// (`verify --shard`), the merge of all shards judges every check.
pub fn judge(case: Case, results: Vec<(String, Result<History, SolveError>)>) -> CaseRun {
    let mut warnings = case.scene.warnings();
    for (name, result) in &results {
        if let Ok(history) = result {
            warnings.extend(history.metadata.warnings.iter().map(|w| format!("{name}: {w}")));
        }
    }
    let histories: Histories = results.into_iter().collect();
    let outcomes = case
        .checks
        .iter()
        .filter(|c| c.solvers().all(|name| histories.contains_key(name)))
        .map(|c| c.evaluate(&histories))
        .collect();
    CaseRun {
        case,
        warnings,
        histories,
        outcomes,
    }
}
