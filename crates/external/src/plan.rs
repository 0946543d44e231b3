//! What a scene asks of an external deck (the axisymmetric decks, the 3D deck, the CalculiX
//! decks): the steps it computes, whether the tangential mode is solved, the grip of the far face,
//! the candidate contact zone, and the penalty factor every deck's contact is set with.

use super::deck::ComputedStep;
use spherecontact_model::domain::Grip;
use spherecontact_model::scene::Scene;

/// Penalty factor: k = KFAC · E / h, normal and tangential. Reason: at 1e3 the penetration at the
/// pole is below 1e-3 h and P moves by less than 0.01 % when kfac doubles (docs/toolchain.md);
/// a sticking node's displacement error q/k is below 1e-5 of the shift.
pub const KFAC: f64 = 1e3;

/// Candidate contact zone, in units of the path's largest Hertz contact radius (as fem-axisym):
/// the finite body's contact is 0.15–0.2 % wider than Hertz's, far inside it.
pub const CANDIDATE_ZONE: f64 = 1.25;

/// What a scene asks of a deck: its steps, modes, grip and candidate zone.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Every step of the path, as the deck computes it.
    pub steps: Vec<ComputedStep>,
    /// Whether the tangential mode is solved (the path moves tangentially).
    pub tangential: bool,
    /// How the far face is held: the scene's `[domain]` grip, the one its mesh is tagged with.
    pub grip: Grip,
    /// Candidate contact zone [m].
    pub candidate_radius: f64,
}

impl Plan {
    /// The plan of `scene` at pole size `resolution`.
    ///
    /// Grip: the scene's (`scene.domain.grip`), as for the mesh's far-face tag and every other
    /// FEM solver: one case means one domain and one grip ([`super::axisym::applicable`] refuses
    /// a tangential path under the axial grip).
    pub fn of(scene: &Scene, resolution: f64) -> Self {
        let tangential = !scene.path.is_normal_only();
        let steps = scene
            .steps()
            .iter()
            .map(|s| ComputedStep {
                step: s.index,
                d: s.delta_n / 2.0,
                t: s.delta_t / 2.0,
                position: s.position,
            })
            .collect();
        Self {
            steps,
            tangential,
            grip: scene.domain.grip,
            candidate_radius: (CANDIDATE_ZONE * scene.max_contact_radius()).max(3.0 * resolution),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plan_walks_every_step_with_half_displacements() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 10.0, 17.0]);
        let plan = Plan::of(&scene, 2e-5);
        assert_eq!(plan.steps.len(), scene.steps().len());
        let last = plan.steps.last().unwrap();
        assert_eq!((last.step, last.position), (8, Some(2)));
        assert!((last.d - 8.5e-6).abs() < 1e-18 && last.t == 0.0);
        assert!(plan.steps[3].position.is_none());
        // The scene's grip (the default: rigid), the one its mesh is tagged with.
        assert!(!plan.tangential && plan.grip == Grip::Rigid);
        scene.domain.grip = Grip::Axial;
        assert_eq!(Plan::of(&scene, 2e-5).grip, Grip::Axial);
        let c = scene.max_contact_radius();
        assert!((plan.candidate_radius - 1.25 * c).abs() < 1e-15);
    }
}
