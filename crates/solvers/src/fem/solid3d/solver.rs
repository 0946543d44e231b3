//! `fem-3d`: the 3D finite element solver (10-node tetrahedra) of the contact of identical
//! spheres with Coulomb friction and history, on the shared contact engine.
//!
//! One body by the symmetry of the contact plane, its half y ≥ 0 by the symmetry of the plane
//! y = 0 (the plane that contains the paper's shift), the case's `[domain]` (hemisphere or cap,
//! its grip) meshed by gmsh ([`super::meshing`]), factored and condensed once onto the contact
//! candidates ([`super::model`]); the path is walked by the one path walker
//! ([`spherecontact_model::driver`]) over [`super::walk::Walker`], one engine increment a step. P and Q_x are
//! the engine's resultants over the mirrored half (P checked against the far face's reaction);
//! c and p0 come from [`super::measures`].
//!
//! The contact multipliers live at the corners of the quadratic faces, linear on each face
//! ([`Rule::Corners`]), chosen by measurement (`examples/fem3d_transverse.rs`,
//! `examples/fem3d_timing.rs --path`). With multipliers at every node of the faces, linear on
//! their sub-triangles ([`Rule::SubTriangles`], as many multipliers as displacement nodes),
//! p and q oscillated from node to node: at position 5 a sample departed from its neighbours'
//! mean by 0.23 of max p and 1.08 of max|q_y| (the BEM: 0.04 and 0.21), a single stick node
//! gave max|q_y|/max|q_x| = 0.155 against the BEM's 0.049 (and grew as the engine's tolerance
//! tightened: a poorly determined mode), and the engine needed about 450 gradient steps an
//! increment. With the corners (a multiplier space one order below the displacements', a
//! quarter of the points: 286 at the default mesh) no oscillation is left but a one-point spike
//! at the stick edge (pointwise ratio 0.056–0.12 from c_max/6 to /14); on the traction's hat
//! averages, the values the rule determines ([`crate::fit::recovery`]), the ratio converges
//! (0.0498, 0.0504 at c_max/10, /14; the BEM 0.0492), the whole paper path's contact solves take under a second,
//! and Q stays within 0.16 % of the corrected reference's peak (0.12 % with every node). The
//! corner values are not samples of the pressure (they overshoot a concave one by O(h²), +0.3 %
//! in p0 at c_max/10): p0 is fitted to their hat averages ([`super::measures`]).
//!
//! The tangential algorithm: the engine's direct active-set solver cycled without converging on
//! the paper path's first frictional increment with multipliers at every node, so fem-3d asks
//! the engine for its iterative algorithms ([`Method::Iterative`]: Polonsky–Keer for the normal
//! problem, accelerated projected gradients for the tangential one). The products read only the
//! loaded columns and the step is set by a power estimate of the largest eigenvalue
//! ([`spherecontact_contact::dense`]). The tangential tolerance is 1e-5 (the engine's default is 1e-8),
//! measured on the whole paper path with multipliers at every node: the worst
//! |Q − Q_mdr-domain| was 0.119 %, 0.120 %, 0.122 % of the peak at 1e-6, 1e-5, 1e-4; at
//! position 5 the stick semi-axes moved by 4.6 µm from 1e-6 to 1e-5 (a twentieth of an
//! element); with the corners, max|q_y|/max|q_x| moved from 0.0559 to 0.0587 from 1e-5 to 1e-7.

use std::path::PathBuf;
use std::time::Instant;

use serde_json::json;

use super::contact;
use super::meshing::{self, Zones};
use super::model::{Model, Settings};
use super::surface::Rule;
use super::system::Grip;
use super::walk::{Record, Tangential, Walker};
use crate::fem::element::tri6::Lame;
use crate::fem::pole::{self, PoleSized};
use spherecontact_contact::{Method, Settings as ContactSettings};
use spherecontact_model::domain::Grip as DomainGrip;
use spherecontact_model::driver;
use spherecontact_model::history::{History, Metadata, StepResult};
use spherecontact_model::limits::SOLID_POLE;
use spherecontact_model::memory::{self, Budget};
use spherecontact_model::resolution::{PoleLimits, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_model::stick_slope::StickSlope;
use spherecontact_system::toolchain::Toolchain;

/// Default pole element size in units of the path's largest contact radius: c_max/10 keeps P
/// within 0.1 % of its mesh limit and the set-up near 20 s (`examples/fem3d_timing.rs`).
pub const POLE_DIVISIONS: f64 = 10.0;
/// The engine's tangential tolerance (a fraction of the traction scale, [`spherecontact_contact::coulomb`]):
/// see the module doc.
pub const TANGENTIAL_TOLERANCE: f64 = 1e-5;
/// Relative disagreement of the engine's P and the far-face reaction that is reported: the same
/// equilibrium, so anything above round-off means an assembly or solve error.
const BALANCE: f64 = 1e-6;

/// The solver and its resolution.
#[derive(Clone, Debug)]
pub struct FemSolid3d {
    /// Pole element size [m]; `None`: the largest contact radius / [`POLE_DIVISIONS`].
    pub pole_size: Option<f64>,
    /// The engine's algorithm and tolerances (see the module doc).
    pub contact: ContactSettings,
    /// When set, the volume and the contact surface are written there as VTU at every position
    /// that records fields.
    pub vtu_dir: Option<PathBuf>,
    /// Where the contact multipliers live (corners by default: see the module doc).
    pub rule: Rule,
    /// The regularised stick's slope ([`spherecontact_model::stick_slope`]); `None` (the default): exact
    /// Coulomb friction.
    pub stick_slope: Option<StickSlope>,
}

impl Default for FemSolid3d {
    fn default() -> Self {
        Self {
            pole_size: None,
            contact: ContactSettings {
                method: Method::Iterative,
                tangential_tolerance: TANGENTIAL_TOLERANCE,
                ..ContactSettings::default()
            },
            vtu_dir: None,
            rule: Rule::Corners,
            stick_slope: None,
        }
    }
}

impl FemSolid3d {
    /// The solver with pole element size `h` [m].
    pub fn with_pole_size(h: f64) -> Self {
        Self {
            pole_size: Some(h),
            ..Self::default()
        }
    }

    /// Why this solver does not apply to `scene`, if it does not.
    fn applicability(scene: &Scene) -> Result<(), SolveError> {
        let not = |why: &str| Err(SolveError::NotApplicable(why.into()));
        if !scene.pair.body1.radius.is_finite() || !scene.pair.body2.radius.is_finite() {
            return not("a flat body: fem-3d models two spheres (one body by symmetry)");
        }
        if !scene.pair.is_symmetric() {
            return not(
                "dissimilar bodies: fem-3d models identical spheres only (one body by the symmetry of the contact plane; \
                 two different bodies would couple the normal and tangential problems)",
            );
        }
        if scene.domain.grip == DomainGrip::Axial && Tangential::of(scene) == Tangential::Solved {
            return not("an axial grip leaves the far face free in its plane: it cannot be shifted (frictionless scenes only)");
        }
        Ok(())
    }

    /// The pole size for `scene`.
    fn pole_size(&self, scene: &Scene) -> Result<f64, SolveError> {
        match self.pole_size {
            Some(h) if h > 0.0 && h.is_finite() => Ok(h),
            Some(h) => Err(SolveError::Failed(format!("pole size {h} m is not positive"))),
            None => Ok(scene.max_contact_radius() / POLE_DIVISIONS),
        }
    }

    /// The model of `scene` at pole size `h`, with its candidate radius and gmsh's time; refused
    /// before it is factored when its estimated peak memory exceeds the budget
    /// ([`spherecontact_model::memory`]: the estimate grows at least as (c_max/h)³, the element count).
    fn model(&self, scene: &Scene, h: f64) -> Result<(Model, f64, f64), SolveError> {
        let radius = scene.pair.body1.radius;
        let zones = Zones::new(scene.max_contact_radius(), h);
        let geometry = meshing::geometry(radius, scene.domain.height(radius), h, zones);
        geometry.check().map_err(|e| {
            SolveError::NotApplicable(format!(
                "the contact zone (c_max = {:.3e} m, {:.2} R) does not fit the graded mesh of the {}: {e}",
                scene.max_contact_radius(),
                scene.max_contact_radius() / radius,
                scene.domain.describe()
            ))
        })?;
        let (mesh, mesh_s) = meshing::generate(&geometry, &Toolchain::default())?;
        let lame = Lame::of(&scene.pair.body1.material);
        let settings = Settings::fastest(zones.candidate_radius, grip(scene), self.rule);
        let planned = Model::plan(mesh, lame, &settings).map_err(SolveError::Failed)?;
        let budget = Budget::new(self.name(), scene.max_contact_radius(), h, memory::SOLID);
        budget
            .check(&planned.estimate().map_err(SolveError::Failed)?)
            .map_err(|e| SolveError::Failed(e.to_string()))?;
        let model = planned.build().map_err(SolveError::Failed)?;
        Ok((model, zones.candidate_radius, mesh_s))
    }
}

/// The model's grip for the scene's domain.
fn grip(scene: &Scene) -> Grip {
    match scene.domain.grip {
        DomainGrip::Rigid => Grip::Rigid,
        DomainGrip::Axial => Grip::Axial,
    }
}

impl PoleSized for FemSolid3d {
    const LIMITS: PoleLimits = SOLID_POLE;

    fn sized(&self, h: f64) -> Self {
        let pole_size = Some(h);
        FemSolid3d {
            pole_size,
            ..self.clone()
        }
    }

    fn writing_to(&self, dir: &std::path::Path) -> Self {
        let vtu_dir = Some(dir.to_path_buf());
        FemSolid3d {
            vtu_dir,
            ..self.clone()
        }
    }
}

impl Solver for FemSolid3d {
    fn name(&self) -> &'static str {
        "fem-3d"
    }

    fn kind(&self) -> Kind {
        Kind::FiniteElement
    }

    fn description(&self) -> &'static str {
        "3D FEM (10-node tetrahedra, gmsh mesh of the half body), normal contact and Coulomb friction with history by the shared engine on the condensed contact surface"
    }

    fn writing_fields_to(&self, dir: &std::path::Path) -> Option<Box<dyn Solver>> {
        pole::writing_fields_to(self, dir)
    }

    fn with_stick_slope(&self, slope: StickSlope) -> Option<Box<dyn Solver>> {
        Some(Box::new(FemSolid3d {
            stick_slope: Some(slope),
            ..self.clone()
        }))
    }

    /// A pole element size: `c/N` or a length, within [`SOLID_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        pole::at_resolution(self, scene, value)
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        let h = self.pole_size(scene).ok()?;
        Some(spherecontact_model::cost::fem_3d(
            scene.max_contact_radius() / h,
            scene.steps().len(),
        ))
    }

    /// Pole sizes c_max/4 … c_max/14.
    fn resolution_ladder(&self, scene: &Scene) -> Vec<Box<dyn Solver>> {
        pole::ladder(self, scene, &[4.0, 6.0, 10.0, 14.0])
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        Self::applicability(scene)?;
        let metadata = Metadata {
            model: "3D finite elements".into(),
            ..Metadata::default()
        };
        if let Some(history) = driver::never_closed_history(scene, metadata) {
            // Nothing to size the mesh by and nothing to solve: the walker's rule.
            return Ok(history);
        }
        let h = self.pole_size(scene)?;
        let (model, candidate_radius, mesh_s) = self.model(scene, h)?;
        let mode = Tangential::of(scene);
        let stick_slope = self
            .stick_slope
            .map(|s| s.per_metre(scene.pair.body1.material.young, h));
        let engine = contact::engine(
            &model,
            scene.friction,
            mode == Tangential::Solved,
            self.contact,
            stick_slope,
        )
        .map_err(|e| SolveError::Failed(e.to_string()))?;
        let mut walker = Walker::new(
            &model,
            scene,
            engine,
            h,
            candidate_radius,
            self.vtu_dir.as_deref(),
        );
        let t = Instant::now();
        let steps = driver::walk(scene, &mut walker)?;
        let contact_s = t.elapsed().as_secs_f64();
        let run = Finished {
            scene,
            model: &model,
            pole_size: h,
            mode,
            method: self.contact.method,
            stick_slope: self.stick_slope.zip(stick_slope),
            mesh_s,
            contact_s,
        };
        Ok(run.history(steps, walker.record))
    }
}

/// A finished walk, to be written up.
struct Finished<'a> {
    scene: &'a Scene,
    model: &'a Model,
    pole_size: f64,
    mode: Tangential,
    method: Method,
    /// The regularised stick's slope: its factor of E/h and λ [Pa/m].
    stick_slope: Option<(StickSlope, f64)>,
    mesh_s: f64,
    contact_s: f64,
}

impl Finished<'_> {
    fn warnings(&self, record: &Record) -> Vec<String> {
        let mut warnings = Vec::new();
        if let (Some(first), Some(last)) = (record.unresolved.first(), record.unresolved.last()) {
            warnings.push(format!(
                "pole element ({:.3e} m) is not smaller than half the contact radius at {} steps \
                 (δn from {first:.3e} to {last:.3e} m): P, Q, c and p0 are unreliable there (p0 is left \
                 empty where fewer than two loaded nodes lie within c/2); refine the mesh (pole size < c/10)",
                self.pole_size,
                record.unresolved.len()
            ));
        }
        if record.balance > BALANCE {
            warnings.push(format!(
                "contact force and far-face reaction differ by {:.2e} (relative)",
                record.balance
            ));
        }
        warnings
    }

    fn model_text(&self) -> String {
        let friction = match self.mode {
            Tangential::Solved => format!(
                "Coulomb friction μ = {} with history{} (disc friction set, q_y solved; Q_y = 0 by the symmetry of y = 0)",
                self.scene.friction,
                self.stick_slope.map_or_else(String::new, |(s, lambda)| format!(
                    ", its stick regularised: stick slope λ = {} E/h = {lambda:.4e} Pa/m (a sticking point slips q/λ elastically)",
                    s.factor()
                )),
            ),
            Tangential::Zero => "μ = 0: Q = 0 exactly".into(),
            Tangential::Absent => "frictionless (no tangential motion)".into(),
        };
        format!(
            "3D linear elasticity, small strain, {friction}; identical spheres by symmetry: one body against the \
             contact plane at δn/2 and δt/2, its half y ≥ 0 with u_y = 0 on y = 0; domain: {}",
            self.scene.domain.describe()
        )
    }

    fn history(&self, steps: Vec<StepResult>, record: Record) -> History {
        let (model, t) = (self.model, self.model.times);
        let increments = record.increment_s.len();
        let mut sorted = record.increment_s.clone();
        sorted.sort_by(f64::total_cmp);
        let extra = [
            ("domain", json!(self.scene.domain.describe())),
            ("dofs", json!(model.dofs())),
            ("nodes", json!(model.mesh.nodes.len())),
            ("tetrahedra", json!(model.mesh.tetrahedra.len())),
            ("pole_size_m", json!(self.pole_size)),
            ("memory_estimate_bytes", json!(model.memory_estimate)),
            ("candidates", json!(model.surface.len())),
            ("factor_entries", json!(model.factor.factor_entries())),
            ("mesh_s", json!(self.mesh_s)),
            ("assembly_s", json!(t.assembly)),
            ("ordering_s", json!(t.ordering)),
            ("factor_s", json!(t.factor)),
            ("condense_s", json!(t.condense)),
            ("contact_s", json!(self.contact_s)),
            ("contact_method", json!(format!("{:?}", self.method))),
            ("stick_slope_pa_per_m", json!(self.stick_slope.map(|(_, lambda)| lambda))),
            ("increments", json!(increments)),
            (
                "increment_median_s",
                json!(sorted.get(increments / 2).copied().unwrap_or(0.0)),
            ),
            ("increment_max_s", json!(sorted.last().copied().unwrap_or(0.0))),
            ("iterations_total", json!(record.normal_iterations.0)),
            ("iterations_max", json!(record.normal_iterations.1)),
            ("tangential_iterations_total", json!(record.tangential_iterations.0)),
            ("tangential_iterations_max", json!(record.tangential_iterations.1)),
            ("reaction_mismatch_max", json!(record.balance)),
            (
                "tangential_force_y",
                json!("0 at every step: q_y is odd in y (the plane y = 0 is a plane of symmetry)"),
            ),
            ("stick_semi_axes_m", json!(record.semi_axes)),
            (
                "stick_semi_axes_method",
                json!("2 sqrt of the stick zone's area-weighted central second moments along x and y (an ellipse's semi-axes)"),
            ),
            (
                "stick_radius_method",
                json!("c sqrt(A_stick / A_contact) of the nodal areas (fit::stick, every solver's measure)"),
            ),
            (
                "p0_method",
                json!("least-squares fit a0 + a1 (r/c)^2 + a2 (r/c)^4 to nodal pressures on 0 < r <= c/2"),
            ),
            (
                "c_method",
                json!("c = sqrt(5/2 <r^2>), <r^2> the pressure-weighted mean of r^2 (Hertz profile: 2/5 c^2)"),
            ),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_owned(), v))
        .collect();
        History {
            metadata: Metadata {
                model: self.model_text(),
                resolution: format!(
                    "10-node tetrahedra, pole size {:.3e} m, {} DOFs, {} candidate contact nodes",
                    self.pole_size,
                    model.dofs(),
                    model.surface.len()
                ),
                warnings: self.warnings(&record),
                extra,
                ..Metadata::default()
            },
            steps,
            fields: record.fields,
        }
    }
}
