//! The incremental Mindlin–Deresiewicz tangential relation that the Thornton and the
//! Zhang & Vu-Quoc laws share: Cattaneo–Mindlin–Masing tangent stiffness, the oblique-increment
//! term μΔN(1 − θ), and turning points that drift with the normal force.
//!
//! 1D only: δt and Q act along one fixed axis and are signed; a 3D law would project on the
//! current force direction.
//!
//! # The increment (Mindlin & Deresiewicz 1953; Thornton 1991; Thornton & Yin 1991)
//!
//! With k0 = 8G*a (Mindlin's initial stiffness at contact radius a), d = ±1 the direction of the
//! tangential motion and θ the stick-zone factor of the branch being followed, an increment
//! (Δδ, ΔN) changes the tangential force by
//!
//! ```text
//! ΔT = k0 Δδ                               if ΔN > 0 and k0|Δδ| ≤ μΔN   (no slip)
//! ΔT = k0 θ Δδ + d μΔN (1 − θ)             otherwise                     (slip annulus)
//! ```
//! The second line is Mindlin & Deresiewicz's oblique increment inverted for ΔT: the increment is
//! a proportional part μΔN, taken with no slip (compliance 1/k0), plus a tangential part
//! ΔT − dμΔN at constant normal load (compliance 1/(k0θ)); so Δδ = dμΔN/k0 + (ΔT − dμΔN)/(k0θ).
//! Written with (−1)^k for loading (k = 0), unloading (1) and reloading (2) it is Thornton's form
//! ΔT = 8G*aθΔδ + (−1)^k μΔN(1 − θ). The first line is M&D's case |ΔT| ≤ μΔN (no slip anywhere);
//! the two lines meet at k0|Δδ| = μΔN, so the force is continuous in Δδ.
//!
//! The stick factor θ is the cube root of the unslipped fraction of the branch's load capacity:
//!
//! ```text
//! virgin (loading):            θ³ = 1 − (dT + s)/(μN)
//! from turning point T_r:      θ³ = 1 − (d(T − T_r) + 2s)/(2μN)      (unloading, reloading)
//! ```
//! At constant N (s = 0) these are exact: Cattaneo–Mindlin's virgin curve
//! Q = μP[1 − (1 − δ/δs)^{3/2}] has dQ/dδ = 8G*a(1 − Q/μP)^{1/3}, and Masing's branch
//! Q = Q_r ± 2f(|δ − δ_r|/2) has dQ/dδ = 8G*a(1 − |Q − Q_r|/2μP)^{1/3}. How N, a and s are taken
//! is the [`Evaluation`]. Turning points drift with the normal force, T_r ← T_r + d_r μΔN (d_r: the
//! direction of the motion that ended at T_r), Thornton's (1991) T* ← T* + μΔN, T** ← T** − μΔN,
//! which keeps the stick factors consistent when N changes.
//!
//! Branches: a reversal of the motion records the force as a turning point; a branch that reaches
//! the turning point before its own start closes its loop (Masing–Madelung), and the first branch
//! off the virgin curve becomes the virgin curve of the opposite direction at −T_r. How many
//! turning points are remembered is the [`Memory`]. Every increment ends with the Coulomb cap
//! |T| ≤ μN. θ³ is clamped to [0, 1]: above 1 it would mean a stiffness beyond k0 (it happens
//! when ΔN < 0 at small T with the shift s, and θ = 1 is then the no-slip limit), below 0 a root
//! of a negative number (only after the cap or by rounding).
//!
//! Sources: Mindlin & Deresiewicz (1953, J. Appl. Mech. 20, 327) for the oblique increments and
//! their no-slip case (also Johnson 1985, *Contact Mechanics*, ch. 7); Thornton (1991) for the
//! loading / unloading / reloading form with T*, T** and their drift.

use super::incremental::{coulomb_cap, Increment, TangentialLaw};
use spherecontact_model::scene::Scene;

/// Which turning points a law remembers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Memory {
    /// Thornton's T* and T**: a reversal during reloading starts a new unloading from the current
    /// force and forgets the older loop.
    TwoTurningPoints,
    /// Every turning point, with Masing–Madelung loop closure (nested loops are remembered).
    Masing,
}

/// Where in the increment the stiffness and stick factor are evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluation {
    /// Thornton's form: a and N at the end of the increment, with the shift s = μΔN in θ.
    EndWithShift,
    /// The force-driven Mindlin–Deresiewicz compliance of the state at the start of the
    /// increment: a and N at the start, s = 0.
    Start,
}

/// A turning point of the tangential history.
#[derive(Clone, Copy, Debug, PartialEq)]
struct TurningPoint {
    /// The force at the reversal [N] (drifts with N).
    force: f64,
    /// The direction (±1) of the motion that ended here.
    direction: f64,
}

/// The state of an incremental Mindlin–Deresiewicz law.
#[derive(Clone, Debug)]
pub struct MdIncremental {
    /// Mindlin's effective shear modulus G* [Pa].
    shear_modulus: f64,
    /// Friction coefficient μ.
    friction: f64,
    memory: Memory,
    evaluation: Evaluation,
    /// Current tangential force T [N].
    force: f64,
    /// Current direction of motion (±1; 0 before any motion).
    direction: f64,
    /// Remembered turning points, oldest first.
    turning_points: Vec<TurningPoint>,
}

impl MdIncremental {
    /// A law for a scene's pair and friction, with no history.
    pub fn new(scene: &Scene, memory: Memory, evaluation: Evaluation) -> Self {
        Self {
            shear_modulus: scene.pair.mindlin_shear_modulus(),
            friction: scene.friction,
            memory,
            evaluation,
            force: 0.0,
            direction: 0.0,
            turning_points: Vec::new(),
        }
    }

    /// Records a reversal of the motion into `direction`.
    fn reverse(&mut self, direction: f64) {
        if self.memory == Memory::TwoTurningPoints && self.turning_points.len() == 2 {
            self.turning_points.clear(); // Thornton: a new T*, the older loop forgotten
        }
        self.turning_points.push(TurningPoint {
            force: self.force,
            direction: self.direction,
        });
        self.direction = direction;
    }

    /// θ for motion in `direction` at normal force `normal` with shift `shift` (μΔN or 0).
    fn stick_factor(&self, direction: f64, normal: f64, shift: f64) -> f64 {
        let capacity = self.friction * normal;
        if capacity <= 0.0 {
            return 0.0;
        }
        let used = match self.turning_points.last() {
            None => (direction * self.force + shift) / capacity,
            Some(tp) => (direction * (self.force - tp.force) + 2.0 * shift) / (2.0 * capacity),
        };
        (1.0 - used).clamp(0.0, 1.0).cbrt()
    }

    /// Pops the turning points whose loops the current branch has closed.
    fn close_loops(&mut self) {
        while let Some(last) = self.turning_points.last() {
            let n = self.turning_points.len();
            let target = if n == 1 {
                -last.force // the mirror point on the virgin curve
            } else {
                self.turning_points[n - 2].force
            };
            if self.direction * (self.force - target) < 0.0 {
                break;
            }
            self.turning_points.truncate(if n == 1 { 0 } else { n - 2 });
        }
    }
}

impl TangentialLaw for MdIncremental {
    fn advance(&mut self, increment: &Increment) -> f64 {
        let (before, after) = (increment.before, increment.after);
        if self.friction * after.force <= 0.0 {
            self.reset(); // no friction capacity: no force, nothing to remember
            return 0.0;
        }
        let delta = increment.delta_t;
        let direction = if delta == 0.0 {
            if self.direction == 0.0 {
                1.0
            } else {
                self.direction
            }
        } else {
            delta.signum()
        };
        if delta != 0.0 {
            if self.direction != 0.0 && direction != self.direction {
                self.reverse(direction);
            }
            self.direction = direction;
        }
        let mu_dn = self.friction * (after.force - before.force);
        let (state, shift) = match self.evaluation {
            Evaluation::EndWithShift => (after, mu_dn),
            Evaluation::Start => (before, 0.0),
        };
        let k0 = 8.0 * self.shear_modulus * state.radius;
        let change = if mu_dn > 0.0 && (k0 * delta).abs() <= mu_dn {
            k0 * delta
        } else {
            let theta = self.stick_factor(direction, state.force, shift);
            k0 * theta * delta + direction * mu_dn * (1.0 - theta)
        };
        self.force = coulomb_cap(self.force + change, self.friction, after.force);
        for tp in &mut self.turning_points {
            tp.force += tp.direction * mu_dn;
        }
        if self.direction != 0.0 {
            self.close_loops();
        }
        self.force
    }

    fn reset(&mut self) {
        self.force = 0.0;
        self.direction = 0.0;
        self.turning_points.clear();
    }
}

/// Scenes and increments for the laws' unit tests.
#[cfg(test)]
pub(crate) mod fixtures {
    use super::super::incremental::{Increment, NormalState};
    use spherecontact_model::fixtures::paper_pair;
    use spherecontact_model::path::{LoadingPath, Position};
    use spherecontact_model::scene::Scene;

    /// The paper's spheres (R = 0.1 m, E = 70 GPa, ν = 0.3) with μ = 0.2.
    pub fn paper_scene() -> Scene {
        let origin = Position {
            delta_n: 0.0,
            delta_t: 0.0,
        };
        Scene {
            name: "unit".into(),
            pair: paper_pair(),
            friction: 0.2,
            path: LoadingPath::try_new(vec![origin], vec![]).expect("one position"),
            domain: Default::default(),
            fields: Default::default(),
        }
    }

    /// The increment from approach `from` to `to` [m] with tangential increment `delta_t` [m].
    pub fn increment(scene: &Scene, from: f64, to: f64, delta_t: f64) -> Increment {
        let hertz = scene.hertz();
        let state = |d: f64| NormalState {
            force: hertz.force(d),
            radius: hertz.contact_radius(d),
        };
        Increment {
            before: state(from),
            after: state(to),
            delta_t,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::fixtures::{increment, paper_scene};
    use super::*;
    use approx::assert_relative_eq;

    const UM: f64 = 1e-6;

    #[test]
    fn normal_loading_without_tangential_motion_gives_no_force() {
        // Requirement: Mindlin & Deresiewicz's no-slip case; without it the μΔN(1 − θ) term
        // would give Q = μΔN at δt = 0 on the first increment (θ = 0 when N_before = 0).
        // Exact: 0.
        let scene = paper_scene();
        for evaluation in [Evaluation::EndWithShift, Evaluation::Start] {
            let mut law = MdIncremental::new(&scene, Memory::Masing, evaluation);
            for k in 1..50 {
                let (from, to) = (k as f64 * 0.3 * UM, (k + 1) as f64 * 0.3 * UM);
                assert_eq!(law.advance(&increment(&scene, from, to, 0.0)), 0.0);
            }
        }
    }

    #[test]
    fn oblique_increment_is_continuous_at_the_no_slip_limit() {
        // Requirement: the no-slip line ΔT = k0Δδ and the slip line k0θΔδ + dμΔN(1 − θ) meet at
        // k0|Δδ| = μΔN. Reference: k0Δδ at the limit. Tolerance: 1e-12 relative (rounding),
        // from a loaded state (T = 0.5 μN) with an increment just either side of the limit.
        let scene = paper_scene();
        let hertz = scene.hertz();
        let (from, to) = (17.0 * UM, 17.1 * UM);
        let mu_dn = scene.friction * (hertz.force(to) - hertz.force(from));
        let k0 = 8.0 * scene.pair.mindlin_shear_modulus() * hertz.contact_radius(to);
        let limit = mu_dn / k0;
        let start = |law: &mut MdIncremental| {
            let t = 0.5 * scene.friction * hertz.force(from);
            law.force = t;
            law.direction = 1.0;
        };
        let mut below = MdIncremental::new(&scene, Memory::Masing, Evaluation::EndWithShift);
        let mut above = below.clone();
        start(&mut below);
        start(&mut above);
        let t0 = below.force;
        let q_below = below.advance(&increment(&scene, from, to, limit * (1.0 - 1e-13)));
        let q_above = above.advance(&increment(&scene, from, to, limit * (1.0 + 1e-13)));
        assert_relative_eq!(q_below - t0, mu_dn, max_relative = 1e-12);
        assert_relative_eq!(q_above - t0, mu_dn, max_relative = 1e-12);
    }

    #[test]
    fn turning_points_drift_with_the_normal_force() {
        // Requirement: Thornton's T* ← T* + μΔN, T** ← T** − μΔN. Exact up to rounding (1e-12).
        let scene = paper_scene();
        let mut law = MdIncremental::new(&scene, Memory::Masing, Evaluation::EndWithShift);
        let d = 17.0 * UM;
        law.advance(&increment(&scene, d, d, 0.5 * UM)); // load
        law.advance(&increment(&scene, d, d, -0.2 * UM)); // unload: T* recorded
        law.advance(&increment(&scene, d, d, 0.1 * UM)); // reload: T** recorded
        let [t_star, t_star_star] = [law.turning_points[0].force, law.turning_points[1].force];
        let hertz = scene.hertz();
        let mu_dn = scene.friction * (hertz.force(17.2 * UM) - hertz.force(d));
        law.advance(&increment(&scene, d, 17.2 * UM, 0.0));
        assert_relative_eq!(law.turning_points[0].force, t_star + mu_dn, max_relative = 1e-12);
        assert_relative_eq!(
            law.turning_points[1].force,
            t_star_star - mu_dn,
            max_relative = 1e-12
        );
    }

    #[test]
    fn thornton_forgets_the_older_loop_and_masing_does_not() {
        // Requirement: with T* and T** only, a reversal during reloading replaces T* by the
        // current force; Masing memory keeps the whole stack. Exact: stack sizes and contents.
        let scene = paper_scene();
        let d = 17.0 * UM;
        let strokes = [0.6, -0.3, 0.2, -0.1];
        let run = |memory| {
            let mut law = MdIncremental::new(&scene, memory, Evaluation::EndWithShift);
            for s in strokes {
                law.advance(&increment(&scene, d, d, s * UM));
            }
            law
        };
        let (thornton, masing) = (run(Memory::TwoTurningPoints), run(Memory::Masing));
        assert_eq!(masing.turning_points.len(), 3);
        assert_eq!(thornton.turning_points.len(), 1);
        assert_eq!(thornton.turning_points[0], masing.turning_points[2]);
    }
}
