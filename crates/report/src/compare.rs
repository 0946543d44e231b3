//! `compare`: one report of a case — its solvers side by side, its checks, P against δn, Q along
//! the path, surface fields at the case's focus position, and every solver's error against its
//! reference.

use anyhow::Result;

use super::document::{Document, Section};
use super::figures;
use super::glance;
use spherecontact_check::Verdict;
use spherecontact_verify::CaseRun;

/// The "Case" section: description, bodies, warnings and the solver table in full (folded: the
/// first screen has a line per solver).
pub fn case_section(run: &CaseRun) -> Section {
    let scene = &run.case.scene;
    let body = |b: &spherecontact_model::pair::Body| {
        let radius = if b.radius.is_infinite() {
            "a flat".to_owned()
        } else {
            format!("R = {} m", b.radius)
        };
        format!(
            "{radius}, E = {:.4e} Pa, ν = {}",
            b.material.young, b.material.poisson
        )
    };
    let mut paragraphs = vec![
        run.case.description.clone(),
        format!(
            "Body 1: {}. Body 2: {}. Friction μ = {}. {} path positions, {} steps. File: {}.",
            body(&scene.pair.body1),
            body(&scene.pair.body2),
            scene.friction,
            scene.path.positions().len(),
            scene.steps().len(),
            run.case.file.display()
        ),
    ];
    paragraphs.extend(figures::warnings(run).iter().map(|w| match w.solvers.len() {
        0 => format!("Warning: {}", w.text),
        _ => format!("Warning ({}): {}", w.solvers.join(", "), w.text),
    }));
    Section {
        title: "Case and solvers".into(),
        paragraphs,
        tables: vec![figures::solver_table(run)],
        figures: vec![],
        folded: true,
    }
}

/// The "Checks" section: counts and the check table, folded when every check passed or is
/// informational (open when a reader has something to look at).
pub fn checks_section(run: &CaseRun) -> Section {
    Section {
        title: "Checks".into(),
        paragraphs: vec![format!(
            "{}. INFO checks measure approximate laws and are never judged; N/A names a solver that is not \
             available; KNOWN is a defect of an external code shown with its evidence (it does not fail the run), \
             FIXED? a known failure that passes (it fails the run until its mark is removed). The most severe first, by solver.",
            glance::verdict_counts(&run.outcomes)
        )],
        tables: vec![figures::check_table(run)],
        figures: vec![],
        folded: run
            .outcomes
            .iter()
            .all(|o| matches!(o.verdict, Verdict::Ok | Verdict::Info)),
    }
}

/// A section holding figures only (dropped by the caller when it has none).
pub fn figure_section(title: &str, figures: Vec<super::document::Figure>) -> Section {
    Section {
        title: title.into(),
        figures,
        ..Section::default()
    }
}

/// The compare report of a case run.
pub fn document(run: &CaseRun) -> Result<Document> {
    let focus = run.case.focus;
    let mut fields = figures::profiles(run, focus)?;
    fields.extend(figures::maps(run, focus)?);
    let sections = vec![
        glance::section(run, None),
        figure_section("Loading path", vec![figures::loading_path(run)?]),
        figure_section("Normal force", figures::normal_force(run)?.into_iter().collect()),
        figure_section(
            "Tangential force",
            figures::tangential_force(run)?.into_iter().collect(),
        ),
        figure_section(&format!("Surface fields at position {focus}"), fields),
        figure_section("Errors against the references", figures::errors(run)?),
        super::dem_scoreboard::section(run),
        checks_section(run),
        case_section(run),
    ];
    Ok(Document {
        title: format!("spherecontact: {}", run.case.name()),
        sections: sections
            .into_iter()
            .filter(|s| !s.tables.is_empty() || !s.figures.is_empty())
            .collect(),
    })
}
