//! How ccx reports an error: ccx exits with code 0 after some fatal errors, so a line holding
//! `*ERROR` in its output makes a run a failure, shown with ccx's own words for the harness's run
//! and by its line for a folder run elsewhere.

use std::path::Path;

use crate::deck::LOG_STEM;
use crate::readback::read_output;
use spherecontact_model::limits::MAX_DECK_LOG_BYTES;
use spherecontact_model::solver::SolveError;

/// ccx exits with code 0 after some fatal errors (an input file it cannot open): a line holding
/// `*ERROR` in its output makes the run a failure. The index of the first such line of `stdout`.
fn first_error(stdout: &str) -> Option<usize> {
    stdout.lines().position(|l| l.contains("*ERROR"))
}

/// The error ccx reported in the `deck.stdout` of a folder its deck ran in elsewhere (`run.sh`
/// logs there), named by its line and not quoted: the folder is foreign input (docs/security.md,
/// "Deck folders"); the solver's own run shows ccx's words ([`reported_error`]).
pub fn logged_error(dir: &Path) -> Result<(), SolveError> {
    let name = format!("{LOG_STEM}.stdout");
    let stdout = read_output(dir, &name, MAX_DECK_LOG_BYTES).map_err(SolveError::Failed)?;
    match first_error(&stdout) {
        Some(line) => Err(SolveError::Failed(format!(
            "{}:{}: ccx reported an error (a line with `*ERROR`) and exited with code 0 (allowed: a \
             log without `*ERROR`; that line and the next say what went wrong)",
            dir.join(&name).display(),
            line + 1
        ))),
        None => Ok(()),
    }
}

/// The error ccx reported in the output `stdout` of the harness's own run of it, with its first
/// lines (a program's output, shown as every program's is).
pub fn reported_error(stdout: &str) -> Result<(), SolveError> {
    match first_error(stdout) {
        Some(error) => {
            let lines: Vec<&str> = stdout.lines().skip(error).take(6).collect();
            Err(SolveError::Failed(format!(
                "ccx reported an error and exited with code 0: {}",
                lines.join("\n")
            )))
        }
        None => Ok(()),
    }
}
