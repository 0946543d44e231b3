//! The no-slip Hertz–Mindlin spring with a Coulomb cap, incremental: the tangential law that YADE
//! (`Law2_ScGeom_MindlinPhys_Mindlin`) and LAMMPS (`tangential mindlin/force`) ship, and its variant
//! whose stored force shrinks with the contact on unloading (Kratos' `DEM_D_Hertz_viscous_Coulomb`,
//! LAMMPS' `mindlin_rescale/force`).
//!
//! The tangential stiffness is Mindlin's initial stiffness at the current contact radius,
//! k_t = 8 G* c = 8 G* √(R* δn), and the force is integrated incrementally and capped:
//!
//! ```text
//! Q ← clamp(Q + k_t(c_after) Δδt, −μP, μP)
//! ```
//! This is YADE's force-incremental form. LIGGGHTS (`tangential history`) and LAMMPS
//! (`mindlin`) store the accumulated displacement instead and multiply it by the current k_t,
//! which differs when δn varies ([`super::hertz_mindlin_total`]). Neither has the
//! micro-slip softening of Mindlin's law, so Q rises too steeply before gross sliding.
//!
//! The rescaled variant ([`HertzMindlinSpring::rescaled`]) first scales the stored force by the
//! contact's shrinkage when the overlap decreases, as Kratos does (`minoring_factor =
//! sqrt(indentation / previous_indentation)` in `DEM_D_Hertz_viscous_Coulomb_CL.cpp`):
//!
//! ```text
//! Q ← clamp(Q · c_after/c_before + k_t(c_after) Δδt, −μP, μP)   when c_after < c_before
//! ```
//! so that a stored force never outlives the contact that carries it (c/c_before = √(δ/δ_before)).

use super::incremental::{coulomb_cap, Increment, TangentialLaw};
use spherecontact_model::scene::Scene;

/// State of the Hertz–Mindlin spring law.
pub struct HertzMindlinSpring {
    /// Mindlin's effective shear modulus G* [Pa].
    shear_modulus: f64,
    /// Friction coefficient μ.
    friction: f64,
    /// Current tangential force Q [N].
    force: f64,
    /// Whether the stored force is scaled by c_after/c_before when the contact shrinks.
    rescale_on_unloading: bool,
}

impl HertzMindlinSpring {
    /// The law for a scene's pair and friction, with no history.
    pub fn new(scene: &Scene) -> Self {
        Self {
            shear_modulus: scene.pair.mindlin_shear_modulus(),
            friction: scene.friction,
            force: 0.0,
            rescale_on_unloading: false,
        }
    }

    /// The variant whose stored force is scaled by c_after/c_before when the contact shrinks.
    pub fn rescaled(scene: &Scene) -> Self {
        Self {
            rescale_on_unloading: true,
            ..Self::new(scene)
        }
    }
}

impl TangentialLaw for HertzMindlinSpring {
    fn advance(&mut self, increment: &Increment) -> f64 {
        let (before, after) = (increment.before.radius, increment.after.radius);
        let stored = if self.rescale_on_unloading && after < before {
            self.force * (after / before)
        } else {
            self.force
        };
        let stiffness = 8.0 * self.shear_modulus * after;
        self.force = coulomb_cap(
            stored + stiffness * increment.delta_t,
            self.friction,
            increment.after.force,
        );
        self.force
    }

    fn reset(&mut self) {
        self.force = 0.0;
    }
}
