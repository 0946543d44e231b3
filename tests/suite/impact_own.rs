//! A user's own law or code in an impact case (issue 39, docs/impact.md "Your own law or code
//! in an impact"): stored sweep tables and programs are solvers of an impact case with the rules
//! of a path case's — a kind, opt-in programs, files inside the case's tree, read against the
//! sweep with the file's line and column named — and are judged by the same checks.
//!
//! Run: `cargo test --test suite impact_own::`.

use crate::common;

use std::path::Path;

use common::spherecontact;

/// An elastic normal impact (one point) whose own solvers are `own`, with one check on `lab`.
fn case(own: &str, check: &str) -> String {
    format!(
        r#"kind = "impact"
name = "own"
friction = 0.0
solvers = ["mdr", "lab"]

[body1]
radius = 0.10
young = 7.0e10
poisson = 0.30
density = 2699
velocity = [0, -0.2]

[body2]
rigid_flat = true
{own}
[[checks]]
solver = "lab"
quantity = "{check}"
reference = {{ solver = "mdr" }}
tolerance = 1e-15
reason = "the stored table is mdr's own run, written in shortest round-trip form: read back bit for bit"
"#
    )
}

const STORED: &str = "\n[[stored_results]]\nname = \"lab\"\nkind = \"dem-code\"\nfile = \"lab.csv\"\n";

/// `run` of mdr on the case in `dir`: its sweep table, as a user would store a run.
fn mdr_table(dir: &Path) -> String {
    std::fs::write(
        dir.join("mdr-only.toml"),
        case("", "max_overlap")
            .replace(", \"lab\"]", "]")
            .replace("solver = \"lab\"", "solver = \"mdr\""),
    )
    .unwrap();
    let out = dir.join("mdr-run");
    let run = spherecontact(
        &["run", "mdr-only.toml", "--solver", "mdr", "--out", "mdr-run"],
        dir,
    );
    common::assert_success(&run);
    std::fs::read_to_string(out.join("mdr.csv")).unwrap()
}

/// Requirement: stored results of an impact are judged as any solver's. Reference: mdr's own
/// run, stored; tolerance 1e-15 (round-trip exact, see the case's reason).
#[test]
fn a_stored_sweep_table_is_judged_by_the_checks() {
    let dir = tempfile::tempdir().unwrap();
    let table = mdr_table(dir.path());
    std::fs::write(dir.path().join("lab.csv"), &table).unwrap();
    std::fs::write(dir.path().join("case.toml"), case(STORED, "max_normal_force")).unwrap();
    let out = spherecontact(&["verify", "case.toml"], dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    common::assert_success(&out);
    let row = stdout
        .lines()
        .find(|l| l.contains("lab max_normal_force"))
        .expect("a row for the stored solver");
    assert!(row.starts_with("OK "), "{row}");
    assert!(row.contains("error 0.0000e0"), "{row}");
}

/// Requirement: a defect of a stored table is a case error (exit 2) naming the file, its line
/// (the header is line 1) and the column; nothing runs.
#[test]
fn a_bad_stored_table_is_refused_naming_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let table = mdr_table(dir.path());
    let mut lines: Vec<String> = table.lines().map(str::to_owned).collect();
    let mut cells: Vec<&str> = lines[1].split(',').collect();
    cells[3] = "nan";
    lines[1] = cells.join(",");
    std::fs::write(dir.path().join("lab.csv"), lines.join("\n") + "\n").unwrap();
    std::fs::write(dir.path().join("case.toml"), case(STORED, "max_normal_force")).unwrap();
    let out = spherecontact(&["verify", "case.toml"], dir.path());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("stored_results[0].file"), "{stderr}");
    assert!(
        stderr.contains("lab.csv: line 2, column max_normal_force: not a finite number"),
        "{stderr}"
    );
}

/// Requirement: a program named by an impact case runs only when allowed: N/A without the
/// opt-in (never a pass), its command shown; with it, its table is judged.
#[test]
fn an_impact_program_runs_only_when_allowed() {
    let dir = tempfile::tempdir().unwrap();
    let table = mdr_table(dir.path());
    std::fs::write(dir.path().join("lab.csv"), &table).unwrap();
    // The program copies the stored table to the file the harness reads ({history}).
    let own = "\n[[command_solvers]]\nname = \"lab\"\nkind = \"dem-law\"\ncommand = [\"cp\", \"{case_dir}/lab.csv\", \"{history}\"]\ntimeout = 10\n";
    std::fs::write(dir.path().join("case.toml"), case(own, "max_overlap")).unwrap();
    let refused = spherecontact(&["verify", "case.toml"], dir.path());
    let stdout = String::from_utf8_lossy(&refused.stdout);
    assert!(stdout.contains("lab would run (timeout 10 s): cp"), "{stdout}");
    let row = stdout
        .lines()
        .find(|l| l.contains("lab max_overlap"))
        .expect("a row");
    assert!(row.starts_with("N/A"), "{row}");
    let allowed = spherecontact(&["verify", "case.toml", "--allow-commands"], dir.path());
    common::assert_success(&allowed);
    let stdout = String::from_utf8_lossy(&allowed.stdout);
    let row = stdout
        .lines()
        .find(|l| l.contains("lab max_overlap"))
        .expect("a row");
    assert!(row.starts_with("OK "), "{row}");
}
