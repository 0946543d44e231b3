//! What a case's baseline may hold, read off the case before anything runs, and the check that
//! a baseline (a file from elsewhere) holds nothing else.

use crate::plan::Member;
use crate::{baseline::key, baseline::Baseline};

/// What a case's baseline may hold, read off the case before anything runs: the baseline's
/// entries are checked against it when the file is loaded ([`Baseline::load`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// The case's name.
    pub name: String,
    /// Each check's words ([`key`], [`spherecontact_reference::impact::problem::ImpactCheck::key`]) and the solvers
    /// it needs, by index.
    pub checks: Vec<(String, Vec<String>)>,
    /// Its path's steps (a path case) or its sweep's points (an impact case).
    pub steps: usize,
    /// What [`Shape::steps`] counts, in words.
    pub unit: &'static str,
    /// Every solver it runs.
    pub solvers: Vec<String>,
}

impl Shape {
    /// The shape of `case`.
    pub fn of(case: &Member) -> Self {
        match case {
            Member::Path(case) => Self::of_path(case),
            Member::Impact(case) => Shape {
                name: case.name.clone(),
                checks: case
                    .checks
                    .iter()
                    .map(|c| (c.key(), c.solvers().cloned().collect()))
                    .collect(),
                steps: case.points().len(),
                unit: "sweep points",
                solvers: case.required_solvers(),
            },
        }
    }

    /// The shape of the path case `case`.
    pub fn of_path(case: &spherecontact_case::Case) -> Self {
        Shape {
            name: case.name().to_owned(),
            checks: case
                .checks
                .iter()
                .map(|c| (key(c), c.solvers().cloned().collect()))
                .collect(),
            steps: case.scene.steps().len(),
            unit: "steps",
            solvers: case.required_solvers(),
        }
    }

    /// Checks every entry of `baseline` against this case: its name, the solvers it runs (a
    /// finite wall time each), and for each check the index of a check of the case with the same
    /// words, values at increasing steps (or sweep points) of the case, each finite, and a solver
    /// entry for each solver the check needs. The entry at fault and why, else.
    pub fn admits(&self, baseline: &Baseline) -> Result<(), (String, String)> {
        if baseline.case != self.name {
            return Err((
                "case".into(),
                format!("another case's baseline (allowed: `{}`)", self.name),
            ));
        }
        for (k, (name, solver)) in baseline.solvers.iter().enumerate() {
            let entry = || format!("solvers (entry {})", k + 1);
            if !self.solvers.contains(name) {
                return Err((entry(), "a solver the case does not run".into()));
            }
            if !(solver.wall_s.is_finite() && solver.wall_s >= 0.0) {
                return Err((
                    entry(),
                    "wall_s is not a finite time (allowed: 0 or more seconds)".into(),
                ));
            }
        }
        for (k, record) in baseline.checks.iter().enumerate() {
            let entry = || format!("checks[{k}]");
            let named = self
                .checks
                .get(record.index)
                .filter(|(key, _)| *key == record.check);
            let Some((_, solvers)) = named else {
                return Err((
                    entry(),
                    format!(
                        "index {} and its words name no check of the case (allowed: the index of one of \
                         its {} checks, with its words)",
                        record.index,
                        self.checks.len()
                    ),
                ));
            };
            if let Some(problem) = self.values_problem(&record.values) {
                return Err((entry(), problem));
            }
            if let Some(solver) = solvers.iter().find(|s| !baseline.solvers.contains_key(*s)) {
                return Err((entry(), format!("its solver `{solver}` has no [solvers] entry")));
            }
        }
        Ok(())
    }

    /// What is wrong with a check's recorded `values`, if anything: none, a step not after the
    /// one before or past the case's, a value that is not finite.
    fn values_problem(&self, values: &[(usize, f64)]) -> Option<String> {
        if values.is_empty() {
            return Some("values is empty (allowed: the [step, value] pairs the check judged)".into());
        }
        let mut previous = None;
        for (k, &(step, value)) in values.iter().enumerate() {
            if step >= self.steps {
                return Some(format!(
                    "values[{k}]: step {step} is past the case's {} {} (allowed: 0 to {})",
                    self.steps,
                    self.unit,
                    self.steps.saturating_sub(1)
                ));
            }
            if previous.is_some_and(|p| step <= p) {
                return Some(format!(
                    "values[{k}]: step {step} does not follow step {} (allowed: increasing steps)",
                    previous.unwrap_or_default()
                ));
            }
            if !value.is_finite() {
                return Some(format!("values[{k}]: the value is not a finite number"));
            }
            previous = Some(step);
        }
        None
    }
}
