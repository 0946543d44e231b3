//! Extreme but valid cases (`tests/hostile/extreme/*.toml`), each run with every in-crate solver:
//! every solver answers or names the reason it cannot, never panics, and its answer obeys the
//! invariants of contact mechanics (see [`judge`]).
//!
//! A solver that fails on a case must be expected by a line of the case file's header,
//! `# diagnostic: SOLVER: FRAGMENT`, and its message must contain FRAGMENT: an unexpected failure
//! is a test failure. Run: `cargo test --test suite hostile_extreme::`.

use crate::common;

use std::path::{Path, PathBuf};

use spherecontact::case::Case;
use spherecontact::history::History;
use spherecontact::registry;
use spherecontact::report::history_files;
use spherecontact::solver::{self, SolveError};

/// The cases' folder.
fn folder() -> PathBuf {
    common::root().join("tests/hostile/extreme")
}

/// Every solver of this build that runs in-crate (not an external program: a deck or a DEM code).
fn in_crate_solvers() -> Vec<String> {
    registry::in_crate().iter().map(|s| s.name().to_owned()).collect()
}

/// The failures a case file's header expects: (solver, message fragment).
fn expected_diagnostics(text: &str) -> Vec<(String, String)> {
    text.lines()
        .filter_map(|l| l.strip_prefix("# diagnostic: "))
        .map(|l| {
            let (solver, fragment) = l.split_once(": ").expect("`# diagnostic: SOLVER: FRAGMENT`");
            (solver.to_owned(), fragment.to_owned())
        })
        .collect()
}

/// Relative round-off allowed in the force invariants of each solver, with its reason.
fn force_tolerance(solver: &str) -> f64 {
    match solver {
        // BEM: the tangential problem is solved to a relative residual of 1e-5 (Bem tolerances),
        // the normal one to 1e-6 at 64²; |Q| ≤ μP holds panel by panel to that residual.
        "bem" => 1e-5,
        // FEM: Newton on the condensed contact problem; P is a sum of multipliers ≥ 0 up to the
        // factorisation's round-off (κ ~ 1e8 for graded meshes, times 1e-16).
        "fem-axisym" => 1e-8,
        // Closed forms, MDR and the DEM laws: sums of terms each within its Coulomb bound, exact
        // up to the round-off of summing a few thousand terms.
        _ => 1e-12,
    }
}

/// The invariants of one solver's history on `case`; returns what is broken, if anything.
fn judge(case: &Case, solver: &str, history: &History) -> Vec<String> {
    let mut broken = Vec::new();
    let scene = &case.scene;
    let hertz = scene.hertz();
    let p_scale = hertz.force(scene.path.max_approach().max(0.0));
    let tol = force_tolerance(solver);
    // Every output cell is a finite number or empty.
    let csv = history_files::to_csv(history).unwrap() + &history_files::fields_to_csv(history).unwrap();
    for line in csv
        .lines()
        .filter(|l| !l.starts_with(|c: char| c.is_alphabetic()))
    {
        for cell in line.split(',').filter(|c| !c.is_empty()) {
            if !cell.parse::<f64>().is_ok_and(f64::is_finite) {
                broken.push(format!("cell `{cell}` in `{line}`"));
            }
        }
    }
    for row in &history.steps {
        let at = format!("step {} (δn = {:e} m)", row.step, row.delta_n);
        let p = row.normal_force.unwrap_or(0.0);
        let q = row.tangential_force.unwrap_or(0.0);
        if p < -tol * p_scale {
            broken.push(format!("P = {p:e} N < 0 at {at}"));
        }
        if q.abs() > scene.friction * p.max(0.0) + tol * p_scale.max(p) {
            broken.push(format!(
                "|Q| = {:e} N > μP = {:e} N at {at}",
                q.abs(),
                scene.friction * p
            ));
        }
        if row.delta_n < 0.0 && (p != 0.0 || q != 0.0) {
            broken.push(format!("force at an open gap: P = {p:e}, Q = {q:e} at {at}"));
        }
        if let (Some(stick), Some(c)) = (row.stick_radius, row.contact_radius) {
            let resolution = stick_resolution(history, c);
            if stick > c + resolution {
                broken.push(format!(
                    "stick radius {stick:e} m > contact radius {c:e} m + {resolution:e} m at {at}"
                ));
            }
        }
    }
    broken
}

/// How far the stick radius may exceed the contact radius for the solver of `history`: the
/// discretisation each solver states (MDR: one spring cell; BEM: one panel); 1e-12 c for the
/// closed forms and DEM laws, which report the stick radius as a fraction of c.
fn stick_resolution(history: &History, c: f64) -> f64 {
    let extra = |key: &str| history.metadata.extra.get(key).and_then(|v| v.as_f64());
    match history.metadata.solver.as_str() {
        "bem" => extra("panel_size_m").unwrap_or(0.0),
        "mdr" => extra("spring_spacing_m").unwrap_or(0.0),
        _ => 1e-12 * c,
    }
}

/// Runs every in-crate solver on the case file `name` and asserts the invariants.
fn run_extreme(name: &str) {
    let file = folder().join(name);
    let text = std::fs::read_to_string(&file).unwrap();
    let case = Case::load(&file).unwrap_or_else(|e| panic!("{e}"));
    let expected = expected_diagnostics(&text);
    let mut problems = Vec::new();
    for solver_name in &in_crate_solvers() {
        let s = registry::by_name(solver_name).unwrap();
        let expectation = expected.iter().find(|(s, _)| s == solver_name);
        let result = solver::run(s.as_ref(), &case.scene);
        // The outcome matrix, for `--nocapture`.
        eprintln!(
            "{name:<40} {solver_name:<22} {}",
            result
                .as_ref()
                .map_or_else(|e| e.to_string(), |_| "answered".into())
        );
        match (result, expectation) {
            (Ok(history), None) => {
                for broken in judge(&case, solver_name, &history) {
                    problems.push(format!("{solver_name}: {broken}"));
                }
            }
            (Ok(_), Some((_, fragment))) => {
                problems.push(format!("{solver_name}: answered where `{fragment}` was expected"))
            }
            (Err(SolveError::NotApplicable(reason)), None) => {
                if reason.trim().is_empty() {
                    problems.push(format!("{solver_name}: not applicable without a reason"));
                }
            }
            (Err(e), Some((_, fragment))) if e.to_string().contains(fragment.as_str()) => {}
            (Err(e), _) => problems.push(format!("{solver_name}: {e}")),
        }
    }
    assert!(problems.is_empty(), "{name}:\n{}", problems.join("\n"));
}

macro_rules! extreme {
    ($($test:ident: $file:literal,)*) => {
        $(
            #[test]
            fn $test() {
                run_extreme($file);
            }
        )*

        /// Every case file of the folder has its test above.
        #[test]
        fn every_extreme_case_file_is_run() {
            let mut files: Vec<String> = std::fs::read_dir(folder())
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            files.sort();
            let mut listed = vec![$($file.to_owned()),*];
            listed.sort();
            assert_eq!(files, listed);
            assert!(files.len() >= 20, "the issue asks for at least 20 extreme cases");
        }
    };
}

extreme! {
    tiny_approach: "tiny-approach.toml",
    huge_approach: "huge-approach.toml",
    tiny_radius: "tiny-radius.toml",
    huge_radius: "huge-radius.toml",
    soft_gel: "soft-gel.toml",
    stiffest: "stiffest.toml",
    nearly_incompressible: "nearly-incompressible.toml",
    auxetic_limit: "auxetic-limit.toml",
    frictionless_sliding: "frictionless-sliding.toml",
    friction_ten: "friction-ten.toml",
    tangential_jump: "tangential-jump.toml",
    many_reversals: "many-reversals.toml",
    grazing_jitter: "grazing-jitter.toml",
    sphere_on_flat: "sphere-on-flat.toml",
    extreme_mismatch: "extreme-mismatch.toml",
    radius_mismatch: "radius-mismatch.toml",
    always_apart: "always-apart.toml",
    loaded_start: "loaded-start.toml",
    single_position: "single-position.toml",
    touching_only: "touching-only.toml",
    gross_slip_then_separation: "gross-slip-then-separation.toml",
    largest_approach_at_the_radius: "largest-approach-at-the-radius.toml",
}

#[test]
fn every_extreme_case_lists_every_in_crate_solver() {
    for entry in std::fs::read_dir(folder()).unwrap() {
        let file = entry.unwrap().path();
        let case = Case::load(Path::new(&file)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(case.solvers, in_crate_solvers(), "{}", file.display());
    }
}
