//! The shared driver of the incremental DEM tangential laws.
//!
//! A DEM code advances a contact by increments: the normal force comes from Hertz at the new
//! approach, and a tangential law updates the tangential force from the old one, the tangential
//! displacement increment Δδt and the change of normal state. This driver walks a scene's path
//! that way for any [`TangentialLaw`], so every law sees exactly the same increments.
//!
//! Contact rules, the same for every law: while the gap is open the force is zero and the law's
//! history is cleared (the path walker's rule, [`spherecontact_model::driver`]); on the increment that closes
//! the gap the contact starts with Q = 0 (the contact had zero radius, hence zero stiffness, at
//! the increment's start).

use spherecontact_model::driver::{self, PathIncrement, PathModel};
use spherecontact_model::hertz::Hertz;
use spherecontact_model::history::{History, Metadata, StepResult};
use spherecontact_model::path::Step;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};

/// The Hertz normal state at one end of an increment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalState {
    /// Normal force P [N].
    pub force: f64,
    /// Contact radius c [m].
    pub radius: f64,
}

/// One increment of a contact that is closed at both of its ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Increment {
    /// The normal state at the start.
    pub before: NormalState,
    /// The normal state at the end.
    pub after: NormalState,
    /// The tangential displacement increment Δδt [m].
    pub delta_t: f64,
}

/// An incremental tangential force–displacement law.
pub trait TangentialLaw {
    /// Advances the law over `increment` and returns the tangential force at its end [N].
    fn advance(&mut self, increment: &Increment) -> f64;

    /// Forgets the contact's history (the gap opened).
    fn reset(&mut self);
}

/// An incremental law driven along a scene's path: Hertz normal force, the law's tangential force.
pub struct IncrementalSolver {
    /// The command-line name.
    pub name: &'static str,
    /// One line: the law and its source.
    pub description: &'static str,
    /// Makes the law for a scene (its material constants and friction).
    pub make_law: fn(&Scene) -> Box<dyn TangentialLaw>,
}

impl Solver for IncrementalSolver {
    fn name(&self) -> &'static str {
        self.name
    }

    fn kind(&self) -> Kind {
        Kind::DemLaw
    }

    fn description(&self) -> &'static str {
        self.description
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        Some(spherecontact_model::cost::law(scene.steps().len()))
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let steps = scene.steps();
        let mut walker = Walker {
            law: (self.make_law)(scene),
            hertz: scene.hertz(),
        };
        let rows = driver::walk(scene, &mut walker)?;
        Ok(History {
            metadata: Metadata {
                model: format!(
                    "Hertz normal force; incremental tangential law: {}",
                    self.description
                ),
                resolution: format!("{} increments", steps.len().saturating_sub(1)),
                warnings: driver::never_closed(scene, true)
                    .map(|_| vec![driver::NEVER_CLOSES.to_string()])
                    .unwrap_or_default(),
                ..Metadata::default()
            },
            steps: rows,
            fields: Vec::new(),
        })
    }
}

/// A law as the path walker drives it, with Hertz's normal force.
struct Walker {
    law: Box<dyn TangentialLaw>,
    hertz: Hertz,
}

impl Walker {
    fn normal_at(&self, delta_n: f64) -> NormalState {
        NormalState {
            force: self.hertz.force(delta_n),
            radius: self.hertz.contact_radius(delta_n),
        }
    }
}

impl PathModel for Walker {
    fn advance(&mut self, increment: &PathIncrement) -> Result<StepResult, SolveError> {
        let step = increment.step;
        let after = self.normal_at(step.delta_n);
        let tangential = match increment.before {
            Some(before) if !increment.closing() => self.law.advance(&Increment {
                before: self.normal_at(before.delta_n),
                after,
                delta_t: increment.shift(),
            }),
            _ => {
                // The contact starts with Q = 0: it had zero radius, hence zero stiffness, at the
                // start of the increment that closes the gap.
                self.law.reset();
                0.0
            }
        };
        Ok(StepResult {
            normal_force: Some(after.force),
            tangential_force: Some(tangential),
            contact_radius: Some(after.radius),
            peak_pressure: Some(self.hertz.peak_pressure(step.delta_n)),
            ..StepResult::at(step)
        })
    }

    fn release(&mut self, _step: &Step) {
        self.law.reset();
    }
}

/// Clamps a tangential force to the Coulomb limit |Q| ≤ μP.
pub fn coulomb_cap(force: f64, friction: f64, normal_force: f64) -> f64 {
    let limit = friction * normal_force.max(0.0);
    force.clamp(-limit, limit)
}
