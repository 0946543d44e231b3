//! The contact along a path: the normal and tangential problems advanced one increment at a
//! time, with the memory Coulomb friction needs (the traction at the start of each increment,
//! the slip accumulated since each point came into contact).
//!
//! Per increment: the normal problem at the new approach (pressures from the multipliers), then
//! the tangential increment with the bound g_i = μ s_i p_i of the new pressure (s_i = 1 unless
//! [`Contact::with_bound_scale`]). Points out of contact carry nothing and forget their history;
//! a point entering contact starts at q = 0. Both problems start from the previous increment's
//! answer extrapolated along the last change (the change per unit of approach and of shift), and
//! the products with C are carried, so an increment that changes nothing costs no product.

use super::coulomb::{self, CoulombCost, CoulombError, CoulombProblem, CoulombState};
use super::normal::{NormalError, NormalProblem, NormalState};
use super::operator::{resultant, update_after_changes, Compliance};
use super::set::{norm_at, FrictionSet};

/// Which algorithm solves the problems.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// Direct for an operator that holds a matrix of at most [`DIRECT_LIMIT`] rows, iterative
    /// otherwise.
    #[default]
    Auto,
    /// Conjugate gradients (any operator).
    Iterative,
    /// Dense Cholesky on the active blocks (operators that hold a matrix).
    Direct,
}

/// The largest matrix (rows) [`Method::Auto`] solves directly: below it one Cholesky of the
/// active block (n³/3 operations) costs less than the few hundred dense products (n² each) of an
/// iterative solve.
pub const DIRECT_LIMIT: usize = 1500;

/// Tolerances and iteration caps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Normal problem, iterative: weighted rms gap on the contact over the approach.
    pub normal_tolerance: f64,
    /// Tangential problem: see [`super::coulomb`].
    pub tangential_tolerance: f64,
    /// Iteration cap of either problem.
    pub max_iterations: usize,
    /// The algorithm.
    pub method: Method,
    /// Multiplier per unit penetration that seeds a contact from nothing; `None`: 1/λ_max of the
    /// normal compliance.
    pub seed_stiffness: Option<f64>,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            normal_tolerance: 1e-10,
            tangential_tolerance: 1e-8,
            max_iterations: 10_000,
            method: Method::Auto,
            seed_stiffness: None,
        }
    }
}

/// Why an increment failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ContactError {
    /// The normal problem failed.
    #[error(transparent)]
    Normal(#[from] NormalError),
    /// The tangential problem failed.
    #[error(transparent)]
    Tangential(#[from] CoulombError),
    /// The operators, the set or the data do not fit together.
    #[error("{0}")]
    Mismatch(String),
}

/// What an increment cost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IncrementCost {
    /// Iterations of the normal problem (CG steps or active-set rounds).
    pub normal_iterations: usize,
    /// Iterations and products of the tangential problem.
    pub tangential: CoulombCost,
}

/// The tangential side: its operator, set and memory.
struct Tangential<T> {
    op: T,
    set: FrictionSet,
    friction: f64,
    scale: Vec<f64>,
    state: CoulombState,
    slip: Vec<f64>,
    /// The last increment's change of q and of C q, and its shift, for the predictor.
    change: Vec<f64>,
    displacement_change: Vec<f64>,
    last_shift: Vec<f64>,
}

/// A contact on m points, advanced one increment at a time.
pub struct Contact<N: Compliance, T: Compliance> {
    normal: N,
    separation: Vec<f64>,
    settings: Settings,
    state: NormalState,
    approach: f64,
    /// The last increment's change of λ and of C λ and of the approach, for the predictor.
    change: Vec<f64>,
    displacement_change: Vec<f64>,
    last_step: f64,
    /// A starting guess of λ for the next normal solve ([`Contact::guess_normal`]).
    guess: Option<Vec<f64>>,
    tangential: Option<Tangential<T>>,
}

fn use_direct(method: Method, op: &dyn Compliance) -> bool {
    match method {
        Method::Direct => true,
        Method::Iterative => false,
        Method::Auto => op.matrix().is_some_and(|m| m.nrows() <= DIRECT_LIMIT),
    }
}

impl<N: Compliance, T: Compliance> Contact<N, T> {
    /// A frictionless contact: `normal` (one component) on points of initial separation
    /// `separation` [m].
    pub fn new(normal: N, separation: Vec<f64>, settings: Settings) -> Result<Self, ContactError> {
        let m = normal.points();
        if normal.components() != 1 || separation.len() != m {
            return Err(ContactError::Mismatch(format!(
                "the normal compliance has {} components on {m} points for {} separations (expected 1 component, one separation a point)",
                normal.components(),
                separation.len()
            )));
        }
        Ok(Self {
            normal,
            separation,
            settings,
            state: NormalState::zeros(m),
            approach: 0.0,
            change: vec![0.0; m],
            displacement_change: vec![0.0; m],
            last_step: 0.0,
            guess: None,
            tangential: None,
        })
    }

    /// Adds Coulomb friction μ = `friction` with the tangential compliance `op` (on the same
    /// points, as many components as `set` has).
    pub fn with_friction(mut self, op: T, set: FrictionSet, friction: f64) -> Result<Self, ContactError> {
        let (m, k) = (self.normal.points(), set.components());
        if op.points() != m || op.components() != k {
            return Err(ContactError::Mismatch(format!(
                "the tangential compliance has {} components on {} points; the set needs {k} on {m}",
                op.components(),
                op.points()
            )));
        }
        if !(friction.is_finite() && friction >= 0.0) {
            return Err(ContactError::Mismatch(format!(
                "friction {friction} is not a finite μ ≥ 0"
            )));
        }
        self.tangential = Some(Tangential {
            op,
            set,
            friction,
            scale: vec![1.0; m],
            state: CoulombState::zeros(m, k),
            slip: vec![0.0; m * k],
            change: vec![0.0; m * k],
            displacement_change: vec![0.0; m * k],
            last_shift: vec![0.0; k],
        });
        Ok(self)
    }

    /// Scales the Coulomb bound point by point, g_i = μ s_i λ_i (for a tangential multiplier
    /// that is not measured like the normal one, e.g. a Fourier amplitude).
    pub fn with_bound_scale(mut self, scale: Vec<f64>) -> Result<Self, ContactError> {
        match &mut self.tangential {
            Some(t) if scale.len() == t.scale.len() && scale.iter().all(|s| s.is_finite() && *s >= 0.0) => {
                t.scale = scale;
                Ok(self)
            }
            _ => Err(ContactError::Mismatch(
                "the bound scale needs friction and one finite s ≥ 0 a point".into(),
            )),
        }
    }

    /// Moves to approach `approach` [m] with the rigid tangential shift increment `shift` (one
    /// value a tangential component; ignored without friction).
    pub fn advance(&mut self, approach: f64, shift: &[f64]) -> Result<IncrementCost, ContactError> {
        let normal_iterations = self.solve_normal(approach)?;
        let tangential = self.solve_tangential(shift)?;
        Ok(IncrementCost {
            normal_iterations,
            tangential,
        })
    }

    fn solve_normal(&mut self, approach: f64) -> Result<usize, ContactError> {
        let opening: Vec<f64> = self.separation.iter().map(|h| h - approach).collect();
        let previous = self.state.clone();
        let step = approach - self.approach;
        self.approach = approach;
        let guess = self.guess.take();
        let iterations = if opening.iter().all(|&o| o >= 0.0) {
            // λ = 0 meets every condition where nothing overlaps.
            self.state.multipliers.fill(0.0);
            self.state.displacement.fill(0.0);
            0
        } else {
            let direct = use_direct(self.settings.method, &self.normal);
            if let Some(guess) = guess {
                self.state.multipliers = guess;
                self.normal
                    .apply(&self.state.multipliers, &mut self.state.displacement);
            } else if !direct {
                self.predict_normal(step);
            }
            let seed_stiffness = self
                .settings
                .seed_stiffness
                .unwrap_or(1.0 / self.normal.largest_eigenvalue());
            let mut problem = NormalProblem {
                op: &mut self.normal,
                opening: &opening,
                scale: approach.abs().max(f64::MIN_POSITIVE),
                tolerance: self.settings.normal_tolerance,
                max_iterations: self.settings.max_iterations,
                seed_stiffness,
            };
            if direct {
                problem.solve_direct(&mut self.state)?
            } else {
                problem.solve_iterative(&mut self.state)?
            }
        };
        for i in 0..self.change.len() {
            self.change[i] = self.state.multipliers[i] - previous.multipliers[i];
            self.displacement_change[i] = self.state.displacement[i] - previous.displacement[i];
        }
        self.last_step = step;
        Ok(iterations)
    }

    /// A starting guess λ ≥ 0 of the next normal solve in place of the last answer (e.g. a
    /// coarser discretisation's answer, interpolated: nested iteration). It changes where the
    /// solver starts, not the answer it converges to, nor the memory of the path (the change
    /// the next predictor extrapolates is still measured from the last answer).
    pub fn guess_normal(&mut self, multipliers: Vec<f64>) -> Result<(), ContactError> {
        if multipliers.len() != self.separation.len()
            || !multipliers.iter().all(|p| p.is_finite() && *p >= 0.0)
        {
            return Err(ContactError::Mismatch(format!(
                "a normal guess needs one finite λ ≥ 0 a point ({} points, got {} values)",
                self.separation.len(),
                multipliers.len()
            )));
        }
        self.guess = Some(multipliers);
        Ok(())
    }

    /// Starts the normal solve from the last answer extrapolated along the last change.
    fn predict_normal(&mut self, step: f64) {
        if self.last_step == 0.0 || step == 0.0 {
            return;
        }
        let ratio = step / self.last_step;
        let mut clamped = Vec::new();
        for i in 0..self.change.len() {
            let p = self.state.multipliers[i] + ratio * self.change[i];
            self.state.displacement[i] += ratio * self.displacement_change[i];
            if p < 0.0 {
                clamped.push((i, -p));
            }
            self.state.multipliers[i] = p.max(0.0);
        }
        update_after_changes(
            &mut self.normal,
            &clamped,
            &self.state.multipliers,
            &mut self.state.displacement,
        );
    }

    fn solve_tangential(&mut self, shift: &[f64]) -> Result<CoulombCost, ContactError> {
        let Some(t) = &mut self.tangential else {
            return Ok(CoulombCost::default());
        };
        let (m, k) = (self.separation.len(), t.set.components());
        if shift.len() != k {
            return Err(ContactError::Mismatch(format!(
                "{} shift components for a tangential set of {k}",
                shift.len()
            )));
        }
        let bound: Vec<f64> = (0..m)
            .map(|i| t.friction * t.scale[i] * self.state.multipliers[i])
            .collect();
        let previous = t.state.clone();
        let idle = shift.iter().all(|&s| s == 0.0) && previous.traction.iter().all(|&q| q == 0.0);
        let cost = if idle || bound.iter().all(|&g| g == 0.0) {
            // q = 0 solves the increment exactly: nothing shifts and nothing is loaded, or
            // nothing is in contact.
            t.state.traction.fill(0.0);
            t.state.displacement.fill(0.0);
            t.state.slipping.fill(false);
            CoulombCost::default()
        } else {
            let direct = use_direct(self.settings.method, &t.op);
            if !direct {
                predict_tangential(t, shift);
            }
            let mut problem = CoulombProblem {
                op: &mut t.op,
                bound: &bound,
                previous: &previous.traction,
                previous_displacement: &previous.displacement,
                shift,
                tolerance: self.settings.tangential_tolerance,
                max_iterations: self.settings.max_iterations,
            };
            let cost = if direct {
                problem.solve_direct(&mut t.state)?
            } else {
                problem.solve_iterative(&mut t.state)?
            };
            // Slipping points accumulate their slip; sticking points take the shift up
            // elastically (their residual slip is not accumulated).
            let slip = coulomb::slip_increment(&problem, &t.state);
            for i in (0..m).filter(|&i| t.state.slipping[i]) {
                for c in 0..k {
                    t.slip[c * m + i] += slip[c * m + i];
                }
            }
            cost
        };
        for i in (0..m).filter(|&i| bound[i] <= 0.0) {
            for c in 0..k {
                t.slip[c * m + i] = 0.0;
            }
        }
        for j in 0..m * k {
            t.change[j] = t.state.traction[j] - previous.traction[j];
            t.displacement_change[j] = t.state.displacement[j] - previous.displacement[j];
        }
        t.last_shift.copy_from_slice(shift);
        Ok(cost)
    }

    /// The gap opened: forgets everything (multipliers, tractions, slip, the predictor's last
    /// change); the next [`Contact::advance`] starts a contact from rest.
    pub fn release(&mut self) {
        self.state.multipliers.fill(0.0);
        self.state.displacement.fill(0.0);
        self.change.fill(0.0);
        self.displacement_change.fill(0.0);
        self.last_step = 0.0;
        if let Some(t) = &mut self.tangential {
            let (m, k) = (self.separation.len(), t.set.components());
            t.state = CoulombState::zeros(m, k);
            t.slip.fill(0.0);
            t.change.fill(0.0);
            t.displacement_change.fill(0.0);
            t.last_shift.fill(0.0);
        }
    }

    /// The multipliers λ (pressures or nodal forces).
    pub fn pressure(&self) -> &[f64] {
        &self.state.multipliers
    }

    /// The gaps o + Cλ [m] at the last approach.
    pub fn gaps(&self) -> Vec<f64> {
        let opening: Vec<f64> = self.separation.iter().map(|h| h - self.approach).collect();
        self.state.gaps(&opening)
    }

    /// The resultant normal force Σ a_i λ_i.
    pub fn normal_force(&self) -> f64 {
        resultant(self.normal.weights(), &self.state.multipliers, 0)
    }

    /// The tangential multipliers q (component-major; empty without friction).
    pub fn traction(&self) -> &[f64] {
        self.tangential.as_ref().map_or(&[], |t| &t.state.traction)
    }

    /// The resultant of tangential component `c` (0 without friction).
    pub fn tangential_force(&self, c: usize) -> f64 {
        self.tangential
            .as_ref()
            .map_or(0.0, |t| resultant(t.op.weights(), &t.state.traction, c))
    }

    /// Stick (true) or not at each point: in contact and strictly inside the friction set. Without
    /// friction every point in contact slips (μ = 0 holds nothing).
    pub fn stick(&self) -> Vec<bool> {
        let p = &self.state.multipliers;
        match &self.tangential {
            Some(t) if t.friction > 0.0 => (0..p.len())
                .map(|i| p[i] > 0.0 && t.scale[i] > 0.0 && !t.state.slipping[i])
                .collect(),
            _ => vec![false; p.len()],
        }
    }

    /// The slip accumulated since each point last came into contact (component-major; empty
    /// without friction) [m].
    pub fn slip(&self) -> &[f64] {
        self.tangential.as_ref().map_or(&[], |t| &t.slip)
    }

    /// |q_i| at point `i` (0 without friction).
    pub fn traction_magnitude(&self, i: usize) -> f64 {
        self.tangential
            .as_ref()
            .map_or(0.0, |t| norm_at(&t.state.traction, self.separation.len(), i))
    }

    /// The normal compliance.
    pub fn normal_operator(&self) -> &N {
        &self.normal
    }
}

/// Starts the tangential solve from the last answer extrapolated along the last change, by the
/// ratio of this shift to the last one.
fn predict_tangential<T: Compliance>(t: &mut Tangential<T>, shift: &[f64]) {
    let last: f64 = t.last_shift.iter().map(|s| s * s).sum();
    if last == 0.0 {
        return;
    }
    let ratio = shift.iter().zip(&t.last_shift).map(|(s, l)| s * l).sum::<f64>() / last;
    for j in 0..t.change.len() {
        t.state.traction[j] += ratio * t.change[j];
        t.state.displacement[j] += ratio * t.displacement_change[j];
    }
}
