//! The FEniCSx 3D deck `fenicsx-3d`: dolfinx 0.5.2 (Debian) on the quadratic-tetrahedron mesh of
//! `fem-3d` (half of the hemisphere or cap, [`spherecontact_solvers::fem::mesh::solid_geo`]), one sphere against its symmetry
//! plane, normal penalty contact and Coulomb friction with history on the contact surface (the
//! disc), condensed onto the candidate nodes; under `mpirun` with a chosen rank count (template
//! `templates/fenicsx_3d.py`; the model and the cluster how-to: docs/external-decks.md).
//!
//! Heavy: not in the shipped cases' default solver lists; `cases-heavy/paper-fig7-3d.toml` names it.

use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::json;

use super::axisym::{deck_input, Options};
use super::deck::{self, Deck, DeckKind, RunDir, TimeBudget};
use super::plan::{Plan, KFAC};
use super::readback::{self, DeckRow, Outcome};
use super::record::{record_run, RunFacts, FINITE_BODY};
use super::split;
use super::surface3d::{self, Surface3};
use spherecontact_model::domain::Grip;
use spherecontact_model::history::{History, Metadata};
use spherecontact_model::limits::{MAX_DECK_CLOCK_BYTES, MAX_DECK_TABLE_BYTES, SOLID_POLE};
use spherecontact_model::resolution::{self, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::split::{DeckCommand, SplitDeck};
use spherecontact_model::solver::Kind;
use spherecontact_model::solver::{SolveError, Solver};
use spherecontact_solvers::fem::mesh::solid_geo::{self, SolidMeshFiles, Zones};
use spherecontact_system::process::Job;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The solver name.
pub const NAME: &str = "fenicsx-3d";

/// The deck template.
pub const TEMPLATE: &str = include_str!("templates/fenicsx_3d.py");

/// Default pole element size, as a fraction of the path's largest contact radius: a coarse mesh,
/// c_max/5 (measured on the paper's spheres: 32.6k DOFs, 319 candidate nodes, a set-up of 7 s
/// CPU on one core; docs/external-decks.md). Finer meshes through [`Options::resolution`].
pub const DEFAULT_POLE_FRACTION: f64 = 1.0 / 5.0;

pub use spherecontact_model::limits::MAX_RANKS;

/// Time allowed for start-up (imports, form compilation on a first run), for the set-up
/// (assembly, factorisation, one solve per candidate DOF: minutes at c_max/8) and per computed
/// step (a dense semi-smooth Newton on the candidates: below a second at c_max/8).
const BUDGET: TimeBudget = TimeBudget {
    start: Duration::from_secs(180),
    setup: Duration::from_secs(1800),
    per_step: Duration::from_secs(3),
};

/// Cap on the tangential Newton iterations per increment: the averaged contact rule couples
/// neighbouring nodes; measured up to 35 iterations on the frictional path of
/// `tests/external_3d.rs` (0.5 µm increments of δt at c_max/5). A step that hits the cap is
/// flagged.
pub const MAX_ITERATIONS: u32 = 60;

/// The 3D deck run by dolfinx on `ranks` MPI processes (1: plain python, no mpirun).
#[derive(Clone, Copy, Debug)]
pub struct Fenicsx3d {
    /// MPI ranks.
    pub ranks: u32,
}

impl Deck for Fenicsx3d {
    const KIND: DeckKind = DeckKind {
        name: NAME,
        description: "FEniCSx (dolfinx) 3D FEM on quadratic tetrahedra, half of one sphere on its symmetry plane, penalty, Coulomb with history on the disc, MPI (heavy)",
        tool: Tool::Dolfinx,
        template: TEMPLATE,
        file_name: "deck3d.py",
    };

    type Mesh = SolidMeshFiles;

    fn mesh_file<'a>(&self, mesh: &'a SolidMeshFiles) -> &'a Path {
        &mesh.msh
    }

    /// `python3 deck3d.py` on one rank; `mpirun -np N python3 deck3d.py` on more, with the two
    /// variables OpenMPI needs to run as root, and `--oversubscribe` beyond the machine's cores.
    fn job(&self, toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job {
        if self.ranks <= 1 {
            return deck::python_job(toolchain, deck, timeout);
        }
        let python = toolchain.python.display().to_string();
        let deck = deck.display().to_string();
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let mut args = vec!["-np".to_owned(), self.ranks.to_string()];
        if usize::try_from(self.ranks).unwrap_or(usize::MAX) > cores {
            args.push("--oversubscribe".into());
        }
        args.extend([python, deck]);
        Job {
            program: "mpirun".into(),
            args,
            env: [
                ("OMPI_ALLOW_RUN_AS_ROOT".into(), "1".into()),
                ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM".into(), "1".into()),
            ]
            .into_iter()
            .chain(deck::single_threaded())
            .collect(),
            timeout,
        }
    }

    fn exit_code_meaning(&self, code: i32) -> &'static str {
        match code {
            1 => "uncaught Python exception on a rank (traceback in stderr)",
            2 => "Python or mpirun could not open the deck or its arguments were wrong",
            _ => "unexpected exit code (mpirun reports a rank that died)",
        }
    }
}

/// The 3D deck as a [`Solver`].
pub struct Solid3dDeck {
    /// The deck (its rank count).
    pub deck: Fenicsx3d,
    /// How it is run.
    /// How it is run (the same options as the axisymmetric decks'; the default pole size is
    /// [`DEFAULT_POLE_FRACTION`] of the largest contact radius, the default time limit 33 min +
    /// 3 s per step).
    pub options: Options,
}

/// What a finished 3D run left, read back.
struct Run3 {
    rows: Vec<DeckRow>,
    surfaces: Vec<Surface3>,
    triangles: Vec<[usize; 3]>,
    resolution: f64,
    /// Wall seconds of gmsh, the deck and the reading back.
    wall_s: [f64; 3],
    timing: Vec<(String, f64)>,
}

impl Solid3dDeck {
    /// The deck on `ranks` MPI ranks (1: serial), default options.
    pub fn new(ranks: u32) -> Self {
        Self {
            deck: Fenicsx3d { ranks },
            options: Options::default(),
        }
    }

    /// Meshes, runs the deck and reads back, in `dir`.
    fn run_in(&self, scene: &Scene, plan: &Plan, resolution: f64, dir: &RunDir) -> Result<Run3, SolveError> {
        let (text, mesh_s) = self.prepare(scene, plan, resolution, dir.path())?;
        let timeout = self.options.timeout.unwrap_or(BUDGET.limit(plan.steps.len()));
        let toolchain = &self.options.toolchain;
        let run = deck::launch(&self.deck, toolchain, dir.path(), &text, &plan.steps, timeout)?;
        let mut read = read_outputs(dir.path(), plan, resolution)?;
        read.wall_s[0] = mesh_s;
        read.wall_s[1] = run.wall_s;
        Ok(read)
    }

    /// Meshes the body into `dir` (`body.geo`, `body.msh`): the filled deck's text and gmsh's
    /// wall time [s].
    fn prepare(
        &self,
        scene: &Scene,
        plan: &Plan,
        resolution: f64,
        dir: &Path,
    ) -> Result<(String, f64), SolveError> {
        let zones = Zones::new(scene.max_contact_radius(), resolution);
        let r = scene.pair.body1.radius;
        let geometry = solid_geo::geometry(r, scene.domain.height(r), resolution, zones);
        let mesh = solid_geo::mesh(&geometry, dir, "body", &self.options.toolchain)?;
        let max_iterations = self.options.max_iterations.unwrap_or(MAX_ITERATIONS);
        let text = self.options.deck_text.clone().unwrap_or_else(|| {
            deck::fill(
                TEMPLATE,
                &deck_input(&self.deck, scene, resolution, plan, &mesh, max_iterations),
            )
        });
        Ok((text, mesh.wall_s))
    }

    /// Writes everything the deck needs to run elsewhere (a cluster: docs/external-decks.md, "On a
    /// cluster") into the existing folder `dir`, without running it: `body.geo`, `body.msh`,
    /// `deck3d.py` and `path.txt`.
    pub fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError> {
        applicable(scene)?;
        let (resolution, plan) = self.plan(scene);
        let (text, _) = self.prepare(scene, &plan, resolution, dir)?;
        deck::write_deck(&self.deck, dir, &text, &plan.steps)
    }

    /// The pole size and plan of `scene` for this deck.
    fn plan(&self, scene: &Scene) -> (f64, Plan) {
        let c_max = scene.max_contact_radius();
        let resolution = self.options.resolution.unwrap_or(DEFAULT_POLE_FRACTION * c_max);
        let mut plan = Plan::of(scene, resolution);
        plan.candidate_radius = Zones::new(c_max, resolution).candidate_radius;
        (resolution, plan)
    }

    /// The history of a run directory that the deck finished elsewhere (on a cluster, by hand:
    /// docs/external-decks.md, "On a cluster"), read back as after the solver's own run. The
    /// directory's `path.txt` must list `scene`'s computed steps; the pole size is this solver's
    /// (its resolution option, or the default), for the metadata and the edge check.
    pub fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError> {
        applicable(scene)?;
        let (resolution, plan) = self.plan(scene);
        readback::check_path_file(dir, &plan.steps, &scene.name)?;
        let run = read_outputs(dir, &plan, resolution)?;
        let ranks = run
            .timing
            .iter()
            .find(|(phase, _)| phase == "ranks")
            .and_then(|(_, n)| {
                (n.fract() == 0.0 && (1.0..=f64::from(MAX_RANKS)).contains(n)).then_some(*n as u32)
            })
            .unwrap_or(self.deck.ranks);
        let mut history = history(scene, split::RUN_ELSEWHERE, &plan, &run, ranks);
        history.metadata.solver = NAME.into();
        Ok(history)
    }
}

/// Reads the deck's output files in `dir` (steps.csv, surface.csv, triangles.csv, timing.csv)
/// and checks them against each other; the wall times of meshing and solving are left at zero.
fn read_outputs(dir: &Path, plan: &Plan, resolution: f64) -> Result<Run3, SolveError> {
    let start = Instant::now();
    let read =
        |name: &str| readback::read_output(dir, name, MAX_DECK_TABLE_BYTES).map_err(SolveError::Failed);
    let rows = readback::parse_steps(&read("steps.csv")?, &plan.steps).map_err(SolveError::Failed)?;
    let indices: Vec<usize> = plan.steps.iter().map(|s| s.step).collect();
    let surfaces = surface3d::parse_surface3(&read("surface.csv")?, &indices).map_err(SolveError::Failed)?;
    check_consistency(&rows, &surfaces, resolution)?;
    let nodes = surfaces.first().map_or(0, |s| s.nodes.len());
    let triangles = surface3d::parse_triangles(&read("triangles.csv")?, nodes).map_err(SolveError::Failed)?;
    let timing = readback::read_optional_output(dir, "timing.csv", MAX_DECK_CLOCK_BYTES)
        .map_err(SolveError::Failed)?
        .map(|t| parse_phases(&t))
        .unwrap_or_default();
    Ok(Run3 {
        rows,
        surfaces,
        triangles,
        resolution,
        wall_s: [0.0, 0.0, start.elapsed().as_secs_f64()],
        timing,
    })
}

/// Largest disagreement between the deck's P and the nodal sum of surface.csv, relative to the
/// larger of P and 1 N: both are the same sum written with 17 digits, so 1e-9 separates
/// round-off from a file that belongs to another step or run.
const SUM_AGREEMENT: f64 = 1e-9;

/// The two files agree (P = 2 Σ ω p at every step) and no step's contact reaches the outermost
/// candidate ring (within one element of it).
fn check_consistency(rows: &[DeckRow], surfaces: &[Surface3], resolution: f64) -> Result<(), SolveError> {
    for (row, surface) in rows.iter().zip(surfaces) {
        let sum = surface.normal_force();
        let departure = (sum - row.force_contact).abs() / row.force_contact.abs().max(1.0);
        if departure > SUM_AGREEMENT {
            return Err(SolveError::Failed(format!(
                "step {}: P of steps.csv and 2 Σ ω p of surface.csv differ by {departure:.1e} of the \
                 larger of P and 1 N (allowed: {SUM_AGREEMENT:e}: the same sum, written twice)",
                row.step
            )));
        }
        if surface.edge_loaded(resolution) {
            return Err(SolveError::Failed(format!(
                "step {}: the contact reached the outermost candidate ring: the candidate zone is \
                 too small for this model",
                row.step
            )));
        }
    }
    Ok(())
}

/// The `phase,seconds` lines of the deck's timing.csv.
fn parse_phases(text: &str) -> Vec<(String, f64)> {
    text.lines()
        .skip(1)
        .filter_map(|l| l.split_once(','))
        .filter_map(|(p, v)| Some((p.trim().to_owned(), v.trim().parse::<f64>().ok()?)))
        .filter(|(_, v)| v.is_finite())
        .collect()
}

impl Solver for Solid3dDeck {
    fn name(&self) -> &'static str {
        NAME
    }

    fn kind(&self) -> Kind {
        Kind::FiniteElement
    }

    fn description(&self) -> &'static str {
        self.deck.description()
    }

    /// A pole element size: `c/N` or a length, within [`SOLID_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let mut options = self.options.clone();
        options.resolution = Some(resolution::pole_size(self.name(), scene, value, SOLID_POLE)?);
        Ok(Box::new(Solid3dDeck {
            deck: self.deck,
            options,
        }))
    }

    fn cores(&self) -> usize {
        self.deck.ranks as usize
    }

    fn with_ranks(&self, ranks: u32) -> Option<Box<dyn Solver>> {
        Some(Box::new(Solid3dDeck {
            deck: Fenicsx3d { ranks },
            options: self.options.clone(),
        }))
    }

    fn split_deck(&self) -> Option<&dyn SplitDeck> {
        Some(self)
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        applicable(scene)?;
        let toolchain = &self.options.toolchain;
        let version = toolchain
            .require(Tool::Dolfinx)
            .map_err(SolveError::Unavailable)?;
        if self.deck.ranks > 1 && spherecontact_system::toolchain::which(Path::new("mpirun")).is_none() {
            return Err(SolveError::Unavailable(
                "mpirun not found on PATH; install: apt-get install openmpi-bin (or scripts/setup.sh)".into(),
            ));
        }
        let (resolution, plan) = self.plan(scene);
        let run = deck::in_run_dir("spherecontact-fenicsx-3d-", |dir| {
            self.run_in(scene, &plan, resolution, dir)
        })?;
        Ok(history(scene, &version, &plan, &run, self.deck.ranks))
    }
}

/// `NotApplicable` unless the scene is two identical finite spheres held rigidly (the model).
fn applicable(scene: &Scene) -> Result<(), SolveError> {
    if !scene.pair.is_symmetric() || !scene.pair.body1.radius.is_finite() {
        return Err(SolveError::NotApplicable(
            "the 3D deck models two identical spheres through their symmetry plane; different \
             spheres or a sphere on a flat are not modelled"
                .into(),
        ));
    }
    if scene.domain.grip != Grip::Rigid {
        return Err(SolveError::NotApplicable(
            "the 3D deck grips the far face rigidly (every component follows the approach and \
             shift); the axial grip is not modelled"
                .into(),
        ));
    }
    Ok(())
}

/// The 3D deck written and read apart: its inherent [`Solid3dDeck::write_run`] and
/// [`Solid3dDeck::read_run`].
impl SplitDeck for Solid3dDeck {
    fn settings(&self, scene: &Scene) -> serde_json::Value {
        json!({ "pole_element_m": self.plan(scene).0 })
    }

    /// `python3 deck3d.py` on one rank, `mpirun -np N python3 deck3d.py` on the case's N.
    fn command(&self) -> DeckCommand {
        split::deck_command(&self.deck, &self.options.toolchain)
    }

    fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError> {
        Solid3dDeck::write_run(self, scene, dir)
    }

    fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError> {
        Solid3dDeck::read_run(self, scene, dir)
    }
}

/// One `History` row per path step, the fields at the positions the case records, the metadata.
fn history(scene: &Scene, version: &str, plan: &Plan, run: &Run3, ranks: u32) -> History {
    let forces: Vec<[f64; 2]> = run
        .rows
        .iter()
        .map(|r| [r.force_contact, r.tangential_force])
        .collect();
    let (steps, fields) =
        surface3d::step_results(scene, plan.tangential, &forces, &run.surfaces, &run.triangles);
    History {
        metadata: metadata(scene, version, plan, run, ranks),
        steps,
        fields,
    }
}

/// How the history was obtained.
fn metadata(scene: &Scene, version: &str, plan: &Plan, run: &Run3, ranks: u32) -> Metadata {
    let capped: Vec<usize> = run
        .rows
        .iter()
        .filter(|r| r.outcome == Outcome::Capped)
        .map(|r| r.step)
        .collect();
    let mut metadata = Metadata {
        version: format!("dolfinx {version}"),
        model: format!(
            "3D, half of one sphere (y ≥ 0; {}) against its symmetry plane, exact for identical \
             spheres; P2 on quadratic tetrahedra; penalty k = {KFAC:e} E/h with fem-3d's contact \
             rule (multipliers at the faces' corners, linear on each face; averaged gap), condensed \
             onto the candidate nodes; {}",
            scene.domain.describe(),
            if plan.tangential {
                "Coulomb with history on the disc |q| ≤ μp, all-stick predictor every increment"
            } else {
                "frictionless (the path has no tangential motion)"
            }
        ),
        resolution: format!(
            "pole element {:.3} µm (c_max/{:.1}); every path step computed; {ranks} MPI rank(s)",
            run.resolution * 1e6,
            scene.max_contact_radius() / run.resolution
        ),
        warnings: vec![FINITE_BODY.into()],
        ..Metadata::default()
    };
    let facts = RunFacts {
        // The condensed nodes (the deck's count); surface.csv holds their corners, the contact
        // points (`deck_points`).
        candidate_nodes: run
            .timing
            .iter()
            .find(|(phase, _)| phase == "candidates")
            .map_or(0, |(_, n)| n.round() as usize),
        capped: &capped,
        wall_s: run.wall_s,
    };
    record_run(&mut metadata, plan, &facts);
    let extra = &mut metadata.extra;
    extra.insert("ranks".into(), json!(ranks));
    extra.insert(
        "contact_measures".into(),
        json!("fem-3d's (fit::surface): c from the pressure's second moment, p0 from the smooth even fit on r ≤ c/2, the stick radius c √(A_stick/A_contact) of the nodal areas (fit::stick)"),
    );
    for (phase, value) in &run.timing {
        extra.insert(format!("deck_{phase}"), json!(value));
    }
    metadata
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::{DeckInput, PATH_FILE};

    #[test]
    fn one_rank_runs_python_and_more_run_mpirun_as_root() {
        let toolchain = Toolchain::default();
        let serial = Fenicsx3d { ranks: 1 }.job(&toolchain, Path::new("d.py"), Duration::from_secs(9));
        assert_eq!(serial.program, toolchain.python);
        assert_eq!(serial.args, ["d.py"]);
        let parallel = Fenicsx3d { ranks: 2 }.job(&toolchain, Path::new("d.py"), Duration::from_secs(9));
        assert_eq!(parallel.program, Path::new("mpirun"));
        assert_eq!(&parallel.args[..2], ["-np", "2"]);
        assert_eq!(parallel.args.last().map(String::as_str), Some("d.py"));
        assert!(parallel
            .env
            .iter()
            .any(|(k, v)| k == "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM" && v == "1"));
    }

    #[test]
    fn every_key_of_the_3d_template_is_filled() {
        let input = DeckInput {
            scene: "s".into(),
            mesh: "body.msh".into(),
            radius_mm: 100.0,
            young_mpa: 7e4,
            poisson: 0.3,
            h_mm: 0.2,
            kfac: 1e3,
            friction: 0.2,
            grip: Grip::Rigid,
            candidate_radius_mm: 1.3,
            tangential: true,
            max_iterations: 30,
        };
        let text = deck::fill(TEMPLATE, &input);
        assert!(!deck::has_unfilled_key(&text), "unfilled key");
        assert!(text.contains("r_cand = 1.3e0") && text.contains(PATH_FILE));
    }

    #[test]
    fn different_spheres_are_not_applicable() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        scene.pair.body2.radius = 0.05;
        let e = Solid3dDeck::new(1).solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::NotApplicable(_)), "{e}");
    }

    #[test]
    fn the_axial_grip_is_not_applicable() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        scene.domain.grip = Grip::Axial;
        let e = Solid3dDeck::new(1).solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::NotApplicable(_)), "{e}");
    }

    #[test]
    fn timing_phases_are_read_and_garbage_is_skipped() {
        let phases = parse_phases("phase,seconds\nsetup,1.5\npath,nan\nranks,2\n");
        assert_eq!(phases, [("setup".to_owned(), 1.5), ("ranks".to_owned(), 2.0)]);
    }
}
