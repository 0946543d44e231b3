//! `kratos-3d` as a [`Solver`] and a [`SplitDeck`]: mesh (gmsh, fem-3d's geometry), write the
//! deck's files ([`super::mdpa`], [`super::project`], the driver), run the driver under the process
//! handling of every deck ([`deck::launch`]: its own process group, a time limit, its log kept on
//! failure), read back ([`super::results`]) into the History of fem-3d's layout
//! ([`surface3d::step_results`]).
//!
//! A step that Kratos did not converge has no values in the History (its checks are NOOK), nor,
//! under friction, any step after it (its state, not an equilibrium, is the next step's history);
//! the convergence record of every step is in the metadata.

use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::json;

use super::bricks8;
use super::linear::LinearBody;
use super::mdpa::{MdpaSpec, STEM};
use super::project::{ProjectSpec, MATERIALS, MAX_ITERATIONS, PROJECT};
use super::results::{self, KratosStep};
use super::slave::slave_nodes;
use crate::axisym::Options;
use crate::deck::{self, Deck, DeckKind, RunDir, TimeBudget};
use crate::plan::Plan;
use crate::readback::{self, read_output};
use crate::record::FINITE_BODY;
use crate::split;
use crate::surface3d::{self, Surface3};
use spherecontact_model::domain::Grip;
use spherecontact_model::history::{History, Metadata};
use spherecontact_model::kratos_settings::{Element, Settings};
use spherecontact_model::limits::{MAX_DECK_TABLE_BYTES, SOLID_POLE};
use spherecontact_model::resolution::{self, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::split::{DeckCommand, SplitDeck};
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_solvers::fem::mesh::solid;
use spherecontact_solvers::fem::mesh::solid_geo::{self, SolidMeshFiles, Zones};
use spherecontact_system::process::Job;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The solver name.
pub const NAME: &str = "kratos-3d";

/// The driver template (a fixed file: it reads every number from `path.txt`).
pub const TEMPLATE: &str = include_str!("templates/kratos_3d.py");

/// Default pole element size, as a fraction of the path's largest contact radius: c_max/5, as
/// ccx-3d's tetrahedra (Kratos' direct solve takes about 0.5 s a Newton iteration there on this
/// machine: docs/external-decks.md, "Kratos 3D").
pub const DEFAULT_POLE_FRACTION: f64 = 1.0 / 5.0;

/// Time allowed: start-up (the imports, about 1 s), set-up (reading the MDPA, the contact search)
/// and per computed step ([`MAX_ITERATIONS`] iterations at about 1.3 s each on c_max/5, with a
/// margin for finer meshes and a loaded machine).
const BUDGET: TimeBudget = TimeBudget {
    start: Duration::from_secs(60),
    setup: Duration::from_secs(60),
    per_step: Duration::from_secs(300),
};

/// The deck: the driver run by the Python of the project's Kratos environment.
#[derive(Clone, Copy, Debug)]
pub struct KratosSolidDeck;

impl Deck for KratosSolidDeck {
    const KIND: DeckKind = DeckKind {
        name: NAME,
        description: "Kratos ContactStructuralMechanicsApplication 3D FEM, SmallDisplacementElement3D4N on the corners of fem-3d's gmsh mesh of the half body or SmallDisplacementElement3D8N on gmsh's bricks of it (the whole body under friction), both spheres meshed (the second mirrored), mortar contact (augmented Lagrangian with Coulomb friction, frictionless, or penalty), every step's convergence kept",
        tool: Tool::KratosContact,
        template: TEMPLATE,
        file_name: "kratos_3d.py",
    };

    type Mesh = SolidMeshFiles;

    fn mesh_file<'a>(&self, mesh: &'a SolidMeshFiles) -> &'a Path {
        &mesh.msh
    }

    /// `python kratos_3d.py` (the project's Kratos Python), one OpenMP thread.
    fn job(&self, toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job {
        Job {
            program: toolchain.kratos_python.clone(),
            args: vec![deck.display().to_string()],
            env: deck::single_threaded(),
            timeout,
        }
    }

    /// Python's codes: 1 after an uncaught exception (Kratos' errors are `RuntimeError`s) or the
    /// driver's own `sys.exit` with a message.
    fn exit_code_meaning(&self, code: i32) -> &'static str {
        match code {
            1 => "the driver or Kratos stopped with an error (its message and traceback in stderr)",
            _ => "unexpected exit code",
        }
    }
}

/// `kratos-3d` as a [`Solver`].
#[derive(Clone, Debug, Default)]
pub struct KratosSolid {
    /// How it is run (toolchain, pole size, time limit, a replacement driver text).
    pub options: Options,
    /// The case's Kratos settings.
    pub settings: Settings,
}

/// A finished run, read back.
struct Run {
    steps: Vec<KratosStep>,
    surfaces: Vec<Surface3>,
    triangles: Vec<[usize; 3]>,
    nodes: usize,
    elements: usize,
    slave_faces: usize,
    /// Wall seconds of gmsh, Kratos and the reading back.
    wall_s: [f64; 3],
}

impl KratosSolid {
    /// The pole size and plan of `scene` (fem-3d's candidate zone).
    fn plan(&self, scene: &Scene) -> (f64, Plan) {
        let c_max = scene.max_contact_radius();
        let h = self.options.resolution.unwrap_or(DEFAULT_POLE_FRACTION * c_max);
        let mut plan = Plan::of(scene, h);
        plan.candidate_radius = Zones::new(c_max, h).candidate_radius;
        (h, plan)
    }

    /// The first-order body of gmsh's `body.msh` in `dir`, of the case's element.
    fn read_body(&self, dir: &Path) -> Result<LinearBody, SolveError> {
        let failed = |e: String| SolveError::Failed(format!("reading gmsh's mesh: {e}"));
        let path = dir.join("body.msh");
        match self.settings.element {
            Element::Tet4 => {
                let mesh = solid::read(&path).map_err(|e| failed(e.to_string()))?;
                LinearBody::of(&mesh).map_err(failed)
            }
            Element::Hex8 => bricks8::read(&path).map_err(failed),
        }
    }

    fn project(&self, scene: &Scene, plan: &Plan) -> ProjectSpec {
        ProjectSpec {
            young: scene.pair.body1.material.young,
            poisson: scene.pair.body1.material.poisson,
            friction: scene.friction,
            settings: self.settings,
            tangential: plan.tangential,
            steps: plan.steps.len(),
        }
    }

    /// Meshes the body into `dir` and writes every file of the deck there (the driver under its
    /// file name, `path.txt`): the body and gmsh's wall time.
    fn prepare(
        &self,
        scene: &Scene,
        plan: &Plan,
        h: f64,
        dir: &Path,
    ) -> Result<(LinearBody, f64), SolveError> {
        let zones = Zones::new(scene.max_contact_radius(), h);
        let r = scene.pair.body1.radius;
        let geometry = solid_geo::geometry(r, scene.domain.height(r), h, zones);
        let toolchain = &self.options.toolchain;
        let files = match self.settings.element {
            Element::Tet4 => solid_geo::mesh(&geometry, dir, "body", toolchain)?,
            Element::Hex8 => bricks8::mesh(&geometry, dir, "body", toolchain)?,
        };
        let body = self.read_body(dir)?;
        let project = self.project(scene, plan);
        let slave_faces = body.candidate_faces(plan.candidate_radius);
        if slave_faces.is_empty() {
            return Err(SolveError::Failed(
                "no contact face lies within the candidate radius".into(),
            ));
        }
        let model = modelled(&body, project.frictional());
        let mdpa = MdpaSpec {
            body: &model,
            slave_faces: &model.candidate_faces(plan.candidate_radius),
            reported: &LinearBody::nodes_of(&slave_faces),
        };
        let json = |value: serde_json::Value| serde_json::to_string_pretty(&value).unwrap_or_default();
        for (name, text) in [
            (format!("{STEM}.mdpa"), mdpa.text()),
            (PROJECT.to_owned(), json(project.project())),
            (MATERIALS.to_owned(), json(project.materials())),
        ] {
            std::fs::write(dir.join(&name), text)
                .map_err(|e| SolveError::Failed(format!("writing {name}: {e}")))?;
        }
        let driver = self.options.deck_text.as_deref().unwrap_or(TEMPLATE);
        deck::write_deck(&KratosSolidDeck, dir, driver, &plan.steps)?;
        Ok((body, files.wall_s))
    }

    /// Meshes, writes, runs and reads back, in `dir`.
    fn run_in(&self, scene: &Scene, plan: &Plan, h: f64, dir: &RunDir) -> Result<Run, SolveError> {
        let (body, mesh_s) = self.prepare(scene, plan, h, dir.path())?;
        let timeout = self.options.timeout.unwrap_or(BUDGET.limit(plan.steps.len()));
        let run = deck::run_written(&KratosSolidDeck, &self.options.toolchain, dir.path(), timeout)?;
        self.read(plan, &body, dir.path(), [mesh_s, run.wall_s])
    }

    /// Reads the run's output in `dir` back.
    fn read(
        &self,
        plan: &Plan,
        body: &LinearBody,
        dir: &Path,
        [mesh_s, solve_s]: [f64; 2],
    ) -> Result<Run, SolveError> {
        let start = Instant::now();
        let indices: Vec<usize> = plan.steps.iter().map(|s| s.step).collect();
        let failed = SolveError::Failed;
        let steps = results::parse_steps(
            &read_output(dir, "steps.csv", MAX_DECK_TABLE_BYTES).map_err(failed)?,
            &indices,
        )
        .map_err(failed)?;
        let faces = body.candidate_faces(plan.candidate_radius);
        let (slaves, triangles) = slave_nodes(body, &faces);
        let text = read_output(dir, "surface.csv", MAX_DECK_TABLE_BYTES).map_err(failed)?;
        let surfaces = results::parse_surface(&text, &steps, &slaves)
            .map_err(failed)?
            .into_iter()
            .zip(&indices)
            .map(|(nodes, &step)| Surface3 { step, nodes })
            .collect();
        let model = modelled(body, self.settings.formulation.frictional(plan.tangential));
        Ok(Run {
            steps,
            surfaces,
            triangles,
            nodes: model.nodes.len(),
            elements: model.elements.len(),
            slave_faces: model.candidate_faces(plan.candidate_radius).len(),
            wall_s: [mesh_s, solve_s, start.elapsed().as_secs_f64()],
        })
    }

    /// Writes everything the deck needs to run by hand into the existing folder `dir`.
    pub fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError> {
        applicable(scene)?;
        let dir = &dir
            .canonicalize()
            .map_err(|e| SolveError::Failed(format!("{}: {e}", dir.display())))?;
        let (h, plan) = self.plan(scene);
        self.prepare(scene, &plan, h, dir).map(drop)
    }

    /// The history of a run directory that [`KratosSolid::write_run`] wrote and Kratos finished
    /// elsewhere.
    pub fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError> {
        applicable(scene)?;
        let (h, plan) = self.plan(scene);
        readback::check_path_file(dir, &plan.steps, &scene.name)?;
        let body = self.read_body(dir)?;
        let run = self.read(&plan, &body, dir, [0.0; 2])?;
        Ok(self.history(scene, split::RUN_ELSEWHERE, &plan, h, &run))
    }

    /// One row per path step (none at a step Kratos did not converge, nor after it under
    /// friction), the fields at the converged positions, the metadata.
    fn history(&self, scene: &Scene, version: &str, plan: &Plan, h: f64, run: &Run) -> History {
        let forces: Vec<[f64; 2]> = run.steps.iter().map(|s| s.forces).collect();
        // Frictionless contact on a tangential path answers the normal problem only: no Q, no stick.
        let frictional = self.settings.formulation.frictional(plan.tangential);
        let tangential = plan.tangential && frictional;
        let (mut steps, mut fields) =
            surface3d::step_results(scene, tangential, &forces, &run.surfaces, &run.triangles);
        let mut lost = false;
        for (row, step) in steps.iter_mut().zip(&run.steps) {
            lost = !step.converged || (lost && frictional);
            if lost {
                row.normal_force = None;
                row.tangential_force = None;
                row.contact_radius = None;
                row.peak_pressure = None;
                row.stick_radius = None;
                fields.retain(|f| Some(f.position) != row.position);
            }
        }
        History {
            metadata: self.metadata(scene, version, plan, h, run),
            steps,
            fields,
        }
    }

    fn metadata(&self, scene: &Scene, version: &str, plan: &Plan, h: f64, run: &Run) -> Metadata {
        let frictional = self.settings.formulation.frictional(plan.tangential);
        let friction = match frictional {
            true => format!("Coulomb friction μ = {}", scene.friction),
            false => "frictionless".to_owned(),
        };
        let mut metadata = Metadata {
            version: format!("Kratos {version}"),
            model: format!(
                "3D, {} ({}; the second mirrored through the contact plane); {} {}; mortar contact \
                 {} ({}, factor {:e} E/h), {friction}; P and Q from the far face's reaction{}, p \
                 and q Kratos' augmented nodal pressures at the slave nodes (y ≥ 0)",
                match frictional {
                    true =>
                        "both spheres whole (the half mesh and its mirror image through y = 0: \
                             a mortar half model under friction needs the multiplier held on the plane)",
                    false => "the halves (y ≥ 0) of both spheres",
                },
                scene.domain.describe(),
                self.settings.element.keyword(),
                self.settings.element.mesh(),
                self.settings.formulation.name(),
                self.settings.formulation.mortar_type(plan.tangential),
                self.settings.stiffness_factor(),
                if frictional { "" } else { " × 2" },
            ),
            resolution: format!(
                "pole element {:.3} µm (c_max/{:.1}), {} {} and {} nodes a sphere, {} slave faces; \
                 every path step computed (Newton, at most {MAX_ITERATIONS} iterations)",
                h * 1e6,
                scene.max_contact_radius() / h,
                run.elements,
                self.settings.element.plural(),
                run.nodes,
                run.slave_faces
            ),
            warnings: vec![FINITE_BODY.to_owned()],
            ..Metadata::default()
        };
        let not_converged: Vec<usize> = run
            .steps
            .iter()
            .filter(|s| !s.converged)
            .map(|s| s.step)
            .collect();
        if !not_converged.is_empty() {
            metadata.warnings.push(format!(
                "Kratos did not converge at steps {not_converged:?} (within {MAX_ITERATIONS} Newton \
                 iterations): no values there{}",
                if frictional {
                    " nor after the first (its state carries over)"
                } else {
                    ""
                }
            ));
        }
        let extra = &mut metadata.extra;
        extra.insert("kratos".into(), self.settings.describe(plan.tangential));
        extra.insert(
            "convergence_by_step".into(),
            json!(run
                .steps
                .iter()
                .map(|s| json!({"step": s.step, "converged": s.converged, "iterations": s.iterations, "residual": s.residual}))
                .collect::<Vec<_>>()),
        );
        extra.insert("steps_not_converged".into(), json!(not_converged));
        // What Kratos left at every step, converged or not: evidence, never values.
        extra.insert(
            "forces_as_left_by_step".into(),
            json!(run.steps.iter().map(|s| s.forces).collect::<Vec<_>>()),
        );
        extra.insert(
            "forces_other_far_face_by_step".into(),
            json!(run.steps.iter().map(|s| s.forces_other).collect::<Vec<_>>()),
        );
        extra.insert("grip".into(), json!(plan.grip.name()));
        extra.insert("candidate_radius_m".into(), json!(plan.candidate_radius));
        let [meshing, solving, reading] = run.wall_s;
        extra.insert("meshing_s".into(), json!(meshing));
        extra.insert("solving_s".into(), json!(solving));
        extra.insert("reading_back_s".into(), json!(reading));
        extra.insert(
            "solving_s_per_step".into(),
            json!(solving / plan.steps.len().max(1) as f64),
        );
        extra.insert(
            "kratos_step_s".into(),
            json!(run.steps.iter().map(|s| s.wall_s).collect::<Vec<_>>()),
        );
        metadata
    }
}

/// The body Kratos is given for the `half` meshed: the half itself (its symmetry plane held at
/// u_y = 0 on both spheres) for frictionless contact; the whole body under friction, where the
/// half's plane would need the tangential multiplier's y component held too ([`super::linear`];
/// measured: Q/P at gross sliding 0.15–0.18 on the half with the master's plane nodes free, for
/// μ = 0.2, and 0.1997 on the whole; docs/external-decks.md, "Kratos 3D").
fn modelled(half: &LinearBody, frictional: bool) -> LinearBody {
    match frictional {
        true => half.whole(),
        false => half.clone(),
    }
}

/// Why the model does not apply to `scene`, if it does not: two identical finite spheres (one
/// mesh mirrored), held rigidly on their far faces (the driver holds all three components).
fn applicable(scene: &Scene) -> Result<(), SolveError> {
    if !scene.pair.is_symmetric() || !scene.pair.body1.radius.is_finite() {
        return Err(SolveError::NotApplicable(
            "kratos-3d models two identical spheres through their plane of contact; different \
             spheres or a sphere on a flat are not modelled"
                .into(),
        ));
    }
    if scene.domain.grip != Grip::Rigid {
        return Err(SolveError::NotApplicable(
            "kratos-3d holds the far faces rigidly (all three components); the axial grip is not modelled"
                .into(),
        ));
    }
    Ok(())
}

impl Solver for KratosSolid {
    fn name(&self) -> &str {
        NAME
    }

    fn kind(&self) -> Kind {
        Kind::FiniteElement
    }

    fn description(&self) -> &str {
        KratosSolidDeck::KIND.description
    }

    /// A pole element size: `c/N` or a length, within [`SOLID_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let mut solver = self.clone();
        solver.options.resolution = Some(resolution::pole_size(NAME, scene, value, SOLID_POLE)?);
        Ok(Box::new(solver))
    }

    fn with_kratos(&self, settings: &Settings) -> Option<Box<dyn Solver>> {
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
            .require(Tool::KratosContact)
            .map_err(SolveError::Unavailable)?;
        let (h, plan) = self.plan(scene);
        let run = deck::in_run_dir("spherecontact-kratos-3d-", |dir| {
            self.run_in(scene, &plan, h, dir)
        })?;
        Ok(self.history(scene, &version, &plan, h, &run))
    }
}

impl SplitDeck for KratosSolid {
    fn settings(&self, scene: &Scene) -> serde_json::Value {
        let (h, plan) = self.plan(scene);
        json!({ "pole_element_m": h, "kratos": self.settings.describe(plan.tangential) })
    }

    /// `python kratos_3d.py` on one thread, as the solver's own run starts it.
    fn command(&self) -> DeckCommand {
        split::deck_command(&KratosSolidDeck, &self.options.toolchain)
    }

    fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError> {
        KratosSolid::write_run(self, scene, dir)
    }

    fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError> {
        KratosSolid::read_run(self, scene, dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requirement: without Kratos' contact wheels the solver is not available (never a pass),
    /// and different spheres are not modelled.
    #[test]
    fn a_missing_kratos_is_unavailable_and_different_spheres_not_applicable() {
        let scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        let mut solver = KratosSolid::default();
        solver.options.toolchain.kratos_python = "/nonexistent/python".into();
        let e = solver.solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::Unavailable(_)), "{e}");
        assert!(e.to_string().contains("Kratos contact"), "{e}");
        let mut other = scene.clone();
        other.pair.body2.radius = 0.05;
        let e = KratosSolid::default().solve(&other).unwrap_err();
        assert!(matches!(e, SolveError::NotApplicable(_)), "{e}");
    }

    /// Requirement: the driver is a fixed file with no placeholder (nothing of the case is pasted
    /// into it) and runs on one thread with the project's Kratos Python.
    #[test]
    fn the_driver_is_fixed_and_runs_on_one_thread() {
        assert!(!TEMPLATE.contains('@'), "a placeholder in the driver");
        let job = KratosSolidDeck.job(
            &Toolchain::default(),
            Path::new("kratos_3d.py"),
            Duration::from_secs(1),
        );
        assert_eq!(
            job.program,
            Path::new(spherecontact_system::toolchain::KRATOS_PYTHON)
        );
        assert!(job.env.contains(&("OMP_NUM_THREADS".into(), "1".into())));
    }
}
