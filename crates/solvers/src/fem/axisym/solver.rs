//! `fem-axisym`: the axisymmetric finite element solver, normal contact (Fourier mode n = 0) and
//! the tangential path with Coulomb friction and memory (mode n = 1, [`super::tangential`]).
//!
//! Per path step the contact is re-solved on the condensed systems (each stiffness is factored
//! once per mesh) by the shared engine. It reports P from the multipliers (Σλ) and checks it
//! against the reaction on each body's far boundary; c and p0 come from [`super::pressure`] (p0
//! is a fit to the nodal pressures near the axis, not the axis node's multiplier); Q is the sum
//! of the n = 1 ring forces and the stick radius every solver's measure, c √(|S| / |A|) of the
//! nodes' ring weights ([`crate::fit::stick::stick_radius`]).

use std::path::PathBuf;
use std::time::Instant;

use serde_json::json;

use super::meshing::{self, Origin};
use super::model::{AxisymContact, Model, Settings};
use super::output;
use super::output_n1::{self, TangentialState};
use super::pressure::{self, Profile};
use super::tangential::Mode;
use crate::fem::element::tri6::Integration;
use crate::fem::factor::Ordering;
use crate::fem::pole::{self, PoleSized};
use crate::fit::stick;
use spherecontact_model::driver;
use spherecontact_model::history::{
    History, Layout, Metadata, StepResult, SurfaceField, TangentialComponents,
};
use spherecontact_model::limits::MERIDIAN_POLE;
use spherecontact_model::progress;
use spherecontact_model::resolution::{PoleLimits, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_system::toolchain::Toolchain;

/// Default pole element size in units of the path's largest contact radius. At c/40 the P, p0
/// and c errors on the paper's spheres are within 0.5 % (`examples/fem_timing.rs`).
pub const POLE_DIVISIONS: f64 = 40.0;
/// Candidate contact zone, in units of the largest contact radius.
const CANDIDATE_ZONE: f64 = 1.25;
/// Poisson ratio above which the volumetric term is under-integrated against locking.
const NEAR_INCOMPRESSIBLE: f64 = 0.45;
/// p0/E above which the small-strain model is doubtful: strains ~ p0/E exceed 1 %, where the
/// neglected quadratic strain terms and the parabolic profile are no longer below 0.5 %.
const SMALL_STRAIN: f64 = 0.01;
/// Relative disagreement of Σλ and the far-boundary reaction that is reported: both are the
/// same equilibrium, so anything above round-off means an assembly or solve error.
const BALANCE: f64 = 1e-6;

/// The solver and its resolution.
#[derive(Clone, Debug, Default)]
pub struct FemAxisym {
    /// Pole element size h0 [m]; `None`: the largest contact radius / [`POLE_DIVISIONS`].
    pub pole_size: Option<f64>,
    /// Fill-reducing ordering of the Cholesky factorisation (`None`: AMD).
    pub ordering: Option<Ordering>,
    /// When set, displacement and stress fields are written there as VTU at every position.
    pub vtu_dir: Option<PathBuf>,
    /// Element integration (`None`: full, selective reduced above ν = 0.45).
    pub integration: Option<Integration>,
    /// A gmsh MSH 4.1 mesh of the sphere to use instead of the generated one (symmetric
    /// reduction only; see [`crate::fem::mesh::msh`] for its conventions).
    pub mesh_file: Option<PathBuf>,
    /// The external tools, for a case whose `[domain]` asks for `mesher = "gmsh"`
    /// ([`super::meshing`]).
    pub toolchain: Toolchain,
    /// Growth of the element size away from the contact's fine zone (`None`:
    /// [`super::model::GROWTH`]); smaller refines the far field, which the finite body's
    /// compliance depends on.
    pub growth: Option<f64>,
}

impl FemAxisym {
    /// The solver with pole element size `h` [m].
    pub fn with_pole_size(h: f64) -> Self {
        Self {
            pole_size: Some(h),
            ..Self::default()
        }
    }

    /// The mesh and solver settings for `scene`.
    pub fn settings(&self, scene: &Scene) -> Result<Settings, SolveError> {
        let c = scene.max_contact_radius();
        let pole_size = match self.pole_size {
            Some(h) if h > 0.0 && h.is_finite() => h,
            Some(h) => return Err(SolveError::Failed(format!("pole size {h} m is not positive"))),
            None if c > 0.0 => c / POLE_DIVISIONS,
            None => {
                return Err(SolveError::NotApplicable(
                    "the path never closes the gap: nothing to size the mesh by".into(),
                ))
            }
        };
        let nu = [scene.pair.body1, scene.pair.body2].map(|b| b.material.poisson);
        let integration = self
            .integration
            .unwrap_or(if nu.iter().any(|&n| n > NEAR_INCOMPRESSIBLE) {
                Integration::SelectiveReduced
            } else {
                Integration::Full
            });
        Ok(Settings {
            pole_size,
            candidate_radius: (CANDIDATE_ZONE * c).max(3.0 * pole_size),
            ordering: self.ordering.unwrap_or(Ordering::Amd),
            integration,
            domain: scene.domain,
            growth: self.growth.unwrap_or(super::model::GROWTH),
            shear: Mode::of(scene) == Mode::Solved,
            contact_radius: c,
        })
    }
}

impl PoleSized for FemAxisym {
    const LIMITS: PoleLimits = MERIDIAN_POLE;

    fn sized(&self, h: f64) -> Self {
        let pole_size = Some(h);
        FemAxisym {
            pole_size,
            ..self.clone()
        }
    }

    fn writing_to(&self, dir: &std::path::Path) -> Self {
        let vtu_dir = Some(dir.to_path_buf());
        FemAxisym {
            vtu_dir,
            ..self.clone()
        }
    }
}

impl Solver for FemAxisym {
    fn name(&self) -> &'static str {
        "fem-axisym"
    }

    fn kind(&self) -> Kind {
        Kind::FiniteElement
    }

    fn description(&self) -> &'static str {
        "axisymmetric FEM (6-node triangles, graded mesh): normal contact (n = 0) and Coulomb friction with history (n = 1) by the shared engine on the condensed contact line"
    }

    fn writing_fields_to(&self, dir: &std::path::Path) -> Option<Box<dyn Solver>> {
        pole::writing_fields_to(self, dir)
    }

    /// A pole element size: `c/N` or a length, within [`MERIDIAN_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        pole::at_resolution(self, scene, value)
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        let settings = self.settings(scene).ok()?;
        let divisions = settings.contact_radius / settings.pole_size;
        Some(spherecontact_model::cost::fem_axisym(
            divisions,
            scene.steps().len(),
        ))
    }

    /// Pole sizes c_max/5 … c_max/80, halving (the external decks' ladder and beyond).
    fn resolution_ladder(&self, scene: &Scene) -> Vec<Box<dyn Solver>> {
        pole::ladder(self, scene, &[5.0, 10.0, 20.0, 40.0, 80.0])
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        if !scene.pair.body1.radius.is_finite() && !scene.pair.body2.radius.is_finite() {
            return Err(SolveError::NotApplicable(
                "two flats have no Hertz contact".into(),
            ));
        }
        let metadata = Metadata {
            model: "axisymmetric finite elements, frictionless".into(),
            ..Metadata::default()
        };
        if let Some(history) = driver::never_closed_history(scene, metadata) {
            // Nothing to size the mesh by and nothing to solve: the walker's rule.
            return Ok(history);
        }
        let settings = self.settings(scene)?;
        let (model, origin) = meshing::model(scene, &settings, self.mesh_file.as_deref(), &self.toolchain)?;
        let mode = Mode::of(scene);
        let shear_time = model.bodies.iter().map(|b| b.times[3]).sum();
        let mut run = Run::new(&model, scene, mode).map_err(SolveError::Failed)?;
        let t = Instant::now();
        let steps = scene.steps();
        for (k, step) in steps.iter().enumerate() {
            run.step(&model, scene, step, self.vtu_dir.as_deref())?;
            progress::tick(k + 1, steps.len());
        }
        let contact_time = t.elapsed().as_secs_f64();
        Ok(run.finish(&model, &settings, &origin, [shear_time, contact_time]))
    }
}

/// The state carried along the path and the rows produced.
struct Run {
    contact: AxisymContact,
    /// The tangential problem's mode, and the relative shift δt of the last step.
    mode: Mode,
    previous_t: f64,
    steps: Vec<StepResult>,
    fields: Vec<SurfaceField>,
    iterations: (usize, usize),
    balance: f64,
    unresolved: Vec<f64>,
    max_strain: f64,
    pole_size: f64,
}

impl Run {
    fn new(model: &Model, scene: &Scene, mode: Mode) -> Result<Self, String> {
        Ok(Self {
            contact: model.contact(scene.friction)?,
            mode,
            previous_t: scene.path.positions()[0].delta_t,
            steps: Vec::new(),
            fields: Vec::new(),
            iterations: (0, 0),
            balance: 0.0,
            unresolved: Vec::new(),
            max_strain: 0.0,
            pole_size: model.bodies[0].mesh.pole_size(),
        })
    }

    fn step(
        &mut self,
        model: &Model,
        scene: &Scene,
        step: &spherecontact_model::path::Step,
        vtu_dir: Option<&std::path::Path>,
    ) -> Result<(), SolveError> {
        let approach = model.reduction.approach(step.delta_n);
        let shift = [model.reduction.shift(step.delta_t - self.previous_t)];
        self.previous_t = step.delta_t;
        let shift: &[f64] = if self.mode == Mode::Solved { &shift } else { &[] };
        if step.delta_n <= 0.0 {
            // The walker's rule (spherecontact_model::driver): an open gap forgets the contact's history.
            self.contact.release();
        }
        let cost = self
            .contact
            .advance(approach, shift)
            .map_err(|e| SolveError::Failed(format!("step {}: {e}", step.index)))?;
        let forces = self.contact.pressure().to_vec();
        if forces.last().is_some_and(|&f| f > 0.0) {
            return Err(SolveError::Failed(format!(
                "step {}: the contact reached the edge of the candidate zone ({} m)",
                step.index,
                model.radii.last().copied().unwrap_or(0.0)
            )));
        }
        self.iterations = (
            self.iterations.0 + cost.normal_iterations,
            self.iterations.1.max(cost.normal_iterations),
        );
        let force = self.contact.normal_force();
        self.check_balance(model, &forces, force);
        let profile = pressure::recover(&model.radii, &model.weights, &forces);
        self.judge_resolution(&profile, force, step.delta_n, scene);
        let solved = self.mode == Mode::Solved;
        if let Some(position) = step.position.filter(|&p| scene.records_fields_at(p)) {
            let field = SurfaceField {
                position,
                points: model.radii.iter().map(|&r| [r, 0.0]).collect(),
                pressure: profile.pressure.clone(),
                traction: solved.then(|| self.traction(model)),
                stick: solved.then(|| self.contact.stick()),
                slip: solved.then(|| self.slip(model)),
                components: TangentialComponents::AlongX,
                layout: Layout::Profile,
            };
            if let Some(dir) = vtu_dir {
                let stem = format!("{}-fem-axisym-{position}", scene.name);
                spherecontact_system::io::create_folder(dir)
                    .map_err(|e| SolveError::Failed(format!("creating {}: {e}", dir.display())))?;
                let path = dir.join(format!("{stem}.vtu"));
                output::write_fields(model, &forces, approach, &path)
                    .map_err(|e| SolveError::Failed(format!("writing {}: {e}", path.display())))?;
                if solved {
                    let state = TangentialState {
                        normal: &forces,
                        tangential: self.contact.traction(),
                        approach,
                        shift: model.reduction.shift(step.delta_t),
                        field: &field,
                    };
                    output_n1::write(model, &state, dir, &stem).map_err(|e| {
                        SolveError::Failed(format!(
                            "writing the n = 1 fields {stem}-*.vtu in {}: {e}",
                            dir.display()
                        ))
                    })?;
                }
            }
            self.fields.push(field);
        }
        let (tangential_force, stick_radius) = match self.mode {
            Mode::Solved => (
                Some(self.contact.tangential_force(0)),
                (force > 0.0).then(|| {
                    let c = profile.radius.unwrap_or(0.0);
                    stick::stick_radius(c, &model.weights, &profile.pressure, &self.contact.stick())
                }),
            ),
            Mode::Zero => (Some(0.0), None),
            Mode::Absent | Mode::NotApplicable(_) => (None, None),
        };
        self.steps.push(StepResult {
            normal_force: Some(force),
            tangential_force,
            contact_radius: profile.radius,
            peak_pressure: profile.peak,
            stick_radius,
            ..StepResult::at(step)
        });
        Ok(())
    }

    /// The traction along x at the candidates, q_i = f_i / w_i (the axis node, of zero weight,
    /// takes its neighbour's value), as (q_x, q_y = 0): the model has no q_y.
    fn traction(&self, model: &Model) -> Vec<[f64; 2]> {
        let (f, w) = (self.contact.traction(), &model.weights);
        let nodal = |i: usize| (w[i] > 0.0).then(|| f[i] / w[i]);
        (0..f.len())
            .map(|i| {
                [
                    nodal(i)
                        .or_else(|| (i + 1 < f.len()).then(|| nodal(i + 1)).flatten())
                        .unwrap_or(0.0),
                    0.0,
                ]
            })
            .collect()
    }

    /// The relative slip of the surfaces (body 1 − body 2) along x at the candidates,
    /// accumulated since each node last came into contact: the engine's slip against the
    /// symmetry plane, doubled for one sphere of two (the condensed shift is half of δt).
    fn slip(&self, model: &Model) -> Vec<[f64; 2]> {
        let per_relative = model.reduction.approach(1.0);
        self.contact
            .slip()
            .iter()
            .map(|s| [s / per_relative, 0.0])
            .collect()
    }

    /// Σλ against each body's far-boundary reaction ρ·λ.
    fn check_balance(&mut self, model: &Model, forces: &[f64], force: f64) {
        for body in &model.bodies {
            let reaction: f64 = body
                .condensed
                .reaction
                .iter()
                .zip(forces)
                .map(|(r, l)| r * l)
                .sum();
            if force > 0.0 {
                self.balance = self.balance.max((reaction - force).abs() / force);
            }
        }
    }

    fn judge_resolution(&mut self, profile: &Profile, force: f64, delta_n: f64, scene: &Scene) {
        if force > 0.0 && (profile.radius.is_none() || profile.radius < Some(2.0 * self.pole_size)) {
            self.unresolved.push(delta_n);
        }
        let young = scene
            .pair
            .body1
            .material
            .young
            .min(scene.pair.body2.material.young);
        if let Some(p0) = profile.peak {
            self.max_strain = self.max_strain.max(p0 / young);
        }
    }

    fn finish(
        self,
        model: &Model,
        settings: &Settings,
        origin: &Origin,
        [shear_time, contact_time]: [f64; 2],
    ) -> History {
        let mut warnings = Vec::new(); // the scene's own warnings are reported by verify
        if let (Some(first), Some(last)) = (self.unresolved.first(), self.unresolved.last()) {
            warnings.push(format!(
                "pole element ({:.3e} m) is not smaller than half the contact radius at {} steps \
                 (δn from {first:.3e} to {last:.3e} m): the contact spans at most two elements, so P, c and \
                 p0 are unreliable there (c and p0 are left empty where no node beyond the axis is \
                 loaded); refine the mesh (pole size < c/10)",
                self.pole_size,
                self.unresolved.len()
            ));
        }
        if self.max_strain > SMALL_STRAIN {
            warnings.push(format!(
                "peak pressure reaches {:.2} % of Young's modulus: strains beyond 1 %, outside the \
                 small-strain (linear elastic, linear kinematics) validity of this model",
                100.0 * self.max_strain
            ));
        }
        if let Mode::NotApplicable(reason) = &self.mode {
            warnings.push(reason.clone());
        }
        if self.balance > BALANCE {
            warnings.push(format!(
                "contact force and far-boundary reaction differ by {:.2e} (relative)",
                self.balance
            ));
        }
        let dofs: usize = model.bodies.iter().map(|b| b.dofs()).sum();
        let extra = [
            ("reduction", json!(format!("{:?}", model.reduction))),
            (
                "fourier_modes",
                json!(if self.mode == Mode::Solved {
                    vec![0, 1]
                } else {
                    vec![0]
                }),
            ),
            ("domain", json!(settings.domain)),
            ("mesh", json!(origin.description)),
            ("gmsh_s", json!(origin.gmsh_s)),
            ("dofs", json!(dofs)),
            (
                "nodes",
                json!(model.bodies.iter().map(|b| b.mesh.nodes.len()).sum::<usize>()),
            ),
            (
                "elements",
                json!(model.bodies.iter().map(|b| b.mesh.triangles.len()).sum::<usize>()),
            ),
            ("pole_size_m", json!(settings.pole_size)),
            ("memory_estimate_bytes", json!(model.memory_estimate)),
            ("candidates", json!(model.radii.len())),
            ("integration", json!(format!("{:?}", settings.integration))),
            ("ordering", json!(format!("{:?}", settings.ordering))),
            (
                "factor_entries",
                json!(model
                    .bodies
                    .iter()
                    .map(|b| b.factor.factor_entries())
                    .sum::<usize>()),
            ),
            (
                "assembly_s",
                json!(model.bodies.iter().map(|b| b.times[0]).sum::<f64>()),
            ),
            (
                "factor_s",
                json!(model.bodies.iter().map(|b| b.times[1]).sum::<f64>()),
            ),
            (
                "condense_s",
                json!(model.bodies.iter().map(|b| b.times[2]).sum::<f64>()),
            ),
            ("fourier_one_s", json!(shear_time)),
            ("contact_s", json!(contact_time)),
            ("iterations_total", json!(self.iterations.0)),
            ("iterations_max", json!(self.iterations.1)),
            ("reaction_mismatch_max", json!(self.balance)),
            (
                "p0_method",
                json!("least-squares fit a0 + a1 (r/c)^2 + a2 (r/c)^4 to nodal pressures on 0 < r <= c/2"),
            ),
            (
                "c_method",
                json!("zero of a least-squares quadratic in r fitted to p^2 at the last 16 loaded nodes"),
            ),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_owned(), v))
        .collect();
        History {
            metadata: Metadata {
                model: format!(
                    "axisymmetric linear elasticity, small strain; {}; {}; each sphere modelled as a {} \
                     (a flat: the region within {} c_max of the pole, held on that arc with the same grip)",
                    match self.mode {
                        Mode::Solved => "Fourier modes n = 0 (normal) and n = 1 (tangential: Coulomb with memory, \
                                         traction along x as Mindlin–Deresiewicz assume; no q_y, circular stick zone)",
                        Mode::Zero => "Fourier mode n = 0 (normal); μ = 0, so Q = 0 exactly",
                        Mode::Absent | Mode::NotApplicable(_) => "Fourier mode n = 0 (normal contact only)",
                    },
                    model.reduction.describe(),
                    settings.domain.describe(),
                    super::model::FLAT_DOMAIN
                ),
                resolution: format!(
                    "6-node triangles, pole size {:.3e} m, {} DOFs, {} candidate contact nodes; mesh {}",
                    settings.pole_size,
                    dofs,
                    model.radii.len(),
                    origin.description
                ),
                warnings,
                extra,
                ..Metadata::default()
            },
            steps: self.steps,
            fields: self.fields,
        }
    }
}
