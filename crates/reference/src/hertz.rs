//! The Hertz closed form (see [`spherecontact_model::hertz`]) as a solver: P, c and p0 at every step.

use spherecontact_model::history::{History, Metadata, StepResult};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};

/// The Hertz closed form as a solver: P, c and p0 at every step; no tangential force.
pub struct HertzSolver;

impl Solver for HertzSolver {
    fn name(&self) -> &'static str {
        "hertz"
    }

    fn kind(&self) -> Kind {
        Kind::Analytic
    }

    fn description(&self) -> &'static str {
        "Hertz closed form: normal force, contact radius, peak pressure"
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        Some(spherecontact_model::cost::law(scene.steps().len()))
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let hertz = scene.hertz();
        let steps = scene
            .steps()
            .iter()
            .map(|step| StepResult {
                normal_force: Some(hertz.force(step.delta_n)),
                contact_radius: Some(hertz.contact_radius(step.delta_n)),
                peak_pressure: Some(hertz.peak_pressure(step.delta_n)),
                ..StepResult::at(step)
            })
            .collect();
        Ok(History {
            metadata: Metadata {
                model: "Hertz: elastic half-spaces, parabolic profiles, frictionless".into(),
                resolution: "closed form".into(),
                ..Metadata::default()
            },
            steps,
            fields: Vec::new(),
        })
    }
}
