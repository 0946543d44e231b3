//! The one path walker of the incremental solvers (bem, mdr, the DEM tangential laws): it walks a
//! scene's path step by step and applies the same two rules to every solver.
//!
//! - **An open gap** (δn ≤ 0 at a step): zero force, memory cleared. The walker writes the row
//!   itself (P = Q = 0, contact radius 0, peak pressure 0, no stick radius) and tells the model to
//!   forget its history ([`PathModel::release`]); the model is not advanced.
//! - **A path that never closes the gap** (the largest Hertz contact radius is zero): nothing to
//!   discretise and nothing to solve. The answer is zeros at every step, with a note in the
//!   metadata ([`NEVER_CLOSES`]); it is not a failure ([`never_closed`]).
//!
//! Every other step is an increment of a closed contact handed to the model
//! ([`PathModel::advance`]) with the tangential shift since the previous step and whether the gap
//! was open at its start (the first step counts as opening from rest): how a model starts a
//! contact on the increment that closes the gap is its own (the DEM laws start at Q = 0; the
//! surface models load the new contact with the increment's shift).

use crate::history::{History, Metadata, StepResult};
use crate::path::Step;
use crate::progress;
use crate::scene::Scene;
use crate::solver::SolveError;

/// The note of a path that never closes the gap.
pub const NEVER_CLOSES: &str = "the path never closes the gap: every force is zero (nothing to solve)";

/// One increment of a closed contact: from the previous step to `step` (δn > 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathIncrement<'a> {
    /// The step at the end of the increment.
    pub step: &'a Step,
    /// The step at its start; `None` at the path's first step.
    pub before: Option<&'a Step>,
}

impl PathIncrement<'_> {
    /// The tangential shift increment Δδt since the previous step (0 at the first step) [m].
    pub fn shift(&self) -> f64 {
        self.before.map_or(0.0, |b| self.step.delta_t - b.delta_t)
    }

    /// The gap was open at the start (or this is the first step): the contact has no history.
    pub fn closing(&self) -> bool {
        self.before.is_none_or(|b| b.delta_n <= 0.0)
    }
}

/// A solver's model as the walker drives it.
pub trait PathModel {
    /// Advances over an increment whose gap is closed at its end; the step's row.
    fn advance(&mut self, increment: &PathIncrement) -> Result<StepResult, SolveError>;

    /// The gap is open at `step`: forget the contact's history (the walker writes the row).
    fn release(&mut self, step: &Step);

    /// Whether the model's rows carry the peak pressure (its open rows then say 0 there).
    fn reports_peak_pressure(&self) -> bool {
        true
    }
}

/// The row of a step whose gap is open: zero force, zero contact (and zero peak pressure for a
/// model that reports it).
pub fn open_row(step: &Step, peak_pressure: bool) -> StepResult {
    StepResult {
        normal_force: Some(0.0),
        tangential_force: Some(0.0),
        contact_radius: Some(0.0),
        peak_pressure: peak_pressure.then_some(0.0),
        ..StepResult::at(step)
    }
}

/// Walks the path of `scene` with `model` (see the module doc); one row a step, each reported
/// to the run's progress meter ([`crate::progress::tick`]).
pub fn walk(scene: &Scene, model: &mut dyn PathModel) -> Result<Vec<StepResult>, SolveError> {
    let steps = scene.steps();
    let mut rows = Vec::with_capacity(steps.len());
    for (k, step) in steps.iter().enumerate() {
        if step.delta_n > 0.0 {
            let before = k.checked_sub(1).map(|j| &steps[j]);
            rows.push(model.advance(&PathIncrement { step, before })?);
        } else {
            model.release(step);
            rows.push(open_row(step, model.reports_peak_pressure()));
        }
        progress::tick(k + 1, steps.len());
    }
    Ok(rows)
}

/// The rows of a path that never closes the gap ([`open_row`] at every step), or `None` when the
/// path closes it somewhere; put [`NEVER_CLOSES`] in the metadata's warnings with them.
pub fn never_closed(scene: &Scene, peak_pressure: bool) -> Option<Vec<StepResult>> {
    (scene.max_contact_radius() <= 0.0).then(|| {
        scene
            .steps()
            .iter()
            .map(|step| open_row(step, peak_pressure))
            .collect()
    })
}

/// The whole answer of a surface solver on a path that never closes the gap: the rows of
/// [`never_closed`] (with peak pressures), no fields, and [`NEVER_CLOSES`] added to `metadata`'s
/// warnings; `None` when the path closes the gap somewhere.
pub fn never_closed_history(scene: &Scene, mut metadata: Metadata) -> Option<History> {
    let steps = never_closed(scene, true)?;
    metadata.warnings.push(NEVER_CLOSES.into());
    Some(History {
        metadata,
        steps,
        fields: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Records what the walker asked of it.
    #[derive(Default)]
    struct Recorder {
        calls: Vec<String>,
    }

    impl PathModel for Recorder {
        fn advance(&mut self, increment: &PathIncrement) -> Result<StepResult, SolveError> {
            self.calls.push(format!(
                "advance {} shift {:.0e} closing {}",
                increment.step.index,
                increment.shift(),
                increment.closing()
            ));
            Ok(StepResult {
                normal_force: Some(1.0),
                ..StepResult::at(increment.step)
            })
        }

        fn release(&mut self, step: &Step) {
            self.calls.push(format!("release {}", step.index));
        }
    }

    fn scene(positions: &[(f64, f64)]) -> Scene {
        let (delta_n, delta_t): (Vec<f64>, Vec<f64>) =
            positions.iter().map(|&(n, t)| (n * 1e6, t * 1e6)).unzip();
        crate::fixtures::paper_scene(&delta_n, &delta_t, 1)
    }

    #[test]
    fn an_open_gap_releases_and_writes_zeros() {
        // Closed, open (separation), closed again with a shift.
        let scene = scene(&[(1e-6, 0.0), (-1e-6, 1e-6), (1e-6, 3e-6)]);
        let mut model = Recorder::default();
        let rows = walk(&scene, &mut model).expect("walks");
        assert_eq!(
            model.calls,
            [
                "advance 0 shift 0e0 closing true",
                "release 1",
                "advance 2 shift 2e-6 closing true"
            ]
        );
        assert_eq!(rows[1].normal_force, Some(0.0));
        assert_eq!(rows[1].tangential_force, Some(0.0));
        assert_eq!(rows[2].normal_force, Some(1.0));
        assert!(never_closed(&scene, true).is_none());
    }

    #[test]
    fn a_path_that_never_closes_is_zeros() {
        let scene = scene(&[(0.0, 0.0), (-1e-6, 1e-6)]);
        let rows = never_closed(&scene, true).expect("never closes");
        assert_eq!(rows.len(), 2);
        assert!(rows
            .iter()
            .all(|r| r.normal_force == Some(0.0) && r.tangential_force == Some(0.0)));
    }
}
