//! The quantities of an impact's outcome (the columns of `DIR/<solver>.csv`), from an
//! integration, with their sign conventions (docs/impact.md):
//!
//! - `normal_restitution` e_n = (v1z − v2z)_after / (v2z − v1z)_before: separation speed over
//!   approach speed;
//! - `tangential_restitution` e_t = s_after / s_before, s the relative tangential velocity of
//!   the contact points (body 1's v_x + R1ω1 minus body 2's): negative when the contact point's
//!   tangential motion reverses; undefined when s_before = 0;
//! - `rebound_angular_velocity`: ω1 after the impact, signed so that ω1 > 0 moves body 1's
//!   contact point towards +x;
//! - `rebound_angle`: atan2(s_after, (v1z − v2z)_after), the angle of the contact point's
//!   rebound velocity (relative to body 2's contact point) from the outward normal;
//!   undefined when that velocity is zero.

use super::integrator::Integration;
use crate::impact::problem::{Point, Quantity};

/// A slip speed below this fraction of the approach speed counts as none (e_t undefined):
/// rounding in the velocities is ~1e-16 of them; 1e-12 leaves four orders of margin.
const NO_SLIP: f64 = 1e-12;

/// The outcome of one impact: a value (or none) per quantity.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Outcome {
    values: [Option<f64>; 7],
}

impl Outcome {
    /// The outcome with these values, in the order of [`Quantity::ALL`] (a sweep table's row,
    /// [`super::table`]); a non-finite value is none.
    pub fn from_values(values: [Option<f64>; 7]) -> Self {
        Self {
            values: values.map(|v| v.filter(|v| v.is_finite())),
        }
    }

    /// The outcome of `integration` of `point`.
    pub fn of(point: &Point, integration: &Integration) -> Self {
        let arms = point.lever_arms();
        let approach = integration.before.approach_rate();
        let separation = -integration.after.approach_rate();
        let (slip_before, slip_after) = (integration.before.slip(arms), integration.after.slip(arms));
        let tangential = (slip_before.abs() > NO_SLIP * approach).then(|| slip_after / slip_before);
        let angle = (slip_after != 0.0 || separation != 0.0).then(|| slip_after.atan2(separation));
        let mut values = [None; 7];
        for (slot, quantity) in values.iter_mut().zip(Quantity::ALL) {
            *slot = match quantity {
                Quantity::ContactDuration => Some(integration.duration),
                Quantity::MaxNormalForce => Some(integration.max_normal_force),
                Quantity::MaxOverlap => Some(integration.max_overlap),
                Quantity::NormalRestitution => Some(separation / approach),
                Quantity::TangentialRestitution => tangential,
                Quantity::ReboundAngularVelocity => Some(integration.after.body1[2]),
                Quantity::ReboundAngle => angle,
            }
            .filter(|v| v.is_finite());
        }
        Self { values }
    }

    /// The value of `quantity`, if defined.
    pub fn get(&self, quantity: Quantity) -> Option<f64> {
        // The variants are declared in the order of `Quantity::ALL`.
        self.values[quantity as usize]
    }

    /// True when every defined value is finite (as every outcome computed is: a run read back
    /// from a run file is checked for it, `merge` (spherecontact-verify)).
    pub fn is_finite(&self) -> bool {
        self.values.iter().flatten().all(|v| v.is_finite())
    }
}
