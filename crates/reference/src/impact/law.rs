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
//! a linear spring; for Hertz it does not (its restitution is measured, docs/impact.md). The DEM
//! codes' own damping laws differ from it only in the coefficient of δn^{1/4} δ̇, and they bound
//! friction by the total normal force: `code_rule` (spherecontact-impact) builds their [`Damping`].

use crate::incremental::{Increment, IncrementalSolver, NormalState, TangentialLaw};
use crate::mdr::SpringBed;
use spherecontact_model::domain::Domain;
use spherecontact_model::hertz::Hertz;
use spherecontact_model::pair::ContactPair;
use spherecontact_model::path::{LoadingPath, Position};
use spherecontact_model::scene::{FieldPositions, Scene};

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

    /// The elastic normal force at approach `delta_n`, without changing the state [N].
    fn elastic_normal(&self, delta_n: f64) -> f64;

    /// Friction μ × `scale` for the next step (the total normal force over the elastic one, when
    /// the total bounds friction).
    fn scale_friction(&mut self, scale: f64) -> Result<(), LawError>;
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
    /// A law whose friction is fixed at its making was asked to bound it by the total force.
    #[error("this law bounds friction by the elastic normal force only (asked for μ × {0})")]
    FixedFriction(f64),
}

/// MDR's spring bed (`crate::mdr`) as the contact law.
pub struct MdrLaw {
    bed: SpringBed,
    friction: f64,
}

impl MdrLaw {
    /// A bed of `springs` springs whose window holds contact radii up to `max_contact_radius`.
    pub fn new(pair: &ContactPair, friction: f64, max_contact_radius: f64, springs: usize) -> Self {
        Self {
            bed: SpringBed::with_window(pair, friction, max_contact_radius, springs),
            friction,
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

    fn elastic_normal(&self, delta_n: f64) -> f64 {
        self.bed.normal_force(delta_n).0
    }

    /// Each spring's Coulomb limit becomes μ × `scale` × its normal force: the total normal
    /// pressure taken as the elastic one scaled (the damping pressure distributed like it).
    fn scale_friction(&mut self, scale: f64) -> Result<(), LawError> {
        self.bed.set_friction(self.friction * scale);
        Ok(())
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

    fn elastic_normal(&self, delta_n: f64) -> f64 {
        self.hertz.force(delta_n)
    }

    fn scale_friction(&mut self, scale: f64) -> Result<(), LawError> {
        if scale == 1.0 {
            Ok(())
        } else {
            Err(LawError::FixedFriction(scale))
        }
    }
}

/// Which normal force bounds friction under damping.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrictionBound {
    /// μ times the elastic normal force (the harness's laws).
    Elastic,
    /// μ times the total (elastic + viscous, clamped at zero) normal force (LAMMPS, YADE).
    Total,
}

/// A viscous normal damping c δn^{1/4} δ̇ (Tsuji's form) and the friction bound that goes with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Damping {
    /// c: the coefficient of δn^{1/4} δ̇ [N s/m^{5/4}].
    coefficient: f64,
    /// Which normal force bounds friction.
    pub bound: FrictionBound,
}

impl Damping {
    /// The harness's damping of restitution `e` (0 < e ≤ 1) for effective mass `mass` and
    /// `hertz` (see the module doc): c = 2 √(5/6) |β| √(m* 2E* √R*), friction bounded by the
    /// elastic force.
    pub fn new(restitution: f64, mass: f64, hertz: &Hertz) -> Self {
        let log = restitution.ln();
        let beta = log / (log * log + std::f64::consts::PI.powi(2)).sqrt();
        let stiffness_scale = 2.0 * hertz.effective_modulus * hertz.effective_radius.sqrt();
        Self {
            coefficient: 2.0 * (5.0_f64 / 6.0).sqrt() * beta.abs() * (stiffness_scale * mass).sqrt(),
            bound: FrictionBound::Elastic,
        }
    }

    /// A damping of coefficient `coefficient` [N s/m^{5/4}] with friction bounded by `bound`.
    pub fn with_coefficient(coefficient: f64, bound: FrictionBound) -> Self {
        Self { coefficient, bound }
    }

    /// c, the coefficient of δn^{1/4} δ̇ [N s/m^{5/4}].
    pub fn coefficient(&self) -> f64 {
        self.coefficient
    }

    /// The total normal force: `elastic` plus the viscous force at approach `delta_n` and
    /// approach rate `rate` = dδn/dt, clamped at zero.
    pub fn total(&self, elastic: f64, delta_n: f64, rate: f64) -> f64 {
        (elastic + self.coefficient * delta_n.max(0.0).powf(0.25) * rate).max(0.0)
    }
}
