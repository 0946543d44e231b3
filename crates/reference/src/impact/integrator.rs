//! Rigid-body dynamics of an impact: translation (normal and tangential) and rotation of both
//! bodies under a contact law, by velocity Verlet (kick–drift–kick).
//!
//! Per step of length h: the velocities and spins take half a step of the old accelerations;
//! the approach moves by the normal approach rate and the contact point by the relative
//! tangential velocity of the contact points (body 1's, v1x + R1ω1, minus body 2's,
//! v2x + R2ω2), each over h at those half-step velocities; the law gives the forces at the new
//! approach (the damping uses the half-step approach rate); the velocities take the other half
//! step. The normal direction is held fixed (the small-displacement assumption of Hertz and
//! Mindlin: the bodies' tangential travel during contact is a few contact radii at most, far
//! below the radii that would turn the normal).
//!
//! Forces: P ≥ 0 pushes body 1 along +z and body 2 along −z; Q acts on body 1 along −x and on
//! body 2 along +x, at the contact points, so that I1 dω1/dt = −R1 Q and I2 dω2/dt = +R2 Q (in
//! the per-body spin sign of `case` (spherecontact-impact)). A rigid flat has infinite mass and inertia.
//!
//! When the total normal force bounds friction ([`FrictionBound::Total`]), the law's friction is
//! scaled by total/elastic before each step, both at the step's end state.
//!
//! The contact starts at first touch (δn = 0) and ends when δn returns to zero; the end time is
//! interpolated linearly within the last step.

use super::law::{ContactLaw, Damping, FrictionBound, LawError};
use crate::impact::problem::Point;

/// The velocities of both bodies: centre (x, z) and spin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// Body 1: [v_x, v_z, ω].
    pub body1: [f64; 3],
    /// Body 2: [v_x, v_z, ω].
    pub body2: [f64; 3],
}

/// One recorded instant of an impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Time since first touch [s].
    pub time: f64,
    /// Approach δn [m].
    pub overlap: f64,
    /// Total normal force [N].
    pub normal_force: f64,
    /// Tangential force Q [N].
    pub tangential_force: f64,
    /// The velocities.
    pub motion: Motion,
}

/// What an integration returns: the extremes, the contact duration, the final velocities and a
/// thinned trace.
#[derive(Clone, Debug, PartialEq)]
pub struct Integration {
    /// Contact duration [s].
    pub duration: f64,
    /// Largest total normal force [N].
    pub max_normal_force: f64,
    /// Largest approach [m].
    pub max_overlap: f64,
    /// The velocities before the impact.
    pub before: Motion,
    /// The velocities after it.
    pub after: Motion,
    /// Every `stride`-th step (and the last), when asked for.
    pub trace: Vec<Sample>,
}

/// A failed integration.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum IntegrationError {
    /// The law failed.
    #[error(transparent)]
    Law(#[from] LawError),
    /// The contact outlasted the step budget.
    #[error("the contact did not end within {0} steps")]
    TooLong(usize),
    /// The bodies do not approach.
    #[error("the bodies do not approach (normal approach speed {0:.3e} m/s ≤ 0)")]
    NoApproach(f64),
}

/// The integration settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stepping {
    /// The time step [s].
    pub step: f64,
    /// At most this many steps.
    pub max_steps: usize,
    /// Record every `stride`-th step; 0: record nothing.
    pub stride: usize,
}

/// Inverse masses and inertias and the radii of the two bodies.
struct Inertia {
    inverse_mass: [f64; 2],
    inverse_inertia: [f64; 2],
    radius: [f64; 2],
}

impl Inertia {
    fn of(point: &Point) -> Self {
        Self {
            inverse_mass: [1.0 / point.body1.mass(), 1.0 / point.body2.mass()],
            inverse_inertia: [1.0 / point.body1.inertia(), 1.0 / point.body2.inertia()],
            radius: point.lever_arms(),
        }
    }

    /// The accelerations [a_x, a_z, α] of both bodies under normal force `p` and tangential `q`.
    fn accelerations(&self, p: f64, q: f64) -> Motion {
        let [m1, m2] = self.inverse_mass;
        let [i1, i2] = self.inverse_inertia;
        let [r1, r2] = self.radius;
        Motion {
            body1: [-q * m1, p * m1, -r1 * q * i1],
            body2: [q * m2, -p * m2, r2 * q * i2],
        }
    }
}

impl Motion {
    /// The initial velocities of `point`.
    pub fn of(point: &Point) -> Self {
        let b = |body: &crate::impact::problem::ImpactBody| [body.velocity[0], body.velocity[1], body.spin];
        Self {
            body1: b(&point.body1),
            body2: b(&point.body2),
        }
    }

    /// The relative tangential velocity of the contact points (body 1's minus body 2's), with
    /// the bodies' lever arms `radius` ([`Point::lever_arms`]).
    pub fn slip(&self, radius: [f64; 2]) -> f64 {
        (self.body1[0] + radius[0] * self.body1[2]) - (self.body2[0] + radius[1] * self.body2[2])
    }

    /// The rate of approach dδn/dt = v2z − v1z.
    pub fn approach_rate(&self) -> f64 {
        self.body2[1] - self.body1[1]
    }

    /// `self + scale × rates`, component by component.
    fn kicked(&self, rates: &Motion, scale: f64) -> Self {
        let add = |v: [f64; 3], a: [f64; 3]| [v[0] + scale * a[0], v[1] + scale * a[1], v[2] + scale * a[2]];
        Self {
            body1: add(self.body1, rates.body1),
            body2: add(self.body2, rates.body2),
        }
    }
}

/// Integrates the impact of `point` under `law` (and `damping`, if any) from first touch to
/// separation.
pub fn integrate(
    point: &Point,
    law: &mut dyn ContactLaw,
    damping: Option<&Damping>,
    stepping: Stepping,
) -> Result<Integration, IntegrationError> {
    let approach = point.approach_speed();
    if approach <= 0.0 || approach.is_nan() {
        return Err(IntegrationError::NoApproach(approach));
    }
    let inertia = Inertia::of(point);
    let h = stepping.step;
    let before = Motion::of(point);
    let mut motion = before;
    let mut acceleration = inertia.accelerations(0.0, 0.0);
    let (mut overlap, mut time) = (0.0_f64, 0.0_f64);
    let (mut max_normal_force, mut max_overlap) = (0.0_f64, 0.0_f64);
    let mut trace = Vec::new();
    let record = |sample: Sample, index: usize, trace: &mut Vec<Sample>| {
        if stepping.stride > 0 && index.is_multiple_of(stepping.stride) {
            trace.push(sample);
        }
    };
    record(
        Sample {
            time,
            overlap,
            normal_force: 0.0,
            tangential_force: 0.0,
            motion,
        },
        0,
        &mut trace,
    );
    law.release();
    for index in 1..=stepping.max_steps {
        let half = motion.kicked(&acceleration, 0.5 * h);
        let rate = half.approach_rate();
        let previous = overlap;
        overlap += rate * h;
        time += h;
        let (p, q) = if overlap > 0.0 {
            // The damping's rate at the step's end, predicted with the old accelerations (the
            // half-step rate would make the scheme first order in a damped impact).
            let predicted = half.kicked(&acceleration, 0.5 * h).approach_rate();
            if let Some(d) = damping.filter(|d| d.bound == FrictionBound::Total) {
                let elastic = law.elastic_normal(overlap);
                let scale = if elastic > 0.0 {
                    d.total(elastic, overlap, predicted) / elastic
                } else {
                    1.0
                };
                law.scale_friction(scale)?;
            }
            let forces = law.advance(overlap, half.slip(inertia.radius) * h)?;
            let p = damping.map_or(forces.normal, |d| d.total(forces.normal, overlap, predicted));
            (p, forces.tangential)
        } else {
            law.release();
            (0.0, 0.0)
        };
        acceleration = inertia.accelerations(p, q);
        motion = half.kicked(&acceleration, 0.5 * h);
        max_normal_force = max_normal_force.max(p);
        max_overlap = max_overlap.max(overlap);
        let sample = Sample {
            time,
            overlap,
            normal_force: p,
            tangential_force: q,
            motion,
        };
        if overlap <= 0.0 {
            // Separation within this step: δn fell from `previous` > 0 to `overlap` ≤ 0.
            let duration = time - h + h * previous / (previous - overlap);
            if stepping.stride > 0 {
                trace.push(sample);
            }
            return Ok(Integration {
                duration,
                max_normal_force,
                max_overlap,
                before,
                after: motion,
                trace,
            });
        }
        record(sample, index, &mut trace);
    }
    Err(IntegrationError::TooLong(stepping.max_steps))
}
