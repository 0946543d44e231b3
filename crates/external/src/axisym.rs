//! The axisymmetric run shared by the external decks: check that the scene fits the model, mesh
//! it, write the deck and its list of steps, run it once for the whole path, read back, and give
//! one `History` row per path step ([`super::record`]).
//!
//! Model (docs/external-decks.md): two identical spheres (Dundurs β = 0) are symmetric about their
//! contact plane; the pressure is even and the tangential displacement odd across it, so one
//! sphere against the plane is exact, and the problem splits into the axisymmetric Fourier mode
//! n = 0 (normal: approach δn/2, frictionless) and the mode n = 1 (tangential: far face shifted by
//! δt/2, Coulomb with history on the contact line under the n = 0 pressure). The deck walks every
//! step of the path with history. Different spheres, or a sphere on a flat, are not modelled
//! (`NotApplicable`).

use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::json;

use super::deck::{self, Deck, DeckInput, RunDir, TimeBudget};
use super::field_files;
use super::plan::{Plan, CANDIDATE_ZONE, KFAC};
use super::readback::{self, DeckRow};
use super::record::{self, Run, Timing};
use super::split;
use super::surface::{self, Surface};
use spherecontact_model::domain::Grip;
use spherecontact_model::history::History;
use spherecontact_model::limits::{MAX_DECK_CLOCK_BYTES, MAX_DECK_TABLE_BYTES, MERIDIAN_POLE};
use spherecontact_model::resolution::{self, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::split::{DeckCommand, SplitDeck};
use spherecontact_model::solver::Kind;
use spherecontact_model::solver::{SolveError, Solver};
use spherecontact_solvers::fem::mesh::geo::{self, MeshFiles};
use spherecontact_system::toolchain::{Tool, Toolchain};

/// Cap on contact iterations per step and mode; a step that hits it is flagged.
pub const MAX_ITERATIONS: u32 = 30;

/// Time allowed for start-up (imports, dolfinx's form compilation on a first run), for the set-up
/// (assembly, factorisation and one solve per candidate DOF: 10–40 s at c/40, minutes at c/80),
/// and per computed step (milliseconds at c/40).
const BUDGET: TimeBudget = TimeBudget {
    start: Duration::from_secs(120),
    setup: Duration::from_secs(600),
    per_step: Duration::from_millis(500),
};

/// How a deck (axisymmetric or 3D) is run.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// The executables.
    pub toolchain: Toolchain,
    /// Pole element size [m]; default [`geo::default_resolution`] (axisymmetric decks).
    pub resolution: Option<f64>,
    /// Time limit for the deck; default 12 min + 0.5 s per step (axisymmetric decks).
    pub timeout: Option<Duration>,
    /// A replacement deck text (already filled), for fault tests and experiments.
    pub deck_text: Option<String>,
    /// Cap on contact iterations per step; default [`MAX_ITERATIONS`].
    pub max_iterations: Option<u32>,
}

/// An external deck as a [`Solver`].
pub struct AxisymSolver<D: Deck<Mesh = MeshFiles>> {
    /// The deck.
    pub deck: D,
    /// How it is run.
    pub options: Options,
}

/// Pole element sizes of the external ladder, as fractions of the path's largest contact radius.
pub const LADDER: [f64; 4] = [1.0 / 10.0, 1.0 / 20.0, 1.0 / 40.0, 1.0 / 80.0];

impl<D: Deck<Mesh = MeshFiles> + 'static> Solver for AxisymSolver<D> {
    fn name(&self) -> &'static str {
        self.deck.name()
    }

    fn kind(&self) -> Kind {
        Kind::FiniteElement
    }

    /// A pole element size: `c/N` or a length, within [`MERIDIAN_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let mut options = self.options.clone();
        options.resolution = Some(resolution::pole_size(self.name(), scene, value, MERIDIAN_POLE)?);
        Ok(Box::new(AxisymSolver {
            deck: self.deck.clone(),
            options,
        }))
    }

    fn resolution_ladder(&self, scene: &Scene) -> Vec<Box<dyn Solver>> {
        LADDER
            .iter()
            .map(|fraction| {
                let mut options = self.options.clone();
                options.resolution = Some(fraction * scene.max_contact_radius());
                Box::new(AxisymSolver {
                    deck: self.deck.clone(),
                    options,
                }) as Box<dyn Solver>
            })
            .collect()
    }

    fn description(&self) -> &'static str {
        self.deck.description()
    }

    fn split_deck(&self) -> Option<&dyn SplitDeck> {
        Some(self)
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        applicable(scene)?;
        let toolchain = &self.options.toolchain;
        let version = toolchain
            .require(self.deck.tool())
            .map_err(SolveError::Unavailable)?;
        toolchain.require(Tool::Meshio).map_err(SolveError::Unavailable)?;
        let resolution = self.pole_size(scene);
        let plan = Plan::of(scene, resolution);
        let run = deck::in_run_dir(&format!("spherecontact-{}-", self.deck.name()), |dir| {
            self.run_in(scene, resolution, &plan, dir)
        })?;
        Ok(record::history(&self.deck, scene, &version, &plan, &run))
    }
}

impl<D: Deck<Mesh = MeshFiles>> AxisymSolver<D> {
    /// A deck with default options.
    pub fn new(deck: D) -> Self {
        Self {
            deck,
            options: Options::default(),
        }
    }

    /// The pole element size [m]: the option's, or [`geo::default_resolution`].
    fn pole_size(&self, scene: &Scene) -> f64 {
        self.options
            .resolution
            .unwrap_or_else(|| geo::default_resolution(scene))
    }

    /// Writes, runs the deck and reads back, in `dir`: the one path of the in-process run and of
    /// a deck written and read apart ([`SplitDeck`]).
    fn run_in(&self, scene: &Scene, resolution: f64, plan: &Plan, dir: &RunDir) -> Result<Run, SolveError> {
        let mesh = self.write_in(scene, resolution, plan, dir.path())?;
        let meshing_s = mesh.wall_s;
        let timeout = self.options.timeout.unwrap_or(BUDGET.limit(plan.steps.len()));
        let run = deck::run_written(&self.deck, &self.options.toolchain, dir.path(), timeout)?;
        let mut read = self.read_in(scene, plan, mesh, dir.path())?;
        read.timing.meshing_s = meshing_s;
        read.timing.solving_s = run.wall_s;
        Ok(read)
    }

    /// Meshes the scene into `dir` and writes the deck and its list of steps there: the mesh.
    fn write_in(
        &self,
        scene: &Scene,
        resolution: f64,
        plan: &Plan,
        dir: &Path,
    ) -> Result<MeshFiles, SolveError> {
        let mesh = geo::mesh(scene, resolution, dir, &self.options.toolchain)?;
        let max_iterations = self.options.max_iterations.unwrap_or(MAX_ITERATIONS);
        let input = deck_input(&self.deck, scene, resolution, plan, &mesh, max_iterations);
        let text = self
            .options
            .deck_text
            .clone()
            .unwrap_or_else(|| deck::fill(self.deck.template(), &input));
        deck::write_deck(&self.deck, dir, &text, &plan.steps)?;
        Ok(mesh)
    }

    /// Reads back the run the deck finished in `dir` on `mesh` (its reading time; meshing and
    /// solving left at zero); writes nothing into `dir`.
    fn read_in(&self, scene: &Scene, plan: &Plan, mesh: MeshFiles, dir: &Path) -> Result<Run, SolveError> {
        let start = Instant::now();
        let radius_mm = scene.pair.body1.radius * 1e3;
        let (rows, surfaces) =
            read_back(dir, plan, radius_mm, &self.options.toolchain).map_err(SolveError::Failed)?;
        let deck_clock = readback::read_optional_output(dir, "timing.csv", MAX_DECK_CLOCK_BYTES)
            .map_err(SolveError::Failed)?
            .map_or((None, None), |t| readback::parse_timing(&t));
        Ok(Run {
            rows,
            surfaces,
            mesh,
            timing: Timing {
                reading_s: start.elapsed().as_secs_f64(),
                ..Timing::default()
            },
            deck_clock,
        })
    }
}

impl<D: Deck<Mesh = MeshFiles> + 'static> SplitDeck for AxisymSolver<D> {
    fn settings(&self, scene: &Scene) -> serde_json::Value {
        json!({ "pole_element_m": self.pole_size(scene) })
    }

    fn command(&self) -> DeckCommand {
        split::deck_command(&self.deck, &self.options.toolchain)
    }

    fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError> {
        applicable(scene)?;
        let resolution = self.pole_size(scene);
        self.write_in(scene, resolution, &Plan::of(scene, resolution), dir)
            .map(drop)
    }

    fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError> {
        applicable(scene)?;
        let toolchain = &self.options.toolchain;
        toolchain.require(Tool::Meshio).map_err(SolveError::Unavailable)?;
        let resolution = self.pole_size(scene);
        let plan = Plan::of(scene, resolution);
        let mesh = MeshFiles::in_folder(dir, resolution)?;
        let run = self.read_in(scene, &plan, mesh, dir)?;
        Ok(record::history(
            &self.deck,
            scene,
            split::RUN_ELSEWHERE,
            &plan,
            &run,
        ))
    }
}

/// The numbers a deck's template is filled with (mm, N, MPa): the scene's sphere, the pole size
/// `resolution` [m], the plan's grip, candidates and tangential switch, the deck's mesh file of
/// `mesh`, and the cap on contact iterations.
pub(crate) fn deck_input<D: Deck>(
    deck: &D,
    scene: &Scene,
    resolution: f64,
    plan: &Plan,
    mesh: &D::Mesh,
    max_iterations: u32,
) -> DeckInput {
    let body = scene.pair.body1;
    DeckInput {
        scene: scene.name.clone(),
        mesh: deck
            .mesh_file(mesh)
            .file_name()
            .map_or_else(String::new, |f| f.to_string_lossy().into_owned()),
        radius_mm: body.radius * 1e3,
        young_mpa: body.material.young * 1e-6,
        poisson: body.material.poisson,
        h_mm: resolution * 1e3,
        kfac: KFAC,
        friction: scene.friction,
        grip: plan.grip,
        candidate_radius_mm: plan.candidate_radius * 1e3,
        tangential: plan.tangential,
        max_iterations,
    }
}

/// Reads steps.csv and surface.csv, and checks the field files through meshio against the nodal
/// pressures (the same numbers, written twice: a field file that disagrees is garbage).
fn read_back(
    dir: &Path,
    plan: &Plan,
    radius_mm: f64,
    toolchain: &Toolchain,
) -> Result<(Vec<DeckRow>, Vec<Surface>), String> {
    let read = |name: &str| readback::read_output(dir, name, MAX_DECK_TABLE_BYTES);
    let rows = readback::parse_steps(&read("steps.csv")?, &plan.steps)?;
    let indices: Vec<usize> = plan.steps.iter().map(|s| s.step).collect();
    let surfaces = surface::parse_surface(&read("surface.csv")?, &indices)?;
    if let Some(s) = surfaces.iter().find(|s| s.edge_loaded()) {
        return Err(format!(
            "step {}: the contact reached the outermost candidate node: the candidate zone, \
             {CANDIDATE_ZONE} × the largest Hertz contact radius, is too small for this model",
            s.step
        ));
    }
    let at_positions: Vec<(&DeckRow, &Surface)> = rows
        .iter()
        .zip(&surfaces)
        .filter(|(r, _)| r.field_file.is_some())
        .collect();
    let files: Vec<String> = at_positions
        .iter()
        .filter_map(|(r, _)| r.field_file.clone())
        .collect();
    if files.len() != plan.steps.iter().filter(|s| s.position.is_some()).count() {
        return Err("steps.csv: a path position has no field file".into());
    }
    let window_mm = plan.candidate_radius * 1e3;
    let profiles = field_files::read_profiles(dir, &files, radius_mm, window_mm, toolchain, BUDGET.start)?;
    for ((file, profile), (_, surface)) in files.iter().zip(&profiles).zip(&at_positions) {
        record::check_field_file(file, profile, surface)?;
    }
    Ok((rows, surfaces))
}

/// `NotApplicable` unless the scene is two identical finite spheres (the symmetric model) whose
/// far faces can carry the path: a shift needs the rigid grip.
pub fn applicable(scene: &Scene) -> Result<(), SolveError> {
    if !scene.pair.is_symmetric() {
        return Err(SolveError::NotApplicable(
            "the external decks model two identical spheres through their symmetry plane; \
             different spheres or a sphere on a flat are not modelled yet"
                .into(),
        ));
    }
    if !scene.pair.body1.radius.is_finite() {
        return Err(SolveError::NotApplicable(
            "two flats have no contact to model".into(),
        ));
    }
    if scene.domain.grip == Grip::Axial && !scene.path.is_normal_only() {
        return Err(SolveError::NotApplicable(
            "the axial grip leaves the far face free to slide, so the path's tangential shift \
             cannot be imposed (grip = \"rigid\" in [domain])"
                .into(),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::freefem::FreeFem;

    #[test]
    fn different_spheres_are_not_applicable() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        scene.pair.body2.radius = 0.05;
        let e = AxisymSolver::new(FreeFem).solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::NotApplicable(_)), "{e}");
    }

    #[test]
    fn a_shift_under_the_axial_grip_is_not_applicable() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        scene.domain.grip = Grip::Axial;
        assert!(applicable(&scene).is_ok());
        let positions = scene.path.positions().to_vec();
        let shifted: Vec<_> = positions
            .iter()
            .map(|p| spherecontact_model::path::Position { delta_t: 1e-6, ..*p })
            .collect();
        scene.path = spherecontact_model::path::LoadingPath::try_new(shifted, vec![4]).unwrap();
        let e = applicable(&scene).unwrap_err();
        assert!(
            matches!(e, SolveError::NotApplicable(_)) && e.to_string().contains("rigid"),
            "{e}"
        );
    }

    #[test]
    fn a_missing_tool_is_unavailable_not_a_failure() {
        let scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        let mut solver = AxisymSolver::new(FreeFem);
        solver.options.toolchain.freefem = "/nonexistent/FreeFem++".into();
        let e = solver.solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::Unavailable(_)), "{e}");
        assert!(e.to_string().contains("scripts/setup.sh"), "{e}");
    }
}
