//! The one-screen summary printed after a report: which solvers ran, the check counts, and P
//! and Q of every solver at the case's focus position.

use std::fmt::Write;

use super::format_value;
use crate::check::Verdict;
use crate::text::one_line;
use crate::verify::CaseRun;

/// The summary text.
pub fn screen(run: &CaseRun) -> String {
    let focus = run.case.focus;
    let mut text = format!("{}: P and Q at position {focus}\n", run.case.name());
    let names = run.case.required_solvers();
    // The solver column as wide as the longest name (lammps-mindlin-rescale-force: 28).
    let width = names.iter().map(|n| n.chars().count()).max().unwrap_or(0);
    for name in names {
        let _ = match run.histories.get(&name) {
            Some(Ok(history)) => {
                let row = history.at_position(focus);
                writeln!(
                    text,
                    "  {name:<width$} P = {:>11} N   Q = {:>11} N   {:>9.3} ms",
                    format_value(row.and_then(|r| r.normal_force)),
                    format_value(row.and_then(|r| r.tangential_force)),
                    history.metadata.wall_time_s * 1e3
                )
            }
            Some(Err(e)) => writeln!(text, "  {name:<width$} missing: {}", one_line(&e.to_string())),
            None => writeln!(text, "  {name:<width$} not run"),
        };
    }
    for warning in super::figures::warnings(run) {
        let _ = writeln!(text, "  warning: {}", one_line(&warning.to_string()));
    }
    let count = |v: Verdict| run.outcomes.iter().filter(|o| o.verdict == v).count();
    let _ = writeln!(
        text,
        "checks: {} OK, {} NOOK, {} informational, {} not available, {} known failures, {} known failures that pass (FIXED?)",
        count(Verdict::Ok),
        count(Verdict::Nook),
        count(Verdict::Info),
        count(Verdict::Unavailable),
        count(Verdict::Known),
        count(Verdict::Fixed)
    );
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::Case;
    use crate::check::Histories;

    #[test]
    fn the_solver_column_is_as_wide_as_the_longest_name() {
        let long = "a-command-solver-named-at-length-35";
        let text = format!(
            "friction = 0.2\nsolvers = [\"hertz\", \"{long}\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
             [path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n\
             [[command_solvers]]\nname = \"{long}\"\ncommand = [\"true\"]\n"
        );
        let case = Case::parse(std::path::Path::new("wide.toml"), &text).unwrap();
        let run = CaseRun {
            case,
            warnings: Vec::new(),
            histories: Histories::new(),
            outcomes: Vec::new(),
        };
        let screen = screen(&run);
        let rows: Vec<&str> = screen.lines().filter(|l| l.ends_with("not run")).collect();
        assert_eq!(rows.len(), 2, "{screen}");
        // Both rows put "not run" in the same column, one space after the longest name.
        assert!(
            rows.iter().all(|r| r.len() == 2 + long.len() + " not run".len()),
            "{screen}"
        );
    }
}
