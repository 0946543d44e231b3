//! One run of a program as a solver: in a fresh temporary folder that is removed on success and
//! kept (and named in the message) on failure, with the program's ending put into words.
//!
//! Shared by the command solvers a case names and the DEM codes driven through generated input
//! (`crate::dem`); the process handling itself is [`spherecontact_system::process`].

use std::path::Path;
use std::time::Duration;

use super::deck::RunDir;
use spherecontact_model::limits::MAX_SHOWN_LINES;
use spherecontact_model::solver::SolveError;
use spherecontact_system::process::{self, Environment, Job, Run};

/// Runs `work` in a fresh folder named after `solver`; a failure keeps the folder and says where.
pub fn in_run_folder<T>(
    solver: &str,
    work: impl FnOnce(&Path) -> Result<T, SolveError>,
) -> Result<T, SolveError> {
    in_run_folder_kept_if(solver, |dir| work(dir).map(|value| (value, false)))
}

/// [`in_run_folder`], the folder also kept on success when `work` says so (its second value: an
/// output refused in part, whose reasons name the folder, [`kept_in`]).
pub fn in_run_folder_kept_if<T>(
    solver: &str,
    work: impl FnOnce(&Path) -> Result<(T, bool), SolveError>,
) -> Result<T, SolveError> {
    let mut dir = RunDir::new(&format!("spherecontact-{solver}-"))
        .map_err(|e| SolveError::Failed(format!("no temporary directory: {e}")))?;
    match work(dir.path()) {
        Err(SolveError::Failed(message)) => {
            Err(SolveError::Failed(format!("{message} {}", kept_in(&dir.keep()))))
        }
        Ok((value, keep)) => {
            if keep {
                dir.keep();
            }
            Ok(value)
        }
        Err(other) => Err(other),
    }
}

/// What a message adds of a run folder kept for inspection.
pub fn kept_in(dir: &Path) -> String {
    format!("(input, stdout and stderr kept in {})", dir.display())
}

/// Runs `job` in `dir` in `environment` (stdout and stderr in `<stem>.stdout`, `<stem>.stderr`)
/// and turns any ending but exit code 0 into a failure with the last lines of its output;
/// `meaning` puts the program's own exit codes into words.
pub fn run_to_success(
    job: &Job,
    dir: &Path,
    stem: &str,
    program: &str,
    meaning: impl Fn(i32) -> &'static str,
    environment: &Environment,
) -> Result<Run, SolveError> {
    let run = process::run_in(job, dir, stem, environment)
        .map_err(|e| SolveError::Failed(format!("{program} could not start: {e}")))?;
    match run.ending.failure(program, job.timeout, meaning) {
        Some(why) => Err(SolveError::Failed(format!(
            "{why}; last output:\n{}",
            run.tail(MAX_SHOWN_LINES)
        ))),
        None => Ok(run),
    }
}

/// The time limit for a program that takes `per_step` for each of `steps` steps after
/// `start_up`.
pub fn time_limit(start_up: Duration, per_step: Duration, steps: usize) -> Duration {
    start_up + per_step.saturating_mul(u32::try_from(steps).unwrap_or(u32::MAX))
}
