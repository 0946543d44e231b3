//! A program named by a case as a solver, and results stored in a file: the example command
//! solver against `hertz` at round-off, and every fault reported with its log while the other
//! solvers go on.

use crate::common;

use spherecontact::case::Case;
use spherecontact::check::Verdict;
use spherecontact::external::permission::CommandPermission;
use spherecontact::solver::SolveError;
use spherecontact::verify::{self, CaseRun};
use std::path::Path;

/// A case of the paper's spheres with one command solver `mine` running `command` (TOML array
/// text) with a time limit of `timeout` s, checked against `hertz`.
fn case_text(command: &str, timeout: f64) -> String {
    format!(
        r#"
friction = 0.2
solvers = ["hertz", "mine"]
[body1]
radius = 0.1
young = 70e9
poisson = 0.3
[path]
unit = "um"
delta_n = [0, 10, 17]
delta_t = [0, 0, 2]
substeps = 5
[[command_solvers]]
name = "mine"
kind = "analytic"
command = {command}
timeout = {timeout}
[[checks]]
solver = "mine"
quantity = "normal_force"
at = "every-step"
reference = {{ solver = "hertz" }}
tolerance = 1e-14
reason = "the same closed form"
"#
    )
}

/// The example solver's path.
fn example() -> String {
    common::root()
        .join("examples/hertz_command_solver.py")
        .display()
        .to_string()
}

/// Writes the case into a fresh folder and runs it.
fn run(text: &str) -> (tempfile::TempDir, CaseRun) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("case.toml");
    std::fs::write(&file, text).unwrap();
    let mut case = Case::load(&file).unwrap_or_else(|e| panic!("{e}"));
    case.permit_commands(&CommandPermission::allowed());
    (dir, verify::run_case(case))
}

/// The failure message of solver `mine`, after checking that `hertz` still ran and that the
/// check on `mine` is NOOK.
fn failure(run: &CaseRun) -> String {
    assert!(run.histories["hertz"].is_ok(), "the other solver must go on");
    assert_eq!(run.outcomes[0].verdict, Verdict::Nook);
    assert!(!run.passed());
    match &run.histories["mine"] {
        Err(SolveError::Failed(message)) => message.clone(),
        other => panic!("expected a failure, got {other:?}"),
    }
}

/// The command that runs the example and then `edit` (a shell command) on its output.
fn corrupted(edit: &str) -> String {
    // A TOML literal string: the shell command keeps its backslashes; `edit` quotes with ".
    format!(r#"["sh", "-c", 'python3 {} {{scene}} && {edit}']"#, example())
}

#[test]
fn the_example_command_solver_matches_hertz_at_round_off() {
    let mut case = common::case("cases/command-solver.toml");
    case.permit_commands(&CommandPermission::allowed());
    let run = verify::run_case(case);
    for outcome in &run.outcomes {
        assert_eq!(outcome.verdict, Verdict::Ok, "{outcome:?}");
    }
    assert!(run.passed());
    let history = run.histories["hertz-python"].as_ref().unwrap();
    assert_eq!(history.steps.len(), 51);
    assert!(history.steps.iter().all(|r| r.tangential_force.is_none()));
}

#[test]
fn the_round_off_check_can_fail() {
    // E one part in 1e12 too large: far below any physics, far above round-off.
    let command = format!(
        r#"["sh", "-c", "sed 's/e_star = 1 \\//e_star = (1 + 1e-12) \\//' {} > h.py && python3 h.py {{scene}}"]"#,
        example()
    );
    let (_dir, run) = run(&case_text(&command, 60.0));
    assert!(run.histories["mine"].is_ok(), "{:?}", run.histories["mine"]);
    assert_eq!(run.outcomes[0].verdict, Verdict::Nook);
    let error = run.outcomes[0].error.unwrap();
    assert!(error > 5e-13 && error < 2e-12, "error {error}");
}

#[test]
fn a_missing_program_is_a_failure_of_that_solver() {
    let (_dir, run) = run(&case_text(r#"["./no-such-solver", "{scene}"]"#, 60.0));
    let message = failure(&run);
    assert!(
        message.contains("`") && message.contains("not found"),
        "{message}"
    );
}

#[test]
fn a_non_zero_exit_is_reported_with_its_log_kept() {
    let (_dir, run) = run(&case_text(
        r#"["sh", "-c", "echo 'my solver: bad mesh' >&2; exit 3"]"#,
        60.0,
    ));
    let message = failure(&run);
    assert!(message.contains("exited with code 3"), "{message}");
    assert!(message.contains("my solver: bad mesh"), "{message}");
    let kept = message.rsplit("kept in ").next().unwrap().trim_end_matches(')');
    let kept = Path::new(kept);
    assert!(kept.join("scene.json").is_file() && kept.join("command.stderr").is_file());
    std::fs::remove_dir_all(kept).unwrap();
}

#[test]
fn a_hanging_program_is_killed_at_its_timeout() {
    let start = std::time::Instant::now();
    let (_dir, run) = run(&case_text(r#"["sh", "-c", "sleep 30 & sleep 30"]"#, 0.5));
    let message = failure(&run);
    assert!(message.contains("did not finish within 0.5 s"), "{message}");
    assert!(start.elapsed().as_secs_f64() < 20.0, "killed late");
}

#[test]
fn garbage_output_is_reported_with_file_line_and_column() {
    let cases = [
        // a cell too many on the first data row
        (
            corrupted(r#"sed -i "2s/\$/,1/" history.csv"#),
            "cells in a row under a header of 7 columns",
        ),
        // the last rows missing
        (
            corrupted(r#"sed -i "5,\$d" history.csv"#),
            "3 rows for a path of 11 steps",
        ),
        // no file at all
        (r#"["true"]"#.to_owned(), "cannot read"),
    ];
    for (command, expected) in cases {
        let (_dir, run) = run(&case_text(&command, 60.0));
        let message = failure(&run);
        assert!(message.contains(expected), "{expected}: {message}");
        let kept = message.rsplit("kept in ").next().unwrap().trim_end_matches(')');
        std::fs::remove_dir_all(kept).unwrap();
    }
}

/// Requirement (issue 39, "Messages"): a NaN in one quantity of a program's results fails that
/// quantity's checks only, named by the file's own line (the example writes with Python's csv:
/// CRLF line ends) and column, the run folder kept; the other quantity's check is judged (the
/// example is Hertz to round-off: OK); a check of a quantity without a column says so, with the
/// header's columns. Line 3 is step 1 (the header is line 1).
#[test]
fn a_nan_in_one_quantity_fails_that_quantity_s_checks_only() {
    let command = corrupted(r#"sed -i "3s/,[^,]*\$/,nan/" history.csv"#);
    let check = |quantity: &str| {
        format!(
            "[[checks]]\nsolver = \"mine\"\nquantity = \"{quantity}\"\nat = \"every-step\"\n\
             reference = {{ solver = \"hertz\" }}\ntolerance = 1e-12\nreason = \"the same closed form\"\n"
        )
    };
    let text = case_text(&command, 60.0) + &check("peak_pressure") + &check("tangential_force");
    let (_dir, run) = run(&text);
    assert!(run.histories["mine"].is_ok(), "{:?}", run.histories["mine"]);
    let [normal, peak, tangential] = &run.outcomes[..] else {
        panic!("three checks: {:?}", run.outcomes)
    };
    assert_eq!(normal.verdict, Verdict::Ok, "{normal:?}");
    assert_eq!(peak.verdict, Verdict::Nook);
    let message = peak.message.as_deref().unwrap();
    assert!(
        message.starts_with("mine: ")
            && message
                .contains("/history.csv:3: column `peak_pressure`: not finite (allowed: a finite number"),
        "{message}"
    );
    let kept = message.rsplit("kept in ").next().unwrap().trim_end_matches(')');
    assert!(Path::new(kept).join("history.csv").is_file(), "{message}");
    std::fs::remove_dir_all(kept).unwrap();
    assert_eq!(tangential.verdict, Verdict::Nook);
    let message = tangential.message.as_deref().unwrap();
    assert!(
        message.ends_with(
            "history.csv: no column `tangential_force` in the header (columns: step, position, \
             delta_n, delta_t, normal_force, contact_radius, peak_pressure)"
        ),
        "{message}"
    );
}

// --- Stored results ---------------------------------------------------------------------------

/// A case whose solver `stored` is the History CSV `file` (beside the case), checked against
/// `hertz`.
fn stored_case(dir: &Path, csv: &str) -> Result<Case, String> {
    std::fs::write(dir.join("stored.csv"), csv).unwrap();
    let text = case_text(r#"["true"]"#, 1.0)
        .replace("\"mine\"", "\"stored\"")
        .replace(
            "[[command_solvers]]\nname = \"stored\"\nkind = \"analytic\"\ncommand = [\"true\"]\ntimeout = 1\n",
            "[[stored_results]]\nname = \"stored\"\nkind = \"analytic\"\nfile = \"stored.csv\"\n",
        )
        .replace("tolerance = 1e-14", "tolerance = 1e-10");
    let file = dir.join("case.toml");
    std::fs::write(&file, text).unwrap();
    Case::load(&file).map_err(|e| e.to_string())
}

/// Hertz's history along the stored case's path, as `spherecontact run` writes it.
fn hertz_csv(dir: &Path) -> String {
    let case = stored_case(dir, "step,position,delta_n,delta_t\n").err();
    assert!(case.is_some(), "a file without rows must not validate");
    let probe = case_text(r#"["true"]"#, 1.0);
    let file = dir.join("probe.toml");
    std::fs::write(&file, probe).unwrap();
    let case = Case::load(&file).unwrap();
    let solver = case.solver("hertz").unwrap();
    let history = spherecontact::solver::run(solver.as_ref(), &case.scene).unwrap();
    spherecontact::report::history_files::to_csv(&history).unwrap()
}

#[test]
fn stored_results_are_checked_like_a_solver() {
    let dir = tempfile::tempdir().unwrap();
    let csv = hertz_csv(dir.path());
    let case = stored_case(dir.path(), &csv).unwrap();
    let run = verify::run_case(case);
    // Written with 11 significant digits: within 5e-11 of Hertz, judged at 1e-10.
    assert_eq!(run.outcomes[0].verdict, Verdict::Ok, "{:?}", run.outcomes[0]);
    assert!(run.outcomes[0].error.unwrap() < 5e-11);
    // A stored value off by 1e-6 is caught by the same check.
    let mut lines: Vec<String> = csv.lines().map(str::to_owned).collect();
    let cells: Vec<&str> = lines[6].split(',').collect();
    let force: f64 = cells[4].parse().unwrap();
    let mut edited: Vec<String> = cells.iter().map(|c| c.to_string()).collect();
    edited[4] = format!("{:e}", force * (1.0 + 1e-6));
    lines[6] = edited.join(",");
    let run = verify::run_case(stored_case(dir.path(), &(lines.join("\n") + "\n")).unwrap());
    assert_eq!(run.outcomes[0].verdict, Verdict::Nook);
}

#[test]
fn stored_results_that_do_not_follow_the_path_are_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let csv = hertz_csv(dir.path());
    let lines: Vec<&str> = csv.lines().collect();
    let in_micrometres = {
        let mut out = vec![lines[0].to_owned()];
        for line in &lines[1..] {
            let mut cells: Vec<String> = line.split(',').map(str::to_owned).collect();
            for k in [2, 3] {
                cells[k] = format!("{:e}", cells[k].parse::<f64>().unwrap() * 1e6);
            }
            out.push(cells.join(","));
        }
        out.join("\n")
    };
    let cases = [
        (lines[..8].join("\n"), "7 rows for a path of 11 steps"),
        (in_micrometres, "looks like µm"),
        (csv.replacen("\n5,1,", "\n5,,", 1), "column `position`"),
        (
            csv.replacen("step,position", "position,step", 1),
            "path columns are missing or out of order",
        ),
    ];
    for (text, expected) in cases {
        let e = stored_case(dir.path(), &text).unwrap_err();
        assert!(
            e.contains("stored_results[0].file") && e.contains("stored.csv"),
            "{e}"
        );
        assert!(e.contains(expected), "{expected}: {e}");
    }
}

#[test]
fn a_case_solver_cannot_take_a_built_in_name_or_a_path_as_name() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("case.toml");
    for (name, expected) in [("mdr", "already a solver's name"), ("../x", "not a plain name")] {
        let text = case_text(r#"["true"]"#, 1.0).replace("name = \"mine\"", &format!("name = \"{name}\""));
        std::fs::write(&file, text).unwrap();
        let e = Case::load(&file).unwrap_err().to_string();
        assert!(
            e.contains("command_solvers[0].name") && e.contains(expected),
            "{e}"
        );
    }
}
