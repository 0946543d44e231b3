//! Helpers of the external-deck tests: whether the tools are installed, the scenes, deck
//! variants.

use std::path::Path;
use std::sync::OnceLock;
use std::time::Duration;

use spherecontact::case::Case;
use spherecontact::domain::Grip;
use spherecontact::external::axisym::AxisymSolver;
use spherecontact::external::deck::Deck;
use spherecontact::external::fenicsx::Fenicsx;
use spherecontact::external::freefem::FreeFem;
use spherecontact::fem::mesh::geo::MeshFiles;
use spherecontact::history::History;
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::solver::{self, Solver};
use spherecontact::toolchain::{Tool, Toolchain};

/// A check that any P at every position passes (tolerance 1: 100 %): what is left to judge is
/// whether the solver gave a history at all (NOOK for a failure, N/A when not installed).
pub fn any_force_check(solver: &str) -> spherecontact::check::CheckSpec {
    use spherecontact::check::{CheckSpec, ErrorMeasure, Reference, Where};
    CheckSpec {
        solver: solver.into(),
        quantity: spherecontact::history::Quantity::NormalForce,
        at: Where::EveryPosition,
        reference: Reference::Value {
            value: 803.76,
            key: "x".into(),
            source: "test".into(),
        },
        measure: ErrorMeasure::Relative,
        tolerance: Some(1.0),
        reason: "any value".into(),
        known_failure: None,
        abs_zero: spherecontact::check::ABS_ZERO,
    }
}

/// True when every external tool works; otherwise prints why the calling test skips.
pub fn tools_present(test: &str) -> bool {
    let missing: Vec<String> = Toolchain::default()
        .doctor()
        .into_iter()
        .filter(|p| !p.available())
        .map(|p| p.line())
        .collect();
    if !missing.is_empty() {
        eprintln!(
            "{test}: skipped, external tools missing (run scripts/setup.sh):\n{}",
            missing.join("\n")
        );
    }
    missing.is_empty()
}

/// True when gmsh and ccx run; otherwise prints why the calling test skips.
pub fn ccx_present(test: &str) -> bool {
    these_tools_present(test, &[Tool::Gmsh, Tool::Ccx])
}

/// True when every tool of `tools` works; otherwise prints why the calling test skips.
pub fn these_tools_present(test: &str, tools: &[Tool]) -> bool {
    let chain = Toolchain::default();
    let missing: Vec<String> = tools
        .iter()
        .map(|&t| chain.probe(t))
        .filter(|p| !p.available())
        .map(|p| p.line())
        .collect();
    if !missing.is_empty() {
        eprintln!("{test}: skipped (run scripts/setup.sh):\n{}", missing.join("\n"));
    }
    missing.is_empty()
}

/// P at position 1 of `history` against mdr-domain's on `scene`, printed with `label`: returns
/// the relative error.
pub fn force_error_against_mdr_domain(
    label: &str,
    history: &spherecontact::history::History,
    scene: &Scene,
) -> f64 {
    let corrected = spherecontact::solver::run(
        spherecontact::registry::by_name("mdr-domain").unwrap().as_ref(),
        scene,
    )
    .unwrap();
    let p = history.at_position(1).unwrap().normal_force.unwrap();
    let reference = corrected.at_position(1).unwrap().normal_force.unwrap();
    let error = p / reference - 1.0;
    eprintln!("{label}: P = {p} N, mdr-domain {reference} N, error {error:+.3e}");
    error
}

/// The hertz-normal case's scene with its path cut to δn 0 → 17 µm (one solve per deck).
pub fn scene_17um() -> Scene {
    let mut scene = Case::load(Path::new("cases/hertz-normal.toml")).unwrap().scene;
    let position = |delta_n: f64| Position {
        delta_n,
        delta_t: 0.0,
    };
    scene.path = LoadingPath::try_new(vec![position(0.0), position(17e-6)], vec![17]).unwrap();
    scene
}

/// FreeFEM's and FEniCSx's axisymmetric decks on [`scene_17um`] at their default resolution, each
/// run once for every test that judges that run (name, history); the caller checks
/// [`tools_present`] first.
pub fn decks_on_scene_17um() -> &'static [(String, History)] {
    static RUNS: OnceLock<Vec<(String, History)>> = OnceLock::new();
    RUNS.get_or_init(|| {
        let scene = scene_17um();
        [
            Box::new(AxisymSolver::new(FreeFem)) as Box<dyn Solver>,
            Box::new(AxisymSolver::new(Fenicsx)),
        ]
        .iter()
        .map(|deck| {
            let history =
                solver::run(deck.as_ref(), &scene).unwrap_or_else(|e| panic!("{}: {e:?}", deck.name()));
            (deck.name().to_owned(), history)
        })
        .collect()
    })
}

pub fn with_deck_text<D: Deck<Mesh = MeshFiles>>(deck: D, text: &str, timeout_s: u64) -> AxisymSolver<D> {
    let mut solver = AxisymSolver::new(deck);
    solver.options.deck_text = Some(text.to_owned());
    solver.options.timeout = Some(Duration::from_secs(timeout_s));
    solver
}

pub fn at_resolution<D: Deck<Mesh = MeshFiles> + 'static>(deck: D, h: f64) -> Box<dyn Solver> {
    let mut solver = AxisymSolver::new(deck);
    solver.options.resolution = Some(h);
    Box::new(solver)
}

/// The paper's spheres pressed to δn = 17 µm (4 increments), sheared to δt = 3 µm (6) and back to
/// −3 µm (12): partial slip, reversal, and gross sliding is not reached (δs = 4.13 µm). The
/// hemisphere is gripped rigidly (the only grip that can impose a shift; the normal scene's
/// axial grip would leave the far face free to slide).
pub fn frictional_scene() -> Scene {
    let mut scene = scene_17um();
    scene.domain.grip = Grip::Rigid;
    let um = |delta_n: f64, delta_t: f64| Position {
        delta_n: delta_n * 1e-6,
        delta_t: delta_t * 1e-6,
    };
    scene.path = LoadingPath::try_new(
        vec![um(0.0, 0.0), um(17.0, 0.0), um(17.0, 3.0), um(17.0, -3.0)],
        vec![4, 6, 12],
    )
    .unwrap();
    scene
}
