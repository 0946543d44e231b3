//! The no-slip Hertz–Mindlin spring with a Coulomb cap, incremental: the tangential law that YADE
//! (`Law2_ScGeom_MindlinPhys_Mindlin`) and LAMMPS (`tangential mindlin/force`) ship.
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
}

impl HertzMindlinSpring {
    /// The law for a scene's pair and friction, with no history.
    pub fn new(scene: &Scene) -> Self {
        Self {
            shear_modulus: scene.pair.mindlin_shear_modulus(),
            friction: scene.friction,
            force: 0.0,
        }
    }
}

impl TangentialLaw for HertzMindlinSpring {
    fn advance(&mut self, increment: &Increment) -> f64 {
        let stiffness = 8.0 * self.shear_modulus * increment.after.radius;
        self.force = coulomb_cap(
            self.force + stiffness * increment.delta_t,
            self.friction,
            increment.after.force,
        );
        self.force
    }

    fn reset(&mut self) {
        self.force = 0.0;
    }
}
