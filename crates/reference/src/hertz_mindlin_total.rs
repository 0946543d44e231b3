//! The no-slip Hertz–Mindlin spring in total form, with a Coulomb cap: the tangential law of
//! LIGGGHTS' `tangential history` and LAMMPS' `tangential mindlin`, written here to mirror them.
//!
//! The history is the accumulated tangential displacement s, not the force; the force is s times
//! Mindlin's initial stiffness at the current contact radius, k_t = 8 G* c = 8 G* √(R* δn), and at
//! the Coulomb limit s is reset so that the force sits on it:
//!
//! ```text
//! s ← s + Δδt;   Q = k_t(c_after) s;   |Q| > μP ⇒ Q = ±μP, s = Q / k_t
//! ```
//! At constant δn it is [`super::hertz_mindlin_spring`]'s law; when δn changes it rescales the
//! force stored so far by c_after/c_before (√(6/5) when δn rises from 5 to 6 µm while sticking),
//! where the incremental spring and Mindlin–Deresiewicz keep it.

use super::incremental::{coulomb_cap, Increment, TangentialLaw};
use spherecontact_model::scene::Scene;

/// State of the total-form spring law.
pub struct HertzMindlinTotal {
    /// Mindlin's effective shear modulus G* [Pa].
    shear_modulus: f64,
    /// Friction coefficient μ.
    friction: f64,
    /// The stored tangential displacement s [m].
    displacement: f64,
}

impl HertzMindlinTotal {
    /// The law for a scene's pair and friction, with no history.
    pub fn new(scene: &Scene) -> Self {
        Self {
            shear_modulus: scene.pair.mindlin_shear_modulus(),
            friction: scene.friction,
            displacement: 0.0,
        }
    }
}

impl TangentialLaw for HertzMindlinTotal {
    fn advance(&mut self, increment: &Increment) -> f64 {
        let stiffness = 8.0 * self.shear_modulus * increment.after.radius;
        if stiffness <= 0.0 {
            self.displacement = 0.0;
            return 0.0;
        }
        self.displacement += increment.delta_t;
        let elastic = stiffness * self.displacement;
        let force = coulomb_cap(elastic, self.friction, increment.after.force);
        if force != elastic {
            self.displacement = force / stiffness;
        }
        force
    }

    fn reset(&mut self) {
        self.displacement = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::incremental::NormalState;

    fn state(radius: f64, force: f64) -> NormalState {
        NormalState { radius, force }
    }

    #[test]
    fn a_rising_normal_load_rescales_the_stored_force() {
        let scene = spherecontact_model::fixtures::test_scene(&[0.0, 5.0]);
        let mut law = HertzMindlinTotal::new(&scene);
        let k = |c: f64| 8.0 * scene.pair.mindlin_shear_modulus() * c;
        let (c5, c6) = (1.0e-4, 1.2e-4);
        let q = law.advance(&Increment {
            before: state(c5, 100.0),
            after: state(c5, 100.0),
            delta_t: 1e-8,
        });
        assert!((q / (k(c5) * 1e-8) - 1.0).abs() < 1e-15);
        let raised = law.advance(&Increment {
            before: state(c5, 100.0),
            after: state(c6, 120.0),
            delta_t: 0.0,
        });
        // The stored displacement times the new stiffness: Q grows as c.
        assert!((raised / q - c6 / c5).abs() < 1e-14);
    }

    #[test]
    fn at_the_cap_the_displacement_is_reset_onto_it() {
        let scene = spherecontact_model::fixtures::test_scene(&[0.0, 5.0]);
        let mut law = HertzMindlinTotal::new(&scene);
        let at = |law: &mut HertzMindlinTotal, dt: f64| {
            law.advance(&Increment {
                before: state(1e-4, 10.0),
                after: state(1e-4, 10.0),
                delta_t: dt,
            })
        };
        assert_eq!(at(&mut law, 1e-3), scene.friction * 10.0);
        // Back by Δ: Q falls from the cap by k_t Δ, not from the displacement driven in.
        let k = 8.0 * scene.pair.mindlin_shear_modulus() * 1e-4;
        let back = at(&mut law, -1e-9);
        assert!((back - (scene.friction * 10.0 - k * 1e-9)).abs() < 1e-12);
    }
}
