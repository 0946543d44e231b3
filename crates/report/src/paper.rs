//! `reproduce-paper`: the paper's case with every available solver, reported in the order of the
//! paper's figures, plus the arithmetic of the paper's own numbers ([`super::paper_numbers`]).

use std::path::Path;

use anyhow::Result;

use super::claims::{self, Study};
use super::compare::{case_section, checks_section, figure_section};
use super::document::Document;
use super::figures;
use super::glance;
use super::paper_numbers::{self, Quoted};
use spherecontact_verify::CaseRun;

/// The reproduce-paper report; `study` resolves the surface-field claims ([`Study::of_ladders`],
/// or [`Study::none`] for the run's own fields only); `discretisation` is the run of the paper's
/// discretisation case, or why there is none ([`super::discretisation`]).
pub fn document(
    run: &CaseRun,
    study: &Study,
    reference_dir: &Path,
    discretisation: &super::discretisation::Discretisation,
) -> Result<Document> {
    let focus = run.case.focus;
    let quoted = Quoted::load(reference_dir)?;
    let mut fields = figures::profiles(run, focus)?;
    fields.extend(figures::maps(run, focus)?);
    let claims = claims::claims(run, study, &quoted);
    let sections = vec![
        glance::section(run, Some(&claims)),
        figure_section(
            "Figure 7: normal and tangential loading",
            vec![figures::loading_path(run)?],
        ),
        figure_section(
            "Figure 8: normal force against Hertz",
            figures::normal_force(run)?.into_iter().collect(),
        ),
        figure_section(
            "Figure 9: tangential force against Mindlin–Deresiewicz",
            figures::tangential_force(run)?.into_iter().collect(),
        ),
        figure_section(
            &format!("Figures 10–12: pressure, frictional stress and contact status at position {focus}"),
            fields,
        ),
        figure_section("Errors against the references", figures::errors(run)?),
        super::discretisation::section(discretisation),
        super::dem_scoreboard::section(run),
        claims::section(run, study, &claims),
        checks_section(run),
        paper_numbers::section(run, &quoted)?,
        case_section(run),
    ];
    Ok(Document {
        title: "spherecontact: reproducing Khawaja & Parvez (two spheres, Hertz and Mindlin–Deresiewicz)"
            .into(),
        sections: sections
            .into_iter()
            .filter(|s| !s.tables.is_empty() || !s.figures.is_empty() || s.title.starts_with("The paper"))
            .collect(),
    })
}
