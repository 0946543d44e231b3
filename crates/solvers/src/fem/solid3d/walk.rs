//! fem-3d along a path: the condensed model advanced by the shared contact engine one increment
//! a step, as the one path walker ([`spherecontact_model::driver`]) drives it.
//!
//! Identical spheres: this body is pushed by δn/2 towards the contact plane and shifted by δt/2
//! along x (its mirror image does the same the other way), so the engine's approach and shift
//! are half the path's; an open gap releases the engine (memory cleared), and the increment that
//! closes it again loads the new contact with its own shift (every point enters at q = 0).
//!
//! Per step: P and Q_x (the engine's resultants over the mirrored half), Q_y = 0 (the plane
//! y = 0 is a plane of symmetry of the whole problem, so q_y is odd in y), the stick radius
//! and the stick zone's semi-axes ([`crate::fit::stick::stick_zone`], every solver's measure); at path positions the
//! surface fields on the contact triangles (mirrored into y < 0) and, when asked, VTU files.

use std::path::Path;
use std::time::Instant;

use super::contact::SolidContact;
use super::measures;
use super::model::Model;
use super::output::{self, Loads, SurfaceValues};
use super::surface::Surface;
use crate::fit::stick;
use spherecontact_model::driver::{PathIncrement, PathModel};
use spherecontact_model::history::{Layout, StepResult, SurfaceField, TangentialComponents};
use spherecontact_model::mirror::Mirror;
use spherecontact_model::path::Step;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::SolveError;

/// What fem-3d does about the tangential problem of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tangential {
    /// Coulomb friction with memory on the shared engine (disc friction set).
    Solved,
    /// μ = 0 with tangential motion: Q = 0 exactly (|q| ≤ μp = 0), nothing to solve.
    Zero,
    /// A path without tangential motion: no tangential columns.
    Absent,
}

impl Tangential {
    /// The mode for `scene`.
    pub fn of(scene: &Scene) -> Self {
        if scene.path.is_normal_only() {
            Self::Absent
        } else if scene.friction == 0.0 {
            Self::Zero
        } else {
            Self::Solved
        }
    }
}

/// What the walk gathered besides the rows.
#[derive(Clone, Debug, Default)]
pub struct Record {
    /// Surface fields at the recorded positions.
    pub fields: Vec<SurfaceField>,
    /// Normal-problem iterations: total and largest of one increment.
    pub normal_iterations: (usize, usize),
    /// Tangential-problem iterations (active-set rounds or gradient steps): total and largest.
    pub tangential_iterations: (usize, usize),
    /// Wall time of each increment's contact solve [s].
    pub increment_s: Vec<f64>,
    /// The largest relative mismatch of P and the far face's reaction.
    pub balance: f64,
    /// δn of the steps whose contact spans less than two pole elements [m].
    pub unresolved: Vec<f64>,
    /// The stick zone's semi-axes at every step (`None`: open, frictionless, or all slipping).
    pub semi_axes: Vec<Option<[f64; 2]>>,
}

/// The model as the walker drives it.
pub struct Walker<'a> {
    model: &'a Model,
    scene: &'a Scene,
    engine: SolidContact,
    mode: Tangential,
    pole_size: f64,
    candidate_radius: f64,
    vtu_dir: Option<&'a Path>,
    /// What the walk gathered.
    pub record: Record,
}

impl<'a> Walker<'a> {
    /// The walker of `model` for `scene` on `engine` (with friction when `mode` is solved).
    pub fn new(
        model: &'a Model,
        scene: &'a Scene,
        engine: SolidContact,
        pole_size: f64,
        candidate_radius: f64,
        vtu_dir: Option<&'a Path>,
    ) -> Self {
        Self {
            model,
            scene,
            engine,
            mode: Tangential::of(scene),
            pole_size,
            candidate_radius,
            vtu_dir,
            record: Record::default(),
        }
    }

    /// Fails when the contact reached the outer element ring of the candidate zone.
    fn check_edge(&self, step: &Step, pressure: &[f64]) -> Result<(), SolveError> {
        let surface = &self.model.surface;
        let edge = self.candidate_radius - self.pole_size;
        match (0..surface.len()).find(|&j| pressure[j] > 0.0 && radius(surface.points[j]) > edge) {
            Some(j) => Err(SolveError::Failed(format!(
                "step {}: the contact reached the outer element ring of the candidate zone (node at r = {:.3e} m)",
                step.index,
                radius(surface.points[j])
            ))),
            None => Ok(()),
        }
    }

    /// The engine's P against the far face's reaction ρ·λ (λ_j = w_j p_j on the half body).
    fn check_balance(&mut self, pressure: &[f64], force: f64) {
        let model = self.model;
        let reaction: f64 = model.condensed.reaction[1]
            .iter()
            .zip(pressure.iter().zip(&model.surface.weights))
            .map(|(r, (p, w))| r * p * w)
            .sum();
        if force > 0.0 {
            self.record.balance = self.record.balance.max((2.0 * reaction - force).abs() / force);
        }
    }

    /// The surface values of the current state at the candidates.
    fn values(&self) -> SurfaceValues {
        let m = self.model.surface.len();
        let pressure = self.engine.pressure().to_vec();
        let (q, s) = (self.engine.traction(), self.engine.slip());
        let pair = |v: &[f64], scale: f64| -> Vec<[f64; 2]> {
            (0..m)
                .map(|j| {
                    if v.is_empty() {
                        [0.0; 2]
                    } else {
                        [scale * v[j], scale * v[m + j]]
                    }
                })
                .collect()
        };
        let stick = self.engine.stick();
        SurfaceValues {
            traction: pair(q, 1.0),
            // The engine's slip is this body's against the contact plane; the pair's relative
            // slip (body 1 − body 2) is twice it.
            slip: pair(s, 2.0),
            status: (0..m)
                .map(|j| match (pressure[j] > 0.0, stick[j]) {
                    (false, _) => -1.0,
                    (true, true) => 1.0,
                    (true, false) => 0.0,
                })
                .collect(),
            pressure,
        }
    }

    /// Records the fields of `position` (and writes its VTU files when asked).
    fn record_fields(&mut self, position: usize, approach: f64, shift: f64) -> Result<(), SolveError> {
        let values = self.values();
        let frictional = self.mode != Tangential::Absent;
        self.record.fields.push(mirrored_field(
            &self.model.surface,
            position,
            &values,
            frictional,
            self.mode == Tangential::Solved,
        ));
        match self.vtu_dir {
            Some(dir) => write_vtu(
                self.model,
                self.scene,
                position,
                &values,
                [shift, 0.0, -approach],
                dir,
            ),
            None => Ok(()),
        }
    }
}

impl PathModel for Walker<'_> {
    fn advance(&mut self, increment: &PathIncrement) -> Result<StepResult, SolveError> {
        let step = increment.step;
        let approach = 0.5 * step.delta_n;
        let shift = [0.5 * increment.shift(), 0.0];
        let shift: &[f64] = if self.mode == Tangential::Solved {
            &shift
        } else {
            &[]
        };
        let t = Instant::now();
        let cost = self
            .engine
            .advance(approach, shift)
            .map_err(|e| SolveError::Failed(format!("step {}: {e}", step.index)))?;
        self.record.increment_s.push(t.elapsed().as_secs_f64());
        let r = &mut self.record;
        r.normal_iterations = (
            r.normal_iterations.0 + cost.normal_iterations,
            r.normal_iterations.1.max(cost.normal_iterations),
        );
        r.tangential_iterations = (
            r.tangential_iterations.0 + cost.tangential.iterations,
            r.tangential_iterations.1.max(cost.tangential.iterations),
        );
        let pressure = self.engine.pressure().to_vec();
        self.check_edge(step, &pressure)?;
        let force = self.engine.normal_force();
        self.check_balance(&pressure, force);
        let surface = &self.model.surface;
        let found = measures::measure(&surface.points, &surface.triangles, &pressure);
        if force > 0.0 && found.radius.is_none_or(|c| c < 2.0 * self.pole_size) {
            self.record.unresolved.push(step.delta_n);
        }
        let zone = (self.mode == Tangential::Solved)
            .then(|| {
                let points: Vec<[f64; 2]> = surface.points.iter().map(|p| [p[0], p[1]]).collect();
                let c = found.radius.unwrap_or(0.0);
                stick::stick_zone(c, &points, &surface.weights, &pressure, &self.engine.stick())
            })
            .flatten();
        self.record.semi_axes.push(zone.map(|z| z.semi_axes));
        if let Some(position) = step.position.filter(|&p| self.scene.records_fields_at(p)) {
            self.record_fields(position, approach, 0.5 * step.delta_t)?;
        }
        let (tangential_force, stick_radius) = match self.mode {
            Tangential::Solved => (
                Some(self.engine.tangential_force(0)),
                (force > 0.0).then(|| zone.map_or(0.0, |z| z.radius)),
            ),
            Tangential::Zero => (Some(0.0), None),
            Tangential::Absent => (None, None),
        };
        Ok(StepResult {
            normal_force: Some(force),
            tangential_force,
            contact_radius: found.radius,
            peak_pressure: found.peak,
            stick_radius,
            ..StepResult::at(step)
        })
    }

    fn release(&mut self, _step: &Step) {
        self.engine.release();
        self.record.semi_axes.push(None);
    }
}

/// Distance of a point from the axis.
fn radius(p: [f64; 3]) -> f64 {
    p[0].hypot(p[1])
}

/// The surface field of the whole contact: the half's nodes and their mirror images in y = 0
/// ([`Mirror`]: q_x, p and the status even, q_y and the y slip odd). `frictional`: the traction
/// and status are given (zero and slipping for μ = 0); `slip`: the slip is resolved.
fn mirrored_field(
    surface: &Surface,
    position: usize,
    values: &SurfaceValues,
    frictional: bool,
    slip: bool,
) -> SurfaceField {
    let mirror = Mirror::new(&surface.on_symmetry);
    let points: Vec<[f64; 2]> = surface.points.iter().map(|p| [p[0], p[1]]).collect();
    let stick: Vec<bool> = mirror.even(&values.status).iter().map(|&s| s > 0.0).collect();
    SurfaceField {
        position,
        points: mirror.odd_y(&points),
        pressure: mirror.even(&values.pressure),
        traction: frictional.then(|| mirror.odd_y(&values.traction)),
        stick: frictional.then_some(stick),
        slip: slip.then(|| mirror.odd_y(&values.slip)),
        components: TangentialComponents::InPlane,
        layout: Layout::Triangles(mirror.triangles(&surface.triangles)),
    }
}

/// Writes the volume (far face translated by `translation`) and the contact surface of
/// position `position` as VTU into `dir`.
fn write_vtu(
    model: &Model,
    scene: &Scene,
    position: usize,
    values: &SurfaceValues,
    translation: [f64; 3],
    dir: &Path,
) -> Result<(), SolveError> {
    let failed = |path: &Path, e: &dyn std::fmt::Display| {
        SolveError::Failed(format!("writing {}: {e}", path.display()))
    };
    spherecontact_system::io::create_folder(dir).map_err(|e| failed(dir, &e))?;
    let w = &model.surface.weights;
    // The multipliers are pressures and tractions; the condensation's loads are λ = w p along +z
    // and −w q in the plane: the slip increment w − C Δq says the surface moves by −C q against
    // the grip, so the contact pushes the body by −q (q is the force on the contact, of the
    // shift's sign).
    let normal: Vec<f64> = values.pressure.iter().zip(w).map(|(p, w)| p * w).collect();
    let tangential: Vec<f64> = model
        .condensed
        .tangential_unknowns
        .iter()
        .map(|&(j, a)| -w[j] * values.traction[j][a])
        .collect();
    let loads = Loads {
        normal: &normal,
        tangential: &tangential,
        translation,
    };
    let volume = dir.join(format!("{}-fem-3d-{position}.vtu", scene.name));
    output::write_volume(model, loads, &volume).map_err(|e| failed(&volume, &e))?;
    let surface = dir.join(format!("{}-fem-3d-{position}-surface.vtu", scene.name));
    output::write_surface(model, values, &surface).map_err(|e| failed(&surface, &e))
}
