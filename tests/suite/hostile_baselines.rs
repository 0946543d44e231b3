//! Baselines are foreign input (issue 42, docs/security.md "Files from elsewhere"): a pull request
//! can add or edit `reference/baselines/<case>.toml`, so a baseline is read by the one reader of
//! files from elsewhere (a regular file in its folder, bounded, never echoed), proves that it fits
//! its case (finite values, steps and indices of the case, the resolution its solvers ran at) or
//! is an error naming it, and `baseline update --baselines DIR` claims its folder as `--out` is
//! claimed, before any case runs. Each test is a finding of the hostile round and fails on the
//! code before its fix (bbd0278).
//!
//! Run: `cargo test --release --test suite hostile_baselines::` (a few seconds: hertz and mdr).

use std::path::Path;

use spherecontact::baseline;

use crate::common::{self, arg};

/// Runs `spherecontact` in `cwd` with `env` set: (exit code, stdout and stderr together).
fn run(args: &[&str], cwd: &Path, env: &[(&str, &str)]) -> (i32, String) {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(args)
        .current_dir(cwd)
        .envs(env.iter().copied())
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&output.stdout).into_owned() + &String::from_utf8_lossy(&output.stderr);
    (output.status.code().unwrap_or(-1), text)
}

/// A folder with `case.toml` (hertz and mdr, one check that passes) and its baseline in `b/`.
fn baselined() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let case = format!(
        "{}\n[[checks]]\nsolver = \"mdr\"\nquantity = \"normal_force\"\nat = \"every-step\"\n\
         reference = {{ solver = \"hertz\" }}\ntolerance = 1e-4\nreason = \"the bed's midpoint rule, 1e-6\"\n",
        common::SMALL_CASE
    );
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let (code, out) = run(
        &["baseline", "update", "case.toml", "--baselines", "b"],
        dir.path(),
        &[],
    );
    assert_eq!(code, 0, "{out}");
    let (code, out) = run(&["verify", "case.toml", "--baselines", "b"], dir.path(), &[]);
    assert_eq!(code, 0, "the baseline fits as written: {out}");
    dir
}

/// The baseline's text with `from` replaced by `to` (once), written back.
fn edit(dir: &Path, from: &str, to: &str) {
    let file = dir.join("b/cli-test.toml");
    let text = common::text(&file);
    assert!(text.contains(from), "{from} in {text}");
    std::fs::write(&file, text.replacen(from, to, 1)).unwrap();
}

/// Finding: a baseline that is a symbolic link printed the line of its target that failed to
/// parse: a link to `/proc/self/environ` printed the environment, to a credentials file its key
/// line. `verify`, `merge`, `slurm` and `baseline update` refuse it, quoting nothing.
#[test]
fn a_baseline_linked_out_of_its_folder_is_refused_without_echoing_it() {
    let dir = baselined();
    let file = dir.path().join("b/cli-test.toml");
    let secret = dir.path().join("credentials");
    std::fs::write(&secret, "[default]\naws_secret_access_key = wJalrXUtnFEMI\n").unwrap();
    let env = [("CI_TOKEN", "ghp_0123456789secret")];
    for target in [secret.as_path(), Path::new("/proc/self/environ")] {
        std::fs::remove_file(&file).unwrap();
        std::os::unix::fs::symlink(target, &file).unwrap();
        for args in [
            &["verify", "case.toml", "--baselines", "b"][..],
            &[
                "slurm",
                "case.toml",
                "--shards",
                "2",
                "--out",
                "s",
                "--baselines",
                "b",
            ],
        ] {
            let (code, out) = run(args, dir.path(), &env);
            assert_eq!(code, 2, "{out}");
            assert!(
                out.contains("a symbolic link that leads out of its folder"),
                "{out}"
            );
            assert!(
                !out.contains("wJalr") && !out.contains("ghp_0123") && !out.contains("aws_"),
                "{out}"
            );
        }
        let (code, out) = run(
            &["baseline", "update", "case.toml", "--baselines", "b"],
            dir.path(),
            &env,
        );
        assert_eq!(code, 2, "{out}");
        assert!(
            out.contains("is a symbolic link") && !out.contains("wJalr"),
            "{out}"
        );
    }
}

/// Finding: a baseline that does not parse echoed its line; now the line and column and the
/// expected form, nothing of the text.
#[test]
fn a_garbled_baseline_is_located_not_quoted() {
    let dir = baselined();
    std::fs::write(
        dir.path().join("b/cli-test.toml"),
        "format = 2\ncase = \"cli-test\"\ntoken = \"ghp_secret\"\n",
    )
    .unwrap();
    let (code, out) = run(&["verify", "case.toml", "--baselines", "b"], dir.path(), &[]);
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("b/cli-test.toml:3:1: unknown field `…`"), "{out}");
    assert!(
        out.contains("(allowed: a baseline written by `spherecontact baseline update`"),
        "{out}"
    );
    assert!(!out.contains("ghp_secret") && !out.contains("token"), "{out}");
}

/// Findings: a value of `nan` or `inf`, a step past the path and another index turned a DRIFT
/// into OK (for nan/inf the row said "drift non-finite"). Each is now an error naming the
/// baseline and its entry, exit 2, before any case runs; so are steps out of order (a value
/// would be compared at another step) and an empty list of values.
#[test]
fn entries_that_do_not_fit_the_case_are_errors_naming_the_baseline() {
    for (from, to, says) in [
        (
            "values = [\n  [0, ",
            "values = [\n  [0, nan], # ",
            "checks[0]: values[0]: the value is not a finite number",
        ),
        (
            "values = [\n  [0, ",
            "values = [\n  [0, inf], # ",
            "checks[0]: values[0]: the value is not a finite number",
        ),
        (
            "values = [\n  [0, ",
            "values = [\n  [9, ",
            "checks[0]: values[0]: step 9 is past the case's 9 steps (allowed: 0 to 8)",
        ),
        (
            "\n  [1, ",
            "\n  [0, ",
            "checks[0]: values[1]: step 0 does not follow step 0 (allowed: increasing steps)",
        ),
        (
            "index = 0",
            "index = 1",
            "checks[0]: index 1 and its words name no check of the case",
        ),
        (
            "check = \"mdr",
            "check = \"hertz",
            "checks[0]: index 0 and its words name no check of the case",
        ),
        (
            "wall_s = ",
            "wall_s = -1.0 # ",
            "solvers (entry 1): wall_s is not a finite time",
        ),
        (
            "[solvers.\"mdr\"]",
            "[solvers.\"bem\"]",
            "solvers (entry 1): a solver the case does not run",
        ),
        (
            "case = \"cli-test\"",
            "case = \"other\"",
            "case: another case's baseline",
        ),
    ] {
        let dir = baselined();
        edit(dir.path(), from, to);
        let (code, out) = run(&["verify", "case.toml", "--baselines", "b"], dir.path(), &[]);
        assert_eq!(code, 2, "{from} → {to}: {out}");
        assert!(
            out.contains("b/cli-test.toml") && out.contains(says),
            "{from} → {to}: {out}"
        );
        assert!(!out.contains("OK "), "nothing ran: {out}");
    }
    // An empty list of values: what no `baseline update` writes.
    let dir = baselined();
    let text = common::text(&dir.path().join("b/cli-test.toml"));
    let start = text.find("values = [\n").unwrap();
    let end = start + text[start..].find("\n]\n").unwrap() + 3;
    std::fs::write(
        dir.path().join("b/cli-test.toml"),
        format!("{}values = []\n{}", &text[..start], &text[end..]),
    )
    .unwrap();
    let (code, out) = run(&["verify", "case.toml", "--baselines", "b"], dir.path(), &[]);
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("checks[0]: values is empty"), "{out}");
}

/// Requirement (issue 39): a baseline of the old format (one value per check, no `format`) is
/// refused with a message saying to run `baseline update`, which rewrites it.
#[test]
fn an_old_format_baseline_is_refused_saying_to_run_baseline_update() {
    let dir = baselined();
    let old = "# Non-regression baseline of case `cli-test`: each check's computed value when last accepted,\n\
               case = \"cli-test\"\n\n[solvers.\"hertz\"]\nversion = \"0.1.0\"\nresolution = \"closed form\"\n\
               wall_s = 1e-4\n\n[[checks]]\nindex = 0\ncheck = \"mdr normal_force at every step vs hertz (relative)\"\n\
               step = 8\nvalue = 1.2e3\n";
    std::fs::write(dir.path().join("b/cli-test.toml"), old).unwrap();
    for args in [
        &["verify", "case.toml", "--baselines", "b"][..],
        &[
            "slurm",
            "case.toml",
            "--shards",
            "2",
            "--out",
            "s",
            "--baselines",
            "b",
        ],
    ] {
        let (code, out) = run(args, dir.path(), &[]);
        assert_eq!(code, 2, "{out}");
        assert!(
            out.contains("b/cli-test.toml: no `format`: a baseline of one value per check")
                && out.contains("run `spherecontact baseline update` to rewrite it"),
            "{out}"
        );
    }
    let (code, out) = run(
        &["baseline", "update", "case.toml", "--baselines", "b"],
        dir.path(),
        &[],
    );
    assert_eq!(code, 0, "{out}");
    assert!(common::text(&dir.path().join("b/cli-test.toml")).contains("\nformat = 2\n"));
    let (code, out) = run(&["verify", "case.toml", "--baselines", "b"], dir.path(), &[]);
    assert_eq!(code, 0, "{out}");
}

/// Finding: an edited resolution string turned a DRIFT into OK (the check was silently not
/// compared). A baseline of another resolution now fails the check (DRIFT, exit 1) saying so.
#[test]
fn a_baseline_of_another_resolution_fails_the_check() {
    let dir = baselined();
    let value = |text: &str| text.lines().find(|l| l.starts_with("  [8, ")).unwrap().to_owned();
    let stored = common::text(&dir.path().join("b/cli-test.toml"));
    edit(dir.path(), &value(&stored), "  [8, 1.0],");
    let (code, out) = run(&["verify", "case.toml", "--baselines", "b"], dir.path(), &[]);
    assert_eq!(code, 1, "a drifted value fails: {out}");
    edit(dir.path(), "resolution = \"", "resolution = \"edited ");
    let (code, out) = run(&["verify", "case.toml", "--baselines", "b"], dir.path(), &[]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("DRIFT") && out.contains("the baseline records another resolution of"),
        "{out}"
    );
    // A resolution chosen on the command line is not the case's: not compared, as documented.
    let (code, out) = run(
        &[
            "verify",
            "case.toml",
            "--baselines",
            "b",
            "--resolution",
            "mdr=8000",
        ],
        dir.path(),
        &[],
    );
    assert_eq!(code, 0, "{out}");
}

/// Finding (issue 39's, closed here with the folder checks): `--baselines no-such-dir` exited 0
/// with no drift column and no warning; a folder that does not exist is an error now.
#[test]
fn a_missing_baselines_folder_is_an_error() {
    let dir = baselined();
    let (code, out) = run(
        &["verify", "case.toml", "--out", "o", "--baselines", "b"],
        dir.path(),
        &[],
    );
    assert_eq!(code, 0, "{out}");
    for command in [
        &["verify", "case.toml"][..],
        &["slurm", "case.toml", "--shards", "2", "--out", "s"],
        &["merge", "o"],
    ] {
        let args = [command, &["--baselines", "no-such-dir"]].concat();
        let (code, out) = run(&args, dir.path(), &[]);
        assert_eq!(code, 2, "{out}");
        assert!(out.contains("--baselines no-such-dir: not a folder"), "{out}");
    }
}

/// Finding (issue 39): a case without a baseline passed unseen. It is said now (NOBASE in the
/// summary, a skipped JUnit test case `baseline`), and `--require-baselines` (CI's) makes it a
/// failure, on `verify` and `merge` alike.
#[test]
fn a_case_without_a_baseline_is_said_and_fails_under_require_baselines() {
    let dir = baselined();
    std::fs::create_dir(dir.path().join("empty")).unwrap();
    let (code, out) = run(
        &[
            "verify",
            "case.toml",
            "--baselines",
            "empty",
            "--junit",
            "j.xml",
            "--out",
            "o",
        ],
        dir.path(),
        &[],
    );
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("NOBASE cli-test: no baseline (empty/cli-test.toml)")
            && out.contains("verify: 1 cases without a baseline"),
        "{out}"
    );
    let xml = common::text(&dir.path().join("j.xml"));
    assert!(
        xml.contains("name=\"baseline\"><skipped message=\"NOBASE cli-test")
            && xml.contains("failures=\"0\""),
        "{xml}"
    );
    for args in [
        &[
            "verify",
            "case.toml",
            "--baselines",
            "empty",
            "--junit",
            "j.xml",
            "--require-baselines",
        ][..],
        &[
            "merge",
            "o",
            "--baselines",
            "empty",
            "--junit",
            "j.xml",
            "--require-baselines",
        ],
    ] {
        let (code, out) = run(args, dir.path(), &[]);
        assert_eq!(code, 1, "{args:?}: {out}");
        assert!(
            out.contains("they count as failures (--require-baselines)"),
            "{out}"
        );
        let xml = common::text(&dir.path().join("j.xml"));
        assert!(
            xml.contains("<failure message=\"NO BASELINE (--require-baselines)\">NOBASE cli-test")
                && xml.contains("failures=\"1\""),
            "{xml}"
        );
    }
    // With its baseline the same flag passes, and the summary says nothing of baselines missing.
    let (code, out) = run(
        &["verify", "case.toml", "--baselines", "b", "--require-baselines"],
        dir.path(),
        &[],
    );
    assert_eq!(code, 0, "{out}");
    assert!(!out.contains("NOBASE"), "{out}");
}

/// Finding: `baseline update --baselines DIR` was not claimed like `--out`: it wrote into
/// system folders, took no lock and checked the folder only after every case had run. It is
/// claimed before any case runs now: system folders and folders of other files are refused
/// (exit 2, nothing written, no solver run), a folder of baselines only is the harness's.
#[test]
fn baseline_update_claims_its_folder_before_any_case_runs() {
    let dir = baselined();
    for (folder, says) in [
        ("/etc", "refused: "),
        ("/usr/lib", "refused: "),
        ("/", "refused: "),
    ] {
        let (code, out) = run(
            &["baseline", "update", "case.toml", "--baselines", folder],
            dir.path(),
            &[],
        );
        assert_eq!(code, 2, "{folder}: {out}");
        assert!(out.contains(&format!("--baselines {folder}: {says}")), "{out}");
        assert!(!out.contains("baseline: "), "nothing was written: {out}");
    }
    let foreign = dir.path().join("foreign");
    std::fs::create_dir(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    let (code, out) = run(
        &["baseline", "update", "case.toml", "--baselines", arg(&foreign)],
        dir.path(),
        &[],
    );
    assert_eq!(code, 2, "{out}");
    assert!(
        out.contains("the folder holds files spherecontact did not write (`notes.txt`"),
        "{out}"
    );
    assert_eq!(std::fs::read_dir(&foreign).unwrap().count(), 1, "nothing written");
    // The folder of baselines `baselined` wrote (no marker yet there) is the harness's; updated
    // again, it is marked and locked.
    std::fs::remove_file(dir.path().join("b").join(spherecontact::io::MARKER)).unwrap();
    assert!(baseline::is_baseline_file(&dir.path().join("b/cli-test.toml")));
    let (code, out) = run(
        &["baseline", "update", "case.toml", "--baselines", "b"],
        dir.path(),
        &[],
    );
    assert_eq!(code, 0, "{out}");
    assert!(dir.path().join("b").join(spherecontact::io::MARKER).exists());
}

/// Requirement: every shipped baseline fits its case (the checks above refuse none of them), and
/// the repository's baselines folder holds baselines only (`baseline update` claims it).
#[test]
fn every_shipped_baseline_fits_its_case() {
    let root = common::root();
    let options = spherecontact::plan::CaseOptions::default();
    let heavy = std::fs::read_dir(root.join("cases-heavy"))
        .unwrap()
        .map(|e| e.unwrap().path());
    let files: Vec<_> = common::every_case_file()
        .into_iter()
        .chain(heavy.filter(|p| p.extension().is_some_and(|e| e == "toml")))
        .collect();
    let cases: Vec<_> = files
        .iter()
        .map(|file| {
            options
                .load_member(file)
                .unwrap_or_else(|e| panic!("{}: {e}", file.display()))
        })
        .collect();
    let loaded = baseline::load_all(&root.join(baseline::DIR), &cases, baseline::Reading::Compare).unwrap();
    let shipped = std::fs::read_dir(root.join(baseline::DIR))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().is_some_and(|n| n != spherecontact::io::MARKER))
        .collect::<Vec<_>>();
    assert!(
        shipped.iter().all(|p| baseline::is_baseline_file(p)),
        "{shipped:?}"
    );
    assert_eq!(loaded.len(), shipped.len(), "every baseline is of a shipped case");
}
