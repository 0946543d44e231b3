//! The findings of the hostile-user review (issue "Robustness"), one regression test each: every
//! one of these failed before its fix.
//!
//! Run: `cargo test --test suite hostile_findings::`.

use crate::common;

use common::spherecontact;
use std::path::Path;
use std::process::{Command, Output};

use spherecontact::case::{Case, MAX_FIELD_POSITIONS};
use spherecontact::history::History;
use spherecontact::registry;
use spherecontact::scene::Scene;
use spherecontact::solver::{self, Kind, SolveError, Solver};

/// A valid case; each test changes one thing.
const VALID: &str = common::SMALL_CASE;

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Writes `text` as case.toml in a fresh folder and runs `args` there.
fn with_case(text: &str, args: &[&str]) -> (tempfile::TempDir, Output) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), text).unwrap();
    let output = spherecontact(args, dir.path());
    (dir, output)
}

fn parse(text: &str) -> Result<Case, String> {
    Case::parse(Path::new("case.toml"), text).map_err(|e| e.to_string())
}

// --- Finding 1: a validated case made a solver panic --------------------------------------------

#[test]
fn subnormal_young_modulus_is_rejected_with_its_range() {
    for young in ["5e-324", "1e-308"] {
        let text = VALID.replacen("young = 70e9", &format!("young = {young}"), 1);
        let message = parse(&text).unwrap_err();
        assert!(message.contains("body1.young"), "{message}");
        assert!(message.contains("case.toml:8:9"), "{message}");
        assert!(message.contains("allowed: 1e3 ≤ E ≤ 1e13 Pa"), "{message}");
    }
}

#[test]
fn an_approach_too_small_for_any_force_is_rejected() {
    // δn = 1e-300 m is finite and positive, but P = 4/3 E* c δn underflows to zero.
    let text = VALID
        .replacen("unit = \"um\"", "unit = \"m\"", 1)
        .replacen("delta_n = [0, 10, 10]", "delta_n = [0, 1e-300, 1e-300]", 1)
        .replacen("delta_t = [0, 0, 1]", "delta_t = [0, 0, 0]", 1);
    let message = parse(&text).unwrap_err();
    assert!(message.contains("path.delta_n"), "{message}");
    assert!(message.contains("normal_force"), "{message}");
}

/// A solver that panics, standing for any bug a case might still reach.
struct Panicking;

impl Solver for Panicking {
    fn name(&self) -> &'static str {
        "panicking"
    }

    fn kind(&self) -> Kind {
        Kind::Analytic
    }
    fn description(&self) -> &'static str {
        "panics"
    }
    fn solve(&self, _: &Scene) -> Result<History, SolveError> {
        let empty: Vec<f64> = Vec::new();
        Ok(History {
            steps: Vec::with_capacity(empty[3] as usize),
            ..History::default()
        })
    }
}

#[test]
fn a_panicking_solver_is_a_failure_of_that_solver() {
    let scene = parse(VALID).unwrap().scene;
    match solver::run(&Panicking, &scene) {
        Err(SolveError::Failed(message)) => {
            assert!(message.contains("internal error"), "{message}");
            assert!(message.contains("index out of bounds"), "{message}");
        }
        other => panic!("expected a failure, got {other:?}"),
    }
}

// --- Finding 2: surface fields at every position, without bound ----------------------------------

/// A valid case of `positions` positions: load, then small reversals of δt at constant δn.
fn many_positions(positions: usize) -> String {
    let delta_n: Vec<String> = (0..positions)
        .map(|k| if k == 0 { "0" } else { "10" }.into())
        .collect();
    let delta_t: Vec<String> = (0..positions)
        .map(|k| {
            if k < 2 {
                "0"
            } else if k % 2 == 0 {
                "0.2"
            } else {
                "-0.2"
            }
            .into()
        })
        .collect();
    VALID
        .replacen(
            "delta_n = [0, 10, 10]",
            &format!("delta_n = [{}]", delta_n.join(", ")),
            1,
        )
        .replacen(
            "delta_t = [0, 0, 1]",
            &format!("delta_t = [{}]", delta_t.join(", ")),
            1,
        )
        .replacen("substeps = 4", "substeps = 1", 1)
}

#[test]
fn surface_fields_are_kept_at_a_bounded_set_of_positions_including_the_focus() {
    let positions = MAX_FIELD_POSITIONS + 8;
    let text = many_positions(positions).replacen("friction = 0.2", "friction = 0.2\nfocus = 20", 1);
    let case = parse(&text).unwrap();
    for name in ["mdr", "cattaneo-mindlin", "bem", "fem-axisym"] {
        let s = registry::by_name(name).unwrap();
        let history = match solver::run(s.as_ref(), &case.scene) {
            Ok(h) => h,
            Err(SolveError::NotApplicable(_)) => continue,
            Err(e) => panic!("{name}: {e}"),
        };
        assert!(
            history.fields.len() <= MAX_FIELD_POSITIONS,
            "{name}: {} fields for a path of {positions} positions",
            history.fields.len()
        );
        assert!(
            history.fields.iter().any(|f| f.position == 20),
            "{name}: no field at the focus position"
        );
    }
}

#[test]
fn a_case_may_name_the_positions_with_fields() {
    let text = VALID.replacen("friction = 0.2", "friction = 0.2\nfields = [1]", 1);
    let case = parse(&text).unwrap();
    let history = solver::run(registry::by_name("mdr").unwrap().as_ref(), &case.scene).unwrap();
    let positions: Vec<_> = history.fields.iter().map(|f| f.position).collect();
    // Position 1 as asked, and the focus (the first position of largest δn, also 1).
    assert_eq!(positions, [1]);
}

#[test]
fn asking_for_too_many_positions_with_fields_is_rejected() {
    let text = many_positions(MAX_FIELD_POSITIONS + 2).replacen(
        "friction = 0.2",
        "friction = 0.2\nfields = \"every-position\"",
        1,
    );
    let message = parse(&text).unwrap_err();
    assert!(message.contains("field `fields`"), "{message}");
    assert!(
        message.contains(&format!("at most {MAX_FIELD_POSITIONS}")),
        "{message}"
    );
}

// --- Finding 3: `mesh` with a relative --out --------------------------------------------------

#[test]
fn mesh_works_with_its_default_relative_output_folder() {
    let gmsh = spherecontact::toolchain::Toolchain::default();
    if gmsh.require(spherecontact::toolchain::Tool::Gmsh).is_err() {
        eprintln!(
            "mesh_works_with_its_default_relative_output_folder: skipped, gmsh missing (scripts/setup.sh)"
        );
        return;
    }
    let (dir, output) = with_case(VALID, &["mesh", "case.toml"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    for file in ["mesh.geo", "mesh.msh", "mesh_p1_mm.msh"] {
        assert!(dir.path().join("out/mesh").join(file).is_file(), "{file}");
    }
}

// --- Finding 4: a case's name became an output folder unchecked --------------------------------

#[test]
fn a_name_that_is_not_a_plain_name_is_rejected_and_nothing_escapes() {
    let text = VALID.replacen("name = \"cli-test\"", "name = \"x/../../../escaped\"", 1);
    let (dir, output) = with_case(&text, &["compare", "case.toml"]);
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    let message = stderr(&output);
    assert!(message.contains("case.toml:2:8"), "{message}");
    assert!(message.contains("field `name`"), "{message}");
    assert!(message.contains("A–Z a–z 0–9 . _ -"), "{message}");
    assert!(!dir.path().join("out").exists());
    assert!(!dir.path().join("escaped").exists());
}

#[test]
fn a_file_stem_that_is_not_a_plain_name_needs_a_name() {
    let text = VALID.replacen("name = \"cli-test\"\n", "", 1);
    let message = Case::parse(Path::new("my case.toml"), &text)
        .unwrap_err()
        .to_string();
    assert!(message.contains("field `name`"), "{message}");
    assert!(message.contains("`my case`"), "{message}");
}

// --- Finding 5: inf in the output from finite inputs -------------------------------------------

#[test]
fn path_values_beyond_the_smaller_radius_are_rejected() {
    let text = VALID
        .replacen("unit = \"um\"", "unit = \"m\"", 1)
        .replacen("delta_n = [0, 10, 10]", "delta_n = [0, 1e-5, 1e-5]", 1)
        .replacen("delta_t = [0, 0, 1]", "delta_t = [0, -1.7e308, 1.7e308]", 1);
    let message = parse(&text).unwrap_err();
    assert!(message.contains("path.delta_t[1]"), "{message}");
    assert!(message.contains("|δt| ≤ 0.1 m"), "{message}");
    assert!(!message.contains("000000000"), "a 300-digit number: {message}");
}

/// A solver whose path columns are not finite: stands for any arithmetic slip.
struct InfinitePath;

impl Solver for InfinitePath {
    fn name(&self) -> &'static str {
        "infinite-path"
    }

    fn kind(&self) -> Kind {
        Kind::Analytic
    }
    fn description(&self) -> &'static str {
        "writes δt = inf"
    }
    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let mut history = solver::run(&spherecontact::analytic::hertz::HertzSolver, scene)?;
        history.steps[1].delta_t = f64::INFINITY;
        Ok(history)
    }
}

#[test]
fn every_output_column_is_checked_for_finite_values() {
    let scene = parse(VALID).unwrap().scene;
    match solver::run(&InfinitePath, &scene) {
        Err(SolveError::Failed(message)) => assert!(message.contains("delta_t"), "{message}"),
        other => panic!("expected a failure, got {other:?}"),
    }
}

// --- Smaller findings ---------------------------------------------------------------------------

#[cfg(unix)]
#[test]
fn a_fifo_as_case_file_is_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("case.toml");
    let c_path = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c_path.as_ptr(), 0o600) }, 0);
    let mut child = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(["run", "case.toml"])
        .current_dir(dir.path())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    // A blocked reader never exits: give it ample time (10 s against a few ms), then fail.
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > std::time::Duration::from_secs(10) {
            child.kill().unwrap();
            panic!("blocked on the FIFO");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert!(
        stderr(&output).contains("not a regular file"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn an_oversized_case_file_is_refused_before_it_is_parsed() {
    let mut text = VALID.to_owned();
    text.push_str(&format!("# {}\n", "x".repeat(5 << 20)));
    let (dir, output) = with_case(&text, &["run", "case.toml"]);
    assert_eq!(output.status.code(), Some(2));
    let message = stderr(&output);
    assert!(message.contains("case.toml"), "{message}");
    assert!(message.contains("allowed: at most 4 MiB"), "{message}");
    assert!(!dir.path().join("out").exists());
}

#[test]
fn a_broken_reference_file_names_the_case_file_and_the_check() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("ref.toml"),
        "[p]\nquantity = \"normal_force\"\nvalue = \"many\"\nunit = \"N\"\nsource = \"s\"\n",
    )
    .unwrap();
    let text = format!(
        "{VALID}\n[[checks]]\nsolver = \"hertz\"\nquantity = \"normal_force\"\nat = {{ position = 1 }}\n\
         reference = {{ file = \"ref.toml\", key = \"p\" }}\ntolerance = 1e-3\nreason = \"r\"\n"
    );
    let case = dir.path().join("case.toml");
    std::fs::write(&case, text).unwrap();
    let message = Case::load(&case).unwrap_err().to_string();
    assert!(message.contains("case.toml:21:"), "{message}");
    assert!(message.contains("checks[0].reference"), "{message}");
    assert!(message.contains("ref.toml"), "{message}");
    assert!(message.contains("`p`"), "{message}");
}

#[test]
fn the_greek_mu_is_accepted_like_the_micro_sign() {
    let greek = parse(&VALID.replacen("unit = \"um\"", "unit = \"μm\"", 1)).unwrap();
    let micro = parse(&VALID.replacen("unit = \"um\"", "unit = \"µm\"", 1)).unwrap();
    assert_eq!(greek.scene.path, micro.scene.path);
    assert_eq!(greek.scene.path.max_approach(), 10.0 * 1e-6);
}

#[test]
fn output_destinations_are_checked_before_any_solver_runs() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), VALID).unwrap();
    std::fs::write(dir.path().join("a-file"), "").unwrap();
    for args in [
        &["verify", "case.toml", "--junit", "no/such/folder/v.xml"][..],
        &["verify", "case.toml", "--junit", "."][..],
        &["compare", "case.toml", "--out", "a-file"][..],
        &["bench", "case.toml", "--repeat", "1", "--out", "a-file/sub"][..],
    ] {
        let output = spherecontact(args, dir.path());
        assert_eq!(output.status.code(), Some(2), "{args:?}: {}", stderr(&output));
        // Nothing ran: no result table, no report.
        assert!(
            output.stdout.is_empty(),
            "{args:?}: ran before checking its output"
        );
    }
}

#[test]
fn a_solver_named_twice_on_the_command_line_is_bad_input() {
    let (dir, output) = with_case(
        VALID,
        &["run", "case.toml", "--solver", "hertz", "--solver", "hertz"],
    );
    assert_eq!(output.status.code(), Some(2));
    assert!(
        stderr(&output).contains("`hertz` is named twice"),
        "{}",
        stderr(&output)
    );
    assert!(!dir.path().join("out").exists());
}

#[test]
fn an_infinite_resolution_is_refused_as_not_finite() {
    let (_dir, output) = with_case(VALID, &["mesh", "case.toml", "--resolution", "inf"]);
    assert_eq!(output.status.code(), Some(2));
    assert!(
        stderr(&output).contains("finite and positive"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_mesh_too_fine_for_the_machine_is_refused_with_the_smallest_allowed_size() {
    let (dir, output) = with_case(VALID, &["mesh", "case.toml", "--resolution", "1e-9"]);
    assert_eq!(output.status.code(), Some(2));
    let message = stderr(&output);
    assert!(message.contains("--resolution"), "{message}");
    assert!(message.contains("finer than allowed"), "{message}");
    assert!(message.contains("allowed: c/N"), "{message}");
    assert!(!dir.path().join("out").exists());
}

#[cfg(unix)]
#[test]
fn a_symlink_loop_under_the_cases_folder_does_not_recurse_forever() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("cases")).unwrap();
    std::fs::write(dir.path().join("cases/case.toml"), VALID).unwrap();
    std::os::unix::fs::symlink("..", dir.path().join("cases/loop")).unwrap();
    let output = spherecontact(&["list"], dir.path());
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(stdout.matches("cli-test").count(), 1, "{stdout}");
}
