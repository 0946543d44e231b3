//! Judging an impact case's checks on its runs: per sweep point the solver's value against the
//! reference's (Hertz's closed forms or another solver in the same variant), the worst error
//! over the sweep against the tolerance.

use std::fmt::Write;

use super::case::{ImpactCase, ImpactCheck, ImpactReference, Point, Quantity, Variant};
use super::closed_form::HertzImpact;
use super::solver_run::SolverRun;
use spherecontact_check::{relative_error, Drift, JudgedValue, Verdict, ABS_ZERO};
use spherecontact_model::hertz::Hertz;
use spherecontact_model::number::format_value;
use spherecontact_reference::impact::outcome::Outcome;

/// The outcome of one check.
#[derive(Clone, Debug)]
pub struct CheckOutcome {
    /// The check.
    pub check: ImpactCheck,
    /// The judgement.
    pub verdict: Verdict,
    /// At the worst point: sweep value, solver's value, reference, error.
    pub worst: Option<Worst>,
    /// Why there is no error (a solver failed, a value is missing).
    pub message: Option<String>,
    /// Every sweep point's judged value (the point's index as its step), in order; empty when
    /// there is no error: what its non-regression baseline records and compares.
    pub judged: Vec<JudgedValue>,
    /// The values against its non-regression baseline, when the case has one for this check
    /// (`baseline` (spherecontact-verify)).
    pub drift: Option<Drift>,
}

/// The worst sweep point of a check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Worst {
    /// The sweep point's index (0 without a sweep).
    pub index: usize,
    /// The sweep value there (SI), if the case sweeps.
    pub at: Option<f64>,
    /// The solver's value.
    pub value: f64,
    /// The reference's.
    pub reference: f64,
    /// The error (relative or absolute).
    pub error: f64,
}

/// Hertz's closed-form value of `quantity` for `point`, if it has one.
fn hertz_value(point: &Point, hertz: &Hertz, quantity: Quantity) -> Option<f64> {
    let closed = HertzImpact::of(point, hertz);
    match quantity {
        Quantity::ContactDuration => Some(closed.duration),
        Quantity::MaxNormalForce => Some(closed.max_force),
        Quantity::MaxOverlap => Some(closed.max_overlap),
        Quantity::NormalRestitution => Some(1.0),
        _ => None,
    }
}

/// The run of `solver` in `variant`.
fn find<'a>(runs: &'a [SolverRun], solver: &str, variant: Variant) -> Option<&'a SolverRun> {
    runs.iter().find(|r| r.solver == solver && r.variant == variant)
}

/// Judges the checks of `case` on `runs`. A check that needs a solver not among them is left
/// out: a shard judges only the checks whose solvers it ran (`verify --shard`), the merge of all
/// shards (and an unsharded run, which runs every solver the checks name) judges every check.
pub fn judge(case: &ImpactCase, runs: &[SolverRun]) -> Vec<CheckOutcome> {
    let ran = |name: &String| runs.iter().any(|r| &r.solver == name);
    case.checks
        .iter()
        .filter(|check| check.solvers().all(ran))
        .map(|check| judge_one(case, check, runs))
        .collect()
}

fn judge_one(case: &ImpactCase, check: &ImpactCheck, runs: &[SolverRun]) -> CheckOutcome {
    let failed = |message: String| CheckOutcome {
        check: check.clone(),
        verdict: if check.tolerance.is_some() {
            Verdict::Nook
        } else {
            Verdict::Info
        },
        worst: None,
        message: Some(message),
        judged: Vec::new(),
        drift: None,
    };
    let Some(subject) = find(runs, &check.solver, check.variant) else {
        return failed(format!("`{}` did not run", check.solver));
    };
    let reference_run = match &check.reference {
        ImpactReference::Hertz => None,
        ImpactReference::Solver(name) => match find(runs, name, check.variant) {
            Some(run) => Some(run),
            None => return failed(format!("`{name}` did not run")),
        },
    };
    if let Some(why) = std::iter::once(subject).chain(reference_run).find_map(|r| {
        r.unavailable
            .as_ref()
            .map(|why| format!("{} not available: {why}", r.solver))
    }) {
        return CheckOutcome {
            check: check.clone(),
            verdict: Verdict::Unavailable,
            worst: None,
            message: Some(why),
            judged: Vec::new(),
            drift: None,
        };
    }
    let hertz = Hertz::of(&case.pair());
    let points = case.points();
    let mut worst: Option<Worst> = None;
    let mut judged = Vec::new();
    for (index, (at, result)) in subject.points.iter().enumerate() {
        let value = match result {
            Ok(outcome) => outcome.get(check.quantity),
            Err(e) => return failed(format!("{}: {e}", check.solver)),
        };
        let reference = match reference_run {
            None => {
                let point = match check.variant {
                    Variant::Prescribed => points[index],
                    Variant::Elastic => points[index].elastic(),
                };
                hertz_value(&point, &hertz, check.quantity)
            }
            Some(run) => match &run.points[index].1 {
                Ok(outcome) => outcome.get(check.quantity),
                Err(e) => return failed(format!("{}: {e}", run.solver)),
            },
        };
        let (value, reference) = match (value, reference) {
            (None, None) => continue,
            (Some(v), Some(r)) => (v, r),
            (v, r) => {
                return failed(format!(
                    "{} undefined in one of them at sweep value {} (value {}, reference {})",
                    check.quantity.name(),
                    format_value(*at),
                    format_value(v),
                    format_value(r)
                ))
            }
        };
        // Against a zero reference the relative error is finite ([`relative_error`]'s abs_zero).
        let error = if check.relative {
            relative_error(value, reference, reference, ABS_ZERO)
        } else {
            (value - reference).abs()
        };
        judged.push(JudgedValue {
            step: index,
            value,
            reference,
        });
        if worst.is_none_or(|w| error > w.error) {
            worst = Some(Worst {
                index,
                at: *at,
                value,
                reference,
                error,
            });
        }
    }
    let verdict = match (check.tolerance, worst) {
        (None, _) => Verdict::Info,
        (Some(t), Some(w)) if w.error <= t => Verdict::Ok,
        (Some(_), None) => Verdict::Nook,
        (Some(_), Some(_)) => Verdict::Nook,
    };
    CheckOutcome {
        check: check.clone(),
        verdict,
        worst,
        message: worst
            .is_none()
            .then(|| "no sweep point defines the quantity".to_owned()),
        judged,
        drift: None,
    }
}

/// One printed row per check, as `verify` prints path cases' checks.
pub fn outcome_row(case: &str, outcome: &CheckOutcome) -> String {
    let check = &outcome.check;
    let reference = match &check.reference {
        ImpactReference::Hertz => "hertz closed form".to_owned(),
        ImpactReference::Solver(name) => name.clone(),
    };
    let unit = check.quantity.unit();
    let mut row = format!(
        "{:<5} {case} | {} {} ({})",
        outcome.verdict.label(),
        check.solver,
        check.quantity.name(),
        check.variant.name()
    );
    if let Some(w) = &outcome.worst {
        let _ = write!(
            row,
            " (worst at {}) | value {} {unit} | ref {} {unit} [{reference}] | error {} ({})",
            format_value(w.at),
            format_value(Some(w.value)),
            format_value(Some(w.reference)),
            format_value(Some(w.error)),
            if check.relative { "relative" } else { "absolute" }
        );
    }
    // A message over lines (a program's last output): its first line in the row, the rest below.
    let (message, more) = outcome
        .message
        .as_deref()
        .map(spherecontact_system::text::row_lines)
        .unzip();
    spherecontact_check::row::push_judgement(
        &mut row,
        check.tolerance,
        outcome.drift.as_ref(),
        message.as_deref(),
    );
    let _ = write!(row, " | {}", check.reason);
    spherecontact_system::text::one_line(&row).into_owned() + more.as_deref().unwrap_or("")
}

/// An outcome per sweep point of a solver's run, for tests and reports.
pub fn values(run: &SolverRun, quantity: Quantity) -> Vec<(Option<f64>, Option<f64>)> {
    run.points
        .iter()
        .map(|(at, r)| (*at, r.as_ref().ok().and_then(|o: &Outcome| o.get(quantity))))
        .collect()
}
