//! The method of dimensionality reduction (Popov & Heß 2015, *Method of Dimensionality Reduction
//! in Contact Mechanics and Friction*, ch. 2–4): exact Mindlin–Deresiewicz for any oblique history.
//!
//! The 3D contact of two elastically similar bodies with gap profile f(r) maps onto a rigid 1D
//! profile g(x) pressed into a Winkler foundation of independent springs of spacing Δx with
//! normal stiffness E* Δx and tangential stiffness G̃ Δx, where
//!
//! ```text
//! g(x) = |x| ∫₀^|x| f'(r) / √(x² − r²) dr      (f = r²/2R*  ⇒  g = x²/R*)
//! G̃   = [(2 − ν1)/(4 G1) + (2 − ν2)/(4 G2)]⁻¹ = 4 G*   (G*: Mindlin's, see `ContactPair`)
//! ```
//! At approach d a spring at x carries w(x) = d − g(x) when positive; the springs in contact span
//! |x| < c = √(R* d), the Hertz radius, and P = 2 ∫₀^c E* w dx = 4/3 E* c d (Hertz).
//!
//! Tangentially every spring in contact keeps its own displacement u(x) and obeys Coulomb's law
//! on its own: an increment Δδt is first taken up elastically (u ← u + Δδt); where that would
//! exceed |G̃ u| ≤ μ E* w(x), the spring slips and u is set to the limit. A spring leaving contact
//! forgets its history. Q = 2 ∫₀^c G̃ u dx. The stick zone is where no spring slipped in the step:
//! its radius is the innermost slipping spring (c when none slips, 0 in gross sliding); in the
//! MDR that 1D radius equals the 3D stick radius.
//!
//! Discretisation: springs at the midpoints of `springs` equal cells on [0, 1.05 c_max] (the
//! problem is even in x, so one half is modelled and doubled). P then has a relative error of
//! order (Δx/c)², from the one cell cut by the contact edge.

use crate::history::{History, Metadata, StepResult};
use crate::scene::Scene;
use crate::solver::{SolveError, Solver};

/// Springs beyond the largest contact radius, as a fraction of it: keeps the contact edge inside
/// the window at every step.
const WINDOW_MARGIN: f64 = 0.05;

/// The MDR solver with a given number of springs on the half-line.
pub struct Mdr {
    /// Springs on [0, 1.05 c_max].
    pub springs: usize,
}

impl Default for Mdr {
    fn default() -> Self {
        Self { springs: 4000 }
    }
}

/// The state of the spring bed along a path.
struct SpringBed {
    /// Spring positions x_i [m].
    x: Vec<f64>,
    /// Profile g(x_i) = x_i²/R* [m].
    profile: Vec<f64>,
    /// Tangential displacement u_i of each spring [m].
    u: Vec<f64>,
    /// Spacing Δx [m].
    dx: f64,
    /// E* [Pa].
    normal_modulus: f64,
    /// G̃ = 4 G* [Pa].
    tangential_modulus: f64,
    /// μ.
    friction: f64,
}

/// The bed's forces after one increment.
struct BedState {
    normal_force: f64,
    tangential_force: f64,
    stick_radius: f64,
}

impl SpringBed {
    fn new(scene: &Scene, springs: usize) -> Self {
        let half_width = (1.0 + WINDOW_MARGIN) * scene.max_contact_radius();
        let dx = half_width / springs as f64;
        let x: Vec<f64> = (0..springs).map(|i| (i as f64 + 0.5) * dx).collect();
        let r_star = scene.pair.effective_radius();
        Self {
            profile: x.iter().map(|x| x * x / r_star).collect(),
            u: vec![0.0; springs],
            x,
            dx,
            normal_modulus: scene.pair.effective_modulus(),
            tangential_modulus: 4.0 * scene.pair.mindlin_shear_modulus(),
            friction: scene.friction,
        }
    }

    /// Moves the rigid profile to approach `delta_n` and shifts it by `increment_t`.
    fn advance(&mut self, delta_n: f64, increment_t: f64) -> BedState {
        let slip_ratio = self.friction * self.normal_modulus / self.tangential_modulus;
        let (mut normal, mut tangential) = (0.0, 0.0);
        let mut innermost_slip = f64::INFINITY;
        let mut outermost_contact = 0.0_f64;
        for i in 0..self.x.len() {
            let w = delta_n - self.profile[i];
            if w <= 0.0 {
                self.u[i] = 0.0;
                continue;
            }
            let trial = self.u[i] + increment_t;
            let limit = slip_ratio * w;
            if trial.abs() > limit {
                self.u[i] = limit.copysign(trial);
                innermost_slip = innermost_slip.min(self.x[i]);
            } else {
                self.u[i] = trial;
            }
            normal += w;
            tangential += self.u[i];
            outermost_contact = self.x[i];
        }
        let contact_radius = if outermost_contact > 0.0 {
            outermost_contact + 0.5 * self.dx
        } else {
            0.0
        };
        BedState {
            normal_force: 2.0 * self.normal_modulus * normal * self.dx,
            tangential_force: 2.0 * self.tangential_modulus * tangential * self.dx,
            stick_radius: if innermost_slip.is_finite() {
                innermost_slip - 0.5 * self.dx
            } else {
                contact_radius
            },
        }
    }
}

impl Solver for Mdr {
    fn name(&self) -> &'static str {
        "mdr"
    }

    fn description(&self) -> &'static str {
        "method of dimensionality reduction (Popov & Heß): exact Mindlin–Deresiewicz for any history"
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let hertz = scene.hertz();
        let steps = scene.steps();
        let mut rows = Vec::with_capacity(steps.len());
        if scene.max_contact_radius() > 0.0 {
            let mut bed = SpringBed::new(scene, self.springs.max(1));
            let mut previous_t = steps[0].delta_t;
            for step in &steps {
                let state = bed.advance(step.delta_n, step.delta_t - previous_t);
                previous_t = step.delta_t;
                let in_contact = step.delta_n > 0.0;
                rows.push(StepResult {
                    normal_force: Some(state.normal_force),
                    tangential_force: Some(state.tangential_force),
                    contact_radius: Some(hertz.contact_radius(step.delta_n)),
                    stick_radius: in_contact.then_some(state.stick_radius),
                    ..StepResult::at(step)
                });
            }
        } else {
            // The gap never closes: no spring ever touches.
            rows.extend(steps.iter().map(|step| StepResult {
                normal_force: Some(0.0),
                tangential_force: Some(0.0),
                contact_radius: Some(0.0),
                ..StepResult::at(step)
            }));
        }
        Ok(History {
            metadata: Metadata {
                model: "MDR: 1D Winkler bed equivalent to elastically similar half-spaces".into(),
                resolution: format!(
                    "{} springs on [0, {:.3e} m]",
                    self.springs,
                    (1.0 + WINDOW_MARGIN) * scene.max_contact_radius()
                ),
                ..Metadata::default()
            },
            steps: rows,
            fields: Vec::new(),
        })
    }
}
