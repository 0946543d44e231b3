//! The Kratos FEM deck `kratos-3d`: a bad `[kratos]` value refused by the command line, a
//! crashing, hanging or garbage-writing driver failing with its reason and log (heavy: each meshes
//! with gmsh), a deck written, run by hand and read back equal to the solver's own run (heavy),
//! the 8-node bricks' run against mdr-domain (heavy), and the frictional ALM's symmetry: friction
//! leaves P as the frictionless ALM's, and gross sliding is at μ (heavy).
//!
//! Run: `cargo test --release --test suite external_kratos3d:: -- --include-ignored`.

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use spherecontact::case::Case;
use spherecontact::kratos::KratosSolid;
use spherecontact::scene::Scene;
use spherecontact::solver::{self, split::SplitDeck, SolveError};
use spherecontact::toolchain::{Tool, Toolchain};

use crate::common::decks::{force_error_against_mdr_domain, these_tools_present};
use crate::common::refused::{assert_refused, Left};
use spherecontact::kratos_settings::{Element, Formulation};

fn normal_case() -> Case {
    Case::load(Path::new("cases/kratos-3d-normal.toml")).unwrap()
}

/// kratos-3d at c_max/2 (the coarsest) on `scene`, with the case's settings.
fn coarse(case: &Case) -> KratosSolid {
    KratosSolid {
        settings: case.kratos,
        options: spherecontact::external::axisym::Options {
            resolution: Some(case.scene.max_contact_radius() / 2.0),
            ..Default::default()
        },
    }
}

/// The failure of a run that must fail; its kept run directory (with the deck's files and the
/// driver's log) checked and removed.
fn failure_of(solver: &KratosSolid, scene: &Scene) -> String {
    let message = match solver::run(solver, scene) {
        Err(SolveError::Failed(m)) => m,
        other => panic!("expected a failure, got {other:?}"),
    };
    let kept = message
        .rsplit("kept in ")
        .next()
        .and_then(|s| s.strip_suffix(')'));
    let kept = Path::new(kept.expect("the run directory is kept on failure"));
    for file in [
        "spheres.mdpa",
        "ProjectParameters.json",
        "kratos_3d.py",
        "deck.stderr",
    ] {
        assert!(kept.join(file).is_file(), "{file} not kept: {message}");
    }
    std::fs::remove_dir_all(kept).ok();
    message
}

/// Requirement: a `[kratos]` value outside its allowed set (the formulation, the element) is
/// refused before anything runs, with exit code 2, the file, the field and the allowed set (exact
/// words).
#[test]
fn a_bad_kratos_setting_exits_2_naming_the_file_the_field_and_the_allowed_set() {
    let bad = [
        (
            "contact = \"lagrange\"",
            "kratos.contact",
            "allowed: alm-frictional, alm-frictionless, penalty",
        ),
        ("element = \"hex20\"", "kratos.element", "allowed: tet4, hex8"),
    ];
    for (line, field, allowed) in bad {
        let dir = tempfile::tempdir().unwrap();
        let text = std::fs::read_to_string("cases/kratos-3d-normal.toml")
            .unwrap()
            .replace("contact = \"alm-frictionless\"", line);
        let case = dir.path().join("bad.toml");
        std::fs::write(&case, text).unwrap();
        assert_refused(&["verify"], &case, &["bad.toml", field, allowed], Left::Marker);
    }
}

/// Requirement: a driver that crashes, hangs or writes garbage makes the run fail with the
/// reason (exit code explained, the time limit, the file and column at fault) and its files
/// kept; never a value. Stand-in drivers replace Kratos' (the mesh and deck are the real ones).
#[test]
#[ignore = "heavy: three gmsh meshes and stand-in driver runs (one killed at a 3 s limit); .ci/run runs it"]
fn a_crashing_hanging_or_garbage_driver_fails_with_its_reason() {
    if !these_tools_present("kratos-3d faults", &[Tool::Gmsh, Tool::KratosContact]) {
        return;
    }
    let case = normal_case();
    let failure = |driver: &str, timeout_s: u64| {
        let mut solver = coarse(&case);
        solver.options.deck_text = Some(driver.to_owned());
        solver.options.timeout = Some(Duration::from_secs(timeout_s));
        failure_of(&solver, &case.scene)
    };
    let crash = failure("import sys\nsys.exit('stand-in: Kratos raised')\n", 60);
    assert!(
        crash.contains("exited with code 1") && crash.contains("stand-in: Kratos raised"),
        "{crash}"
    );
    let hang = failure("import time\ntime.sleep(60)\n", 3);
    assert!(hang.contains("did not finish within 3 s"), "{hang}");
    let garbage =
        "open('steps.csv', 'w').write('step,converged,iterations,residual,P1_N,Q1_N,P2_N,Q2_N,wall_s\\n\
                   0,1,5,0,0,0,0,0,1\\n1,1,5,0,nan,0,0,0,1\\n')\nopen('surface.csv', 'w').write('')\n";
    let garbage = failure(garbage, 60);
    assert!(
        garbage.contains("steps.csv:3") && garbage.contains("P1_N"),
        "{garbage}"
    );
}

/// Requirement: the deck written into a folder (`deck write`), run there by hand with the
/// command the folder names, reads back (`deck read`) to the solver's own history, value for
/// value (the same files, Kratos' direct solve deterministic on one thread: exact equality), and
/// its convergence record says every step converged (the frictionless ALM).
#[test]
#[ignore = "heavy: two Kratos runs of cases/kratos-3d-normal.toml at c_max/2 (about 10 s each); .ci/run runs it"]
fn a_written_deck_run_by_hand_reads_back_as_the_solvers_own_run() {
    if !these_tools_present("kratos-3d deck write/read", &[Tool::Gmsh, Tool::KratosContact]) {
        return;
    }
    let case = normal_case();
    let own = solver::run(&coarse(&case), &case.scene).unwrap();
    assert!(
        own.metadata.version.starts_with("Kratos 10.4"),
        "{}",
        own.metadata.version
    );
    let read = run_by_hand(&case);
    assert_eq!(own.steps.len(), read.steps.len());
    for (a, b) in own.steps.iter().zip(&read.steps) {
        assert_eq!(
            (a.normal_force, a.contact_radius),
            (b.normal_force, b.contact_radius)
        );
    }
}

/// The history of `case`'s deck at c_max/2 written into a folder (`deck write`), run there by
/// hand with the command the folder names and read back (`deck read`), after checking that its
/// convergence record says every step converged.
fn run_by_hand(case: &Case) -> spherecontact::history::History {
    let solver = coarse(case);
    let dir = tempfile::tempdir().unwrap();
    SplitDeck::write_run(&solver, &case.scene, dir.path()).unwrap();
    let command = SplitDeck::command(&solver);
    let status = Command::new(&command.program)
        .args(&command.args)
        .envs(command.env.iter().map(|(k, v)| (k, v)))
        .current_dir(dir.path())
        .stdout(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
    let read = SplitDeck::read_run(&solver, &case.scene, dir.path()).unwrap();
    let record = &read.metadata.extra["convergence_by_step"];
    assert_eq!(record.as_array().unwrap().len(), case.scene.steps().len());
    assert!(
        record.as_array().unwrap().iter().all(|s| s["converged"] == true),
        "{record}"
    );
    assert_eq!(Toolchain::default().kratos_python, command.program);
    read
}

/// Requirement: on 8-node bricks (`[kratos] element = "hex8"`, cases/kratos-3d-hex8.toml's
/// frictionless path at c_max/2, the coarsest) the deck written and run by hand reads back with
/// every step converged (that it equals the solver's own run is the mechanism the tetrahedra's
/// test above checks: the same writer, command and reader), the metadata names the element, and P at δn = 10 µm is mdr-domain's with the first-order bricks' offset measured by
/// the case's mesh study at this mesh (+11.5 %, 405.98 against 363.97 N). Tolerance: that offset
/// ± 0.5 % (the direct solve repeats to 1e-12; the band is for another machine's last digits of a
/// 9-iteration Newton and still fails a wrong element order, a lost brick or an unmirrored
/// sphere, each worth tens of per cent).
#[test]
#[ignore = "heavy: a Kratos run of cases/kratos-3d-hex8.toml at c_max/2 (about 20–40 s); .ci/run runs it"]
fn hex8_bricks_converge_read_back_and_carry_their_measured_offset_from_mdr_domain() {
    if !these_tools_present("kratos-3d hex8", &[Tool::Gmsh, Tool::KratosContact]) {
        return;
    }
    let case = Case::load(Path::new("cases/kratos-3d-hex8.toml")).unwrap();
    assert_eq!(case.kratos.element, Element::Hex8);
    let read = run_by_hand(&case);
    assert!(
        read.metadata.model.contains("SmallDisplacementElement3D8N"),
        "{}",
        read.metadata.model
    );
    let error = force_error_against_mdr_domain("kratos-3d hex8 c/2", &read, &case.scene);
    assert!((error - HEX8_OFFSET_C2).abs() < 5e-3, "{error:+.4e}");
}

/// The relative excess of kratos-3d's P over mdr-domain's on hex8 bricks at c_max/2 at
/// δn = 10 µm, measured (cases/kratos-3d-hex8.toml's mesh study).
const HEX8_OFFSET_C2: f64 = 405.98 / 363.97 - 1.0;

/// `cases/kratos-3d.toml` with its path taken on to gross sliding: δn = 10 µm, then δt = 1 and
/// 6 µm (MD's sliding shift for identical spheres is μ δn (2 − ν)/(2(1 − ν)) = 2.43 µm).
fn sliding_case(dir: &Path) -> Case {
    let text = std::fs::read_to_string("cases/kratos-3d.toml").unwrap();
    let text = text
        .replace("delta_n = [0, 10, 10]", "delta_n = [0, 10, 10, 10]")
        .replace("delta_t = [0, 0, 1]", "delta_t = [0, 0, 1, 6]")
        .replace("substeps = [1, 1]", "substeps = [1, 1, 1]");
    assert!(
        text.contains("delta_t = [0, 0, 1, 6]"),
        "cases/kratos-3d.toml's path changed"
    );
    let file = dir.join("kratos-3d-sliding.toml");
    std::fs::write(&file, text).unwrap();
    Case::load(&file).unwrap()
}

/// Requirement: the frictional ALM (kratos-3d's options, whole bodies) answers the two spheres'
/// symmetry: P at every position equals the frictionless ALM's on the same mesh (identical
/// spheres: the normal and tangential problems decouple), and in gross sliding Q/P is μ.
/// Tolerances: P to 1e-4 relative (measured 3e-6: Newton's residual; the half model with the
/// master's plane nodes free, the defect this guards against, was 1.3e-2 low); Q/P within 2e-3 of
/// μ = 0.2 (measured 0.19942: |q| = μp at every slipping node, Q/P short of μ only by the
/// traction's angle from the shift at the few nodes of this coarse mesh; the half model gave
/// 0.153 on the Figure 7 path).
#[test]
#[ignore = "heavy: two Kratos runs at c_max/2 (about 20 and 5 s); .ci/run runs it"]
fn friction_leaves_p_as_the_frictionless_alms_and_slides_at_mu() {
    if !these_tools_present("kratos-3d symmetry", &[Tool::Gmsh, Tool::KratosContact]) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = sliding_case(dir.path());
    assert_eq!(case.kratos.formulation, Formulation::AlmFrictional);
    let frictional = solver::run(&coarse(&case), &case.scene).unwrap();
    let mut frictionless = coarse(&case);
    frictionless.settings.formulation = Formulation::AlmFrictionless;
    let frictionless = solver::run(&frictionless, &case.scene).unwrap();
    let normal = frictionless.at_position(1).unwrap().normal_force.unwrap();
    for position in 1..=3 {
        let p = frictional.at_position(position).unwrap().normal_force.unwrap();
        assert!(
            (p / normal - 1.0).abs() < 1e-4,
            "position {position}: P = {p} against {normal} N"
        );
    }
    let sliding = frictional.at_position(3).unwrap();
    let ratio = sliding.tangential_force.unwrap() / sliding.normal_force.unwrap();
    assert!((ratio - case.scene.friction).abs() < 2e-3, "Q/P = {ratio}");
}
