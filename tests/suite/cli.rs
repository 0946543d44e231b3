//! The command line end to end: bad input gives a clear message naming file, field and allowed
//! range, exit code 2 and no output; `verify` judges the shipped cases; `run` writes the files.

use crate::common;

use common::{root, spherecontact};

/// A valid case: the small case with one check; each bad-input test breaks one rule of it.
fn valid() -> String {
    format!(
        "{}{}",
        common::SMALL_CASE,
        r#"
[[checks]]
solver = "mdr"
quantity = "normal_force"
at = "every-position"
reference = { solver = "hertz" }
tolerance = 1e-3
reason = "midpoint rule on 4000 springs"
"#
    )
}

/// Writes `text` as case.toml in a fresh folder, runs `run` on it into out/, and returns
/// (exit code, stderr); asserts out/ stays empty whenever the exit code is 2.
fn run_case_text(text: &str) -> (i32, String) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), text).unwrap();
    let output = spherecontact(&["run", "case.toml", "--out", "out"], dir.path());
    let code = output.status.code().unwrap();
    if code == 2 {
        assert!(!dir.path().join("out").exists(), "bad input must write nothing");
    }
    (code, String::from_utf8_lossy(&output.stderr).into_owned())
}

/// Asserts that replacing `from` by `to` in the valid case is rejected with exit code 2 and a
/// message naming the file, `field` and containing `allowed`.
fn assert_rejected(from: &str, to: &str, field: &str, allowed: &str) {
    let valid = valid();
    assert!(valid.contains(from), "test error: `{from}` not in the valid case");
    let (code, stderr) = run_case_text(&valid.replacen(from, to, 1));
    assert_eq!(code, 2, "{from} → {to}: exit code {code}, stderr: {stderr}");
    assert!(stderr.contains("case.toml"), "no file name in: {stderr}");
    assert!(stderr.contains(field), "no field `{field}` in: {stderr}");
    assert!(stderr.contains(allowed), "no `{allowed}` in: {stderr}");
    assert!(!stderr.contains("panicked"), "panic: {stderr}");
}

#[test]
fn the_valid_case_runs() {
    let (code, stderr) = run_case_text(&valid());
    assert_eq!(code, 0, "{stderr}");
}

#[test]
fn young_modulus_must_be_in_its_physical_range() {
    for bad in ["young = 0.0", "young = -70e9", "young = 999.0", "young = 1.1e13"] {
        assert_rejected("young = 70e9", bad, "body1.young", "1e3 ≤ E ≤ 1e13 Pa");
    }
}

#[test]
fn poisson_ratio_must_lie_between_minus_one_and_one_half() {
    assert_rejected("poisson = 0.3", "poisson = 0.5", "body1.poisson", "−1 < ν < 0.5");
    assert_rejected("poisson = 0.3", "poisson = -1.0", "body1.poisson", "−1 < ν < 0.5");
}

#[test]
fn friction_must_be_between_zero_and_ten() {
    assert_rejected("friction = 0.2", "friction = -0.1", "friction", "0 ≤ μ ≤ 10");
    assert_rejected("friction = 0.2", "friction = 10.5", "friction", "0 ≤ μ ≤ 10");
}

#[test]
fn radius_must_be_in_its_physical_range() {
    for bad in ["radius = 0.0", "radius = -inf", "radius = 1e-10", "radius = 2e3"] {
        assert_rejected("radius = 0.1", bad, "body1.radius", "1e-9 ≤ R ≤ 1e3 in m, or inf");
    }
}

#[test]
fn two_flats_are_rejected() {
    assert_rejected(
        "radius = 0.1",
        "radius = inf",
        "body2.radius",
        "at least one finite radius",
    );
}

#[test]
fn numbers_must_be_finite() {
    assert_rejected("young = 70e9", "young = nan", "body1.young", "1e3 ≤ E ≤ 1e13 Pa");
    assert_rejected("friction = 0.2", "friction = inf", "friction", "0 ≤ μ ≤ 10");
    assert_rejected(
        "delta_n = [0, 10, 10]",
        "delta_n = [0, nan, 10]",
        "path.delta_n[1]",
        "finite",
    );
}

#[test]
fn the_path_needs_at_least_one_position() {
    assert_rejected(
        "delta_n = [0, 10, 10]\ndelta_t = [0, 0, 1]",
        "delta_n = []\ndelta_t = []",
        "path.delta_n",
        "at least one",
    );
}

#[test]
fn delta_t_needs_one_value_per_position() {
    assert_rejected(
        "delta_t = [0, 0, 1]",
        "delta_t = [0, 0]",
        "path.delta_t",
        "one per position",
    );
}

#[test]
fn substeps_must_be_at_least_one() {
    assert_rejected("substeps = 4", "substeps = 0", "path.substeps", "from 1 to");
    assert_rejected(
        "substeps = 4",
        "substeps = [4]",
        "path.substeps",
        "one per segment",
    );
}

#[test]
fn the_unit_must_be_known() {
    assert_rejected("unit = \"um\"", "unit = \"inch\"", "path.unit", "m, mm, um, µm");
}

#[test]
fn the_focus_must_be_a_path_position() {
    assert_rejected(
        "friction = 0.2",
        "friction = 0.2\nfocus = 3",
        "focus",
        "allowed: 0 to 2",
    );
    assert_rejected(
        "friction = 0.2",
        "friction = 0.2\nfocus = -1",
        "focus",
        "allowed: 0 to 2",
    );
}

#[test]
fn unknown_fields_are_rejected() {
    assert_rejected(
        "poisson = 0.3",
        "poisson = 0.3\ndensity = 2700",
        "",
        "unknown field `density`",
    );
}

#[test]
fn solvers_must_be_known() {
    assert_rejected(
        "solvers = [\"hertz\", \"mdr\"]",
        "solvers = [\"hertz\", \"ansys\"]",
        "solvers",
        "unknown solver `ansys` (allowed: ",
    );
    // A misspelling names what was meant.
    assert_rejected(
        "solvers = [\"hertz\", \"mdr\"]",
        "solvers = [\"hertz\", \"mdr-domian\"]",
        "solvers",
        "unknown solver `mdr-domian`; did you mean `mdr-domain`? (allowed: ",
    );
    assert_rejected(
        "solvers = [\"hertz\", \"mdr\"]",
        "solvers = []",
        "solvers",
        "at least one",
    );
}

#[test]
fn checks_are_validated() {
    assert_rejected(
        "quantity = \"normal_force\"",
        "quantity = \"torque\"",
        "checks[0].quantity",
        "allowed: normal_force",
    );
    assert_rejected(
        "at = \"every-position\"",
        "at = { position = 7 }",
        "checks[0].at",
        "positions 0 to 2",
    );
    assert_rejected(
        "tolerance = 1e-3",
        "tolerance = 0.0",
        "checks[0].tolerance",
        "tolerance > 0",
    );
    assert_rejected(
        "reason = \"midpoint rule on 4000 springs\"",
        "reason = \" \"",
        "checks[0].reason",
        "needs its reason",
    );
    assert_rejected(
        "tolerance = 1e-3\n",
        "",
        "checks[0].tolerance",
        "required unless informational",
    );
    assert_rejected(
        "reference = { solver = \"hertz\" }",
        "reference = { file = \"nope.toml\", key = \"x\" }",
        "checks[0].reference.file",
        "cannot read",
    );
}

#[test]
fn syntax_errors_give_line_and_column() {
    let (code, stderr) = run_case_text(&valid().replacen("young = 70e9", "young = = 70e9", 1));
    assert_eq!(code, 2);
    assert!(stderr.contains("case.toml:8:"), "no line number in: {stderr}");
}

#[test]
fn a_missing_case_file_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let output = spherecontact(&["run", "missing.toml"], dir.path());
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("missing.toml"));
}

#[test]
fn run_writes_the_documented_csv_columns_and_json() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), valid()).unwrap();
    let output = spherecontact(
        &["run", "case.toml", "--solver", "mdr", "--out", "out"],
        dir.path(),
    );
    assert!(output.status.success());
    let csv = std::fs::read_to_string(dir.path().join("out/mdr.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "step,position,delta_n,delta_t,normal_force,tangential_force,contact_radius,peak_pressure,stick_radius"
    );
    let rows: Vec<_> = lines.collect();
    assert_eq!(rows.len(), 9, "one row per step including step 0");
    assert!(rows[0].starts_with("0,0,"));
    assert!(
        rows[1].starts_with("1,,"),
        "position is empty between positions: {}",
        rows[1]
    );
    let cells: Vec<_> = rows[1].split(',').collect();
    assert_eq!(cells.len(), 9);
    assert_eq!(
        cells[7], "",
        "MDR gives no peak pressure: the cell is empty, not zero or NaN"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/mdr.json")).unwrap()).unwrap();
    assert_eq!(json["metadata"]["solver"], "mdr");
    assert!(json["metadata"]["wall_time_s"].as_f64().unwrap() >= 0.0);
    assert_eq!(json["steps"].as_array().unwrap().len(), 9);
}

/// The shipped cases whose solvers all run in-crate: the hard cases and the sphere on a flat. The
/// cases with decks and DEM codes are verified by CI's own `verify --require-external` step
/// (.ci/run) and their solvers by tests/external*.rs and tests/dem_codes.rs; running them here
/// too, in a debug build, would double CI's longest step.
#[test]
fn verify_passes_on_the_in_crate_shipped_cases_and_writes_junit() {
    let dir = tempfile::tempdir().unwrap();
    let junit = dir.path().join("verify.xml");
    let mut args = vec![
        "verify".to_owned(),
        "--junit".to_owned(),
        junit.to_str().unwrap().to_owned(),
    ];
    let mut hard: Vec<String> = std::fs::read_dir(root().join("cases/hard"))
        .unwrap()
        .map(|e| format!("cases/hard/{}", e.unwrap().file_name().to_string_lossy()))
        .collect();
    hard.sort();
    args.extend(hard);
    args.push("cases/sphere-on-flat.toml".to_owned());
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let output = spherecontact(&args, &root());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.contains("OK    sphere-on-flat | fem-axisym normal_force"));
    assert!(stdout.contains("OK    hard-reversal-every-step | mdr tangential_force"));
    assert!(!stdout.contains("NOOK"));
    let xml = std::fs::read_to_string(junit).unwrap();
    assert!(xml.starts_with("<?xml") && xml.contains("<testsuite name=\"sphere-on-flat\""));
    assert!(xml.contains("<testsuite name=\"hard-grazing\""));
    assert!(xml.contains("failures=\"0\""));
}

#[test]
fn verify_fails_with_exit_code_one_on_a_nook() {
    let dir = tempfile::tempdir().unwrap();
    // MDR cannot meet 1e-12 against Hertz on 4000 springs (its quadrature error is ~1e-7).
    let text = valid().replacen("tolerance = 1e-3", "tolerance = 1e-12", 1);
    std::fs::write(dir.path().join("case.toml"), text).unwrap();
    let output = spherecontact(&["verify", "case.toml"], dir.path());
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stdout).contains("NOOK  cli-test | mdr normal_force"));
}

#[test]
fn run_writes_vtu_fields_for_solvers_that_have_them() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), valid()).unwrap();
    let output = spherecontact(
        &[
            "run",
            "case.toml",
            "--solver",
            "fem-axisym",
            "--solver",
            "mdr",
            "--out",
            "out",
            "--vtu",
        ],
        dir.path(),
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let vtu_dir = dir.path().join("out/fem-axisym-vtu");
    let files: Vec<_> = std::fs::read_dir(&vtu_dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    // Per path position: the meridian volume (n = 0), the n = 1 amplitudes (the case shifts)
    // and the reconstructed 3D contact surface.
    for position in 0..3 {
        for suffix in ["", "-n1", "-surface"] {
            let name = format!("cli-test-fem-axisym-{position}{suffix}.vtu");
            assert!(vtu_dir.join(&name).exists(), "{name} missing: {files:?}");
        }
    }
    assert_eq!(files.len(), 9, "three VTU per path position: {files:?}");
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let xml = roxmltree::Document::parse(&text).unwrap();
        assert_eq!(xml.root_element().attribute("type"), Some("UnstructuredGrid"));
    }
    assert!(!dir.path().join("out/mdr-vtu").exists(), "MDR has no VTU fields");
}

#[test]
fn run_writes_the_bem_maps_as_vtu_grids() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), valid()).unwrap();
    let output = spherecontact(
        &["run", "case.toml", "--solver", "bem", "--out", "out", "--vtu"],
        dir.path(),
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let file = dir.path().join("out/bem-vtu/cli-test-bem-2.vtu");
    let text = std::fs::read_to_string(&file).unwrap();
    let xml = roxmltree::Document::parse(&text).unwrap();
    let piece = xml.descendants().find(|n| n.has_tag_name("Piece")).unwrap();
    // 64² panel centres joined by 63² quads.
    assert_eq!(piece.attribute("NumberOfPoints"), Some("4096"));
    assert_eq!(piece.attribute("NumberOfCells"), Some("3969"));
    for name in ["pressure", "traction", "stick"] {
        assert!(
            xml.descendants().any(|n| n.attribute("Name") == Some(name)),
            "no {name} array"
        );
    }
}

#[test]
fn ranks_must_be_a_rank_count() {
    for bad in ["ranks = 0", "ranks = -2", "ranks = 1025"] {
        assert_rejected(
            "friction = 0.2",
            &format!("friction = 0.2\n{bad}"),
            "ranks",
            "1 ≤ ranks ≤ 1024",
        );
    }
    let (code, stderr) = run_case_text(&valid().replacen("friction = 0.2", "friction = 0.2\nranks = 2", 1));
    assert_eq!(code, 0, "{stderr}");
}
