//! The one-screen summary printed after a report: the verdict counts, the checks a reader must
//! look at first (the most severe, the largest errors), the slowest solvers, and what did not run.

use std::fmt::Write;

use super::glance::{seconds, verdict_counts, weight, worst_text};
use spherecontact_check::Outcome;
use spherecontact_system::text::row_lines;
use spherecontact_verify::CaseRun;

/// How many checks and solvers each list of the screen shows: the screen stays one screen
/// (about 25 lines) whatever the case's size.
const SHOWN: usize = 5;

/// The summary text.
pub fn screen(run: &CaseRun) -> String {
    let names = run.case.required_solvers();
    let ran: Vec<(&String, f64)> = names
        .iter()
        .filter_map(|n| Some((n, run.histories.get(n)?.as_ref().ok()?.metadata.wall_time_s)))
        .collect();
    let mut text = format!(
        "{}: checks {}; solvers {} of {} ran\n",
        run.case.name(),
        verdict_counts(&run.outcomes),
        ran.len(),
        names.len()
    );
    let mut outcomes: Vec<&Outcome> = run.outcomes.iter().collect();
    outcomes.sort_by(|a, b| {
        weight(b)
            .0
            .cmp(&weight(a).0)
            .then(weight(b).1.total_cmp(&weight(a).1))
    });
    if !outcomes.is_empty() {
        let _ = writeln!(
            text,
            "worst checks (the most severe, then the largest against its tolerance):"
        );
    }
    let width = names.iter().map(|n| n.chars().count()).max().unwrap_or(0);
    for o in outcomes.iter().take(SHOWN) {
        let _ = writeln!(text, "  {:<width$} {}", o.spec.solver, worst_text(o));
    }
    let mut slowest = ran.clone();
    slowest.sort_by(|a, b| b.1.total_cmp(&a.1));
    if !slowest.is_empty() {
        let list: Vec<String> = slowest
            .iter()
            .take(SHOWN)
            .map(|(n, s)| format!("{n} {}", seconds(*s)))
            .collect();
        let _ = writeln!(text, "slowest solvers: {}", list.join(", "));
    }
    // The solver column as wide as the longest name (lammps-mindlin-rescale-force: 28).
    for name in &names {
        let _ = match run.histories.get(name) {
            Some(Ok(_)) => Ok(()),
            Some(Err(e)) => {
                let e = e.to_string();
                let (first, more) = row_lines(&e);
                writeln!(text, "  {name:<width$} missing: {first}{more}")
            }
            None => writeln!(text, "  {name:<width$} not run"),
        };
    }
    let warnings = super::figures::warnings(run).len();
    if warnings > 0 {
        let _ = writeln!(
            text,
            "{warnings} warnings: in the report's section \"Case and solvers\""
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_case::Case;
    use spherecontact_check::Histories;

    #[test]
    fn the_solver_column_is_as_wide_as_the_longest_name() {
        let long = "a-command-solver-named-at-length-35";
        let text = format!(
            "friction = 0.2\nsolvers = [\"hertz\", \"{long}\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
             [path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n\
             [[command_solvers]]\nname = \"{long}\"\nkind = \"analytic\"\ncommand = [\"true\"]\n"
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
