//! The CalculiX deck `ccx-3d`: the frictional path in 3D on fem-3d's gmsh mesh of the half body
//! ([`spherecontact_solvers::fem::mesh::solid_geo`]: hemisphere or cap, y ≥ 0) — C3D10 on its tetrahedra, or, by
//! `[calculix] element`, C3D20/C3D20R on the 20-node bricks of the same body
//! ([`super::hex_mesh`], graded faster: the paper's discretisation) — the symmetry plane y = 0
//! held in y, both spheres meshed (the second the mirror image of the first through the contact
//! plane), penalty contact with Coulomb friction and history, one `*STEP` per path step (the
//! case's increments).
//!
//! Why both spheres and not one against a rigid plane (as `ccx-axisym`, which is frictionless):
//! under normal load the surface of a sphere pressed on a rigid plane moves radially against the
//! plane, and friction resists it (measured at c_max/3 after the normal load: |q| = μ p on most
//! of the contact, and Q at δt = 3 µm 13 % below fem-3d's), while two identical spheres' surfaces
//! move alike and do not slip against each other; the symmetry of the contact plane holds for
//! the normal problem only.
//!
//! P and Q from the far face's reaction, the maps at the candidate faces' corners (pressure and
//! traction from the contact's nodal forces, recovered from the displacements CalculiX writes;
//! gap, slip and stick from its contact output), all read from CalculiX's own output
//! ([`super::solid_read`], [`super::nodal_forces`]), in fem-3d's surface layout. The `.inp`
//! ([`super::solid_inp`], template `templates/calculix_3d.inp`) is self-contained.
//!
//! Model and findings: docs/external-decks.md, "CalculiX 3D".

use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::json;

use super::body::Body;
use super::hex_mesh;
use super::solid_inp::SolidDeckSpec;
use super::solid_read::{self, SolidRun, STICK_MARGIN};
use crate::axisym::Options;
use crate::bricks;
use crate::deck::{self, Deck, DeckKind, RunDir, TimeBudget};
use crate::plan::Plan;
use crate::readback;
use crate::record::FINITE_BODY;
use crate::split;
use crate::surface3d;
use crate::{calculix::CcxAxisymDeck, calculix::Settings};
use spherecontact_model::calculix_settings::MeshKind;
use spherecontact_model::domain::Grip;
use spherecontact_model::history::{History, Metadata};
use spherecontact_model::limits::SOLID_POLE;
use spherecontact_model::resolution::{self, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::split::{DeckCommand, SplitDeck};
use spherecontact_model::solver::Kind;
use spherecontact_model::solver::{SolveError, Solver};
use spherecontact_solvers::fem::mesh::solid;
use spherecontact_solvers::fem::mesh::solid_geo::{self, SolidMeshFiles, Zones};
use spherecontact_system::process::Job;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The solver name.
pub const NAME: &str = "ccx-3d";

/// Default pole element size, as a fraction of the path's largest contact radius: c_max/5, the
/// coarse mesh of fenicsx-3d (ccx's direct solves with contact take tens of seconds an increment
/// on finer meshes; docs/external-decks.md).
pub const DEFAULT_POLE_FRACTION: f64 = 1.0 / 5.0;

/// Default pole brick size on the 20-node bricks: c_max/2, the coarsest (on the paper's
/// hemispheres 6 410 nodes a body, ≈ 2.4 s a Newton iteration, 68 s of ccx CPU for
/// `cases/ccx-3d.toml`'s path; 9 212 nodes and 154 s at c_max/4: docs/external-decks.md, "The
/// paper's discretisation").
pub const DEFAULT_BRICK_POLE_FRACTION: f64 = 1.0 / 2.0;

/// Time allowed: start-up, set-up (reading the deck) and per path step (measured ≈ 10 s a step
/// at c_max/4 on the paper's spheres; the budget leaves room for finer meshes and a loaded
/// machine).
const BUDGET: TimeBudget = TimeBudget {
    start: Duration::from_secs(30),
    setup: Duration::from_secs(120),
    per_step: Duration::from_secs(600),
};

/// The deck: `ccx -i job` in the run directory, as `ccx-axisym`'s.
#[derive(Clone, Copy, Debug)]
pub struct CcxSolidDeck;

impl Deck for CcxSolidDeck {
    const KIND: DeckKind = DeckKind {
        name: NAME,
        description: "CalculiX (ccx) 3D FEM, C3D10 on fem-3d's gmsh mesh of the half body (or C3D20/C3D20R on its 20-node bricks), both spheres meshed (the second mirrored), face-to-face penalty contact with Coulomb friction and history",
        tool: Tool::Ccx,
        template: super::solid_inp::TEMPLATE,
        file_name: "job.inp",
    };

    type Mesh = SolidMeshFiles;

    fn mesh_file<'a>(&self, mesh: &'a SolidMeshFiles) -> &'a Path {
        &mesh.msh
    }

    fn job(&self, toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job {
        CcxAxisymDeck.job(toolchain, deck, timeout)
    }

    fn exit_code_meaning(&self, code: i32) -> &'static str {
        CcxAxisymDeck.exit_code_meaning(code)
    }
}

/// `ccx-3d` as a [`Solver`].
#[derive(Clone, Debug, Default)]
pub struct CcxSolid {
    /// How it is run (toolchain, pole size, time limit, a replacement deck text).
    pub options: Options,
    /// The case's CalculiX settings (contact formulation, penalty factor).
    pub settings: Settings,
}

/// A finished run: what was read back, the mesh's size, the wall times.
struct Run {
    read: SolidRun,
    /// The mesh in words.
    mesh: &'static str,
    elements: usize,
    nodes: usize,
    slave_faces: usize,
    stiffness: f64,
    stick_slope: f64,
    /// The steps whose outermost candidate ring carries the contact's force ([`edge_loaded`]).
    edge_steps: Vec<usize>,
    /// Wall seconds of gmsh, ccx and the reading back.
    wall_s: [f64; 3],
}

impl CcxSolid {
    /// The pole size and plan of `scene`: the candidate zone is fem-3d's, so that the slave
    /// faces are fem-3d's candidate faces.
    fn plan(&self, scene: &Scene) -> (f64, Plan) {
        let c_max = scene.max_contact_radius();
        let fraction = match self.settings.element.mesh() {
            MeshKind::Tet10 => DEFAULT_POLE_FRACTION,
            MeshKind::Hex20 => DEFAULT_BRICK_POLE_FRACTION,
        };
        let h = self.options.resolution.unwrap_or(fraction * c_max);
        let mut plan = Plan::of(scene, h);
        plan.candidate_radius = Zones::new(c_max, h).candidate_radius;
        (h, plan)
    }

    /// The body's mesh, `body.msh` in `dir`, of the kind of the case's element.
    fn read_mesh(&self, dir: &Path) -> Result<Body, SolveError> {
        let path = dir.join("body.msh");
        let failed = |e: String| SolveError::Failed(format!("reading gmsh's mesh: {e}"));
        Ok(match self.settings.element.mesh() {
            MeshKind::Tet10 => Body::Tet10(solid::read(&path).map_err(|e| failed(e.to_string()))?),
            MeshKind::Hex20 => Body::Hex20(hex_mesh::read(&path).map_err(|e| failed(e.to_string()))?),
        })
    }

    /// Meshes the body into `dir` (`body.geo`, `body.msh`): the mesh, the filled deck and gmsh's
    /// wall time.
    fn prepare(
        &self,
        scene: &Scene,
        plan: &Plan,
        h: f64,
        dir: &Path,
    ) -> Result<(Body, String, f64), SolveError> {
        let zones = Zones::new(scene.max_contact_radius(), h);
        let r = scene.pair.body1.radius;
        let geometry = solid_geo::geometry(r, scene.domain.height(r), h, zones);
        let toolchain = &self.options.toolchain;
        let (mesh, files) = match self.settings.element.mesh() {
            MeshKind::Tet10 => {
                let files = solid_geo::mesh(&geometry, dir, "body", toolchain)?;
                (self.read_mesh(dir)?, files)
            }
            MeshKind::Hex20 => {
                let (mesh, files) = hex_mesh::mesh(&bricks::graded(&geometry), dir, "body", toolchain)?;
                (Body::Hex20(mesh), files)
            }
        };
        let text = match &self.options.deck_text {
            Some(text) => text.clone(),
            None => self
                .spec(scene, plan, h, &mesh)
                .text()
                .map_err(SolveError::Failed)?,
        };
        Ok((mesh, text, files.wall_s))
    }

    fn spec<'a>(&self, scene: &'a Scene, plan: &'a Plan, h: f64, mesh: &'a Body) -> SolidDeckSpec<'a> {
        SolidDeckSpec {
            scene: &scene.name,
            domain: scene.domain.describe(),
            mesh,
            young: scene.pair.body1.material.young,
            poisson: scene.pair.body1.material.poisson,
            friction: if plan.tangential { scene.friction } else { 0.0 },
            h,
            grip: plan.grip,
            candidate_radius: plan.candidate_radius,
            settings: self.settings,
            steps: &plan.steps,
        }
    }

    /// Writes everything the deck needs to run by hand into the existing folder `dir`, without
    /// running it: `body.geo`, `body.msh`, `job.inp` and `path.txt` (run `OMP_NUM_THREADS=1 ccx
    /// -i job` there, then [`CcxSolid::read_run`]).
    pub fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError> {
        applicable(scene)?;
        // gmsh runs in the folder: a relative path would name another place there.
        let dir = &dir
            .canonicalize()
            .map_err(|e| SolveError::Failed(format!("{}: {e}", dir.display())))?;
        let (h, plan) = self.plan(scene);
        let (_, text, _) = self.prepare(scene, &plan, h, dir)?;
        deck::write_deck(&CcxSolidDeck, dir, &text, &plan.steps)
    }

    /// The history of a run directory that [`CcxSolid::write_run`] wrote and ccx finished
    /// elsewhere, read back as after the solver's own run. The directory's `path.txt` must list
    /// `scene`'s steps; the pole size is this solver's (its resolution option or the default).
    pub fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError> {
        applicable(scene)?;
        let (h, plan) = self.plan(scene);
        readback::check_path_file(dir, &plan.steps, &scene.name)?;
        super::errors::logged_error(dir)?;
        let mesh = self.read_mesh(dir)?;
        let run = self.read(scene, &plan, h, &mesh, dir, [0.0; 2])?;
        Ok(self.history(scene, "(run elsewhere)", &plan, h, &run))
    }

    /// Meshes, writes and runs the deck, and reads back, in `dir`.
    fn run_in(&self, scene: &Scene, plan: &Plan, h: f64, dir: &RunDir) -> Result<Run, SolveError> {
        let (mesh, text, mesh_s) = self.prepare(scene, plan, h, dir.path())?;
        let timeout = self.options.timeout.unwrap_or(BUDGET.limit(plan.steps.len()));
        let toolchain = &self.options.toolchain;
        let run = deck::launch(&CcxSolidDeck, toolchain, dir.path(), &text, &plan.steps, timeout)?;
        super::errors::reported_error(&run.stdout)?;
        self.read(scene, plan, h, &mesh, dir.path(), [mesh_s, run.wall_s])
    }

    /// Reads the run's output in `dir` back.
    fn read(
        &self,
        scene: &Scene,
        plan: &Plan,
        h: f64,
        mesh: &Body,
        dir: &Path,
        [mesh_s, solve_s]: [f64; 2],
    ) -> Result<Run, SolveError> {
        let start = Instant::now();
        let spec = self.spec(scene, plan, h, mesh);
        let read = solid_read::read_back(dir, &spec).map_err(SolveError::Failed)?;
        let edge_steps = read
            .surfaces
            .iter()
            .filter(|surface| edge_loaded(surface, &read.triangles, h))
            .map(|surface| surface.step)
            .collect();
        Ok(Run {
            mesh: mesh.describe(),
            elements: mesh.element_count(),
            nodes: mesh.nodes().len(),
            slave_faces: spec.slave_faces().len(),
            stiffness: spec.stiffness_mpa_per_mm(),
            stick_slope: spec.stick_slope_mpa_per_mm(),
            read,
            edge_steps,
            wall_s: [mesh_s, solve_s, start.elapsed().as_secs_f64()],
        })
    }

    /// One row per path step, the fields, the metadata.
    fn history(&self, scene: &Scene, version: &str, plan: &Plan, h: f64, run: &Run) -> History {
        let read = &run.read;
        let (steps, fields) = surface3d::step_results(
            scene,
            plan.tangential,
            &read.forces,
            &read.surfaces,
            &read.triangles,
        );
        History {
            metadata: self.metadata(scene, version, plan, h, run),
            steps,
            fields,
        }
    }

    fn metadata(&self, scene: &Scene, version: &str, plan: &Plan, h: f64, run: &Run) -> Metadata {
        let friction = if plan.tangential {
            format!(
                "Coulomb friction μ = {} with history, stick slope λ = K/100 (λ = K diverged)",
                scene.friction
            )
        } else {
            "frictionless (the path has no tangential motion)".to_owned()
        };
        let mut metadata = Metadata {
            version: format!("CalculiX {version}"),
            model: format!(
                "3D, the halves (y ≥ 0) of both spheres ({}; the second mirrored through the \
                 contact plane); {} on gmsh's {}; {} penalty contact \
                 K = {:e} E/h; {friction}; P and Q from the far face's reaction × 2, the maps at the \
                 candidate faces' corners: p and q from the contact's nodal forces (sphere 1's \
                 internal forces from CalculiX's displacements, on its elements' own rules), gap, \
                 slip and stick from its contact output",
                scene.domain.describe(),
                self.settings.element.keyword(),
                run.mesh,
                self.settings.formulation.name(),
                self.settings.penalty,
            ),
            resolution: format!(
                "pole element {:.3} µm (c_max/{:.1}), {} elements, {} nodes, {} slave faces; \
                 every path step computed (one *STEP each)",
                h * 1e6,
                scene.max_contact_radius() / h,
                run.elements,
                run.nodes,
                run.slave_faces
            ),
            warnings: vec![FINITE_BODY.to_owned()],
            ..Metadata::default()
        };
        let mismatch = run.read.map_mismatch();
        if mismatch > MAP_MISMATCH {
            metadata.warnings.push(format!(
                "the maps carry P and Q different from the reactions by {mismatch:.2e} of P (more than \
                 {MAP_MISMATCH:e}): contact force outside the candidate faces, or displacements that are not \
                 the deck's (forces_map_by_step against the history's P and Q)"
            ));
        }
        if !run.edge_steps.is_empty() {
            metadata.warnings.push(format!(
                "the contact's forces (recovered from CalculiX's displacements) reach the outermost \
                 candidate ring at steps {:?}: the contact may extend beyond the candidate faces, \
                 which c, p0 and the maps do not see (P and Q come from the reactions); refine the mesh",
                run.edge_steps
            ));
        }
        let extra = &mut metadata.extra;
        extra.insert("calculix".into(), self.settings.describe());
        extra.insert("element".into(), json!(self.settings.element.keyword()));
        extra.insert("penalty_stiffness_mpa_per_mm".into(), json!(run.stiffness));
        extra.insert("stick_slope_mpa_per_mm".into(), json!(run.stick_slope));
        extra.insert(
            "stick_rule".into(),
            json!(format!(
                "a corner node sticks when CalculiX's own |CSHEAR| < μ CPRESS (1 − {STICK_MARGIN}) there"
            )),
        );
        extra.insert("grip".into(), json!(plan.grip.name()));
        extra.insert(
            "computed_steps".into(),
            json!("every step of the path, one *STEP each"),
        );
        extra.insert("candidate_radius_m".into(), json!(plan.candidate_radius));
        extra.insert("forces_plate_by_step".into(), json!(run.read.forces_plane));
        extra.insert("forces_map_by_step".into(), json!(run.read.forces_map));
        extra.insert("map_force_mismatch_max".into(), json!(run.read.map_mismatch()));
        let [meshing, solving, reading] = run.wall_s;
        extra.insert("meshing_s".into(), json!(meshing));
        extra.insert("solving_s".into(), json!(solving));
        extra.insert("reading_back_s".into(), json!(reading));
        extra.insert(
            "solving_s_per_step".into(),
            json!(solving / plan.steps.len().max(1) as f64),
        );
        metadata
    }
}

/// Largest disagreement of the maps' P and Q with the reactions, relative to P, that passes
/// without a warning: the recovered forces are exact to the `.frd`'s 6 digits of displacement
/// (measured 7.5e-7 in P, 6.4e-6 in Q on `cases/ccx-3d.toml`), so 1e-4 leaves a margin of 15.
const MAP_MISMATCH: f64 = 1e-4;

/// Fraction of the peak hat-averaged pressure above which a corner of the outermost candidate
/// ring counts as loaded: the contact's recovered forces there are its own (exact, not an
/// extrapolation), so a corner above the recovery's noise (about 1e-5 of the peak,
/// [`super::nodal_forces`]) is loaded; 5 % keeps the warning for loads that move c and p0.
const EDGE_PRESSURE: f64 = 0.05;

/// Whether a corner within half an element of the outermost candidate ring carries more than
/// [`EDGE_PRESSURE`] of the peak, on the pressure's hat averages (the recovered forces per hat
/// area, what the measures read; the corner values themselves undershoot and overshoot beside a
/// sharp edge): the contact may reach beyond the candidate zone.
fn edge_loaded(surface: &surface3d::Surface3, triangles: &[[usize; 3]], h: f64) -> bool {
    let points: Vec<[f64; 2]> = surface.nodes.iter().map(|n| n.point).collect();
    let pressures: Vec<f64> = surface.nodes.iter().map(|n| n.pressure).collect();
    let averages = spherecontact_solvers::fit::recovery::hat_averages(&points, triangles, &pressures);
    let peak = averages.iter().copied().fold(0.0, f64::max);
    let outer = surface.nodes.iter().map(|n| n.r()).fold(0.0, f64::max);
    surface
        .nodes
        .iter()
        .zip(&averages)
        .any(|(n, &p)| p > EDGE_PRESSURE * peak && n.r() >= outer - 0.5 * h)
}

/// Why the model does not apply to `scene`, if it does not: identical spheres (one body by the
/// symmetry of the contact plane), and a rigid grip on a tangential path.
fn applicable(scene: &Scene) -> Result<(), SolveError> {
    if !scene.pair.is_symmetric() || !scene.pair.body1.radius.is_finite() {
        return Err(SolveError::NotApplicable(
            "ccx-3d models two identical spheres through their plane of contact; different spheres \
             or a sphere on a flat are not modelled"
                .into(),
        ));
    }
    if scene.domain.grip == Grip::Axial && !scene.path.is_normal_only() {
        return Err(SolveError::NotApplicable(
            "an axial grip leaves the far face free in its plane: it cannot be shifted (frictionless scenes only)"
                .into(),
        ));
    }
    Ok(())
}

impl Solver for CcxSolid {
    fn name(&self) -> &str {
        NAME
    }

    fn kind(&self) -> Kind {
        Kind::FiniteElement
    }

    fn description(&self) -> &str {
        CcxSolidDeck::KIND.description
    }

    /// A pole element size: `c/N` or a length, within [`SOLID_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let mut solver = self.clone();
        solver.options.resolution = Some(resolution::pole_size(NAME, scene, value, SOLID_POLE)?);
        Ok(Box::new(solver))
    }

    fn with_calculix(&self, settings: &Settings) -> Option<Box<dyn Solver>> {
        Some(Box::new(Self {
            settings: *settings,
            ..self.clone()
        }))
    }

    fn split_deck(&self) -> Option<&dyn SplitDeck> {
        Some(self)
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        applicable(scene)?;
        let version = self
            .options
            .toolchain
            .require(Tool::Ccx)
            .map_err(SolveError::Unavailable)?;
        let (h, plan) = self.plan(scene);
        let run = deck::in_run_dir("spherecontact-ccx-3d-", |dir| self.run_in(scene, &plan, h, dir))?;
        Ok(self.history(scene, &version, &plan, h, &run))
    }
}

impl SplitDeck for CcxSolid {
    fn settings(&self, scene: &Scene) -> serde_json::Value {
        json!({ "pole_element_m": self.plan(scene).0, "calculix": self.settings.describe() })
    }

    /// `ccx -i job` on one thread, as the solver's own run starts it.
    fn command(&self) -> DeckCommand {
        split::deck_command(&CcxSolidDeck, &self.options.toolchain)
    }

    fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError> {
        CcxSolid::write_run(self, scene, dir)
    }

    fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError> {
        CcxSolid::read_run(self, scene, dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_ccx_is_unavailable_and_different_spheres_not_applicable() {
        let scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        let mut solver = CcxSolid::default();
        solver.options.toolchain.ccx = "/nonexistent/ccx".into();
        let e = solver.solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::Unavailable(_)), "{e}");
        let mut other = scene.clone();
        other.pair.body2.radius = 0.05;
        let e = CcxSolid::default().solve(&other).unwrap_err();
        assert!(matches!(e, SolveError::NotApplicable(_)), "{e}");
    }
}
