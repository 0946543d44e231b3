//! The check table printed by `verify`: one row per check, OK / NOOK / INFO / N/A with value,
//! reference, error, tolerance and the tolerance's reason.

use std::fmt::Write;

use super::format_value;
use crate::check::Outcome;
use crate::verify::CaseRun;

/// One printed row for a check outcome.
pub fn outcome_row(case: &str, outcome: &Outcome) -> String {
    let spec = &outcome.spec;
    let mut row = format!(
        "{:<5} {case} | {} {} at {}",
        outcome.verdict.label(),
        spec.solver,
        spec.quantity,
        spec.at
    );
    if let Some(step) = outcome.worst_step {
        let _ = write!(row, " (worst: step {step})");
    }
    let unit = spec.quantity.unit();
    let _ = write!(
        row,
        " | value {} {unit} | ref {} {unit} [{}] | error {} ({})",
        format_value(outcome.value),
        format_value(outcome.reference),
        spec.reference,
        format_value(outcome.error),
        spec.measure.name(),
    );
    match spec.tolerance {
        Some(t) => {
            let _ = write!(row, " | tol {}", format_value(Some(t)));
        }
        None => row.push_str(" | informational"),
    }
    if let Some(drift) = &outcome.drift {
        let _ = write!(
            row,
            " | drift {} (baseline {}, tol {})",
            format_value(Some(drift.change)),
            format_value(Some(drift.baseline)),
            format_value(Some(drift.tolerance))
        );
    }
    if let Some(message) = &outcome.message {
        let _ = write!(row, " | {message}");
    }
    if !spec.reason.is_empty() {
        let _ = write!(row, " | {}", spec.reason);
    }
    row
}

/// The whole block printed for one case: warnings, then a row per check.
pub fn case_block(run: &CaseRun) -> String {
    let mut text = format!("== {} ({})\n", run.case.name(), run.case.file.display());
    for warning in &run.warnings {
        let _ = writeln!(text, "WARN  {}: {warning}", run.case.name());
    }
    for (name, result) in &run.histories {
        if let Err(error) = result {
            let _ = writeln!(text, "SOLVER {name}: {error}");
        }
    }
    for outcome in &run.outcomes {
        let _ = writeln!(text, "{}", outcome_row(run.case.name(), outcome));
    }
    text
}
