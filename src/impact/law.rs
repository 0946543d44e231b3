//! The contact laws an impact integrates: MDR (exact Mindlin–Deresiewicz, the reference) and
//! the incremental DEM laws, each with the same optional normal damping.
//!
//! A law is driven by the approach δn at the end of each step and the tangential displacement
//! increment of the contact point over the step (body 1's relative to body 2's); it returns the
//! elastic normal force P_e and the tangential force Q (Q > 0 resists a displacement towards +x
//! of body 1's contact point). The laws' friction limit is bounded by the elastic normal force
//! (MDR: each spring's μE*w; DEM laws: μP_e), whatever the damping.
//!
//! **Damping** (when a restitution e < 1 is prescribed): the viscous normal force of Tsuji et al.
//! (1992) as LIGGGHTS and LAMMPS (`damping coeff_restitution`) write it,
//!
//! ```text
//! F_d = −2 √(5/6) β √(S_n m*) δ̇,   β = ln e / √(ln² e + π²),   S_n = 2 E* √(R* δn)
//! ```
//! added to P_e, the total clamped at zero (no attraction). This law returns e exactly only for
//! a linear spring; for Hertz it does not (its restitution is measured, docs/impact.md).

use crate::analytic::incremental::{Increment, IncrementalSolver, NormalState, TangentialLaw};
use crate::analytic::mdr::SpringBed;
use crate::domain::Domain;
use crate::hertz::Hertz;
use crate::pair::ContactPair;
use crate::path::{LoadingPath, Position};
use crate::scene::{FieldPositions, Scene};

/// The forces of a law after one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forces {
    /// Elastic normal force P_e [N].
    pub normal: f64,
    /// Tangential force Q [N].
    pub tangential: f64,
}

/// A contact law as the impact integrator drives it.
pub trait ContactLaw {
    /// The forces after a step to approach `delta_n` > 0 with tangential displacement increment
    /// `increment_t` [m].
    fn advance(&mut self, delta_n: f64, increment_t: f64) -> Result<Forces, LawError>;

    /// The gap opened: the contact forgets its history.
    fn release(&mut self);
}

/// A law that cannot continue.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum LawError {
    /// The approach went beyond the MDR bed's window.
    #[error("the approach {approach:.3e} m left the MDR spring window (reach {reach:.3e} m)")]
    OutsideWindow {
        /// The approach [m].
        approach: f64,
        /// The window's reach [m].
        reach: f64,
    },
}

/// MDR's spring bed (`crate::analytic::mdr`) as the contact law.
pub struct MdrLaw {
    bed: SpringBed,
}

impl MdrLaw {
    /// A bed of `springs` springs whose window holds contact radii up to `max_contact_radius`.
    pub fn new(pair: &ContactPair, friction: f64, max_contact_radius: f64, springs: usize) -> Self {
        Self {
            bed: SpringBed::with_window(pair, friction, max_contact_radius, springs),
        }
    }
}

impl ContactLaw for MdrLaw {
    fn advance(&mut self, delta_n: f64, increment_t: f64) -> Result<Forces, LawError> {
        if delta_n > self.bed.reach() {
            return Err(LawError::OutsideWindow {
                approach: delta_n,
                reach: self.bed.reach(),
            });
        }
        let state = self.bed.advance(delta_n, increment_t);
        Ok(Forces {
            normal: state.normal_force,
            tangential: state.tangential_force,
        })
    }

    fn release(&mut self) {
        self.bed.release();
    }
}

/// An incremental DEM law with Hertz's normal force.
pub struct DemLaw {
    law: Box<dyn TangentialLaw>,
    hertz: Hertz,
    /// The normal state at the end of the previous step in contact; `None` when the contact is
    /// new (it starts with Q = 0, the incremental driver's rule: zero radius, zero stiffness).
    before: Option<NormalState>,
}

impl DemLaw {
    /// The law `solver` makes, for `pair` and `friction`.
    pub fn new(solver: &IncrementalSolver, pair: &ContactPair, friction: f64) -> Self {
        Self {
            law: (solver.make_law)(&law_scene(pair, friction)),
            hertz: Hertz::of(pair),
            before: None,
        }
    }
}

/// The scene the DEM laws are made from: they read its pair and friction only.
fn law_scene(pair: &ContactPair, friction: f64) -> Scene {
    let origin = Position {
        delta_n: 0.0,
        delta_t: 0.0,
    };
    Scene {
        name: "impact".into(),
        pair: *pair,
        friction,
        path: LoadingPath::try_new(vec![origin], Vec::new()).expect("one position is a path"),
        domain: Domain::default(),
        fields: FieldPositions::Every,
    }
}

impl ContactLaw for DemLaw {
    fn advance(&mut self, delta_n: f64, increment_t: f64) -> Result<Forces, LawError> {
        let after = NormalState {
            force: self.hertz.force(delta_n),
            radius: self.hertz.contact_radius(delta_n),
        };
        let tangential = match self.before {
            Some(before) => self.law.advance(&Increment {
                before,
                after,
                delta_t: increment_t,
            }),
            None => {
                self.law.reset();
                0.0
            }
        };
        self.before = Some(after);
        Ok(Forces {
            normal: after.force,
            tangential,
        })
    }

    fn release(&mut self) {
        self.law.reset();
        self.before = None;
    }
}

/// Tsuji's viscous normal damping for a prescribed restitution (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Damping {
    /// 2 √(5/6) |β| √(m* 2E* √R*): the coefficient of δn^{1/4} δ̇ [N s/m^{5/4}].
    coefficient: f64,
}

impl Damping {
    /// The damping of restitution `e` (0 < e ≤ 1; none at 1) for effective mass `mass` and `hertz`.
    pub fn new(restitution: f64, mass: f64, hertz: &Hertz) -> Self {
        let log = restitution.ln();
        let beta = log / (log * log + std::f64::consts::PI.powi(2)).sqrt();
        let stiffness_scale = 2.0 * hertz.effective_modulus * hertz.effective_radius.sqrt();
        Self {
            coefficient: 2.0 * (5.0_f64 / 6.0).sqrt() * beta.abs() * (stiffness_scale * mass).sqrt(),
        }
    }

    /// The total normal force: `elastic` plus the viscous force at approach `delta_n` and
    /// approach rate `rate` = dδn/dt, clamped at zero.
    pub fn total(&self, elastic: f64, delta_n: f64, rate: f64) -> f64 {
        (elastic + self.coefficient * delta_n.max(0.0).powf(0.25) * rate).max(0.0)
    }
}
