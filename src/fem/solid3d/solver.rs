//! `fem-3d`: the 3D finite element solver (10-node tetrahedra) of the normal contact of identical
//! spheres, on the shared contact engine.
//!
//! One body by the symmetry of the contact plane, its half y ≥ 0 by the symmetry of the plane
//! y = 0 (the plane that contains the paper's shift), meshed by gmsh from the scene
//! ([`super::meshing`]), gripped on its far face ([`Grip`]), factored and condensed once onto the
//! contact candidates ([`super::model`]); every path step is one increment of the engine
//! ([`super::contact`]). P is the engine's resultant (Σ a_j p_j over the mirrored half), checked
//! against the far face's reaction; c and p0 come from [`super::measures`].
//!
//! Not built yet: Coulomb friction along the path. A path with tangential motion is answered
//! "not applicable" rather than with a normal-only answer that would pass for the whole one.

use std::path::PathBuf;
use std::time::Instant;

use serde_json::json;

use super::contact::{self, SolidContact};
use super::measures;
use super::meshing::{self, Zones};
use super::model::{Model, Settings};
use super::output::{self, Loads, SurfaceValues};
use super::surface::Surface;
use super::system::Grip;
use crate::contact::Settings as ContactSettings;
use crate::external::toolchain::Toolchain;
use crate::fem::element::tri6::Lame;
use crate::history::{History, Metadata, StepResult, SurfaceField};
use crate::limits::SOLID_POLE;
use crate::path::Step;
use crate::resolution::{self, ResolutionError};
use crate::scene::Scene;
use crate::solver::{SolveError, Solver};

/// Default pole element size in units of the path's largest contact radius: c_max/10 keeps P
/// within 0.1 % of its mesh limit and the set-up near 20 s (`examples/fem3d_timing.rs`).
pub const POLE_DIVISIONS: f64 = 10.0;
/// Relative disagreement of the engine's P and the far-face reaction that is reported: the same
/// equilibrium, so anything above round-off means an assembly or solve error.
const BALANCE: f64 = 1e-6;

/// The solver and its resolution.
#[derive(Clone, Debug, Default)]
pub struct FemSolid3d {
    /// Pole element size [m]; `None`: the largest contact radius / [`POLE_DIVISIONS`].
    pub pole_size: Option<f64>,
    /// How the far face is held (default: rigidly).
    pub grip: Grip,
    /// When set, the volume and the contact surface are written there as VTU at every position
    /// that records fields.
    pub vtu_dir: Option<PathBuf>,
}

impl FemSolid3d {
    /// The solver with pole element size `h` [m] and grip `grip`.
    pub fn with_pole_size(h: f64, grip: Grip) -> Self {
        Self {
            pole_size: Some(h),
            grip,
            vtu_dir: None,
        }
    }

    /// Why this solver does not apply to `scene`, if it does not.
    fn applicability(scene: &Scene) -> Result<(), SolveError> {
        let not = |why: &str| Err(SolveError::NotApplicable(why.into()));
        if !scene.pair.body1.radius.is_finite() || !scene.pair.body2.radius.is_finite() {
            return not("a flat body: fem-3d models two spheres (one hemisphere by symmetry)");
        }
        if !scene.pair.is_symmetric() {
            return not(
                "dissimilar bodies: fem-3d models identical spheres only (one body by the symmetry of the contact plane)",
            );
        }
        if scene.steps().iter().any(|s| s.delta_t != 0.0) {
            return not(
                "tangential motion: fem-3d's Coulomb friction along the path is not built yet (normal contact only)",
            );
        }
        if scene.max_contact_radius() <= 0.0 {
            return not("the path never closes the gap: nothing to size the mesh by");
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
}

impl Solver for FemSolid3d {
    fn name(&self) -> &'static str {
        "fem-3d"
    }

    fn description(&self) -> &'static str {
        "3D FEM (10-node tetrahedra, gmsh mesh of the half hemisphere), frictionless contact by the shared engine on the condensed contact surface"
    }

    fn writing_fields_to(&self, dir: &std::path::Path) -> Option<Box<dyn Solver>> {
        Some(Box::new(FemSolid3d {
            vtu_dir: Some(dir.to_path_buf()),
            ..self.clone()
        }))
    }

    /// Pole sizes c_max/4 … c_max/14.
    /// A pole element size: `c/N` or a length, within [`SOLID_POLE`].
    fn at_resolution(&self, scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let h = resolution::pole_size(self.name(), scene, value, SOLID_POLE)?;
        Ok(Box::new(FemSolid3d {
            pole_size: Some(h),
            ..self.clone()
        }))
    }

    fn resolution_ladder(&self, scene: &Scene) -> Vec<Box<dyn Solver>> {
        [4.0, 6.0, 10.0, 14.0]
            .into_iter()
            .map(|divisions| {
                let rung = FemSolid3d {
                    pole_size: Some(scene.max_contact_radius() / divisions),
                    ..self.clone()
                };
                Box::new(rung) as Box<dyn Solver>
            })
            .collect()
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        Self::applicability(scene)?;
        let h = self.pole_size(scene)?;
        let radius = scene.pair.body1.radius;
        let zones = Zones::new(scene.max_contact_radius(), h);
        let geometry = meshing::geometry(radius, radius, h, zones);
        geometry.check().map_err(|e| {
            SolveError::NotApplicable(format!(
                "the contact zone (c_max = {:.3e} m, {:.2} R) does not fit the graded hemisphere mesh: {e}",
                scene.max_contact_radius(),
                scene.max_contact_radius() / radius
            ))
        })?;
        let (mesh, mesh_s) = meshing::generate(&geometry, &Toolchain::default())?;
        let lame = Lame::of(&scene.pair.body1.material);
        let settings = Settings::fastest(zones.candidate_radius, self.grip);
        let model = Model::build(mesh, lame, &settings).map_err(SolveError::Failed)?;
        let engine = contact::engine(&model, 0.0, false, ContactSettings::default())
            .map_err(|e| SolveError::Failed(e.to_string()))?;
        let mut run = Run::new(engine, h, zones.candidate_radius);
        let t = Instant::now();
        for step in scene.steps() {
            run.step(&model, scene, &step, self.vtu_dir.as_deref())?;
        }
        let contact_s = t.elapsed().as_secs_f64();
        Ok(run.finish(&model, self.grip, mesh_s, contact_s))
    }
}

/// The state carried along the path and the rows produced.
struct Run {
    engine: SolidContact,
    pole_size: f64,
    candidate_radius: f64,
    steps: Vec<StepResult>,
    fields: Vec<SurfaceField>,
    iterations: (usize, usize),
    balance: f64,
    unresolved: Vec<f64>,
}

impl Run {
    fn new(engine: SolidContact, pole_size: f64, candidate_radius: f64) -> Self {
        Self {
            engine,
            pole_size,
            candidate_radius,
            steps: Vec::new(),
            fields: Vec::new(),
            iterations: (0, 0),
            balance: 0.0,
            unresolved: Vec::new(),
        }
    }

    fn step(
        &mut self,
        model: &Model,
        scene: &Scene,
        step: &Step,
        vtu_dir: Option<&std::path::Path>,
    ) -> Result<(), SolveError> {
        // One body of the symmetric pair: pushed by δn/2 towards the contact plane.
        let approach = 0.5 * step.delta_n;
        let cost = self
            .engine
            .advance(approach, &[])
            .map_err(|e| SolveError::Failed(format!("step {}: {e}", step.index)))?;
        self.iterations = (
            self.iterations.0 + cost.normal_iterations,
            self.iterations.1.max(cost.normal_iterations),
        );
        let pressure = self.engine.pressure().to_vec();
        let surface = &model.surface;
        let edge = self.candidate_radius - self.pole_size;
        if let Some(j) = (0..surface.len()).find(|&j| pressure[j] > 0.0 && radius(surface.points[j]) > edge) {
            return Err(SolveError::Failed(format!(
                "step {}: the contact reached the outer element ring of the candidate zone (node at r = {:.3e} m)",
                step.index,
                radius(surface.points[j])
            )));
        }
        let force = self.engine.normal_force();
        self.check_balance(model, &pressure, force);
        let found = measures::measure(&surface.points, &surface.weights, &pressure);
        if force > 0.0 && found.radius.is_none_or(|c| c < 2.0 * self.pole_size) {
            self.unresolved.push(step.delta_n);
        }
        if let Some(position) = step.position.filter(|&p| scene.records_fields_at(p)) {
            self.fields.push(mirrored_field(model, position, &pressure));
            if let Some(dir) = vtu_dir {
                write_vtu(model, scene, position, &pressure, approach, dir)?;
            }
        }
        self.steps.push(StepResult {
            normal_force: Some(force),
            contact_radius: found.radius,
            peak_pressure: found.peak,
            ..StepResult::at(step)
        });
        Ok(())
    }

    /// The engine's P against the far face's reaction ρ·λ (λ_j = w_j p_j on the half body).
    fn check_balance(&mut self, model: &Model, pressure: &[f64], force: f64) {
        let reaction: f64 = model.condensed.reaction[1]
            .iter()
            .zip(pressure.iter().zip(&model.surface.weights))
            .map(|(r, (p, w))| r * p * w)
            .sum();
        if force > 0.0 {
            self.balance = self.balance.max((2.0 * reaction - force).abs() / force);
        }
    }

    fn finish(self, model: &Model, grip: Grip, mesh_s: f64, contact_s: f64) -> History {
        let mut warnings = Vec::new();
        if let (Some(first), Some(last)) = (self.unresolved.first(), self.unresolved.last()) {
            warnings.push(format!(
                "pole element ({:.3e} m) is not smaller than half the contact radius at {} steps \
                 (δn from {first:.3e} to {last:.3e} m): P, c and p0 are unreliable there (p0 is left \
                 empty where fewer than two loaded nodes lie within c/2); refine the mesh (pole size < c/10)",
                self.pole_size,
                self.unresolved.len()
            ));
        }
        if self.balance > BALANCE {
            warnings.push(format!(
                "contact force and far-face reaction differ by {:.2e} (relative)",
                self.balance
            ));
        }
        let t = model.times;
        let extra = [
            ("grip", json!(format!("{grip:?}"))),
            ("dofs", json!(model.dofs())),
            ("nodes", json!(model.mesh.nodes.len())),
            ("tetrahedra", json!(model.mesh.tetrahedra.len())),
            ("pole_size_m", json!(self.pole_size)),
            ("candidates", json!(model.surface.len())),
            ("factor_entries", json!(model.factor.factor_entries())),
            ("mesh_s", json!(mesh_s)),
            ("assembly_s", json!(t.assembly)),
            ("ordering_s", json!(t.ordering)),
            ("factor_s", json!(t.factor)),
            ("condense_s", json!(t.condense)),
            ("contact_s", json!(contact_s)),
            ("iterations_total", json!(self.iterations.0)),
            ("iterations_max", json!(self.iterations.1)),
            ("reaction_mismatch_max", json!(self.balance)),
            (
                "p0_method",
                json!("least-squares fit a0 + a1 (r/c)^2 + a2 (r/c)^4 to nodal pressures on 0 < r <= c/2"),
            ),
            (
                "c_method",
                json!(
                    "c = sqrt(5/2 <r^2>), <r^2> the pressure-weighted mean of r^2 (Hertz profile: 2/5 c^2)"
                ),
            ),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_owned(), v))
        .collect();
        History {
            metadata: Metadata {
                model: format!(
                    "3D linear elasticity, frictionless, small strain; identical spheres by symmetry: one \
                     hemisphere against a rigid frictionless plane at δn/2, its half y ≥ 0 with u_y = 0 on \
                     y = 0; equatorial face gripped {}",
                    match grip {
                        Grip::Rigid => "rigidly (every component follows the approach)",
                        Grip::Axial => "axially (u_z imposed, free in its plane)",
                    }
                ),
                resolution: format!(
                    "10-node tetrahedra, pole size {:.3e} m, {} DOFs, {} candidate contact nodes",
                    self.pole_size,
                    model.dofs(),
                    model.surface.len()
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

/// Distance of a point from the axis.
fn radius(p: [f64; 3]) -> f64 {
    p[0].hypot(p[1])
}

/// The surface field of the whole contact: the half's nodes and their mirror images in y = 0
/// (nodes on the plane once).
fn mirrored_field(model: &Model, position: usize, pressure: &[f64]) -> SurfaceField {
    let surface = &model.surface;
    let mirror = (0..surface.len()).filter(|&j| !surface.on_symmetry[j]);
    let points = surface
        .points
        .iter()
        .map(|p| [p[0], p[1]])
        .chain(
            mirror
                .clone()
                .map(|j| [surface.points[j][0], -surface.points[j][1]]),
        )
        .collect();
    let pressure = pressure
        .iter()
        .copied()
        .chain(mirror.map(|j| pressure[j]))
        .collect();
    SurfaceField {
        position,
        points,
        pressure,
        traction: None,
        stick: None,
        slip: None,
        triangles: Some(mirrored_triangles(surface)),
    }
}

/// The half's sub-triangles and their mirror images, as indices into [`mirrored_field`]'s
/// points: a node on the symmetry plane is its own image, the others' images follow the half's
/// nodes in order (each image triangle's orientation reversed, so all face the same way).
fn mirrored_triangles(surface: &Surface) -> Vec<[usize; 3]> {
    let mut image: Vec<usize> = (0..surface.len()).collect();
    let mut next = surface.len();
    for (j, on_plane) in surface.on_symmetry.iter().enumerate() {
        if !on_plane {
            image[j] = next;
            next += 1;
        }
    }
    let half = surface.triangles.iter().copied();
    let mirrored = surface
        .triangles
        .iter()
        .map(|&[a, b, c]| [image[a], image[c], image[b]]);
    half.chain(mirrored).collect()
}

/// Writes the volume and the contact surface of position `position` as VTU into `dir`.
fn write_vtu(
    model: &Model,
    scene: &Scene,
    position: usize,
    pressure: &[f64],
    approach: f64,
    dir: &std::path::Path,
) -> Result<(), SolveError> {
    let failed = |path: &std::path::Path, e: &dyn std::fmt::Display| {
        SolveError::Failed(format!("writing {}: {e}", path.display()))
    };
    std::fs::create_dir_all(dir).map_err(|e| failed(dir, &e))?;
    let normal: Vec<f64> = pressure
        .iter()
        .zip(&model.surface.weights)
        .map(|(p, w)| p * w)
        .collect();
    let tangential = vec![0.0; model.condensed.tangential_unknowns.len()];
    let loads = Loads {
        normal: &normal,
        tangential: &tangential,
        translation: [0.0, 0.0, -approach],
    };
    let volume = dir.join(format!("{}-fem-3d-{position}.vtu", scene.name));
    output::write_volume(model, loads, &volume).map_err(|e| failed(&volume, &e))?;
    let values = SurfaceValues {
        pressure: pressure.to_vec(),
        traction: vec![[0.0; 2]; pressure.len()],
        slip: vec![[0.0; 2]; pressure.len()],
        // Frictionless: every point in contact slips freely (0), the others are open (−1).
        status: pressure
            .iter()
            .map(|&p| if p > 0.0 { 0.0 } else { -1.0 })
            .collect(),
    };
    let surface = dir.join(format!("{}-fem-3d-{position}-surface.vtu", scene.name));
    output::write_surface(model, &values, &surface).map_err(|e| failed(&surface, &e))
}
