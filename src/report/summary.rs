//! The one-screen summary printed after a report: which solvers ran, the check counts, and P
//! and Q of every solver at the case's focus position.

use std::fmt::Write;

use super::format_value;
use crate::check::Verdict;
use crate::verify::CaseRun;

/// The summary text.
pub fn screen(run: &CaseRun) -> String {
    let focus = run.case.focus;
    let mut text = format!("{}: P and Q at position {focus}\n", run.case.name());
    for name in run.case.required_solvers() {
        let _ = match run.histories.get(&name) {
            Some(Ok(history)) => {
                let row = history.at_position(focus);
                writeln!(
                    text,
                    "  {name:<22} P = {:>11} N   Q = {:>11} N   {:>9.3} ms",
                    format_value(row.and_then(|r| r.normal_force)),
                    format_value(row.and_then(|r| r.tangential_force)),
                    history.metadata.wall_time_s * 1e3
                )
            }
            Some(Err(e)) => writeln!(text, "  {name:<22} missing: {e}"),
            None => writeln!(text, "  {name:<22} not run"),
        };
    }
    for warning in super::figures::warnings(run) {
        let _ = writeln!(text, "  warning: {warning}");
    }
    let count = |v: Verdict| run.outcomes.iter().filter(|o| o.verdict == v).count();
    let _ = writeln!(
        text,
        "checks: {} OK, {} NOOK, {} informational, {} not available",
        count(Verdict::Ok),
        count(Verdict::Nook),
        count(Verdict::Info),
        count(Verdict::Unavailable)
    );
    text
}
