//! # spherecontact-check: checks and verdicts
//!
//! **Job.** What a check asks of a solver's history, and its verdict: OK, NOOK, INFO, N/A or KNOWN, with value, reference, error and tolerance; and the judged rows a path case and an impact case both become ([`judged`]).
//!
//! **May depend on.** `spherecontact-model` and `spherecontact-solvers` (the measures taken on surface maps).
//!
//! **Offers.** `CheckSpec::judge`, `Outcome`, `Verdict` and `Drift`.
//!
//! Checks: a solver's quantity, where along the path, against what reference, within what
//! tolerance and why — judged OK, NOOK, INFO (measured, never judged) or N/A (not installed).
//!
//! A check may carry a **known-failure mark** (`known_failure = "evidence …"` in the case file):
//! a defect of an external code, shown to be the code's and not the deck's, stays a failing check
//! with its tolerance unchanged, but its failure prints as KNOWN (the run still passes) and names
//! its evidence; a marked check that passes prints FIXED? and fails the run, so that the mark is
//! removed when the code is fixed (docs/external-decks.md, "Known failures").
//!
//! Modelled on MOOSE's test specs and Code_Aster's TEST_RESU: a check states its requirement,
//! reference and tolerance with a reason, and its result prints with value, reference and error.

pub mod judged;

pub mod drift;
mod lookup;
mod measure;
pub mod row;

use serde::Serialize;
use std::collections::BTreeMap;

pub use drift::{Change, Drift, JudgedValue};
use lookup::{lookup, unread};
use measure::zeroed;
pub use measure::{relative_error, ErrorMeasure, ABS_ZERO};

use spherecontact_model::history::{History, Quantity, StepResult};
use spherecontact_model::solver::SolveError;

/// Where along the path a check looks.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Where {
    /// Every step, substeps included.
    EveryStep,
    /// Every path position.
    EveryPosition,
    /// One path position.
    Position(usize),
    /// The path positions from the first to the second, inclusive.
    Positions(usize, usize),
}

impl Where {
    /// Whether a row is looked at.
    pub fn selects(&self, row: &StepResult) -> bool {
        match (*self, row.position) {
            (Where::EveryStep, _) => true,
            (Where::EveryPosition, p) => p.is_some(),
            (Where::Position(k), Some(p)) => p == k,
            (Where::Positions(a, b), Some(p)) => (a..=b).contains(&p),
            _ => false,
        }
    }
}

impl std::fmt::Display for Where {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Where::EveryStep => write!(f, "every step"),
            Where::EveryPosition => write!(f, "every position"),
            Where::Position(k) => write!(f, "position {k}"),
            Where::Positions(a, b) => write!(f, "positions {a}–{b}"),
        }
    }
}

/// What a value is compared with.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reference {
    /// The same quantity from another solver at the same step.
    Solver(String),
    /// A stored value with its provenance.
    Value {
        /// The value, SI.
        value: f64,
        /// The reference file and key (`file#key`).
        key: String,
        /// Where the value comes from, in words.
        source: String,
    },
}

impl std::fmt::Display for Reference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Reference::Solver(name) => write!(f, "{name}"),
            Reference::Value { key, .. } => write!(f, "{key}"),
        }
    }
}

/// One validated check of a case.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CheckSpec {
    /// The solver whose result is judged.
    pub solver: String,
    /// The quantity judged.
    pub quantity: Quantity,
    /// Where along the path.
    pub at: Where,
    /// Compared with what.
    pub reference: Reference,
    /// How the difference is measured.
    pub measure: ErrorMeasure,
    /// The largest acceptable error; `None` for an informational check.
    pub tolerance: Option<f64>,
    /// Why the tolerance is what it is (or what an informational check shows).
    pub reason: String,
    /// The evidence of a known defect of the judged code: a failure prints as
    /// [`Verdict::Known`], a pass as [`Verdict::Fixed`].
    pub known_failure: Option<String>,
    /// The magnitude below which a value or reference counts as zero (SI, the quantity's unit;
    /// MOOSE's `abs_zero`), and the smallest denominator of a relative error: a zero reference
    /// then gives a finite error, never +∞ ([`ABS_ZERO`] unless the case sets `abs_zero`).
    pub abs_zero: f64,
}

/// The judgement of one check.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Verdict {
    /// Within tolerance.
    Ok,
    /// Outside tolerance, or the solver failed or gave no value.
    Nook,
    /// Informational: measured and reported, never judged.
    Info,
    /// A solver it needs is not installed.
    Unavailable,
    /// Outside tolerance, as its known-failure mark says: a known defect, not a failure of the run.
    Known,
    /// Within tolerance although marked as a known failure: the defect may be fixed, the mark
    /// must be removed (fails the run).
    Fixed,
    /// The value moved from its non-regression baseline beyond the solver's tolerance
    /// (`baseline` (spherecontact-verify)): a failure, whatever the check's own verdict was.
    Drift,
}

impl Verdict {
    /// Every verdict (a new one joins the counts and orders by being listed here).
    pub const ALL: [Verdict; 7] = [
        Verdict::Ok,
        Verdict::Nook,
        Verdict::Info,
        Verdict::Unavailable,
        Verdict::Known,
        Verdict::Fixed,
        Verdict::Drift,
    ];

    /// The label printed in the result table.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Ok => "OK",
            Verdict::Nook => "NOOK",
            Verdict::Info => "INFO",
            Verdict::Unavailable => "N/A",
            Verdict::Known => "KNOWN",
            Verdict::Fixed => "FIXED?",
            Verdict::Drift => "DRIFT",
        }
    }

    /// Whether this verdict fails the run: NOOK, and FIXED? (a stale known-failure mark).
    pub fn fails_run(self) -> bool {
        matches!(self, Verdict::Nook | Verdict::Fixed | Verdict::Drift)
    }

    /// The verdict of a check whose error was judged `judged`, under its known-failure mark if
    /// it has one: NOOK becomes KNOWN, OK becomes FIXED?.
    pub fn marked(judged: Verdict, known_failure: Option<&str>) -> Verdict {
        match (judged, known_failure) {
            (Verdict::Nook, Some(_)) => Verdict::Known,
            (Verdict::Ok, Some(_)) => Verdict::Fixed,
            (v, _) => v,
        }
    }

    /// How much a reader must look at it, highest first: reports list checks and count
    /// verdicts in this order (a failure, then what could not be judged, then the rest). The one
    /// place where verdicts are ranked.
    pub fn severity(self) -> u8 {
        match self {
            Verdict::Nook | Verdict::Fixed | Verdict::Drift => 4,
            Verdict::Known => 3,
            Verdict::Unavailable => 2,
            Verdict::Info => 1,
            Verdict::Ok => 0,
        }
    }

    /// Every verdict, the most severe first.
    pub fn by_severity() -> [Verdict; 7] {
        let mut all = Verdict::ALL;
        all.sort_by_key(|v| std::cmp::Reverse(v.severity()));
        all
    }
}

/// The result of one check: the verdict and, at the worst step, the value, reference and error.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Outcome {
    /// The check.
    pub spec: CheckSpec,
    /// The judgement.
    pub verdict: Verdict,
    /// The solver's value at the worst step.
    pub value: Option<f64>,
    /// The reference at the worst step.
    pub reference: Option<f64>,
    /// The worst error over the looked-at steps (may be +∞, never NaN).
    pub error: Option<f64>,
    /// The step where the error was worst.
    pub worst_step: Option<usize>,
    /// Why there is no error to show (solver failed, value missing, nothing to compare).
    pub message: Option<String>,
    /// Every value the check judged, in step order (empty when it has no error): what its
    /// non-regression baseline records and compares.
    pub judged: Vec<JudgedValue>,
    /// The values against their non-regression baseline, when the case has one for this check
    /// (`baseline` (spherecontact-verify)).
    pub drift: Option<Drift>,
}

/// The histories of a case's solvers, by name.
pub type Histories = BTreeMap<String, Result<History, SolveError>>;

impl CheckSpec {
    /// The solvers the check needs: its subject, then its reference solver if any.
    pub fn solvers(&self) -> impl Iterator<Item = &String> {
        std::iter::once(&self.solver).chain(match &self.reference {
            Reference::Solver(name) => Some(name),
            Reference::Value { .. } => None,
        })
    }

    /// Judges this check on the histories of a case's solvers.
    pub fn evaluate(&self, histories: &Histories) -> Outcome {
        let subject = match lookup(histories, &self.solver) {
            Ok(history) => history,
            Err((verdict, message)) => return self.outcome_without_error(verdict, message),
        };
        let reference_history = match &self.reference {
            Reference::Solver(name) => match lookup(histories, name) {
                Ok(history) => Some((name.as_str(), history)),
                Err((verdict, message)) => return self.outcome_without_error(verdict, message),
            },
            Reference::Value { .. } => None,
        };
        // A quantity either solver did not read from its results file fails this check alone.
        let unread = unread(&self.solver, subject, self.quantity)
            .or_else(|| reference_history.and_then(|(name, h)| unread(name, h, self.quantity)));
        if let Some(message) = unread {
            return self.outcome_without_error(Verdict::Nook, message);
        }
        let reference_history = reference_history.map(|(_, h)| h);
        if let (Some(field), Some(reference), Where::Position(position)) = (
            spherecontact_solvers::profile::Field::of(self.quantity),
            reference_history,
            self.at,
        ) {
            return self.evaluate_profile(subject, reference, position, field);
        }
        let mut pairs = Vec::new();
        for row in subject.steps.iter().filter(|r| self.at.selects(r)) {
            let reference = match (&self.reference, reference_history) {
                (Reference::Value { value, .. }, _) => Some(*value),
                (_, Some(h)) => h.steps.get(row.step).and_then(|r| self.value(h, r)),
                (_, None) => None,
            };
            let Some(reference) = reference else { continue };
            let Some(value) = self.value(subject, row) else {
                // A run that left a step without a value (an unconverged step) may be a known defect.
                let message = format!("{} gives no {} at step {}", self.solver, self.quantity, row.step);
                let verdict = Verdict::marked(Verdict::Nook, self.known_failure.as_deref());
                return self.outcome_without_error(verdict, message);
            };
            pairs.push(JudgedValue {
                step: row.step,
                value,
                reference,
            });
        }
        if pairs.is_empty() {
            return self.outcome_without_error(Verdict::Nook, format!("nothing to compare at {}", self.at));
        }
        let peak = pairs.iter().map(|p| p.reference.abs()).fold(0.0, f64::max);
        let (worst_step, value, reference, error) = pairs
            .iter()
            .map(|p| {
                (
                    p.step,
                    p.value,
                    p.reference,
                    self.error(p.value, p.reference, peak),
                )
            })
            .fold(
                None,
                |worst: Option<(usize, f64, f64, f64)>, candidate| match worst {
                    Some(w) if w.3 >= candidate.3 => Some(w),
                    _ => Some(candidate),
                },
            )
            .expect("pairs is not empty");
        let verdict = match self.tolerance {
            None => Verdict::Info,
            Some(tolerance) if error <= tolerance => Verdict::Ok,
            Some(_) => Verdict::Nook,
        };
        Outcome {
            spec: self.clone(),
            verdict: Verdict::marked(verdict, self.known_failure.as_deref()),
            value: Some(value),
            reference: Some(reference),
            error: Some(error),
            worst_step: Some(worst_step),
            message: None,
            judged: pairs,
            drift: None,
        }
    }

    /// A profile check: the RMS difference over the annulus (value [Pa]) against the reference
    /// profile's peak (reference [Pa]); the error is their ratio ([`spherecontact_solvers::profile`]).
    fn evaluate_profile(
        &self,
        subject: &History,
        reference: &History,
        position: usize,
        field: spherecontact_solvers::profile::Field,
    ) -> Outcome {
        match spherecontact_solvers::profile::compare(subject, reference, position, field) {
            Ok(c) => {
                let error = c.rms / c.peak;
                let judged = match self.tolerance {
                    None => Verdict::Info,
                    Some(tolerance) if error <= tolerance => Verdict::Ok,
                    Some(_) => Verdict::Nook,
                };
                let worst_step = subject.at_position(position).map(|r| r.step);
                Outcome {
                    spec: self.clone(),
                    verdict: Verdict::marked(judged, self.known_failure.as_deref()),
                    value: Some(c.rms),
                    reference: Some(c.peak),
                    error: Some(error),
                    worst_step,
                    message: None,
                    judged: worst_step
                        .map(|step| JudgedValue {
                            step,
                            value: c.rms,
                            reference: c.peak,
                        })
                        .into_iter()
                        .collect(),
                    drift: None,
                }
            }
            Err(message) => self.outcome_without_error(Verdict::Nook, format!("{}: {message}", self.solver)),
        }
    }

    /// The judged quantity at `row` of `history`: the row's value, or for a map measure its
    /// measure on the field at the row's path position ([`spherecontact_solvers::map_measure`]).
    pub fn value(&self, history: &History, row: &StepResult) -> Option<f64> {
        if self.quantity.is_map_measure() {
            let field = history.field_at(row.position?)?;
            spherecontact_solvers::map_measure::measure(self.quantity, field)
        } else {
            self.quantity.of(row)
        }
    }

    /// The error of `value` against `reference`, `peak` being max |r| over the looked-at steps.
    ///
    /// As MOOSE's CSVDiff does, a value or reference of magnitude below `abs_zero` is zero, and a
    /// relative error divides by at least `abs_zero`: against a zero reference a value v gives
    /// |v| / abs_zero, finite (and large, so a nonzero value still fails), never +∞ or NaN.
    fn error(&self, value: f64, reference: f64, peak: f64) -> f64 {
        match self.measure {
            ErrorMeasure::Absolute => (zeroed(value, self.abs_zero) - zeroed(reference, self.abs_zero)).abs(),
            ErrorMeasure::Relative => relative_error(value, reference, reference, self.abs_zero),
            ErrorMeasure::RelativeToPeak => relative_error(value, reference, peak, self.abs_zero),
        }
    }

    fn outcome_without_error(&self, verdict: Verdict, message: String) -> Outcome {
        Outcome {
            spec: self.clone(),
            verdict,
            value: None,
            reference: None,
            error: None,
            worst_step: None,
            message: Some(message),
            judged: Vec::new(),
            drift: None,
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use spherecontact_model::history::{Layout, Metadata, SurfaceField};

    pub(crate) fn history(values: &[Option<f64>]) -> History {
        History {
            metadata: Metadata::default(),
            fields: Vec::new(),
            steps: values
                .iter()
                .enumerate()
                .map(|(i, v)| StepResult {
                    step: i,
                    position: Some(i),
                    normal_force: *v,
                    ..StepResult::default()
                })
                .collect(),
        }
    }

    pub(crate) fn spec(measure: ErrorMeasure, tolerance: Option<f64>) -> CheckSpec {
        CheckSpec {
            solver: "a".into(),
            quantity: Quantity::NormalForce,
            at: Where::EveryStep,
            reference: Reference::Solver("b".into()),
            measure,
            tolerance,
            reason: "test".into(),
            known_failure: None,
            abs_zero: ABS_ZERO,
        }
    }

    pub(crate) fn histories(a: &[Option<f64>], b: &[Option<f64>]) -> Histories {
        [
            ("a".to_string(), Ok(history(a))),
            ("b".to_string(), Ok(history(b))),
        ]
        .into_iter()
        .collect()
    }

    #[test]
    fn worst_relative_error_decides() {
        let h = histories(
            &[Some(0.0), Some(1.01), Some(2.0)],
            &[Some(0.0), Some(1.0), Some(2.0)],
        );
        let ok = spec(ErrorMeasure::Relative, Some(0.02)).evaluate(&h);
        assert_eq!(ok.verdict, Verdict::Ok);
        assert_eq!(ok.worst_step, Some(1));
        assert!((ok.error.unwrap() - 0.01).abs() < 1e-12);
        assert_eq!(
            spec(ErrorMeasure::Relative, Some(0.005)).evaluate(&h).verdict,
            Verdict::Nook
        );
    }

    #[test]
    fn against_a_zero_reference_the_error_is_finite_and_round_off_is_zero() {
        // Requirement: no check prints inf or NaN. Reference: MOOSE's abs_zero. A value of 1e-9
        // against 0 is 10 abs_zero: error 10, NOOK at any tolerance below it.
        let h = histories(&[Some(1e-9)], &[Some(0.0)]);
        let outcome = spec(ErrorMeasure::Relative, Some(0.1)).evaluate(&h);
        assert!((outcome.error.unwrap() - 10.0).abs() < 1e-9, "{outcome:?}");
        assert_eq!(outcome.verdict, Verdict::Nook);
        // The mortar's unloaded step: −8.8e-22 N against 0 is a zero, error 0 (was +∞).
        let h = histories(&[Some(-8.8e-22)], &[Some(0.0)]);
        for measure in [ErrorMeasure::Relative, ErrorMeasure::RelativeToPeak] {
            let outcome = spec(measure, Some(1e-3)).evaluate(&h);
            assert_eq!((outcome.error, outcome.verdict), (Some(0.0), Verdict::Ok));
        }
        // A case's own abs_zero moves the floor.
        let h = histories(&[Some(2e-6)], &[Some(0.0)]);
        let coarse = CheckSpec {
            abs_zero: 1e-3,
            ..spec(ErrorMeasure::Relative, Some(0.01))
        };
        assert_eq!(coarse.evaluate(&h).error, Some(0.0));
        assert!(spec(ErrorMeasure::Relative, None)
            .evaluate(&h)
            .error
            .unwrap()
            .is_finite());
    }

    #[test]
    fn relative_to_peak_divides_by_the_largest_reference() {
        let h = histories(&[Some(0.1), Some(4.0)], &[Some(0.0), Some(4.0)]);
        let outcome = spec(ErrorMeasure::RelativeToPeak, Some(0.03)).evaluate(&h);
        assert!((outcome.error.unwrap() - 0.025).abs() < 1e-12);
        assert_eq!(outcome.verdict, Verdict::Ok);
    }

    #[test]
    fn missing_value_and_failed_solver_are_nook_and_unavailable_is_na() {
        let h = histories(&[None], &[Some(1.0)]);
        assert_eq!(
            spec(ErrorMeasure::Relative, Some(1.0)).evaluate(&h).verdict,
            Verdict::Nook
        );
        let mut h = histories(&[Some(1.0)], &[Some(1.0)]);
        h.insert("a".into(), Err(SolveError::Failed("boom".into())));
        assert_eq!(
            spec(ErrorMeasure::Relative, Some(1.0)).evaluate(&h).verdict,
            Verdict::Nook
        );
        h.insert("a".into(), Err(SolveError::Unavailable("not installed".into())));
        assert_eq!(
            spec(ErrorMeasure::Relative, Some(1.0)).evaluate(&h).verdict,
            Verdict::Unavailable
        );
    }

    #[test]
    fn a_map_measure_is_read_from_the_fields_at_the_positions() {
        // Four panels, q = (1, ±0.1) (subject) and (1, ±0.08) (reference), at position 1 only.
        let field = |qy: f64| SurfaceField {
            position: 1,
            points: vec![[-0.5, -0.5], [0.5, -0.5], [-0.5, 0.5], [0.5, 0.5]],
            pressure: vec![1.0; 4],
            traction: Some(vec![[1.0, qy], [1.0, -qy], [1.0, -qy], [1.0, qy]]),
            stick: Some(vec![true; 4]),
            layout: Layout::Grid { spacing: 1.0 },
            ..SurfaceField::default()
        };
        let mut h = histories(&[Some(1.0), Some(1.0)], &[Some(1.0), Some(1.0)]);
        for (name, qy) in [("a", 0.1), ("b", 0.08)] {
            h.get_mut(name).unwrap().as_mut().unwrap().fields = vec![field(qy)];
        }
        let check = CheckSpec {
            quantity: Quantity::TransverseRatio,
            at: Where::EveryPosition,
            ..spec(ErrorMeasure::Relative, Some(0.3))
        };
        // Position 0 has no field in either: nothing to compare there, not a failure.
        let outcome = check.evaluate(&h);
        assert_eq!((outcome.verdict, outcome.worst_step), (Verdict::Ok, Some(1)));
        assert!((outcome.error.unwrap() - 0.25).abs() < 1e-12, "{outcome:?}");
        // The subject without its field where the reference has one: NOOK, with the reason.
        h.get_mut("a").unwrap().as_mut().unwrap().fields.clear();
        let outcome = check.evaluate(&h);
        assert_eq!(outcome.verdict, Verdict::Nook);
        assert!(outcome.message.unwrap().contains("no transverse_ratio at step 1"));
    }

    #[test]
    fn a_known_failure_prints_known_and_a_passing_one_fixed_which_fails_the_run() {
        let h = histories(&[Some(1.05)], &[Some(1.0)]);
        let marked = |tolerance| CheckSpec {
            known_failure: Some("evidence".into()),
            ..spec(ErrorMeasure::Relative, Some(tolerance))
        };
        let failing = marked(0.01).evaluate(&h);
        assert_eq!(failing.verdict, Verdict::Known);
        assert!(!failing.verdict.fails_run() && failing.verdict.label() == "KNOWN");
        // The error is still measured and shown, not hidden.
        assert!((failing.error.unwrap() - 0.05).abs() < 1e-12);
        let passing = marked(0.1).evaluate(&h);
        assert_eq!(passing.verdict, Verdict::Fixed);
        assert!(passing.verdict.fails_run() && passing.verdict.label() == "FIXED?");
        // A failed solver stays NOOK under the mark: the mark is for a defect of a run.
        let mut broken = histories(&[Some(1.05)], &[Some(1.0)]);
        broken.insert("a".into(), Err(SolveError::Failed("boom".into())));
        assert_eq!(marked(0.01).evaluate(&broken).verdict, Verdict::Nook);
        // A run that left the step without a value (an unconverged step): KNOWN under the mark.
        let known = marked(0.01).evaluate(&histories(&[None], &[Some(1.0)]));
        assert_eq!((known.verdict, known.error), (Verdict::Known, None));
    }

    #[test]
    fn informational_checks_are_never_judged() {
        let h = histories(&[Some(5.0)], &[Some(1.0)]);
        assert_eq!(
            spec(ErrorMeasure::Relative, None).evaluate(&h).verdict,
            Verdict::Info
        );
    }
}
