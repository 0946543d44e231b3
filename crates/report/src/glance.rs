//! The first screen of a report, the answer before the detail: the verdict counts, one line per
//! claim of the paper (claim, verdict, the number that decides it), and one line per solver
//! (status, model in a few words, resolution, time, worst error against its reference).

use super::claims::{self, Claim};
use super::document::{Cell, Section, Table};
use super::figures::missing_cell;
use spherecontact_case::registry;
use spherecontact_check::{ErrorMeasure, Outcome, Verdict};
use spherecontact_verify::CaseRun;

/// "2 NOOK, 0 N/A, 5 INFO, 40 OK": how many of `verdicts` are each of `order`, in that order.
fn counts<V: Copy + PartialEq>(order: &[V], verdicts: &[V], label: fn(V) -> &'static str) -> String {
    order
        .iter()
        .map(|&v| format!("{} {}", verdicts.iter().filter(|&&w| w == v).count(), label(v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// "2 NOOK, 0 N/A, 5 INFO, 40 OK": every verdict, the most severe first.
pub fn verdict_counts(outcomes: &[Outcome]) -> String {
    let verdicts: Vec<Verdict> = outcomes.iter().map(|o| o.verdict).collect();
    counts(&Verdict::by_severity(), &verdicts, Verdict::label)
}

/// "3 not confirmed, 1 partly, 4 confirmed, 1 not measured".
fn claim_counts(claims: &[Claim]) -> String {
    use claims::Verdict::*;
    let verdicts: Vec<claims::Verdict> = claims.iter().map(|c| c.verdict).collect();
    counts(
        &[NotConfirmed, Partly, Confirmed, NotMeasured],
        &verdicts,
        claims::Verdict::label,
    )
}

/// The first section: counts, the claims (when the report has them) and the solvers.
pub fn section(run: &CaseRun, claims: Option<&[Claim]>) -> Section {
    let failed = run.histories.values().filter(|h| h.is_err()).count();
    let mut counts = format!(
        "Checks: {}. Solvers: {} ran, {failed} missing.",
        verdict_counts(&run.outcomes),
        run.histories.len() - failed
    );
    let mut tables = Vec::new();
    if let Some(claims) = claims {
        counts.push_str(&format!(" The paper's claims: {}.", claim_counts(claims)));
        tables.push(claim_table(claims));
    }
    tables.push(solver_lines(run));
    Section {
        title: "At a glance".into(),
        paragraphs: vec![counts],
        tables,
        ..Section::default()
    }
}

/// One line per claim: verdict, claim, the number that decides it.
fn claim_table(claims: &[Claim]) -> Table {
    Table {
        header: vec!["verdict".into(), "claim of the paper".into(), "decided by".into()],
        rows: claims
            .iter()
            .map(|c| {
                vec![
                    Cell::with_class(c.verdict.label(), c.verdict.class()),
                    Cell::plain(&c.claim),
                    Cell::plain(&c.decides),
                ]
            })
            .collect(),
    }
}

/// A solver's description in a few words: up to its first clause, at most `WORDS` words.
fn model_in_brief(model: &str) -> String {
    /// A few words: a column a reader scans; the full model is in the solver table below.
    const WORDS: usize = 7;
    let clause = model.split([':', ';', '(', ',']).next().unwrap_or(model).trim();
    let words: Vec<&str> = clause.split_whitespace().collect();
    if words.len() > WORDS {
        format!("{} …", words[..WORDS].join(" "))
    } else {
        words.join(" ")
    }
}

/// How much a check asks for a reader's eye: its verdict's severity, then its error against its
/// tolerance (the error itself where none is judged; 0 without an error).
pub fn weight(o: &Outcome) -> (u8, f64) {
    let error = o.error.unwrap_or(0.0);
    let scaled = o.spec.tolerance.filter(|t| *t > 0.0).map_or(error, |t| error / t);
    (o.verdict.severity(), scaled)
}

/// The check of `solver` a reader must see first: the most severe verdict, then the largest
/// error against its tolerance (or the largest error where none is judged).
pub fn worst_check<'a>(run: &'a CaseRun, solver: &str) -> Option<&'a Outcome> {
    run.outcomes
        .iter()
        .filter(|o| o.spec.solver == solver)
        .max_by(|a, b| {
            let (a, b) = (weight(a), weight(b));
            a.0.cmp(&b.0).then(a.1.total_cmp(&b.1))
        })
}

/// `error` of `outcome`'s check as a reader reads it: a percentage for relative measures, the
/// value with its unit for absolute ones.
fn error_text(error: f64, outcome: &Outcome) -> String {
    match outcome.spec.measure {
        ErrorMeasure::Absolute => format!("{error:.3e} {}", outcome.spec.quantity.unit()),
        _ => format!("{:.3} %", error * 100.0),
    }
}

/// "NOOK: normal_force 1.234 % against hertz (≤ 1.000 %)".
pub fn worst_text(outcome: &Outcome) -> String {
    let error = outcome
        .error
        .filter(|e| e.is_finite())
        .map_or_else(|| "no value".to_owned(), |e| error_text(e, outcome));
    let limit = outcome
        .spec
        .tolerance
        .map_or_else(String::new, |t| format!(" (≤ {})", error_text(t, outcome)));
    format!(
        "{}: {} {error} against {}{limit}",
        outcome.verdict.label(),
        outcome.spec.quantity.name(),
        outcome.spec.reference
    )
}

/// One line per solver of the case.
fn solver_lines(run: &CaseRun) -> Table {
    // The time last: the one cell that changes from run to run ends the row.
    let header = [
        "solver",
        "kind",
        "status",
        "model",
        "resolution",
        "worst check",
        "time",
    ];
    let rows = run
        .case
        .required_solvers()
        .iter()
        .map(|name| {
            let worst = worst_check(run, name).map_or_else(|| "no check".to_owned(), worst_text);
            let (status, model, resolution, time) = match run.histories.get(name) {
                Some(Ok(h)) => (
                    Cell::with_class("ran", "ok"),
                    model_in_brief(
                        &registry::by_name(name)
                            .map_or_else(|| h.metadata.model.clone(), |s| s.description().to_owned()),
                    ),
                    h.metadata.resolution.clone(),
                    Cell::with_class(seconds(h.metadata.wall_time_s), "timing"),
                ),
                Some(Err(e)) => (missing_cell(e), String::new(), String::new(), Cell::plain("—")),
                None => (
                    Cell::with_class("not run", "na"),
                    String::new(),
                    String::new(),
                    Cell::plain("—"),
                ),
            };
            vec![
                Cell::plain(name),
                Cell::plain(run.case.kind_in_words(name)),
                status,
                Cell::plain(model),
                Cell::plain(resolution),
                // Plain: the text starts with its verdict, and a verdict's class would keep it on
                // one line.
                Cell::plain(worst),
                time,
            ]
        })
        .collect();
    Table {
        header: header.iter().map(|s| s.to_string()).collect(),
        rows,
    }
}

/// A duration for people: "12.3 ms", "4.56 s".
pub fn seconds(s: f64) -> String {
    if s < 1.0 {
        format!("{:.1} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn models_are_cut_to_a_few_words() {
        assert_eq!(
            model_in_brief("Hertz closed form: P, c, p0"),
            "Hertz closed form",
            "up to the first clause"
        );
        assert_eq!(
            model_in_brief("one two three four five six seven eight"),
            "one two three four five six seven …"
        );
    }

    #[test]
    fn verdicts_are_counted_the_most_severe_first() {
        assert_eq!(
            Verdict::by_severity(),
            [
                Verdict::Nook,
                Verdict::Fixed,
                Verdict::Drift,
                Verdict::Known,
                Verdict::Unavailable,
                Verdict::Info,
                Verdict::Ok
            ]
        );
        assert_eq!(
            counts(&[1, 2], &[2, 2, 1], |v| if v == 1 { "one" } else { "two" }),
            "1 one, 2 two"
        );
    }

    #[test]
    fn durations_read_in_their_unit() {
        assert_eq!(seconds(0.01234), "12.3 ms");
        assert_eq!(seconds(4.561), "4.56 s");
    }
}
