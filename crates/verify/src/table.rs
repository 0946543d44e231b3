//! The check table printed by `verify`: one row per check, OK / NOOK / INFO / N/A / KNOWN /
//! FIXED? with value, reference, error, tolerance and the tolerance's reason.

use std::fmt::Write;

use crate::CaseRun;
use spherecontact_check::judged::{Row, Suite};
use spherecontact_check::Outcome;
use spherecontact_model::number::format_value;
use spherecontact_system::text::one_line;

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
    spherecontact_check::row::push_judgement(
        &mut row,
        spec.tolerance,
        outcome.drift.as_ref(),
        outcome.message.as_deref(),
    );
    if !spec.reason.is_empty() {
        let _ = write!(row, " | {}", spec.reason);
    }
    if let Some(evidence) = &spec.known_failure {
        let _ = write!(row, " | known failure: {evidence}");
    }
    if outcome.verdict == spherecontact_check::Verdict::Fixed {
        row.push_str(" | A KNOWN FAILURE PASSES: the defect may be fixed; remove its known_failure mark");
    }
    // One line, whatever the case's texts hold: a reason cannot start or redraw another row.
    one_line(&row).into_owned()
}

/// The whole block printed for one case: warnings, then a row per check.
pub fn case_block(run: &CaseRun) -> String {
    let file = run.case.file.display().to_string();
    let mut text = format!("== {} ({})\n", run.case.name(), one_line(&file));
    for warning in &run.warnings {
        let _ = writeln!(text, "WARN  {}: {}", run.case.name(), one_line(warning));
    }
    for (name, result) in &run.histories {
        if let Err(error) = result {
            let _ = writeln!(text, "SOLVER {name}: {}", one_line(&error.to_string()));
        }
    }
    for outcome in &run.outcomes {
        let _ = writeln!(text, "{}", outcome_row(run.case.name(), outcome));
    }
    text
}

/// The case's judged checks as the verification job lists them ([`spherecontact_check::judged`]).
pub fn suite(run: &CaseRun) -> Suite {
    let name = run.case.name();
    let rows = run
        .outcomes
        .iter()
        .enumerate()
        .map(|(i, outcome)| {
            let spec = &outcome.spec;
            Row {
                title: format!(
                    "{i:02} {} {} at {} vs {}",
                    spec.solver, spec.quantity, spec.at, spec.reference
                ),
                verdict: outcome.verdict,
                text: outcome_row(name, outcome),
            }
        })
        .collect();
    Suite {
        name: name.to_owned(),
        block: case_block(run),
        rows,
        passed: run.passed(),
        no_baseline: None,
    }
}
