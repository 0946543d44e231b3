//! Requirements of `compare --from DIR` and `reproduce-paper --from DIR` (the report of a case
//! from the run file of `verify --out DIR`, its solvers not run again):
//! - the report's solver files are bit for bit those of a report whose solvers ran, and the
//!   report says where its runs were read from;
//! - bad input (no run file, a run without the case, `--resolution` beside `--from`) exits 2
//!   naming what is wrong, with nothing written.

use std::path::Path;

use crate::common::{assert_success, spherecontact, SMALL_CASE};

/// The small case with one check, so that the reports have a check table.
fn case_text() -> String {
    format!(
        "{SMALL_CASE}
[[checks]]
solver = \"mdr\"
quantity = \"normal_force\"
at = \"every-step\"
reference = {{ solver = \"hertz\" }}
tolerance = 1e-3
reason = \"MDR's P is Hertz's integral by the midpoint rule (docs/paper.md)\"
"
    )
}

/// Every file of `dir/solvers/`, by name, with its bytes.
fn solver_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<_> = std::fs::read_dir(dir.join("solvers"))
        .unwrap()
        .map(|e| {
            let path = e.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read(&path).unwrap())
        })
        .collect();
    files.sort();
    files
}

#[test]
fn a_report_from_a_verify_run_equals_one_whose_solvers_ran() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    std::fs::write(work.join("case.toml"), case_text()).unwrap();
    assert_success(&spherecontact(
        &["verify", "case.toml", "--out", "verified"],
        work,
    ));
    assert_success(&spherecontact(&["compare", "case.toml", "--out", "ran"], work));
    let from = spherecontact(
        &["compare", "case.toml", "--from", "verified", "--out", "read"],
        work,
    );
    assert_success(&from);
    let (ran, read) = (solver_files(&work.join("ran")), solver_files(&work.join("read")));
    assert_eq!(
        ran.len(),
        5,
        "hertz and mdr (.csv and .json; mdr's fields): {:?}",
        ran.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    // The JSON holds the wall time of each run: the CSV histories are compared bit for bit.
    let csv = |files: &[(String, Vec<u8>)]| -> Vec<(String, Vec<u8>)> {
        files.iter().filter(|f| f.0.ends_with(".csv")).cloned().collect()
    };
    assert_eq!(csv(&ran), csv(&read));
    let report = std::fs::read_to_string(work.join("read/report.md")).unwrap();
    assert!(
        report.contains("read from the `verify --out` run file(s) of verified"),
        "{report}"
    );
    let stdout = String::from_utf8_lossy(&from.stdout);
    assert!(stdout.contains("1 OK"), "{stdout}");
}

#[test]
fn bad_from_folders_exit_2_naming_them_with_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    std::fs::write(work.join("case.toml"), case_text()).unwrap();
    std::fs::write(work.join("other.toml"), case_text().replace("cli-test", "other")).unwrap();
    assert_success(&spherecontact(
        &["verify", "other.toml", "--out", "other-run"],
        work,
    ));
    std::fs::create_dir(work.join("empty")).unwrap();
    let cases: [(&[&str], &str); 3] = [
        (&["--from", "empty"], "run.json"),
        (&["--from", "other-run"], "no run of case case.toml"),
        (
            &["--from", "other-run", "--resolution", "mdr=100"],
            "--resolution: not with --from",
        ),
    ];
    for (extra, expected) in cases {
        let args = [&["compare", "case.toml", "--out", "out"], extra].concat();
        let output = spherecontact(&args, work);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{extra:?}: {stderr}");
        assert!(
            stderr.contains(expected),
            "{extra:?}: `{expected}` not in {stderr}"
        );
        assert!(!work.join("out").exists(), "{extra:?}: out/ written");
    }
}
