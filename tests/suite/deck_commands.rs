//! `spherecontact deck write` and `deck read` (docs/external-decks.md, "On a cluster"): for each
//! deck, the folder written, run with the real tool exactly as its README.txt says (`sh run.sh`),
//! and read back, gives the CSV and the fields `spherecontact run --solver NAME` gives on the
//! same case; and the hostile side: a solver that is not a deck, a folder written for another
//! solver, resolution or scene, a garbage manifest, a truncated result file, a folder that is not
//! empty — exit 2 (or 1 for a run's bad output) with a sentence naming the file, nothing written.
//!
//! Tests that need the external tools skip, saying why, where those are absent
//! (`scripts/setup.sh`). Run: `cargo test --test suite deck_commands::` (the 3D deck:
//! `-- --ignored`).

use std::path::Path;

use spherecontact::toolchain::Tool;

use crate::common::decks::these_tools_present as present;
use crate::common::{assert_success, spherecontact, SMALL_CASE};

/// The normal half of the small case (ccx-axisym solves the normal contact, one `*STEP` a
/// position).
fn normal_case() -> String {
    let frictional = "delta_n = [0, 10, 10]\ndelta_t = [0, 0, 1]";
    assert!(SMALL_CASE.contains(frictional));
    SMALL_CASE.replace(frictional, "delta_n = [0, 10]\ndelta_t = [0, 0]")
}

/// The text of a file.
fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The numeric cells of a CSV, row by row (empty cells as `None`), after checking that both
/// files have the same header.
fn cells(text: &str) -> (String, Vec<Vec<Option<f64>>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default().to_owned();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.parse::<f64>().ok()).collect())
        .collect();
    (header, rows)
}

/// Largest difference between two CSVs of the same shape, relative to each column's largest
/// magnitude; panics where one has a value the other lacks.
fn largest_difference(label: &str, a: &str, b: &str) -> f64 {
    let ((header_a, rows_a), (header_b, rows_b)) = (cells(a), cells(b));
    assert_eq!(header_a, header_b, "{label}: headers");
    assert_eq!(rows_a.len(), rows_b.len(), "{label}: rows");
    let columns = rows_a.first().map_or(0, Vec::len);
    let mut worst = 0.0_f64;
    for column in 0..columns {
        let scale = rows_a
            .iter()
            .filter_map(|r| r[column])
            .fold(0.0_f64, |m, v| m.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        for (k, (ra, rb)) in rows_a.iter().zip(&rows_b).enumerate() {
            match (ra[column], rb[column]) {
                (Some(x), Some(y)) => worst = worst.max((x - y).abs() / scale),
                (None, None) => {}
                other => panic!("{label}: row {} column {column}: {other:?}", k + 1),
            }
        }
    }
    worst
}

/// The agreement asked of a folder's run read back and the solver's own run of the same files:
/// the same deck on the same mesh with the same command, so only the solver's round-off moves
/// (FreeFEM's MUMPS_seq: ≈ 1e-14 relative between two runs, docs/external-decks.md; the CSVs
/// print 11 significant digits): 1e-9 of each column's peak separates that from any other
/// file, step or mesh.
const SAME_RUN: f64 = 1e-9;

/// `deck write` → `sh run.sh` (as README.txt says) → `deck read`, against `run --solver`: the
/// largest relative differences of the CSV and of the fields.
fn round_trip(case_text: &str, solver: &str, resolution: &str) -> (f64, f64) {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    std::fs::write(work.join("case.toml"), case_text).unwrap();
    let chosen = format!("{solver}={resolution}");
    let deck_args = ["case.toml", "--solver", solver, "deck", "--resolution", &chosen];
    let written = spherecontact(&[&["deck", "write"], &deck_args[..]].concat(), work);
    assert_success(&written);
    let readme = read(&work.join("deck/README.txt"));
    assert!(readme.contains("    sh run.sh\n"), "{readme}");
    let ran = std::process::Command::new("sh")
        .arg("run.sh")
        .current_dir(work.join("deck"))
        .output()
        .unwrap();
    assert_success(&ran);
    let back = spherecontact(
        &[&["deck", "read"], &deck_args[..], &["--out", "read"]].concat(),
        work,
    );
    assert_success(&back);
    let own = spherecontact(
        &[
            "run",
            "case.toml",
            "--solver",
            solver,
            "--resolution",
            &chosen,
            "--out",
            "own",
        ],
        work,
    );
    assert_success(&own);
    let file = |folder: &str, suffix: &str| read(&work.join(folder).join(format!("{solver}{suffix}")));
    let csv = largest_difference(solver, &file("read", ".csv"), &file("own", ".csv"));
    let fields = largest_difference(solver, &file("read", ".fields.csv"), &file("own", ".fields.csv"));
    let json: serde_json::Value = serde_json::from_str(&file("read", ".json")).unwrap();
    assert!(
        json["metadata"]["version"]
            .as_str()
            .is_some_and(|v| v.contains("(run elsewhere)")),
        "{json}"
    );
    assert_eq!(json["metadata"]["chosen_resolution"], resolution);
    stored_results_are_read(work, case_text, solver);
    eprintln!(
        "{solver}: read back against its own run: CSV {csv:e}, fields {fields:e} of each column's peak"
    );
    assert!(
        csv <= SAME_RUN && fields <= SAME_RUN,
        "{solver}: {csv:e}, {fields:e}"
    );
    (csv, fields)
}

/// The CSV `deck read` wrote into `work/read/`, named by a case in `work` as stored results, is
/// read by `run` as that solver's rows: the workflow of docs/external-decks.md, "On a cluster".
fn stored_results_are_read(work: &Path, case_text: &str, solver: &str) {
    let start = case_text.find("solvers = ").unwrap();
    let end = start + case_text[start..].find('\n').unwrap();
    let stored = format!(
        "{}solvers = [\"deck-read\"]{}\n[[stored_results]]\nname = \"deck-read\"\nkind = \"fe\"\nfile = \"read/{solver}.csv\"\n",
        &case_text[..start],
        &case_text[end..]
    );
    std::fs::write(work.join("stored.toml"), stored).unwrap();
    assert_success(&spherecontact(&["run", "stored.toml", "--out", "stored"], work));
    let rows = |file: &str| {
        let (_, rows) = cells(&read(&work.join(file)));
        rows
    };
    assert_eq!(rows("stored/deck-read.csv"), rows(&format!("read/{solver}.csv")));
}

#[test]
#[ignore = "heavy: the FreeFEM deck twice; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn freefem_axisym_written_run_and_read_back_equals_its_own_run() {
    if present("freefem", &[Tool::Gmsh, Tool::FreeFem, Tool::Meshio]) {
        round_trip(SMALL_CASE, "freefem-axisym", "c/10");
    }
}

#[test]
#[ignore = "heavy: the FEniCSx deck twice; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn fenicsx_axisym_written_run_and_read_back_equals_its_own_run() {
    if present("fenicsx", &[Tool::Gmsh, Tool::Dolfinx, Tool::Meshio]) {
        round_trip(SMALL_CASE, "fenicsx-axisym", "c/10");
    }
}

#[test]
#[ignore] // heavy: ccx twice (13 s CPU, 50 s wall on a shared machine); `cargo test --test suite deck_commands:: -- --ignored`
fn ccx_axisym_written_run_and_read_back_equals_its_own_run() {
    if present("ccx", &[Tool::Gmsh, Tool::Ccx]) {
        round_trip(&normal_case(), "ccx-axisym", "c/10");
    }
}

#[test]
#[ignore] // heavy: the 3D deck twice on its coarsest mesh (minutes); `cargo test --test suite deck_commands:: -- --ignored`
fn fenicsx_3d_written_run_and_read_back_equals_its_own_run() {
    if present("fenicsx-3d", &[Tool::Gmsh, Tool::Dolfinx]) {
        round_trip(&normal_case(), "fenicsx-3d", "c/5");
    }
}

/// The program's exit code and its stderr.
fn failed(output: &std::process::Output) -> (Option<i32>, String) {
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn a_solver_that_is_not_a_deck_exits_2_naming_the_decks_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), SMALL_CASE).unwrap();
    for name in ["bem", "no-such-solver"] {
        for action in ["write", "read"] {
            let output = spherecontact(
                &["deck", action, "case.toml", "--solver", name, "deck"],
                dir.path(),
            );
            let (code, stderr) = failed(&output);
            assert_eq!(code, Some(2), "{stderr}");
            assert!(stderr.contains(&format!("`{name}` is not a deck")), "{stderr}");
            for deck in ["freefem-axisym", "fenicsx-axisym", "fenicsx-3d", "ccx-axisym"] {
                assert!(stderr.contains(deck), "{stderr}");
            }
            assert!(!dir.path().join("deck").exists());
        }
    }
}

/// The case, the deck and its resolution of [`written_folder`].
const WRITTEN: [&str; 5] = [
    "case.toml",
    "--solver",
    "freefem-axisym",
    "--resolution",
    "freefem-axisym=c/10",
];

/// A folder written by `deck write` for [`SMALL_CASE`], freefem-axisym at c/10 (gmsh only).
fn written_folder(work: &Path) -> bool {
    if !present("deck write", &[Tool::Gmsh]) {
        return false;
    }
    std::fs::create_dir_all(work).unwrap();
    std::fs::write(work.join("case.toml"), SMALL_CASE).unwrap();
    let output = spherecontact(&[&["deck", "write"], &WRITTEN[..], &["deck"]].concat(), work);
    assert_success(&output);
    true
}

#[test]
fn a_folder_written_for_another_solver_resolution_or_scene_is_refused_with_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    if !written_folder(work) {
        return;
    }
    std::fs::write(
        work.join("changed.toml"),
        SMALL_CASE.replace("friction = 0.2", "friction = 0.3"),
    )
    .unwrap();
    let reads: [(&[&str], &str); 4] = [
        (
            &[
                "case.toml",
                "--solver",
                "fenicsx-axisym",
                "--resolution",
                "fenicsx-axisym=c/10",
            ],
            "written for solver `freefem-axisym`, but this read is for `fenicsx-axisym`",
        ),
        (
            &["case.toml", "--solver", "freefem-axisym"],
            "written for resolution `c/10`",
        ),
        (
            &[
                "case.toml",
                "--solver",
                "freefem-axisym",
                "--resolution",
                "freefem-axisym=c/20",
            ],
            "but this read is for `c/20`",
        ),
        (
            &[
                "changed.toml",
                "--solver",
                "freefem-axisym",
                "--resolution",
                "freefem-axisym=c/10",
            ],
            "another scene (its `friction` differs)",
        ),
    ];
    for (args, expected) in reads {
        let output = spherecontact(
            &[&["deck", "read"], args, &["deck", "--out", "out"]].concat(),
            work,
        );
        let (code, stderr) = failed(&output);
        assert_eq!(code, Some(2), "{stderr}");
        assert!(
            stderr.contains("manifest.json") && stderr.contains(expected),
            "{stderr}"
        );
        assert!(!work.join("out").exists(), "{stderr}");
    }
    let args = [&["deck", "read"], &WRITTEN[..]].concat();
    for (manifest, expected) in [
        ("{\"format\": 1", "not a deck manifest"),
        ("{}", "not a deck manifest"),
    ] {
        std::fs::write(work.join("deck/manifest.json"), manifest).unwrap();
        let output = spherecontact(&[&args[..], &["deck", "--out", "out"]].concat(), work);
        let (code, stderr) = failed(&output);
        assert_eq!(code, Some(2), "{stderr}");
        assert!(
            stderr.contains("deck/manifest.json") && stderr.contains(expected),
            "{stderr}"
        );
    }
    let output = spherecontact(&[&args[..], &[".", "--out", "out"]].concat(), work);
    let (code, stderr) = failed(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("manifest.json") && stderr.contains("deck write"),
        "{stderr}"
    );
    assert!(!work.join("out").exists());
}

#[test]
fn deck_write_refuses_a_folder_that_is_not_empty_and_leaves_it_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    std::fs::write(work.join("case.toml"), SMALL_CASE).unwrap();
    std::fs::create_dir(work.join("deck")).unwrap();
    std::fs::write(work.join("deck/steps.csv"), "an earlier run's results").unwrap();
    let output = spherecontact(
        &["deck", "write", "case.toml", "--solver", "freefem-axisym", "deck"],
        work,
    );
    let (code, stderr) = failed(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("already holds `steps.csv`") && stderr.contains("--force"),
        "{stderr}"
    );
    let left: Vec<_> = std::fs::read_dir(work.join("deck")).unwrap().collect();
    assert_eq!(left.len(), 1, "{stderr}");
    // A written folder is not empty either: a second write into it is refused.
    if written_folder(&work.join("again")) {
        let output = spherecontact(
            &["deck", "write", "case.toml", "--solver", "freefem-axisym", "deck"],
            &work.join("again"),
        );
        assert_eq!(output.status.code(), Some(2));
    }
}

#[test]
#[ignore = "heavy: a FreeFEM deck written, run and read back; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn a_truncated_or_missing_result_file_fails_naming_it_with_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    if !present("truncated", &[Tool::FreeFem, Tool::Meshio]) || !written_folder(work) {
        return;
    }
    let args = [&["deck", "read"], &WRITTEN[..], &["deck", "--out", "out"]].concat();
    // Not run yet: no steps.csv.
    let (code, stderr) = failed(&spherecontact(&args, work));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("steps.csv") && stderr.contains("output missing"),
        "{stderr}"
    );
    let ran = std::process::Command::new("sh")
        .arg("deck/run.sh")
        .current_dir(work)
        .output()
        .unwrap();
    assert_success(&ran);
    let steps = work.join("deck/steps.csv");
    let text = read(&steps);
    let cuts = [
        (text.len() * 2 / 3, "steps.csv:"),
        (text.lines().next().unwrap().len() + 1, "truncated"),
    ];
    for (cut, expected) in cuts {
        std::fs::write(&steps, &text[..cut]).unwrap();
        let (code, stderr) = failed(&spherecontact(&args, work));
        assert_eq!(code, Some(1), "{stderr}");
        assert!(
            stderr.contains(expected) && !stderr.contains("panick"),
            "{stderr}"
        );
        assert!(!work.join("out").exists(), "{stderr}");
    }
    std::fs::write(&steps, &text).unwrap();
    let field = work.join("deck/field_1.vtu");
    std::fs::write(&field, "<VTKFile garbage").unwrap();
    let (code, stderr) = failed(&spherecontact(&args, work));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("field_1.vtu"), "{stderr}");
    assert!(!work.join("out").exists(), "{stderr}");
}
