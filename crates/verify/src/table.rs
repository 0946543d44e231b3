//! The check table printed by `verify`: one row per check, OK / NOOK / INFO / N/A / KNOWN /
//! FIXED? with value, reference, error, tolerance and the tolerance's reason; a message over lines
//! (a failed program's last output) with its first line in the row and the rest under it, indented.

use std::fmt::Write;

use crate::CaseRun;
use spherecontact_check::judged::{Row, Suite};
use spherecontact_check::Outcome;
use spherecontact_model::number::format_value;
use spherecontact_system::text::{one_line, row_lines};

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
    // A message over lines (a program's last output): its first line in the row, the rest below.
    let (message, more) = outcome.message.as_deref().map(row_lines).unzip();
    spherecontact_check::row::push_judgement(
        &mut row,
        spec.tolerance,
        outcome.drift.as_ref(),
        message.as_deref(),
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
    // One line, whatever the case's texts hold: a reason cannot start or redraw another row; a
    // message's further lines under it, indented.
    one_line(&row).into_owned() + more.as_deref().unwrap_or("")
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
            let error = error.to_string();
            let (first, more) = row_lines(&error);
            let _ = writeln!(text, "SOLVER {name}: {first}{more}");
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

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_model::solver::SolveError;

    /// Requirement (issue 39, "Messages"): a failed program's last output prints as lines, never
    /// as a literal `\n`: in the SOLVER line and in its checks' rows the first line where it was,
    /// each further line under it behind the indent, so that no line of the output can pass for
    /// a row (`NOOK …` at a line's start) and its controls are escaped.
    #[test]
    fn a_failed_program_s_output_prints_as_indented_lines() {
        let case = spherecontact_case::Case::parse(
            std::path::Path::new("c.toml"),
            "friction = 0.2\nsolvers = [\"hertz\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
             [path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n\
             [[checks]]\nsolver = \"hertz\"\nquantity = \"normal_force\"\nat = \"every-step\"\n\
             reference = { solver = \"hertz\" }\ntolerance = 1e-12\nreason = \"r\"\n",
        )
        .unwrap();
        let failure = "mine exited with code 3; last output:\nNOOK fake row\nbad mesh\x1b[2K";
        let mut histories = spherecontact_check::Histories::new();
        histories.insert("hertz".into(), Err(SolveError::Failed(failure.into())));
        let outcomes = case.checks.iter().map(|c| c.evaluate(&histories)).collect();
        let run = CaseRun {
            case,
            warnings: vec![],
            histories,
            outcomes,
        };
        let block = case_block(&run);
        assert!(!block.contains("\\n"), "{block}");
        let lines: Vec<&str> = block.lines().collect();
        let at = lines
            .iter()
            .position(|l| l.starts_with("SOLVER hertz: failed: mine exited with code 3; last output:"))
            .unwrap_or_else(|| panic!("{block}"));
        assert_eq!(lines[at + 1], "      NOOK fake row");
        assert_eq!(lines[at + 2], "      bad mesh\\u{1b}[2K");
        let row = lines.iter().position(|l| l.starts_with("NOOK  c |")).unwrap();
        assert!(
            lines[row].ends_with("| hertz: failed: mine exited with code 3; last output: | r"),
            "{block}"
        );
        assert_eq!(&lines[row + 1..row + 3], &lines[at + 1..at + 3]);
        assert_eq!(block.lines().filter(|l| l.starts_with("NOOK")).count(), 1);
    }
}
