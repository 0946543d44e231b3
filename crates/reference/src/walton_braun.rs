//! Walton & Braun's (1986) tangential law: a Mindlin-like stiffness that softens towards the
//! Coulomb limit from the force at the last reversal, with that force scaled by the normal force
//! (Walton 1993).
//!
//! 1D only: δt and T act along one fixed axis and are signed; "T increasing" is Δδ > 0.
//!
//! ```text
//! k_t = k_t0 (1 − (T − T*)/(μN − T*))^γ     Δδ > 0   (Walton & Braun 1986, J. Rheol. 30, 949)
//! k_t = k_t0 (1 − (T* − T)/(μN + T*))^γ     Δδ < 0
//! ΔT  = k_t Δδ,   then |T| ≤ μN
//! ```
//! with γ = 1/3, k_t0 = 8G*a (Mindlin's initial stiffness at the current contact radius), T the
//! force at the start of the increment, T* = 0 initially and set to T at every reversal of Δδ, and
//! T* ← T* N/N_old whenever the normal force changes (Walton 1993, Mech. Mater. 16, 239).
//!
//! From T* = 0 at constant N this is exactly Cattaneo–Mindlin's virgin curve, whose tangent is
//! 8G*a(1 − T/μN)^{1/3}; after a reversal it is not Masing's branch (which softens over 2μN, not
//! μN + T*), the approximation the harness measures. The base of the power is clamped to [0, 1]:
//! it leaves that range only after T* has been rescaled past T, where the published form would
//! give a stiffness above k_t0 or the root of a negative number.

use super::incremental::{coulomb_cap, Increment, TangentialLaw};
use spherecontact_model::scene::Scene;

/// State of the Walton–Braun law.
pub struct WaltonBraun {
    /// Mindlin's effective shear modulus G* [Pa].
    shear_modulus: f64,
    /// Friction coefficient μ.
    friction: f64,
    /// Current tangential force T [N].
    force: f64,
    /// Force at the last reversal T* [N], scaled with the normal force.
    reversal_force: f64,
    /// Direction of the last motion (±1; 0 before any motion).
    direction: f64,
}

impl WaltonBraun {
    /// The law for a scene's pair and friction, with no history.
    pub fn new(scene: &Scene) -> Self {
        Self {
            shear_modulus: scene.pair.mindlin_shear_modulus(),
            friction: scene.friction,
            force: 0.0,
            reversal_force: 0.0,
            direction: 0.0,
        }
    }

    /// (1 − used)^{1/3} for motion in `direction` under sliding force `limit` = μN.
    fn softening(&self, direction: f64, limit: f64) -> f64 {
        let (t, t_star) = (self.force, self.reversal_force);
        let (used, capacity) = if direction > 0.0 {
            (t - t_star, limit - t_star)
        } else {
            (t_star - t, limit + t_star)
        };
        if capacity <= 0.0 {
            return 0.0;
        }
        (1.0 - used / capacity).clamp(0.0, 1.0).cbrt()
    }
}

impl TangentialLaw for WaltonBraun {
    fn advance(&mut self, increment: &Increment) -> f64 {
        let (before, after) = (increment.before, increment.after);
        let limit = self.friction * after.force;
        if limit <= 0.0 {
            self.reset();
            return 0.0;
        }
        if before.force > 0.0 {
            self.reversal_force *= after.force / before.force;
        }
        let delta = increment.delta_t;
        if delta != 0.0 {
            let direction = delta.signum();
            if self.direction != 0.0 && direction != self.direction {
                self.reversal_force = self.force;
            }
            self.direction = direction;
            let stiffness = 8.0 * self.shear_modulus * after.radius * self.softening(direction, limit);
            self.force += stiffness * delta;
        }
        self.force = coulomb_cap(self.force, self.friction, after.force);
        self.force
    }

    fn reset(&mut self) {
        self.force = 0.0;
        self.reversal_force = 0.0;
        self.direction = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::super::md_incremental::fixtures::{increment, paper_scene};
    use super::*;
    use approx::assert_relative_eq;

    const UM: f64 = 1e-6;

    #[test]
    fn first_increment_has_mindlins_initial_stiffness() {
        // Requirement: k_t0 = 8G*a at the current radius and T* = 0 on a fresh contact.
        // Reference: 8G*aΔδ. Tolerance: 1e-14 (one product).
        let scene = paper_scene();
        let mut law = WaltonBraun::new(&scene);
        let step = increment(&scene, 17.0 * UM, 17.0 * UM, 1e-3 * UM);
        let k0 = 8.0 * scene.pair.mindlin_shear_modulus() * step.after.radius;
        assert_relative_eq!(law.advance(&step), k0 * 1e-9, max_relative = 1e-14);
    }

    #[test]
    fn reversal_force_is_recorded_and_scaled_with_the_normal_force() {
        // Requirement: T* = T at a reversal (Walton & Braun 1986), T* ← T* N/N_old when N changes
        // (Walton 1993), T itself unchanged at Δδ = 0 below the Coulomb limit. Exact up to
        // rounding (1e-12).
        let scene = paper_scene();
        let mut law = WaltonBraun::new(&scene);
        let d = 17.0 * UM;
        let loaded = law.advance(&increment(&scene, d, d, 0.5 * UM));
        assert_eq!(law.reversal_force, 0.0);
        law.advance(&increment(&scene, d, d, -0.1 * UM));
        assert_eq!(law.reversal_force, loaded);
        let t = law.force;
        let step = increment(&scene, d, 20.0 * UM, 0.0);
        assert_eq!(law.advance(&step), t);
        assert_relative_eq!(
            law.reversal_force,
            loaded * step.after.force / step.before.force,
            max_relative = 1e-12
        );
    }

    #[test]
    fn unloading_softens_towards_the_opposite_limit() {
        // Requirement: on unloading the stiffness is k_t0 (1 − (T* − T)/(μN + T*))^{1/3}: k_t0 at
        // the reversal and 0 at T = −μN. Reference: the formula at T = T* and at T = −μN.
        let scene = paper_scene();
        let mut law = WaltonBraun::new(&scene);
        let limit = scene.friction * scene.hertz().force(17.0 * UM);
        law.force = 0.4 * limit;
        law.reversal_force = 0.4 * limit;
        assert_eq!(law.softening(-1.0, limit), 1.0);
        law.force = -limit;
        assert_eq!(law.softening(-1.0, limit), 0.0);
    }
}
