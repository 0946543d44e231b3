//! The CalculiX deck `ccx-axisym` end to end and its faults: ccx missing (N/A), a deck CalculiX
//! refuses, a ccx that hangs (killed at the timeout, the run directory kept), output holding
//! garbage; and a real run on a coarse mesh against Hertz in series with the domain (mdr-domain),
//! which checks the factor 180 of CalculiX's 2-degree segment.
//!
//! Tests that need gmsh and ccx skip, saying why, where those are absent (`scripts/setup.sh`).
//! Run: `cargo test --test suite external_calculix::`.

use std::path::{Path, PathBuf};
use std::time::Duration;

use spherecontact::calculix::CcxAxisym;
use spherecontact::check::{Histories, Verdict};
use spherecontact::solver::{self, SolveError};

use crate::common;
use common::decks::{any_force_check, ccx_present, force_error_against_mdr_domain, scene_17um};
use common::refused::{assert_refused, Left};

/// A stand-in `ccx` (a shell script in `dir`) that answers `-v` as ccx 2.20 does and runs `body`
/// for a job.
pub(crate) fn fake_ccx(dir: &Path, body: &str) -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let path = dir.join("ccx");
    let script = format!(
        "#!/bin/sh\nif [ \"$1\" = \"-v\" ]; then echo; echo 'This is Version 2.20'; exit 201; fi\n{body}\n"
    );
    std::fs::write(&path, script).unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    path
}

/// The failure message of a solve that must fail; the kept run directory is removed.
fn failure(solver: &CcxAxisym) -> String {
    failure_of(solver, &scene_17um())
}

/// The failure message of `solver` on `scene`, which must fail keeping its run directory with
/// the deck `job.inp`; the directory is removed.
pub(crate) fn failure_of(
    solver: &dyn spherecontact::solver::Solver,
    scene: &spherecontact::scene::Scene,
) -> String {
    let message = match solver::run(solver, scene) {
        Err(SolveError::Failed(m)) => m,
        other => panic!("expected a failure, got {other:?}"),
    };
    let kept = message
        .rsplit("kept in ")
        .next()
        .and_then(|s| s.strip_suffix(')'));
    let kept = kept.expect("the run directory is kept on failure");
    assert!(Path::new(kept).join("job.inp").is_file(), "{message}");
    std::fs::remove_dir_all(kept).ok();
    message
}

fn with_fake(dir: &Path, body: &str, timeout_s: u64) -> CcxAxisym {
    let mut solver = CcxAxisym::default();
    solver.options.toolchain.ccx = fake_ccx(dir, body);
    solver.options.timeout = Some(Duration::from_secs(timeout_s));
    solver.options.resolution = Some(scene_17um().max_contact_radius() / 10.0);
    solver
}

#[test]
fn a_missing_ccx_gives_not_available() {
    let mut solver = CcxAxisym::default();
    solver.options.toolchain.ccx = "/nonexistent/ccx".into();
    let scene = scene_17um();
    let result = solver::run(&solver, &scene);
    assert!(matches!(result, Err(SolveError::Unavailable(_))), "{result:?}");
    let histories: Histories = [("ccx-axisym".to_owned(), result)].into_iter().collect();
    let check = any_force_check("ccx-axisym");
    assert_eq!(check.evaluate(&histories).verdict, Verdict::Unavailable);
}

#[test]
#[ignore = "heavy: failing ccx runs, one killed at its timeout; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn a_hanging_ccx_is_killed_and_garbage_or_refused_decks_fail_with_their_reason() {
    if !ccx_present("fault handling") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let hang = failure(&with_fake(dir.path(), "sleep 60", 2));
    assert!(hang.contains("did not finish within 2 s"), "{hang}");
    // Exit 0 without the outputs: a clear message naming the missing file.
    let silent = failure(&with_fake(dir.path(), "exit 0", 30));
    assert!(
        silent.contains("job.dat") && silent.contains("output missing"),
        "{silent}"
    );
    // Totals that are not numbers.
    let garbage = "printf ' total force (fx,fy,fz) for set NFAR and time  0.1000000E+01\\n\\n nan nan nan\\n' > job.dat";
    let nan = failure(&with_fake(dir.path(), garbage, 30));
    assert!(
        nan.contains("job.dat line") && nan.contains("three finite forces"),
        "{nan}"
    );
    // A deck CalculiX refuses (the real ccx): it prints *ERROR and, for this one, exits with code
    // 0 (ccx 2.20): the log's *ERROR lines make it a failure.
    let mut refused = CcxAxisym::default();
    refused.options.deck_text = Some("*HEADING\nbad\n*NODE\n1, 0., 0.\n*BOUNDARY\nNOSUCHSET, 1, 1\n".into());
    refused.options.resolution = Some(scene_17um().max_contact_radius() / 10.0);
    let message = failure(&refused);
    assert!(
        message.contains("ccx reported an error") && message.contains("NOSUCHSET"),
        "{message}"
    );
}

#[test]
#[ignore = "heavy: ccx-axisym and fem-axisym along a path; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn ccx_axisym_on_a_coarse_mesh_agrees_with_hertz_in_series_with_the_domain() {
    if !ccx_present("coarse run") {
        return;
    }
    let scene = scene_17um();
    let mut solver = CcxAxisym::default();
    solver.options.resolution = Some(scene.max_contact_radius() / 10.0);
    let history = solver::run(&solver, &scene).unwrap();
    let error = force_error_against_mdr_domain("ccx-axisym c/10", &history, &scene);
    // The reaction of the 2-degree wedge times 180 against Hertz in series with the axially held
    // hemisphere's compliance: a wrong segment factor would be off by orders of magnitude (or by
    // 2π), the coarse mesh (c_max/10) and the penalty leave a few 1e-3.
    assert!(error.abs() < 5e-3, "P error {error:+.3e}");
    // Only the path positions are computed; position 0 touches without force.
    assert_eq!(history.at_position(0).unwrap().normal_force, Some(0.0));
    let computed = history.steps.iter().filter(|r| r.normal_force.is_some()).count();
    assert_eq!(computed, 2);
    // The metadata records the settings and the plane's reaction, in equilibrium with the far face.
    let extra = &history.metadata.extra;
    assert_eq!(extra["calculix"]["contact"], "face-to-face");
    let plane = extra["normal_force_plane_by_position"][1][1].as_f64().unwrap();
    let p = history.at_position(1).unwrap().normal_force.unwrap();
    assert!((plane / p - 1.0).abs() < 1e-5, "{plane} against {p}");
    assert!(history.field_at(1).is_some());
}

#[test]
fn a_bad_calculix_setting_exits_2_naming_the_field_and_the_allowed_set() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for (file, field, allowed) in [
        (
            "bad-contact.toml",
            "calculix.contact",
            "face-to-face, node-to-face",
        ),
        ("bad-penalty.toml", "calculix.penalty", "1 ≤ penalty ≤ 1000000"),
    ] {
        assert_refused(
            &["run"],
            &root.join("tests/hostile/calculix").join(file),
            &[field, allowed],
            Left::Nothing,
        );
    }
}
