//! Running cases: every solver a case needs, once each, then every check on their histories.

use crate::case::Case;
use crate::check::{Histories, Outcome};
use crate::progress;
use crate::solver::{self, SolveError};

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
    /// True when no check is NOOK or FIXED? (a known failure that passes) and every solver the
    /// case needs either ran or is not installed.
    pub fn passed(&self) -> bool {
        let solvers_ran = self
            .histories
            .values()
            .all(|r| matches!(r, Ok(_) | Err(SolveError::Unavailable(_))));
        solvers_ran && !self.outcomes.iter().any(|o| o.verdict.fails_run())
    }
}

/// Runs every solver the case needs and judges its checks. A solver that fails does not stop
/// the others; the checks that need it are NOOK (or N/A when it is not installed).
pub fn run_case(case: Case) -> CaseRun {
    run_case_with_progress(case, &mut |_, _, _| {})
}

/// [`run_case`], calling `progress(solver, index, count)` before each solver runs; a long solver
/// run is announced and metered on stderr ([`crate::progress`]).
pub fn run_case_with_progress(case: Case, progress: &mut dyn FnMut(&str, usize, usize)) -> CaseRun {
    let mut warnings = case.scene.warnings();
    let mut histories = Histories::new();
    let names = case.required_solvers();
    for (index, name) in names.iter().cloned().enumerate() {
        progress(&name, index, names.len());
        let result = match case.solver(&name) {
            Some(s) => progress::run(s.as_ref(), &case.scene, &format!("{} {name}", case.name())),
            None => Err(solver::SolveError::Unavailable(format!(
                "no solver `{name}` in this build"
            ))),
        };
        if let Ok(history) = &result {
            warnings.extend(history.metadata.warnings.iter().map(|w| format!("{name}: {w}")));
        }
        histories.insert(name, result);
    }
    let outcomes = case.checks.iter().map(|c| c.evaluate(&histories)).collect();
    CaseRun {
        case,
        warnings,
        histories,
        outcomes,
    }
}
