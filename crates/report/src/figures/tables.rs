//! The tables of a report: the check table, the solver table, and the warnings grouped once with
//! the solvers they concern; with the cells other tables borrow from them (a check verdict's
//! class, the status of a solver that did not run).

use super::histories;
use crate::document::{Cell, Table};
use spherecontact_check::{Outcome, Verdict};
use spherecontact_model::number::format_value;
use spherecontact_model::solver::SolveError;
use spherecontact_verify::CaseRun;

/// The CSS class of a check verdict.
pub fn verdict_class(verdict: Verdict) -> &'static str {
    match verdict {
        Verdict::Ok => "ok",
        Verdict::Nook => "nook",
        Verdict::Info => "info",
        Verdict::Unavailable => "na",
        Verdict::Known => "known",
        Verdict::Fixed | Verdict::Drift => "nook",
    }
}

/// The status of a solver that did not run.
pub fn missing_cell(error: &SolveError) -> Cell {
    match error {
        SolveError::Unavailable(_) => Cell::with_class("missing: not available", "na"),
        SolveError::NotApplicable(_) => Cell::with_class("missing: not applicable", "na"),
        SolveError::Failed(_) => Cell::with_class("missing: failed", "nook"),
    }
}

/// A warning stated once, with the solvers that gave it (none for the scene's own).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Warning {
    /// The solvers that gave it, in the case's order; empty for a warning about the scene.
    pub solvers: Vec<String>,
    /// What it says.
    pub text: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.solvers.is_empty() {
            write!(f, "{}", self.text)
        } else {
            write!(f, "{}: {}", self.solvers.join(", "), self.text)
        }
    }
}

/// The run's warnings, each stated once: a solver warning with every solver that gave it,
/// then the scene's own warnings.
pub fn warnings(run: &CaseRun) -> Vec<Warning> {
    let mut grouped: Vec<Warning> = Vec::new();
    let mut from_solvers = Vec::new();
    for (name, history) in histories(run) {
        for text in &history.metadata.warnings {
            from_solvers.push(format!("{name}: {text}"));
            match grouped.iter_mut().find(|w| &w.text == text) {
                Some(w) => w.solvers.push(name.clone()),
                None => grouped.push(Warning {
                    solvers: vec![name.clone()],
                    text: text.clone(),
                }),
            }
        }
    }
    let scene = run
        .warnings
        .iter()
        .filter(|w| !from_solvers.contains(w))
        .map(|w| Warning {
            solvers: Vec::new(),
            text: w.clone(),
        });
    grouped.extend(scene);
    grouped
}

/// The checks in the order a reader takes them in: the most severe verdict first
/// ([`Verdict::severity`]), then by solver in the case's order, then as the case lists them.
pub fn checks_by_severity(run: &CaseRun) -> Vec<&Outcome> {
    let solvers = run.case.required_solvers();
    let rank = |o: &Outcome| {
        solvers
            .iter()
            .position(|s| *s == o.spec.solver)
            .unwrap_or(solvers.len())
    };
    let mut outcomes: Vec<&Outcome> = run.outcomes.iter().collect();
    // A stable sort: the case's own order stays within a solver.
    outcomes.sort_by_key(|o| (std::cmp::Reverse(o.verdict.severity()), rank(o)));
    outcomes
}

/// The check table: verdict, solver, what, value against reference, error against tolerance,
/// and the tolerance's reason; the most severe first, grouped by solver.
pub fn check_table(run: &CaseRun) -> Table {
    // Six columns whose text wraps, so that the table fits a laptop screen with the reason in
    // view: what is checked, the value against its reference, the error against the tolerance,
    // and why that tolerance.
    let header = [
        "verdict",
        "solver",
        "check",
        "value against reference",
        "error (measure) / tolerance",
        "reason",
    ];
    Table {
        header: header.iter().map(|s| s.to_string()).collect(),
        rows: checks_by_severity(run)
            .into_iter()
            .map(|o| {
                let class = verdict_class(o.verdict);
                let unit = o.spec.quantity.unit();
                let worst = o
                    .worst_step
                    .map_or_else(String::new, |step| format!(" (worst: step {step})"));
                let mut reason = o.spec.reason.clone();
                if let Some(evidence) = &o.spec.known_failure {
                    reason = format!("{reason} Known failure: {evidence}");
                }
                if let Some(message) = &o.message {
                    reason = format!("{message}. {reason}");
                }
                let tolerance = o.spec.tolerance.map_or_else(
                    || "informational".to_owned(),
                    |t| format!("≤ {}", format_value(Some(t))),
                );
                vec![
                    Cell::with_class(o.verdict.label(), class),
                    Cell::plain(&o.spec.solver),
                    Cell::plain(format!("{} at {}{worst}", o.spec.quantity.name(), o.spec.at)),
                    Cell::plain(format!(
                        "{} {unit} against {} {unit} ({})",
                        format_value(o.value),
                        format_value(o.reference),
                        o.spec.reference
                    )),
                    Cell::plain(format!(
                        "{} ({}) / {tolerance}",
                        format_value(o.error),
                        o.spec.measure.name()
                    )),
                    Cell::plain(reason),
                ]
            })
            .collect(),
    }
}

/// Whether a metadata key is a duration in seconds (`meshing_s`, `solving_s`, …).
fn is_duration(key: &str) -> bool {
    key.ends_with("_s")
}

/// The wall time, with the solver's own split of it (`meshing 1.37 s, …`) where it gives one.
fn wall_time_of(metadata: &spherecontact_model::history::Metadata) -> String {
    let parts: Vec<String> = metadata
        .extra
        .iter()
        .filter(|(key, _)| is_duration(key))
        .filter_map(|(key, value)| {
            Some(format!(
                "{} {:.3} s",
                key.trim_end_matches("_s").replace('_', " "),
                value.as_f64()?
            ))
        })
        .collect();
    let total = format!("{:.3} ms", metadata.wall_time_s * 1e3);
    if parts.is_empty() {
        total
    } else {
        format!("{total} ({})", parts.join(", "))
    }
}

/// The scalar facts of a solver's metadata (`key = value`), durations excepted (they go with the
/// wall time); lists and long texts are left to the solver's JSON file, and named as such.
fn details_of(extra: &std::collections::BTreeMap<String, serde_json::Value>) -> Vec<String> {
    let mut shown = Vec::new();
    let mut elsewhere = Vec::new();
    for (key, value) in extra.iter().filter(|(key, _)| !is_duration(key)) {
        match value {
            serde_json::Value::Number(n) => match n.as_f64() {
                Some(x) if x.fract() == 0.0 && x.abs() < 1e15 => shown.push(format!("{key} = {x}")),
                Some(x) => shown.push(format!("{key} = {}", significant(x))),
                None => shown.push(format!("{key} = {n}")),
            },
            serde_json::Value::String(text) if text.chars().count() <= 80 => {
                shown.push(format!("{key} = {text}"))
            }
            serde_json::Value::Bool(b) => shown.push(format!("{key} = {b}")),
            _ => elsewhere.push(key.as_str()),
        }
    }
    if !elsewhere.is_empty() {
        shown.push(format!("more in solvers/<name>.json: {}", elsewhere.join(", ")));
    }
    shown
}

/// A measured number to four significant digits, without float noise: "0.1622", "3.492e-5",
/// "2.079e6" ("0.0000" would hide a panel size of 35 µm).
fn significant(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let magnitude = x.abs().log10().floor();
    if !(-3.0..5.0).contains(&magnitude) {
        return format!("{x:.3e}");
    }
    let decimals = (3.0 - magnitude).max(0.0) as usize;
    let text = format!("{x:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

/// The solver table: what ran, how (model, resolution, version, facts) and how long; what did
/// not run and why.
pub fn solver_table(run: &CaseRun) -> Table {
    let header = [
        "solver",
        "status",
        "model",
        "resolution",
        "version",
        "details",
        "wall time",
    ];
    Table {
        header: header.iter().map(|s| s.to_string()).collect(),
        rows: run
            .case
            .required_solvers()
            .iter()
            .map(|name| match run.histories.get(name) {
                Some(Ok(h)) => {
                    let m = &h.metadata;
                    let details = details_of(&m.extra);
                    vec![
                        Cell::plain(name),
                        Cell::with_class("ran", "ok"),
                        Cell::plain(&m.model),
                        Cell::plain(m.resolution_shown()),
                        Cell::plain(&m.version),
                        Cell::plain(details.join("; ")),
                        Cell::with_class(wall_time_of(m), "timing"),
                    ]
                }
                Some(Err(e)) => {
                    let mut row = vec![Cell::plain(name), missing_cell(e), Cell::plain(e.to_string())];
                    row.extend((0..4).map(|_| Cell::plain("—")));
                    row
                }
                None => vec![Cell::plain(name), Cell::with_class("not run", "na")]
                    .into_iter()
                    .chain((0..5).map(|_| Cell::plain("—")))
                    .collect(),
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_list_the_most_severe_first_grouped_by_solver() {
        use spherecontact_case::Case;
        use spherecontact_check::{CheckSpec, ErrorMeasure, Reference, Verdict, Where};
        use spherecontact_model::history::Quantity;
        let text = "friction = 0.2\nsolvers = [\"hertz\", \"mdr\"]\n[body1]\nradius = 0.1\nyoung = 70e9\n\
                    poisson = 0.3\n[path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n";
        let case = Case::parse(std::path::Path::new("order.toml"), text).unwrap();
        let outcome = |solver: &str, verdict: Verdict| Outcome {
            spec: CheckSpec {
                solver: solver.into(),
                quantity: Quantity::NormalForce,
                at: Where::EveryStep,
                reference: Reference::Solver("hertz".into()),
                measure: ErrorMeasure::Relative,
                tolerance: Some(0.01),
                reason: format!("{solver} {}", verdict.label()),
                known_failure: None,
                abs_zero: spherecontact_check::ABS_ZERO,
            },
            verdict,
            value: None,
            reference: None,
            error: Some(0.001),
            worst_step: None,
            message: None,
            judged: Vec::new(),
            drift: None,
        };
        let run = CaseRun {
            case,
            warnings: Vec::new(),
            histories: spherecontact_check::Histories::new(),
            outcomes: vec![
                outcome("mdr", Verdict::Ok),
                outcome("hertz", Verdict::Info),
                outcome("mdr", Verdict::Nook),
                outcome("hertz", Verdict::Ok),
                outcome("hertz", Verdict::Nook),
                outcome("mdr", Verdict::Unavailable),
            ],
        };
        let table = check_table(&run);
        let order: Vec<(&str, &str)> = table
            .rows
            .iter()
            .map(|r| (r[0].text.as_str(), r[1].text.as_str()))
            .collect();
        assert_eq!(
            order,
            [
                ("NOOK", "hertz"),
                ("NOOK", "mdr"),
                ("N/A", "mdr"),
                ("INFO", "hertz"),
                ("OK", "hertz"),
                ("OK", "mdr")
            ]
        );
        // The reason stays in the row, in its own column.
        assert_eq!(table.rows[0][5].text, "hertz NOOK");
    }

    #[test]
    fn details_keep_four_significant_digits() {
        assert_eq!(significant(3.4917e-5), "3.492e-5");
        assert_eq!(significant(0.16218), "0.1622");
        assert_eq!(significant(1238.347), "1238");
        assert_eq!(significant(2079452.5), "2.079e6");
        assert_eq!(significant(0.0), "0");
    }
}
