//! Cattaneo–Mindlin: tangential loading of a Hertz contact at constant normal load, with
//! Masing's rules for unloading and reloading (Mindlin 1949; Mindlin & Deresiewicz 1953;
//! Johnson 1985, §7.1).
//!
//! At normal load P and contact radius c, a tangential displacement δ from a virgin state gives
//!
//! ```text
//! Q(δ) = f(δ) = μP [1 − (1 − δ/δs)^{3/2}]   for 0 ≤ δ ≤ δs,   μP beyond (gross sliding)
//! δs   = 3μP / (16 c G*)                    (G*: Mindlin's effective shear modulus)
//! stick radius  c_s = c (1 − Q/μP)^{1/3}
//! ```
//! so that dQ/dδ at δ = 0 is K_T0 = 8 G* c. Masing: from a reversal point (δr, Qr) the branch is
//! Q = Qr ± 2 f(|δ − δr|/2), with stick radius c (1 − |Q − Qr|/2μP)^{1/3}. The memory rules
//! of Masing and Madelung close the loops: a branch that reaches the reversal point before its
//! own start continues on the branch that led there, and the first branch off the virgin curve
//! rejoins the virgin curve at the mirror of its start.
//!
//! The normal load must be constant while the tangential displacement changes; this solver
//! reports itself not applicable otherwise (MDR covers varying loads).

use crate::history::{History, Metadata, StepResult};
use crate::scene::Scene;
use crate::solver::{SolveError, Solver};

/// The virgin tangential curve of one Hertz contact.
#[derive(Clone, Copy, Debug)]
struct VirginCurve {
    /// Full-sliding force μP [N].
    sliding_force: f64,
    /// Displacement at the onset of gross sliding δs [m].
    sliding_displacement: f64,
}

impl VirginCurve {
    /// f(δ) for δ ≥ 0.
    fn force(&self, delta: f64) -> f64 {
        if delta >= self.sliding_displacement {
            return self.sliding_force;
        }
        self.sliding_force * (1.0 - (1.0 - delta / self.sliding_displacement).powf(1.5))
    }
}

/// A reversal point of the tangential history.
#[derive(Clone, Copy, Debug)]
struct Reversal {
    delta: f64,
    force: f64,
}

/// Masing's hysteresis with Masing–Madelung memory over a virgin curve.
#[derive(Debug)]
struct Masing {
    curve: VirginCurve,
    /// Reversal points still remembered, oldest first.
    reversals: Vec<Reversal>,
    /// Current displacement, force and direction of motion (±1, 0 before any motion).
    delta: f64,
    force: f64,
    direction: f64,
}

impl Masing {
    fn new(curve: VirginCurve) -> Self {
        Self {
            curve,
            reversals: Vec::new(),
            delta: 0.0,
            force: 0.0,
            direction: 0.0,
        }
    }

    /// Moves to displacement `delta` and returns (Q, |Q − Q_branch start| / 2 on a Masing branch,
    /// or |Q| on the virgin curve): the load the stick zone has shed.
    fn move_to(&mut self, delta: f64) -> (f64, f64) {
        let direction = (delta - self.delta).signum();
        if delta != self.delta {
            if self.direction != 0.0 && direction != self.direction {
                self.reversals.push(Reversal {
                    delta: self.delta,
                    force: self.force,
                });
            }
            self.direction = direction;
            self.forget_closed_loops(delta);
        }
        self.delta = delta;
        let (force, shed) = match self.reversals.last() {
            Some(r) => {
                let half = self.curve.force(0.5 * (delta - r.delta).abs());
                (r.force + direction_of(delta - r.delta) * 2.0 * half, half)
            }
            None => {
                let f = self.curve.force(delta.abs());
                (f.copysign(delta), f)
            }
        };
        self.force = force;
        (force, shed)
    }

    /// Pops the reversal points that the motion to `delta` has passed.
    fn forget_closed_loops(&mut self, delta: f64) {
        while let Some(&last) = self.reversals.last() {
            let target = match self.reversals.len() {
                1 => -last.delta, // the mirror point on the virgin curve
                n => self.reversals[n - 2].delta,
            };
            if self.direction * (delta - target) <= 0.0 {
                break;
            }
            let pop = if self.reversals.len() == 1 { 1 } else { 2 };
            self.reversals.truncate(self.reversals.len() - pop);
        }
    }
}

/// The sign of a non-zero displacement change (+1 for zero).
fn direction_of(change: f64) -> f64 {
    if change < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// The Cattaneo–Mindlin closed form as a solver.
pub struct CattaneoMindlin;

impl CattaneoMindlin {
    /// The first step at which the tangential displacement leaves its starting value.
    fn tangential_start(scene: &Scene) -> Result<usize, SolveError> {
        let steps = scene.steps();
        let start = steps
            .iter()
            .position(|s| s.delta_t != steps[0].delta_t)
            .unwrap_or(steps.len());
        let base = if start > 0 { steps[start - 1] } else { steps[0] };
        if let Some(bad) = steps[start..].iter().find(|s| s.delta_n != base.delta_n) {
            return Err(SolveError::NotApplicable(format!(
                "cattaneo-mindlin needs a constant normal approach once tangential loading starts \
                 (δn = {:.4e} m at step {}, {:.4e} m at step {})",
                base.delta_n, base.index, bad.delta_n, bad.index
            )));
        }
        if start < steps.len() && base.delta_n <= 0.0 {
            return Err(SolveError::NotApplicable(format!(
                "tangential loading starts at step {} with the gap open (δn = {:.4e} m)",
                base.index, base.delta_n
            )));
        }
        Ok(start)
    }
}

impl Solver for CattaneoMindlin {
    fn name(&self) -> &'static str {
        "cattaneo-mindlin"
    }

    fn description(&self) -> &'static str {
        "Cattaneo–Mindlin at constant normal load, Masing unloading and reloading"
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let start = Self::tangential_start(scene)?;
        let hertz = scene.hertz();
        let steps = scene.steps();
        let origin = steps[0].delta_t;
        let mut masing: Option<Masing> = None;
        let rows = steps
            .iter()
            .map(|step| {
                let (p, c) = (hertz.force(step.delta_n), hertz.contact_radius(step.delta_n));
                let mut row = StepResult {
                    normal_force: Some(p),
                    contact_radius: Some(c),
                    peak_pressure: Some(hertz.peak_pressure(step.delta_n)),
                    tangential_force: Some(0.0),
                    stick_radius: (c > 0.0).then_some(c),
                    ..StepResult::at(step)
                };
                if step.index >= start {
                    let sliding_force = scene.friction * p;
                    let state = masing.get_or_insert_with(|| {
                        Masing::new(VirginCurve {
                            sliding_force,
                            sliding_displacement: 3.0 * sliding_force
                                / (16.0 * c * scene.pair.mindlin_shear_modulus()),
                        })
                    });
                    let (q, shed) = state.move_to(step.delta_t - origin);
                    row.tangential_force = Some(q);
                    row.stick_radius = Some(if sliding_force > 0.0 && shed < sliding_force {
                        c * (1.0 - shed / sliding_force).cbrt()
                    } else {
                        0.0
                    });
                }
                row
            })
            .collect();
        Ok(History {
            metadata: Metadata {
                model: "Cattaneo–Mindlin: Hertz contact, constant normal load, Masing hysteresis".into(),
                resolution: "closed form".into(),
                ..Metadata::default()
            },
            steps: rows,
            fields: Vec::new(),
        })
    }
}
