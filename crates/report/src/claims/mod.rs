//! The paper's claims put to the test: one row per claim — what the paper says, what the harness
//! measured (with the solver and resolution), the verdict, and the figure or check behind it.
//!
//! A claim that needs a solver or a model this build does not have says so ("not measured:
//! needs fem-3d"); nothing stands in for a measurement. Rows are built from whatever solvers ran,
//! so a new finite element solver or surface-field solver appears in them as it lands:
//! finite element solvers are recognised by the registry's naming (`fem-*`, `freefem-*`,
//! `fenicsx-*`), surface-field solvers by their maps.

mod fields;
mod forces;
pub mod measure;
pub mod study;

pub use study::Study;

use super::document::{Cell, Section, Table};
use super::paper_numbers::Quoted;
use spherecontact_verify::CaseRun;

/// What a measurement says about a claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The measurement agrees with the claim.
    Confirmed,
    /// It agrees with part of it.
    Partly,
    /// It contradicts the claim.
    NotConfirmed,
    /// Nothing in this build measures it.
    NotMeasured,
}

impl Verdict {
    /// The verdict's word.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Confirmed => "confirmed",
            Verdict::Partly => "partly",
            Verdict::NotConfirmed => "not confirmed",
            Verdict::NotMeasured => "not measured",
        }
    }

    /// Its CSS class in the report.
    pub fn class(self) -> &'static str {
        match self {
            Verdict::Confirmed => "ok",
            Verdict::Partly => "info",
            Verdict::NotConfirmed => "nook",
            Verdict::NotMeasured => "na",
        }
    }
}

/// One claim of the paper and what the harness found.
#[derive(Clone, Debug, PartialEq)]
pub struct Claim {
    /// What the paper says, and where.
    pub claim: String,
    /// What was measured, by which solver, at which resolution.
    pub measured: String,
    /// The verdict.
    pub verdict: Verdict,
    /// The verdict in a sentence.
    pub reading: String,
    /// The one number that decides the verdict, against what ("0.41 % against ≤ 1 %").
    pub decides: String,
    /// The figure, check or section behind it.
    pub evidence: String,
}

impl Claim {
    /// A claim nothing in this build measures, and what it needs.
    fn not_measured(claim: &str, needs: &str, evidence: &str) -> Self {
        Self {
            claim: claim.into(),
            measured: format!("not measured: needs {needs}"),
            verdict: Verdict::NotMeasured,
            reading: String::new(),
            decides: format!("needs {needs}"),
            evidence: evidence.into(),
        }
    }
}

/// True for the finite element solvers (in-crate or external decks), by the registry's naming.
pub fn is_finite_element(solver: &str) -> bool {
    spherecontact_model::domain::models_a_finite_body(solver)
}

/// Every claim, in the paper's order.
pub fn claims(run: &CaseRun, study: &Study, quoted: &Quoted) -> Vec<Claim> {
    let mut rows = forces::claims(run, quoted);
    rows.extend(fields::claims(run, study));
    rows
}

/// The section: the claims table and how the surface fields were resolved.
pub fn section(run: &CaseRun, study: &Study, claims: &[Claim]) -> Section {
    let table = Table {
        header: ["claim (paper)", "measured", "verdict", "finding", "behind it"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        rows: claims
            .iter()
            .map(|c| {
                vec![
                    Cell::plain(&c.claim),
                    Cell::plain(&c.measured),
                    Cell::with_class(c.verdict.label(), c.verdict.class()),
                    Cell::plain(&c.reading),
                    Cell::plain(&c.evidence),
                ]
            })
            .collect(),
    };
    let mut paragraphs = vec![
        "Each claim of the paper, what the harness measured on this run, and the verdict. \"Not measured\" names the \
         solver or model a claim needs that this build does not have; no value stands in for it."
            .to_owned(),
    ];
    let (notes, study_table) = study_notes(run, study);
    paragraphs.extend(notes);
    Section {
        title: "The paper's claims in detail".into(),
        paragraphs,
        tables: std::iter::once(table).chain(study_table).collect(),
        figures: vec![],
        folded: true,
    }
}

/// How the surface-field claims were resolved: a sentence, and the study's rungs with their
/// cost (a table, so that the timings are marked as such).
fn study_notes(run: &CaseRun, study: &Study) -> (Vec<String>, Option<Table>) {
    if study::map_solvers(run).is_empty() {
        return (Vec::new(), None);
    }
    let focus = run.case.focus;
    let own = run.case.scene.path.substeps().first().copied().unwrap_or(0);
    if study.solvers.is_empty() {
        return (
            vec![format!(
                "The surface-field claims are measured on this run's own fields ({own} increments a segment): the \
                 resolution study did not run."
            )],
            None,
        );
    }
    let text = format!(
        "The surface-field claims are measured again by each map solver at the two finest rungs of its resolution \
         ladder, on the path cut at position {focus} (the table after the claims), beside this run's own fields ({own} increments a \
         segment). h is the sample spacing over the contact radius c at position {focus}."
    );
    let rows = study
        .solvers
        .iter()
        .flat_map(|s| {
            let rungs = s.rungs.iter().map(|r| {
                vec![
                    Cell::plain(&s.solver),
                    Cell::plain(&r.resolution),
                    Cell::plain(r.increments.to_string()),
                    Cell::with_class(format!("{:.3} ms", r.seconds * 1e3), "timing"),
                ]
            });
            let problems = s.problems.iter().map(|p| {
                vec![
                    Cell::plain(&s.solver),
                    Cell::with_class(format!("failed: {p}"), "nook"),
                    Cell::plain("—"),
                    Cell::plain("—"),
                ]
            });
            rungs.chain(problems).collect::<Vec<_>>()
        })
        .collect();
    let table = Table {
        header: ["solver", "resolution", "increments a segment", "wall time"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        rows,
    };
    (vec![text], Some(table))
}

/// A worst relative difference against the limit that judges it: "0.41 % against ≤ 1.00 %".
fn against_limit(worst: f64, limit: f64) -> String {
    format!("{:.2} % against ≤ {:.2} %", worst * 100.0, limit * 100.0)
}

/// A relative difference as a signed percentage, "+0.37 %".
fn percent(value: f64) -> String {
    format!("{:+.2} %", value * 100.0)
}

#[cfg(test)]
mod tests;
