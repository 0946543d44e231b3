//! `reproduce-paper`: the paper's case with every available solver, reported in the order of the
//! paper's figures, plus the arithmetic of the paper's own numbers.
//!
//! The paper prints its Eqns. 3 and 4 without the −1 exponent and quotes a Hertz peak pressure of
//! 581 MPa (ANSYS: 585 MPa) at 17 µm. [`paper_numbers`] evaluates Hertz under every reading of
//! δn (total approach or per sphere), E* and R* that the text admits and says which, if any,
//! gives 581 MPa.

use std::path::Path;

use anyhow::{anyhow, Result};

use super::compare::{case_section, checks_section, figure_section};
use super::document::{Cell, Document, Section, Table};
use super::figures;
use crate::case::reference;
use crate::hertz::Hertz;
use crate::verify::CaseRun;

/// The approach [m] at which the paper quotes its peak pressures.
pub const QUOTED_APPROACH: f64 = 17e-6;

/// Relative distance within which a reading "reproduces" a quoted value: the quote has three
/// significant figures, so 581 stands for [580.5, 581.5), ±0.09 %.
const THREE_FIGURES: f64 = 0.5 / 581.0;

/// A reading of the paper's formulas.
struct Reading {
    what: String,
    hertz: Hertz,
    approach: f64,
}

/// The readings of δn, E* and R* that the text admits, for the scene's (identical) spheres.
fn readings(run: &CaseRun) -> Vec<Reading> {
    let pair = &run.case.scene.pair;
    let (e, nu, r) = (
        pair.body1.material.young,
        pair.body1.material.poisson,
        pair.body1.radius,
    );
    let moduli = [
        ("E* = E/2(1−ν²) (Eqn. 3 with −1)", pair.effective_modulus()),
        ("E* = E/(1−ν²) (one body)", e / (1.0 - nu * nu)),
    ];
    let radii = [
        ("R* = R/2 (Eqn. 4 with −1)", pair.effective_radius()),
        ("R* = R (one sphere)", r),
    ];
    let approaches = [
        ("δn = 17 µm total (the paper's 2α)", QUOTED_APPROACH),
        ("17 µm per sphere (δn = 34 µm)", 2.0 * QUOTED_APPROACH),
    ];
    let mut list = Vec::new();
    for (approach_text, approach) in approaches {
        for (modulus_text, modulus) in moduli {
            for (radius_text, radius) in radii {
                list.push(Reading {
                    what: format!("{approach_text}; {modulus_text}; {radius_text}"),
                    hertz: Hertz {
                        effective_modulus: modulus,
                        effective_radius: radius,
                    },
                    approach,
                });
            }
        }
    }
    list
}

/// The section on the paper's own numbers.
pub fn paper_numbers(run: &CaseRun, reference_dir: &Path) -> Result<Section> {
    let quoted = |key: &str| {
        reference::load(&reference_dir.join("paper.toml"), key)
            .map_err(|e| anyhow!("reference/paper.toml#{key}: {e:?}"))
            .map(|v| v.value)
    };
    let (hertz_p0, ansys_p0) = (quoted("hertz_p0_17um")?, quoted("ansys_p0_17um")?);
    let rows: Vec<(Reading, f64)> = readings(run)
        .into_iter()
        .map(|r| {
            let p0 = r.hertz.peak_pressure(r.approach);
            (r, p0)
        })
        .collect();
    let closest = rows
        .iter()
        .min_by(|a, b| {
            (a.1 / hertz_p0 - 1.0)
                .abs()
                .total_cmp(&(b.1 / hertz_p0 - 1.0).abs())
        })
        .expect("eight readings");
    let matches: Vec<&str> = rows
        .iter()
        .filter(|(_, p0)| (p0 / hertz_p0 - 1.0).abs() <= THREE_FIGURES)
        .map(|(r, _)| r.what.as_str())
        .collect();
    let standard = run.case.scene.hertz();
    // Under the standard reading p0 ∝ √δ: the approach that would give the quoted value.
    let implied = QUOTED_APPROACH * (hertz_p0 / standard.peak_pressure(QUOTED_APPROACH)).powi(2);
    let table = Table {
        header: ["reading", "P [N]", "c [mm]", "p0 [MPa]", "p0 / 581 MPa − 1"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        rows: rows
            .iter()
            .map(|(r, p0)| {
                let reproduces = (p0 / hertz_p0 - 1.0).abs() <= THREE_FIGURES;
                vec![
                    Cell::plain(&r.what),
                    Cell::plain(format!("{:.2}", r.hertz.force(r.approach))),
                    Cell::plain(format!("{:.5}", r.hertz.contact_radius(r.approach) * 1e3)),
                    Cell::plain(format!("{:.1}", p0 * 1e-6)),
                    Cell::with_class(
                        format!("{:+.2} %", (p0 / hertz_p0 - 1.0) * 100.0),
                        if reproduces { "ok" } else { "" },
                    ),
                ]
            })
            .collect(),
    };
    let verdict = if matches.is_empty() {
        format!(
            "No reading reproduces {:.0} MPa within its three significant figures; the closest is \"{}\" at {:.1} MPa. \
             Under the standard reading 581 MPa would need δn = {:.2} µm, not 17 µm.",
            hertz_p0 * 1e-6,
            closest.0.what,
            closest.1 * 1e-6,
            implied * 1e6
        )
    } else {
        format!(
            "{:.0} MPa is reproduced by: {}.",
            hertz_p0 * 1e-6,
            matches.join("; ")
        )
    };
    Ok(Section {
        title: "The paper's own numbers".into(),
        paragraphs: vec![
            "As printed, Eqn. 3 reads E* = [(1−ν1²)/E1 + (1−ν2²)/E2] and Eqn. 4 reads R* = [1/R1 + 1/R2], without the −1 \
             exponent: the first is then a compliance (1/Pa) and the second a curvature (1/m), and the Hertz formulas \
             become dimensionally inconsistent, so the printed form cannot be meant literally. The standard reading \
             (Johnson 1985) raises both to −1."
                .into(),
            format!(
                "The paper quotes a Hertz peak pressure p0 = {:.0} MPa and an ANSYS maximum of {:.0} MPa at 17 µm. \
                 The table evaluates Hertz for the paper's spheres under each reading of δn, E* and R*.",
                hertz_p0 * 1e-6,
                ansys_p0 * 1e-6
            ),
            verdict,
            format!(
                "The ANSYS value is {:+.2} % from the paper's own Hertz value and {:+.2} % from the standard reading's {:.1} MPa.",
                (ansys_p0 / hertz_p0 - 1.0) * 100.0,
                (ansys_p0 / standard.peak_pressure(QUOTED_APPROACH) - 1.0) * 100.0,
                standard.peak_pressure(QUOTED_APPROACH) * 1e-6
            ),
        ],
        tables: vec![table],
        figures: vec![],
    })
}

/// The reproduce-paper report.
pub fn document(run: &CaseRun, reference_dir: &Path) -> Result<Document> {
    let focus = run.case.focus;
    let mut fields = figures::profiles(run, focus)?;
    fields.extend(figures::maps(run, focus)?);
    let sections = vec![
        case_section(run),
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
        paper_numbers(run, reference_dir)?,
        figure_section("Errors against the references", figures::errors(run)?),
        checks_section(run),
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
