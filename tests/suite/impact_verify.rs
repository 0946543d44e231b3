//! Impact cases as full members of the verification job (issue 31, docs/verification-at-scale.md):
//! their checks are JUnit test cases like a path case's; they run in shards and come back
//! through `run.json` so that `merge` gives the unsharded result (`scale::three_shards_…`
//! merges two impact cases with the hard path cases), and a run file holding a run of the wrong
//! kind or a tampered impact outcome is refused (exit 2); their values have non-regression
//! baselines whose drift fails the run; their labels come from the case file; bad labels exit 2
//! through `verify` too (`tests/hostile/impact/labels-*.toml`); the impact report draws force
//! and overlap against time.
//!
//! Run: `cargo test --test suite impact_verify::`.

use crate::common;

use std::path::Path;

use spherecontact::toolchain::Tool;

use common::{arg as path, header, root, run_in_root as run, spherecontact, text};

/// The normal impact on a flat: one sweep point; the five laws' 20 checks and the DEM codes'
/// 20 (four LAMMPS models and YADE, N/A where the code is not installed).
const NORMAL: &str = "cases/impact/chung-ooi-2.toml";
/// A path case of laws only (fast).
const PATH_CASE: &str = "cases/hard/dissimilar.toml";

#[test]
fn junit_lists_each_impact_check_as_a_test_case() {
    let dir = tempfile::tempdir().unwrap();
    let junit = dir.path().join("verify.xml");
    let none = dir.path().join("no-baselines");
    // An empty baselines folder: a missing one is an error (a typo would hide the check).
    std::fs::create_dir(&none).unwrap();
    let (code, stdout, stderr) = run(&[
        "verify",
        NORMAL,
        PATH_CASE,
        "--junit",
        path(&junit),
        "--baselines",
        path(&none),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let xml = text(&junit);
    let checks = spherecontact::case::load_impact(&root().join(NORMAL))
        .unwrap()
        .checks
        .len();
    // Four closed-form checks for each of the five laws and the seven DEM-code solvers (LAMMPS'
    // four models, YADE, LIGGGHTS, Kratos).
    assert_eq!(checks, 48);
    // One test case a check, and one `baseline` (skipped: the folder holds no baseline of it).
    let impact_cases = xml.matches("<testcase classname=\"chung-ooi-2\"").count();
    assert_eq!(impact_cases, checks + 1, "{xml}");
    assert!(
        xml.contains(&format!(
            "<testsuite name=\"chung-ooi-2\" tests=\"{}\" failures=\"0\">",
            checks + 1
        )),
        "{xml}"
    );
    assert!(
        xml.contains(
            "<testcase classname=\"chung-ooi-2\" name=\"baseline\"><skipped message=\"NOBASE chung-ooi-2"
        ),
        "{xml}"
    );
    assert!(
        xml.contains("name=\"00 mdr contact_duration (prescribed) vs hertz closed form (relative)\""),
        "{xml}"
    );
    // The path case's checks sit beside them in the same document, and the totals count both.
    let path_cases = xml.matches("<testcase classname=\"hard-dissimilar\"").count();
    assert!(path_cases > 1, "{xml}");
    assert!(
        xml.contains(&format!(
            "tests=\"{}\" failures=\"0\" skipped=\"2\"",
            impact_cases + path_cases
        )),
        "{xml}"
    );
    // The printed table has the same rows, and the counts include them.
    assert!(
        stdout.contains("OK    chung-ooi-2 | mdr contact_duration (prescribed)"),
        "{stdout}"
    );
    let passed = stdout.lines().find(|l| l.starts_with("verify: ")).unwrap();
    let ok_rows = stdout.lines().filter(|l| l.starts_with("OK    ")).count();
    assert_eq!(
        passed,
        format!("verify: {ok_rows} passed, 0 failed, 0 informational, 0 not available")
    );
}

#[test]
#[ignore = "heavy: verify on an impact case with LAMMPS and YADE, 4.3 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn the_impact_report_draws_force_and_overlap_against_time_for_every_solver() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&["impact", NORMAL, "--out", path(&out)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    for figure in ["normal-force-time", "overlap-time"] {
        assert!(
            out.join(format!("figures/chung-ooi-2-{figure}.svg")).exists(),
            "{figure}"
        );
        let data = text(&out.join(format!("data/chung-ooi-2-{figure}.csv")));
        for solver in [
            "mdr",
            "hertz-mindlin-spring",
            "thornton",
            "md-incremental",
            "walton-braun",
        ] {
            assert!(data.contains(solver), "{figure}: no {solver} in\n{data}");
        }
    }
}

#[test]
fn a_run_file_whose_impact_case_became_a_path_case_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::copy(root().join(NORMAL), &case).unwrap();
    let (out, none) = (dir.path().join("out"), dir.path().join("none"));
    // An empty baselines folder: a missing one is an error (a typo would hide the check).
    std::fs::create_dir(&none).unwrap();
    let (code, stdout, stderr) = run(&[
        "verify",
        path(&case),
        "--out",
        path(&out),
        "--baselines",
        path(&none),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    std::fs::write(
        &case,
        common::SMALL_CASE.replace("solvers = [\"hertz\", \"mdr\"]", "solvers = [\"mdr\"]"),
    )
    .unwrap();
    let junit = dir.path().join("merged.xml");
    let (code, _, stderr) = run(&["merge", path(&out), "--junit", path(&junit)]);
    assert_eq!(code, 2, "{stderr}");
    // The case file changed since the run: refused by its digest before it is judged.
    assert!(
        stderr.contains("the case file is not the one its runs were made of"),
        "{stderr}"
    );
    assert!(!junit.exists());
}

#[test]
fn a_tampered_impact_run_in_a_run_file_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (out, none) = (dir.path().join("out"), dir.path().join("none"));
    // An empty baselines folder: a missing one is an error (a typo would hide the check).
    std::fs::create_dir(&none).unwrap();
    let (code, stdout, stderr) = run(&["verify", NORMAL, "--out", path(&out), "--baselines", path(&none)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let file = out.join("run.json");
    let stored = text(&file);
    assert!(stored.contains("\"impact\":[{\"solver\":\"mdr\""), "{stored}");
    // An outcome value beyond f64, a quantity that is text, an outcome of six quantities.
    let seven = r#"{"values":["#;
    let start = stored.find(seven).unwrap() + seven.len();
    let end = start + stored[start..].find(']').unwrap();
    let values: Vec<&str> = stored[start..end].split(',').collect();
    assert_eq!(values.len(), 7, "{}", &stored[start..end]);
    let tampered = [
        format!("{}1e400{}", &stored[..start], &stored[start + values[0].len()..]),
        format!("{}\"x\"{}", &stored[..start], &stored[start + values[0].len()..]),
        format!("{}{}", &stored[..start], &stored[start + values[0].len() + 1..]),
    ];
    for text in tampered {
        std::fs::write(&file, &text).unwrap();
        let junit = dir.path().join("merged.xml");
        let (code, _, stderr) = run(&["merge", path(&out), "--junit", path(&junit)]);
        assert_eq!(code, 2, "{stderr}");
        assert!(
            stderr.contains("run.json:1:")
                && stderr.contains("(allowed: a run file written by `spherecontact verify --out`)"),
            "{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(!junit.exists());
    }
}

/// The first value (`  [point, X],`) of the first check entry of a baseline file, scaled by
/// `1 + change`.
fn perturb_first_value(file: &Path, change: f64) {
    let stored = text(file);
    let line = stored.lines().find(|l| l.starts_with("  [")).unwrap();
    let (point, value) = line
        .trim()
        .trim_start_matches('[')
        .trim_end_matches("],")
        .split_once(", ")
        .unwrap();
    let value: f64 = value.parse().unwrap();
    let perturbed = stored.replacen(line, &format!("  [{point}, {:e}],", value * (1.0 + change)), 1);
    assert_ne!(perturbed, stored);
    std::fs::write(file, perturbed).unwrap();
}

#[test]
#[ignore = "heavy: baseline update and verify three times on an impact case with LAMMPS and YADE, 13 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn an_impact_value_that_drifts_from_its_baseline_fails_verify() {
    let dir = tempfile::tempdir().unwrap();
    let baselines = dir.path().join("baselines");
    let junit = dir.path().join("verify.xml");
    let verify = || {
        run(&[
            "verify",
            NORMAL,
            "--baselines",
            path(&baselines),
            "--junit",
            path(&junit),
            "--force",
        ])
    };
    let (code, stdout, stderr) = run(&["baseline", "update", NORMAL, "--baselines", path(&baselines)]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let file = baselines.join("chung-ooi-2.toml");
    let stored = text(&file);
    assert!(
        stored.contains("[solvers.\"mdr\"]")
            && stored.contains("resolution = \"2000 steps per Hertz contact duration, 4000 springs\"")
            && stored
                .contains("check = \"mdr contact_duration (prescribed) vs hertz closed form (relative)\""),
        "{stored}"
    );
    // A baseline holds the checks that have a value: the laws' 20, and the DEM codes' 28 where
    // LAMMPS, YADE, LIGGGHTS and Kratos are installed (N/A checks have none).
    let codes = common::decks::these_tools_present(
        "the DEM codes' baseline values",
        &[Tool::Lammps, Tool::Yade, Tool::Liggghts, Tool::KratosDem],
    );
    let with_value = if codes { 48 } else { 20 };
    assert_eq!(stored.matches("[[checks]]").count(), with_value, "{stored}");
    let (code, stdout, _) = verify();
    assert_eq!(code, 0, "{stdout}");
    // The in-crate integrator is deterministic: the laws' 20 values again to the bit (their drift
    // tolerance is the round-off 1e-12; the DEM codes' is 1e-9, for their own last digits).
    let in_crate_unmoved = stdout
        .lines()
        .filter(|l| l.contains("| drift 0 at all ") && l.contains("tol 1.0000e-12)"))
        .count();
    assert_eq!(in_crate_unmoved, 20, "{stdout}");
    // Below the round-off tolerance (1e-12): no drift verdict.
    perturb_first_value(&file, 1e-14);
    let (code, stdout, _) = verify();
    assert_eq!(code, 0, "{stdout}");
    // Beyond it, well inside the check's own tolerance (1e-6): DRIFT alone fails the run.
    std::fs::write(&file, &stored).unwrap();
    perturb_first_value(&file, 1e-9);
    let (code, stdout, _) = verify();
    assert_eq!(code, 1, "{stdout}");
    let row = stdout
        .lines()
        .find(|l| l.contains("mdr contact_duration (prescribed)"))
        .unwrap();
    assert!(row.starts_with("DRIFT chung-ooi-2"), "{row}");
    assert!(
        row.contains("| drift: first beyond tol at sweep point ")
            && row.contains("(change 1.0000e-9)")
            && row.contains("1 of ")
            && row.contains("tol 1.0000e-12"),
        "{row}"
    );
    assert!(
        stdout.contains("1 checks drifted from their baselines"),
        "{stdout}"
    );
    let xml = text(&junit);
    assert!(
        xml.contains("failures=\"1\"") && xml.contains("<failure message=\"DRIFT\">"),
        "{xml}"
    );
}

#[test]
fn impact_labels_come_from_the_case_file_and_select() {
    let case = spherecontact::case::load_impact(&root().join(NORMAL)).unwrap();
    assert_eq!(case.labels, ["impact", "dem", "fast"]);
    let dir = tempfile::tempdir().unwrap();
    let none = dir.path().join("none");
    // An empty baselines folder: a missing one is an error (a typo would hide the check).
    std::fs::create_dir(&none).unwrap();
    let cases_run = |stdout: &str| -> Vec<String> {
        stdout
            .lines()
            .filter_map(|l| Some(l.strip_prefix("== ")?.split(' ').next()?.to_owned()))
            .collect()
    };
    let (code, stdout, stderr) = run(&[
        "verify",
        NORMAL,
        PATH_CASE,
        "--label",
        "impact",
        "--baselines",
        path(&none),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(cases_run(&stdout), ["chung-ooi-2"]);
    let (code, stdout, stderr) = run(&[
        "verify",
        NORMAL,
        PATH_CASE,
        "--skip-label",
        "impact",
        "--baselines",
        path(&none),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(cases_run(&stdout), ["hard-dissimilar"]);
    // A file of its own labels: the label it lacks leaves it out.
    let relabelled = dir.path().join("case.toml");
    std::fs::write(
        &relabelled,
        text(&root().join(NORMAL)).replace("labels = [\"impact\", \"dem\", \"fast\"]", "labels = [\"dem\"]"),
    )
    .unwrap();
    let (code, _, stderr) = run(&["verify", path(&relabelled), "--label", "impact"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("none selected by label"), "{stderr}");
}

#[test]
fn bad_labels_exit_2_through_verify_writing_nothing() {
    let files: Vec<_> = std::fs::read_dir(root().join("tests/hostile/impact"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_string_lossy().starts_with("labels-"))
        .collect();
    assert_eq!(files.len(), 3);
    for file in files {
        let text = text(&file);
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("case.toml"), &text).unwrap();
        let output = spherecontact(
            &["verify", "case.toml", "--junit", "verify.xml", "--out", "out"],
            dir.path(),
        );
        let stderr = String::from_utf8_lossy(&output.stderr);
        let name = file.file_name().unwrap().to_string_lossy();
        assert_eq!(output.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains("case.toml"), "{name}: {stderr}");
        assert!(stderr.contains(&header(&text, "field")), "{name}: {stderr}");
        assert!(stderr.contains(&header(&text, "says")), "{name}: {stderr}");
        assert!(!stderr.contains("panicked"), "{name}: {stderr}");
        assert!(!dir.path().join("verify.xml").exists(), "{name}: wrote the JUnit");
        assert!(
            !dir.path().join("out").join("run.json").exists(),
            "{name}: wrote a run file"
        );
    }
}
