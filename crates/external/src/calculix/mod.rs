//! The CalculiX deck `ccx-axisym`: normal contact (Fourier n = 0) of one sphere against its
//! symmetry plane on the shared gmsh meridian mesh of the case's `[domain]` ([`super::geo`]),
//! CAX6 on its quadratic triangles, the plane a held strip, penalty contact (face-to-face or
//! node-to-face, [`settings`]), one `*STEP` per path position. P from the reaction on the far
//! face, c, p0 and p(r) from the contact pressure at the slave nodes, all read from CalculiX's own
//! output ([`results`]: `.dat` and `.frd`). The `.inp` ([`inp`], template
//! `templates/calculix_axisym.inp`) is self-contained: a CalculiX user runs it by hand.
//!
//! Model and findings: docs/external-decks.md, "CalculiX".

pub mod body;
pub mod errors;
pub mod hex20;
pub mod hex_mesh;
pub mod inp;
pub mod nodal_forces;
pub mod results;
pub mod solid;
pub mod solid_inp;
pub mod solid_read;

pub use solid::CcxSolid;

use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::json;

use crate::axisym::{self, Options};
use crate::deck::{self, Deck, DeckKind, RunDir, TimeBudget};
use crate::plan::Plan;
use crate::readback::read_output;
use crate::record::FINITE_BODY;
use crate::split::{self, RUN_ELSEWHERE};
use crate::surface::{Node, Surface};
use errors::{logged_error, reported_error};
use inp::{DeckSpec, PositionStep};
pub use spherecontact_model::calculix_settings::Settings;
use spherecontact_model::history::{History, Metadata, StepResult};
use spherecontact_model::limits::{MAX_CCX_RESULTS_BYTES, MERIDIAN_POLE};
use spherecontact_model::resolution::{self, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::split::{DeckCommand, SplitDeck};
use spherecontact_model::solver::Kind;
use spherecontact_model::solver::{SolveError, Solver};
use spherecontact_solvers::fem::mesh::geo::{self, QuadraticMesh};
use spherecontact_system::process::Job;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The solver name.
pub const NAME: &str = "ccx-axisym";

/// CalculiX expands an axisymmetric model into a wedge of 2 degrees, and the forces it prints
/// are those on the wedge: the whole ring carries 360/2 = 180 times as much (checked against
/// Hertz and mdr-domain in `cases/ccx-axisym.toml`).
pub const SEGMENT_FACTOR: f64 = 180.0;

/// Pole element sizes of the ladder (fractions of the largest contact radius): c_max/40 takes
/// about a minute a position with face-to-face contact on a shared machine, so the ladder stops
/// there.
pub const LADDER: [f64; 3] = [1.0 / 10.0, 1.0 / 20.0, 1.0 / 40.0];

/// Time allowed: start-up, set-up (reading the deck, the expansion), and per path position
/// (measured ≈ 13 s at c_max/20 and ≈ 40 s at c_max/40 with face-to-face contact; ≈ 30 Newton
/// iterations while the contact set settles).
const BUDGET: TimeBudget = TimeBudget {
    start: Duration::from_secs(30),
    setup: Duration::from_secs(60),
    per_step: Duration::from_secs(600),
};

/// The deck: `ccx -i job` in the run directory.
#[derive(Clone, Copy, Debug)]
pub struct CcxAxisymDeck;

impl Deck for CcxAxisymDeck {
    const KIND: DeckKind = DeckKind {
        name: NAME,
        description: "CalculiX (ccx) axisymmetric FEM, CAX6 on the shared gmsh mesh, one sphere against a held strip, penalty contact (face-to-face or node-to-face), normal only",
        tool: Tool::Ccx,
        template: inp::TEMPLATE,
        file_name: "job.inp",
    };

    type Mesh = QuadraticMesh;

    fn mesh_file<'a>(&self, mesh: &'a QuadraticMesh) -> &'a Path {
        &mesh.msh41
    }

    /// `ccx -i job` (the input's name without `.inp`), one OpenMP thread (docs: reproducible).
    fn job(&self, toolchain: &Toolchain, deck: &Path, timeout: Duration) -> Job {
        let stem = deck
            .file_stem()
            .map_or_else(|| "job".into(), |s| s.to_string_lossy().into_owned());
        Job {
            program: toolchain.ccx.clone(),
            args: vec!["-i".into(), stem],
            env: deck::single_threaded(),
            timeout,
        }
    }

    /// ccx 2.20's codes, measured: 201 after a fatal `*ERROR` reading the input deck; 0 also
    /// when the input file cannot be opened (so the log is checked for `*ERROR` as well).
    fn exit_code_meaning(&self, code: i32) -> &'static str {
        match code {
            201 => "a fatal error reading the input deck (*ERROR lines in stdout)",
            _ => "unexpected exit code",
        }
    }
}

/// `ccx-axisym` as a [`Solver`].
#[derive(Clone, Debug, Default)]
pub struct CcxAxisym {
    /// How it is run (toolchain, pole size, time limit, a replacement deck text).
    pub options: Options,
    /// The case's CalculiX settings.
    pub settings: Settings,
}

/// What one run left, read back: per position P [N], the surface, and the checks' side facts.
struct Run {
    positions: Vec<PositionStep>,
    force: Vec<f64>,
    force_plane: Vec<f64>,
    force_contact_print: Vec<Option<f64>>,
    surfaces: Vec<Surface>,
    triangles: usize,
    stiffness: f64,
    wall_s: [f64; 3],
}

/// The meridian mesh a deck is written on, and the path positions it computes.
struct Meshed {
    meridian: spherecontact_solvers::fem::mesh::meridian::Mesh,
    positions: Vec<PositionStep>,
    /// gmsh's wall time [s] (0 for a mesh read from a folder).
    wall_s: f64,
}

impl Meshed {
    /// The mesh of `mesh` (gmsh's files) and the positions of `plan`.
    fn read(mesh: &QuadraticMesh, plan: &Plan) -> Result<Self, SolveError> {
        let meridian = spherecontact_solvers::fem::mesh::msh::read(&mesh.msh41)
            .map_err(|e| SolveError::Failed(format!("reading gmsh's mesh: {e}")))?;
        let positions = plan
            .steps
            .iter()
            .filter_map(|s| {
                s.position.map(|position| PositionStep {
                    position,
                    step: s.step,
                    d: s.d,
                })
            })
            .collect();
        Ok(Self {
            meridian,
            positions,
            wall_s: mesh.wall_s,
        })
    }
}

impl SplitDeck for CcxAxisym {
    fn settings(&self, scene: &Scene) -> serde_json::Value {
        json!({ "pole_element_m": self.pole_size(scene), "calculix": self.settings.describe() })
    }

    fn command(&self) -> DeckCommand {
        split::deck_command(&CcxAxisymDeck, &self.options.toolchain)
    }

    fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError> {
        axisym::applicable(scene)?;
        let h = self.pole_size(scene);
        self.write_in(scene, h, &Plan::of(scene, h), dir).map(drop)
    }

    fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError> {
        axisym::applicable(scene)?;
        let h = self.pole_size(scene);
        let plan = Plan::of(scene, h);
        logged_error(dir)?;
        let meshed = Meshed::read(&QuadraticMesh::in_folder(dir)?, &plan)?;
        let run = self.read_in(scene, h, &plan, &meshed, dir)?;
        Ok(self.history(scene, RUN_ELSEWHERE, &plan, h, &run))
    }
}

impl Solver for CcxAxisym {
    fn name(&self) -> &str {
        NAME
    }

    fn kind(&self) -> Kind {
        Kind::FiniteElement
    }

    fn description(&self) -> &str {
        CcxAxisymDeck::KIND.description
    }

    /// A pole element size: `c/N` or a length, within [`MERIDIAN_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let mut solver = self.clone();
        solver.options.resolution = Some(resolution::pole_size(NAME, scene, value, MERIDIAN_POLE)?);
        Ok(Box::new(solver))
    }

    fn resolution_ladder(&self, scene: &Scene) -> Vec<Box<dyn Solver>> {
        LADDER
            .iter()
            .map(|fraction| {
                let mut solver = self.clone();
                solver.options.resolution = Some(fraction * scene.max_contact_radius());
                Box::new(solver) as Box<dyn Solver>
            })
            .collect()
    }

    fn split_deck(&self) -> Option<&dyn SplitDeck> {
        Some(self)
    }

    fn with_calculix(&self, settings: &Settings) -> Option<Box<dyn Solver>> {
        Some(Box::new(Self {
            settings: *settings,
            ..self.clone()
        }))
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        axisym::applicable(scene)?;
        if self.settings.formulation.mortar() {
            return Err(SolveError::NotApplicable(format!(
                "CalculiX 2.20's {} contact refuses the axisymmetric model: the slave nodes carry the \
                 MPCs of its expansion into a 2° wedge (measured: `*ERROR in catsmpcslavno: slavenodes \
                 belonging to unallowed MPCs`; its manual advises mortar for genuine 3D elements only)",
                self.settings.formulation.name()
            )));
        }
        let toolchain = &self.options.toolchain;
        let version = toolchain.require(Tool::Ccx).map_err(SolveError::Unavailable)?;
        let resolution = self.pole_size(scene);
        let plan = Plan::of(scene, resolution);
        let run = deck::in_run_dir("spherecontact-ccx-axisym-", |dir| {
            self.run_in(scene, resolution, &plan, dir)
        })?;
        Ok(self.history(scene, &version, &plan, resolution, &run))
    }
}

impl CcxAxisym {
    /// The pole element size [m]: the option's, or [`geo::default_resolution`].
    fn pole_size(&self, scene: &Scene) -> f64 {
        self.options
            .resolution
            .unwrap_or_else(|| geo::default_resolution(scene))
    }

    /// Writes, runs the deck and reads back, in `dir`: the one path of the in-process run and of
    /// a deck written and read apart ([`SplitDeck`]).
    fn run_in(&self, scene: &Scene, h: f64, plan: &Plan, dir: &RunDir) -> Result<Run, SolveError> {
        let meshed = self.write_in(scene, h, plan, dir.path())?;
        let timeout = self
            .options
            .timeout
            .unwrap_or(BUDGET.limit(meshed.positions.len()));
        let run = deck::run_written(&CcxAxisymDeck, &self.options.toolchain, dir.path(), timeout)?;
        reported_error(&run.stdout)?;
        let mut read = self.read_in(scene, h, plan, &meshed, dir.path())?;
        read.wall_s[..2].copy_from_slice(&[meshed.wall_s, run.wall_s]);
        Ok(read)
    }

    /// Meshes the scene into `dir` and writes the deck and its list of steps there.
    fn write_in(&self, scene: &Scene, h: f64, plan: &Plan, dir: &Path) -> Result<Meshed, SolveError> {
        let mesh = geo::mesh_quadratic(scene, h, dir, &self.options.toolchain)?;
        let meshed = Meshed::read(&mesh, plan)?;
        let text = match &self.options.deck_text {
            Some(text) => text.clone(),
            None => self
                .spec(scene, h, plan, &meshed)
                .text()
                .map_err(SolveError::Failed)?,
        };
        deck::write_deck(&CcxAxisymDeck, dir, &text, &plan.steps)?;
        Ok(meshed)
    }

    /// Reads back the run the deck finished in `dir` on `meshed` (its reading time; meshing and
    /// solving left at zero); writes nothing into `dir`. ccx exits with code 0 after some
    /// errors: its output was searched for `*ERROR` before ([`reported_error`], [`logged_error`]).
    fn read_in(
        &self,
        scene: &Scene,
        h: f64,
        plan: &Plan,
        meshed: &Meshed,
        dir: &Path,
    ) -> Result<Run, SolveError> {
        let start = Instant::now();
        let mut read = read_back(dir, &self.spec(scene, h, plan, meshed)).map_err(SolveError::Failed)?;
        read.wall_s[2] = start.elapsed().as_secs_f64();
        Ok(read)
    }

    /// The deck of `scene` at pole size `h` on the mesh `meshed`.
    fn spec<'a>(&self, scene: &'a Scene, h: f64, plan: &Plan, meshed: &'a Meshed) -> DeckSpec<'a> {
        DeckSpec {
            scene: &scene.name,
            domain: scene.domain.describe(),
            mesh: &meshed.meridian,
            young: scene.pair.body1.material.young,
            poisson: scene.pair.body1.material.poisson,
            h,
            grip: plan.grip,
            candidate_radius: plan.candidate_radius,
            settings: self.settings,
            positions: &meshed.positions,
        }
    }

    /// One row per path step (values at the positions), the fields, the metadata.
    fn history(&self, scene: &Scene, version: &str, plan: &Plan, h: f64, run: &Run) -> History {
        let mut fields = Vec::new();
        let mut by_position = run.positions.iter().zip(&run.force).zip(&run.surfaces);
        let mut steps = Vec::new();
        for step in scene.steps() {
            let mut row = StepResult::at(&step);
            if let Some(position) = step.position {
                if let Some(((_, &force), surface)) = by_position.next() {
                    let measures = surface.measures();
                    row.normal_force = Some(force);
                    row.contact_radius = measures.contact_radius;
                    row.peak_pressure = measures.peak_pressure;
                    if scene.records_fields_at(position) {
                        fields.push(surface.field(position, measures.pressure, false));
                    }
                }
            }
            steps.push(row);
        }
        History {
            metadata: self.metadata(scene, version, plan, h, run),
            steps,
            fields,
        }
    }

    fn metadata(&self, scene: &Scene, version: &str, plan: &Plan, h: f64, run: &Run) -> Metadata {
        let mut warnings = vec![FINITE_BODY.to_owned()];
        if plan.tangential {
            warnings.push(
                "the path's tangential motion is not modelled: ccx-axisym solves the normal contact \
                 (exact for identical spheres, whose normal and tangential problems do not couple)"
                    .into(),
            );
        }
        if run.force_contact_print.iter().any(Option::is_none) && self.settings.formulation.face_to_face() {
            warnings.push("*CONTACT PRINT CF printed no total at some positions".into());
        }
        let mut metadata = Metadata {
            version: format!("CalculiX {version}"),
            model: format!(
                "axisymmetric ({}, expanded by CalculiX into a 2° wedge), one sphere ({}) against a \
                 held strip on its symmetry plane, exact for identical spheres; normal contact, {} \
                 penalty K = {:e} E/h; P from the far face's reaction × {SEGMENT_FACTOR}",
                spherecontact_model::calculix_settings::AXISYMMETRIC_ELEMENT,
                scene.domain.describe(),
                self.settings.formulation.name(),
                self.settings.penalty
            ),
            resolution: format!(
                "pole element {:.3} µm (c_max/{:.0}), {} triangles; the path positions computed",
                h * 1e6,
                scene.max_contact_radius() / h,
                run.triangles
            ),
            warnings,
            ..Metadata::default()
        };
        let per_position = |values: Vec<serde_json::Value>| {
            json!(run
                .positions
                .iter()
                .zip(values)
                .map(|(p, v)| json!([p.position, v]))
                .collect::<Vec<_>>())
        };
        let contact_sum: Vec<_> = run.surfaces.iter().map(|s| json!(nodal_force(s))).collect();
        let extra = &mut metadata.extra;
        extra.insert("calculix".into(), self.settings.describe());
        extra.insert(
            "element_axisymmetric".into(),
            json!(spherecontact_model::calculix_settings::AXISYMMETRIC_ELEMENT),
        );
        extra.insert("penalty_stiffness_mpa_per_mm".into(), json!(run.stiffness));
        extra.insert("grip".into(), json!(plan.grip.name()));
        extra.insert(
            "computed_steps".into(),
            json!("the path positions, one *STEP each (frictionless elastic contact has no history)"),
        );
        extra.insert("candidate_radius_m".into(), json!(plan.candidate_radius));
        extra.insert("reaction_segment_factor".into(), json!(SEGMENT_FACTOR));
        extra.insert(
            "normal_force_plane_by_position".into(),
            per_position(run.force_plane.iter().map(|f| json!(f)).collect()),
        );
        extra.insert(
            "normal_force_contact_print_by_position".into(),
            per_position(run.force_contact_print.iter().map(|f| json!(f)).collect()),
        );
        extra.insert(
            "normal_force_nodal_pressures_by_position".into(),
            per_position(contact_sum),
        );
        let [meshing, solving, reading] = run.wall_s;
        extra.insert("meshing_s".into(), json!(meshing));
        extra.insert("solving_s".into(), json!(solving));
        extra.insert("reading_back_s".into(), json!(reading));
        metadata
    }
}

/// 2π Σ ω_i p_i over the slave nodes [N]: the force the nodal pressures carry by the consistent
/// ring weights (metadata: where it departs from the reaction, the pressures are not the
/// contact's).
fn nodal_force(surface: &Surface) -> f64 {
    std::f64::consts::TAU * surface.nodes.iter().map(|n| n.weight * n.pressure).sum::<f64>()
}

/// Largest disagreement between the reactions of the far face and of the plane, relative to the
/// larger and 1 N: the body's equilibrium, printed by CalculiX to 7 digits.
const EQUILIBRIUM: f64 = 1e-5;

/// Reads `job.dat` and `job.frd` in `dir` for the deck of `spec`.
fn read_back(dir: &Path, spec: &DeckSpec) -> Result<Run, String> {
    let n = spec.positions.len();
    let dat = read_output(dir, "job.dat", MAX_CCX_RESULTS_BYTES)?;
    let far = results::last_per_step(&results::totals(&dat, "NFAR")?, |t| t.time, n, "job.dat NFAR")?;
    let plane = results::last_per_step(&results::totals(&dat, "NPLANE")?, |t| t.time, n, "job.dat NPLANE")?;
    let printed = results::contact_totals(&dat);
    let frd = results::parse_frd(&read_output(dir, "job.frd", MAX_CCX_RESULTS_BYTES)?)?;
    let (points, weights) = slave_nodes(spec);
    // The .frd's 6 digits put a node within 1e-5 mm of its point; points are h/2 apart or more.
    let tolerance = 0.01 * spec.h * 1e3;
    let mut run = Run {
        positions: spec.positions.to_vec(),
        force: Vec::new(),
        force_plane: Vec::new(),
        force_contact_print: Vec::new(),
        surfaces: Vec::new(),
        triangles: spec.mesh.triangles.len(),
        stiffness: spec.stiffness_mpa_per_mm(),
        wall_s: [0.0; 3],
    };
    for (k, (position, (far, plane))) in spec.positions.iter().zip(far.iter().zip(&plane)).enumerate() {
        // `+ 0.0` turns the −0 of an untouched plane into 0.
        let (p_far, p_plane) = (
            -far.force[1] * SEGMENT_FACTOR + 0.0,
            plane.force[1] * SEGMENT_FACTOR + 0.0,
        );
        let departure = (p_far - p_plane).abs() / p_far.abs().max(p_plane.abs()).max(1.0);
        if departure > EQUILIBRIUM {
            return Err(format!(
                "job.dat step {}: the far face's and the plane's reactions differ by {departure:.1e} \
                 of the larger and 1 N: not in equilibrium (allowed: {EQUILIBRIUM:e})",
                k + 1
            ));
        }
        let time = (k + 1) as f64;
        let block = frd.contact_at_step(k);
        let values = match block {
            Some(block) => results::on_meridian(block, &frd.nodes, &points, tolerance)?,
            None if p_far.abs() <= EQUILIBRIUM => vec![(0.0, 0.0); points.len()],
            None => {
                return Err(format!(
                    "job.frd: no contact output at step {} although the far face carries a load \
                     (allowed: none only below {EQUILIBRIUM} N)",
                    k + 1
                ))
            }
        };
        let surface = Surface {
            step: position.step,
            nodes: points
                .iter()
                .zip(&weights)
                .zip(values)
                .map(|((point, &weight), (open, pressure))| Node {
                    r: point[0] * 1e-3,
                    weight,
                    gap: open * 1e-3,
                    pressure: pressure.max(0.0) * 1e6,
                    traction_x: 0.0,
                    stick: false,
                    slip: 0.0,
                })
                .collect(),
        };
        if surface.edge_loaded() {
            return Err(format!(
                "step {}: the contact reached the outermost slave node: the candidate zone is too small",
                position.step
            ));
        }
        run.force.push(p_far);
        run.force_plane.push(p_plane);
        run.force_contact_print.push(
            printed
                .iter()
                .rev()
                .find(|t| (t.time - time).abs() < 1e-6)
                .map(|t| t.force[1] * SEGMENT_FACTOR),
        );
        run.surfaces.push(surface);
    }
    Ok(run)
}

/// The slave surface's nodes, from the pole: their meridian points (r, z) [mm] and ring weights
/// ω = ∫ N r ds [m², per radian; 0 on the axis].
fn slave_nodes(spec: &DeckSpec) -> (Vec<[f64; 2]>, Vec<f64>) {
    let mut order: Vec<usize> = Vec::new();
    let mut weight: std::collections::HashMap<usize, f64> = Default::default();
    for edge in spec.candidate_edges() {
        let [a, m, b] = edge.map(|n| spec.mesh.nodes[n]);
        let w = spherecontact_solvers::fem::element::tri6::edge_weights(a, m, b);
        for (k, &node) in edge.iter().enumerate() {
            if !weight.contains_key(&node) {
                order.push(node);
            }
            *weight.entry(node).or_default() += w[k] / std::f64::consts::TAU;
        }
    }
    order.sort_by(|a, b| spec.mesh.nodes[*a][0].total_cmp(&spec.mesh.nodes[*b][0]));
    let points = order
        .iter()
        .map(|&n| spec.mesh.nodes[n].map(|x| x * 1e3))
        .collect();
    let weights = order
        .iter()
        .map(|n| {
            if spec.mesh.nodes[*n][0] == 0.0 {
                0.0
            } else {
                weight[n]
            }
        })
        .collect();
    (points, weights)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_ccx_is_unavailable_not_a_failure() {
        let scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        let mut solver = CcxAxisym::default();
        solver.options.toolchain.ccx = "/nonexistent/ccx".into();
        let e = solver.solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::Unavailable(_)), "{e}");
        assert!(e.to_string().contains("calculix-ccx"), "{e}");
    }

    #[test]
    fn the_job_runs_ccx_on_the_deck_stem_with_one_thread() {
        let job = CcxAxisymDeck.job(
            &Toolchain::default(),
            Path::new("/tmp/x/job.inp"),
            Duration::from_secs(5),
        );
        assert_eq!(job.args, ["-i", "job"]);
        assert!(job.env.contains(&("OMP_NUM_THREADS".into(), "1".into())));
    }
}
