//! Run files are foreign input (issue 42, docs/security.md "Files from elsewhere"): a `run.json`
//! that `merge`, `compare --from` or `reproduce-paper --from` reads proves what it is before any
//! verdict — the same harness, its case files byte for byte (their SHA-256, checked before a case
//! file is parsed), the same paths, every history on its case's path — and is read by the one
//! reader of files from elsewhere (a regular file in its folder, bounded, never echoed). Each
//! test is a finding of the hostile round that turned a failing verification green or leaked a
//! file, and fails on the code before its fix (bbd0278).
//!
//! Run: `cargo test --release --test suite hostile_runfiles::` (about 5 s: hertz and mdr only).

use std::path::Path;

use crate::common::{self, arg};

/// A case whose one check fails (mdr against hertz at 1e-12: the bed's midpoint rule is 1e-6
/// off at the first steps), so that only a forged run could make it pass.
const FAILING: &str = r#"
name = "forged"
friction = 0.2
solvers = ["hertz", "mdr"]

[body1]
radius = 0.1
young = 70e9
poisson = 0.3

[path]
unit = "um"
delta_n = [0, 10, 10]
delta_t = [0, 0, 1]
substeps = 4

[[checks]]
solver = "mdr"
quantity = "normal_force"
at = "every-step"
reference = { solver = "hertz" }
tolerance = 1e-12
reason = "fails on purpose: the midpoint rule on 4000 springs is about 1e-6 off"
"#;

/// Runs `spherecontact` in `cwd`: (exit code, stdout, stderr).
fn run(args: &[&str], cwd: &Path) -> (i32, String, String) {
    let output = common::spherecontact(args, cwd);
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// A folder with `case.toml` (the failing case), an empty baselines folder `none`, and the
/// `verify --out out` run of it, which fails (exit 1).
fn verified() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), FAILING).unwrap();
    std::fs::create_dir(dir.path().join("none")).unwrap();
    let (code, stdout, stderr) = run(
        &["verify", "case.toml", "--out", "out", "--baselines", "none"],
        dir.path(),
    );
    assert_eq!(code, 1, "the case fails as it is: {stdout}{stderr}");
    assert!(stdout.contains("NOOK"), "{stdout}");
    dir
}

/// `merge out` in `dir`: (exit code, stdout, stderr).
fn merge(dir: &Path) -> (i32, String, String) {
    run(&["merge", "out", "--baselines", "none"], dir)
}

/// Edits the run file of `dir` with `edit`.
fn edit_run_file(dir: &Path, edit: impl FnOnce(&mut serde_json::Value)) {
    let file = dir.join("out/run.json");
    let mut json: serde_json::Value = serde_json::from_str(&common::text(&file)).unwrap();
    edit(&mut json);
    std::fs::write(&file, json.to_string()).unwrap();
}

/// The stored history of `solver` in a run file.
fn history<'a>(json: &'a mut serde_json::Value, solver: &str) -> &'a mut serde_json::Value {
    json["runs"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|r| r["solver"] == solver)
        .map(|r| &mut r["result"]["history"])
        .unwrap()
}

/// Asserts a refusal with exit code 2 whose message holds `fragment`, no panic.
fn assert_refused((code, stdout, stderr): (i32, String, String), fragment: &str) {
    assert_eq!(code, 2, "{stdout}{stderr}");
    assert!(stderr.contains(fragment), "no `{fragment}` in: {stderr}");
    assert!(
        !stderr.contains("panicked") && !stdout.contains(" OK "),
        "{stdout}{stderr}"
    );
}

/// Requirement: the run file merged unedited gives the live run's verdict (exit 1, NOOK): the
/// checks below refuse forgeries, not honest runs.
#[test]
fn an_unedited_run_file_merges_to_the_live_verdict() {
    let dir = verified();
    let (code, stdout, stderr) = merge(dir.path());
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(stdout.contains("NOOK"), "{stdout}");
}

/// Finding: a history cut to one row turned the failing check into OK (exit 0).
#[test]
fn a_history_cut_to_one_row_is_refused() {
    let dir = verified();
    edit_run_file(dir.path(), |json| {
        for solver in ["mdr", "hertz"] {
            history(json, solver)["steps"].as_array_mut().unwrap().truncate(1);
        }
    });
    assert_refused(merge(dir.path()), "1 rows for a path of 9 steps");
}

/// Finding: another path's values were accepted (every δn doubled, the forces left).
#[test]
fn a_history_of_another_path_is_refused() {
    let dir = verified();
    edit_run_file(dir.path(), |json| {
        for row in history(json, "mdr")["steps"].as_array_mut().unwrap() {
            let delta_n = row["delta_n"].as_f64().unwrap();
            row["delta_n"] = serde_json::json!(2.0 * delta_n);
        }
    });
    assert_refused(merge(dir.path()), "is not on the path's step 1");
}

/// Finding: a shard from before the case was edited (fewer steps) merged silently.
#[test]
fn a_run_of_a_case_edited_since_is_refused_naming_it() {
    let dir = verified();
    let case = dir.path().join("case.toml");
    std::fs::write(&case, FAILING.replace("substeps = 4", "substeps = 50")).unwrap();
    assert_refused(
        merge(dir.path()),
        "cases[0] (`case.toml`): the case file is not the one its runs were made of",
    );
    // An edit that keeps the path (a comment) is another file all the same: the digest is the bytes'.
    std::fs::write(&case, format!("{FAILING}# a comment\n")).unwrap();
    assert_refused(merge(dir.path()), "its SHA-256 differs");
}

/// Requirement: a run file of another harness version or format is refused, naming the file.
#[test]
fn a_run_file_of_another_version_or_format_is_refused() {
    let dir = verified();
    edit_run_file(dir.path(), |json| json["harness"] = "spherecontact 0.0.9".into());
    assert_refused(merge(dir.path()), "written by another version of the harness");
    edit_run_file(dir.path(), |json| json["format"] = 1.into());
    assert_refused(merge(dir.path()), "out/run.json: format 1 (allowed: 2)");
}

/// Finding: `cases` may name any file and merge loaded it as a case, showing its first key
/// name. A file of secrets named as a case is now read only to be digested: nothing of it is
/// shown, and a name that is not a `.toml` file is refused unread.
#[test]
fn a_run_file_naming_another_file_as_its_case_learns_nothing_of_it() {
    let dir = verified();
    let secret = dir.path().join("credentials.toml");
    std::fs::write(&secret, "aws_secret_access_key = \"wJalrXUtnFEMI\"\n").unwrap();
    edit_run_file(dir.path(), |json| json["cases"][0]["file"] = arg(&secret).into());
    let (code, stdout, stderr) = merge(dir.path());
    assert_refused(
        (code, stdout.clone(), stderr.clone()),
        "the case file is not the one its runs were made of",
    );
    assert!(
        !format!("{stdout}{stderr}").contains("aws_secret") && !stderr.contains("wJalr"),
        "{stderr}"
    );
    edit_run_file(dir.path(), |json| json["cases"][0]["file"] = "/etc/passwd".into());
    assert_refused(
        merge(dir.path()),
        "not a case file's name (allowed: a .toml file)",
    );
}

/// Findings: `run.json` had no size limit (2 GiB read whole) and was read through links; a FIFO
/// is refused at once rather than blocking, a link out of the folder is refused, and a parse
/// error names line and column without quoting the file.
#[test]
fn a_run_file_is_read_as_a_file_from_elsewhere() {
    let dir = verified();
    let file = dir.path().join("out/run.json");
    std::fs::remove_file(&file).unwrap();
    let large = std::fs::File::create(&file).unwrap();
    large.set_len(2 << 30).unwrap();
    assert_refused(merge(dir.path()), "(allowed: at most 1024 MiB)");
    std::fs::remove_file(&file).unwrap();
    let secret = dir.path().join("secret.txt");
    std::fs::write(&secret, "{\"format\": \"ghp_token0123\"}").unwrap();
    std::os::unix::fs::symlink(&secret, &file).unwrap();
    assert_refused(merge(dir.path()), "a symbolic link that leads out of its folder");
    std::fs::remove_file(&file).unwrap();
    std::fs::copy(&secret, &file).unwrap();
    let (code, stdout, stderr) = merge(dir.path());
    assert_refused((code, stdout, stderr.clone()), "out/run.json:1:");
    assert!(!stderr.contains("ghp_token"), "{stderr}");
    std::fs::remove_file(&file).unwrap();
    rustix::fs::mkfifoat(rustix::fs::CWD, &file, rustix::fs::Mode::from_raw_mode(0o600)).unwrap();
    assert_refused(merge(dir.path()), "a FIFO");
}

/// Requirement: `compare --from` refuses a forged run as merge does (one reader for both).
#[test]
fn compare_from_a_forged_run_is_refused() {
    let dir = verified();
    edit_run_file(dir.path(), |json| {
        history(json, "mdr")["steps"].as_array_mut().unwrap().truncate(1);
    });
    assert_refused(
        run(
            &["compare", "case.toml", "--from", "out", "--out", "report"],
            dir.path(),
        ),
        "1 rows for a path of 9 steps",
    );
    assert!(!dir.path().join("report").exists());
}

/// Finding (of this round's review): two huge recorded wall times summed to `inf` in merge's
/// line; a run's times and cores must be a run's.
#[test]
fn a_run_of_impossible_times_is_refused() {
    let dir = verified();
    edit_run_file(dir.path(), |json| {
        json["runs"][0]["wall_s"] = serde_json::json!(1.7e308)
    });
    assert_refused(merge(dir.path()), "its wall_s, cost_s or cores is not a run's");
    edit_run_file(dir.path(), |json| {
        json["runs"][0]["wall_s"] = serde_json::json!(0.1);
        json["runs"][0]["cores"] = serde_json::json!(0);
    });
    assert_refused(merge(dir.path()), "at least one core");
}
