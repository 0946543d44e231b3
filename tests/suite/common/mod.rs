//! Helpers shared by the integration tests.
#![allow(dead_code)] // each test binary uses a different subset

pub mod decks;
pub mod friction;
pub mod leftovers;
pub mod peak;
pub mod reads;
pub mod refused;

use spherecontact::case::Case;
use spherecontact::check::Reference;
use spherecontact::history::History;
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::{registry, solver};
use std::path::{Path, PathBuf};

/// A small valid case of the paper's spheres (hertz and mdr, three positions, 8 increments): the
/// tests of the command line and of hostile inputs each break or change one thing of it.
pub const SMALL_CASE: &str = r#"
name = "cli-test"
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
"#;

/// Runs the `spherecontact` command with `args` in the folder `cwd`.
pub fn spherecontact(args: &[&str], cwd: &Path) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

/// Asserts that a run of the program succeeded (exit code 0), showing its output otherwise.
pub fn assert_success(output: &std::process::Output) {
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Runs the `spherecontact` command with `args` in the crate's folder: (exit code, stdout,
/// stderr).
pub fn run_in_root(args: &[&str]) -> (i32, String, String) {
    let output = spherecontact(args, &root());
    (
        output.status.code().unwrap(),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// The text of the file at `path`.
pub fn text(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `p` as a command-line argument.
pub fn arg(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// What a hostile file's header line `# key: value` says (its message must hold the value).
pub fn header(text: &str, key: &str) -> String {
    text.lines()
        .find_map(|l| l.strip_prefix(&format!("# {key}: ")))
        .unwrap_or_else(|| panic!("no `# {key}:` header"))
        .to_owned()
}

/// The crate's folder (where cases/ and reference/ live).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A shipped case, loaded and validated.
pub fn case(relative: &str) -> Case {
    Case::load(&root().join(relative)).unwrap_or_else(|e| panic!("{e}"))
}

/// Every shipped path case file (impact cases, `kind = "impact"`, are left out: they are not
/// [`Case`]s; tests/impact.rs runs them).
pub fn all_case_files() -> Vec<PathBuf> {
    let mut files = every_case_file();
    files.retain(|f| !spherecontact::case::is_impact(&std::fs::read_to_string(f).unwrap()));
    files
}

/// Every `.toml` file under cases/, path and impact cases alike.
pub fn every_case_file() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "toml") {
                out.push(path);
            }
        }
    }
    let mut files = Vec::new();
    walk(&root().join("cases"), &mut files);
    files.sort();
    files
}

/// The paper's scene with its path replaced by `positions` (µm) at `substeps` per segment.
pub fn paper_scene_with_path(positions_um: &[(f64, f64)], substeps: usize) -> Scene {
    let mut scene = case("cases/paper-fig7.toml").scene;
    let positions: Vec<_> = positions_um
        .iter()
        .map(|&(n, t)| Position {
            delta_n: n * 1e-6,
            delta_t: t * 1e-6,
        })
        .collect();
    let segments = positions.len() - 1;
    scene.path = LoadingPath::try_new(positions, vec![substeps; segments]).unwrap();
    scene
}

/// The paper's scene (cases/paper-fig7.toml) with `substeps` on every segment.
pub fn paper_scene_with_substeps(substeps: usize) -> Scene {
    let mut scene = case("cases/paper-fig7.toml").scene;
    let positions = scene.path.positions().to_vec();
    let segments = positions.len() - 1;
    scene.path = LoadingPath::try_new(positions, vec![substeps; segments]).unwrap();
    scene
}

/// Runs the named solver on a scene.
pub fn solve(name: &str, scene: &Scene) -> History {
    let solver = registry::by_name(name).unwrap_or_else(|| panic!("no solver {name}"));
    solver::run(solver.as_ref(), scene).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Two identical spheres of radius `radius` [m], modulus `young` [Pa] and Poisson ratio `poisson`.
pub fn identical_spheres(radius: f64, young: f64, poisson: f64) -> ContactPair {
    let body = Body {
        radius,
        material: Material { young, poisson },
    };
    ContactPair {
        body1: body,
        body2: body,
    }
}

/// A normal-only scene of `pair` (μ = 0.2) through the approaches `delta_um` [µm], one increment
/// per segment.
pub fn normal_scene(pair: ContactPair, delta_um: &[f64]) -> Scene {
    let positions = delta_um
        .iter()
        .map(|&d| Position {
            delta_n: d * 1e-6,
            delta_t: 0.0,
        })
        .collect();
    let path = LoadingPath::try_new(positions, vec![1; delta_um.len() - 1]).unwrap();
    Scene {
        name: "test".into(),
        pair,
        friction: 0.2,
        path,
        domain: Default::default(),
        fields: Default::default(),
    }
}

/// [`paper_case_in_crate`] with `increments` increments a segment (a report's layout does not
/// depend on them; 10 make a run of seconds).
pub fn paper_case_coarse(increments: usize) -> Case {
    let mut case = paper_case_in_crate();
    let positions = case.scene.path.positions().to_vec();
    let segments = positions.len() - 1;
    case.scene.path = LoadingPath::try_new(positions, vec![increments; segments]).expect("path");
    case
}

/// The paper's case with the in-crate solvers only (the external decks, tested in
/// tests/external.rs, would make report tests minutes long), and the checks that need no deck.
pub fn paper_case_in_crate() -> Case {
    let mut case = case("cases/paper-fig7.toml");
    // The decks and the DEM codes are tested in tests/external*.rs and tests/dem_codes.rs.
    case.solvers.retain(|s| registry::is_in_crate(s));
    case.checks.retain(|c| {
        registry::is_in_crate(&c.solver)
            && match &c.reference {
                Reference::Solver(name) => registry::is_in_crate(name),
                Reference::Value { .. } => true,
            }
    });
    case
}

/// The reproduce-paper report of `run` without the resolution study's rungs (`Study::none`) and
/// without the paper's discretisation run (the report tests do not run CalculiX's bricks:
/// `calculix_hex20::` does).
pub fn paper_document(run: &spherecontact::verify::CaseRun) -> spherecontact::report::document::Document {
    use spherecontact::report::discretisation::Discretisation;
    spherecontact::report::paper::document(
        run,
        &spherecontact::report::claims::Study::none(),
        &root().join("reference"),
        &Discretisation::NotRun("not run by this test"),
    )
    .expect("the paper report")
}
