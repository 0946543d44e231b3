//! The paper's own numbers: the peak pressures it quotes at 17 µm and the readings of its
//! formulas that would give them.
//!
//! The paper prints its Eqns. 3 and 4 without the −1 exponent and quotes a Hertz peak pressure of
//! 581 MPa (ANSYS: 585 MPa) at 17 µm. [`section`] evaluates Hertz under every reading of
//! δn (total approach or per sphere), E* and R* that the text admits and says which, if any,
//! gives 581 MPa; [`reading_verdict`] is the same answer for the claims.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, Result};

use super::document::{Cell, Section, Table};
use spherecontact_case::{reference, Case};
use spherecontact_model::hertz::Hertz;
use spherecontact_verify::CaseRun;

/// The approach [m] at which the paper quotes its peak pressures.
pub const QUOTED_APPROACH: f64 = 17e-6;

/// Relative distance within which a reading "reproduces" a quoted value: the quote has three
/// significant figures, so 581 stands for [580.5, 581.5), ±0.09 %.
pub const THREE_FIGURES: f64 = 0.5 / 581.0;

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

/// The peak pressures the paper quotes at 17 µm [Pa].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quoted {
    /// Its Hertz value (581 MPa).
    pub hertz_p0: f64,
    /// Its ANSYS value (585 MPa).
    pub ansys_p0: f64,
}

/// Where the paper's quoted values are kept, beside the case's folder: read as the case's own
/// files are ([`spherecontact_case::reads`]).
pub const QUOTED_FILE: &str = "../reference/paper.toml";

impl Quoted {
    /// The quoted values for `case`, from [`QUOTED_FILE`] in its tree, with the folder that holds
    /// it (which [`crate::paper::document`] reads them from); an error names the file
    /// and why.
    pub fn for_case(case: &Case) -> Result<(PathBuf, Self)> {
        let file = case
            .tree
            .resolve(QUOTED_FILE)
            .map_err(|e| anyhow!("the paper's reference file {e}"))?;
        let folder = file.parent().unwrap_or(Path::new("/")).to_path_buf();
        let quoted = Self::load(&folder)?;
        Ok((folder, quoted))
    }

    /// The quoted values from `reference/paper.toml`.
    pub fn load(reference_dir: &Path) -> Result<Self> {
        let quoted = |key: &str| {
            reference::load(&reference_dir.join("paper.toml"), key)
                .map_err(|e| anyhow!("the paper's quoted value `{key}`: {e}"))
                .map(|v| v.value)
        };
        Ok(Self {
            hertz_p0: quoted("hertz_p0_17um")?,
            ansys_p0: quoted("ansys_p0_17um")?,
        })
    }
}

/// Which readings of the paper's formulas give its Hertz p0.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadingVerdict {
    /// The readings that reproduce it within its three significant figures.
    pub matches: Vec<String>,
    /// The closest reading and its p0 [Pa].
    pub closest: (String, f64),
    /// p0 at 17 µm under the standard reading [Pa].
    pub standard_p0: f64,
    /// The approach that would give the quoted value under the standard reading [m].
    pub implied_approach: f64,
}

/// Hertz's p0 under every reading, and which reproduce `hertz_p0`.
fn evaluate(rows: &[(Reading, f64)], run: &CaseRun, hertz_p0: f64) -> ReadingVerdict {
    let misfit = |p0: f64| (p0 / hertz_p0 - 1.0).abs();
    let closest = rows
        .iter()
        .min_by(|a, b| misfit(a.1).total_cmp(&misfit(b.1)))
        .map(|(r, p0)| (r.what.clone(), *p0))
        .unwrap_or_default();
    let standard = run.case.scene.hertz().peak_pressure(QUOTED_APPROACH);
    ReadingVerdict {
        matches: rows
            .iter()
            .filter(|(_, p0)| misfit(*p0) <= THREE_FIGURES)
            .map(|(r, _)| r.what.clone())
            .collect(),
        closest,
        standard_p0: standard,
        // Under the standard reading p0 ∝ √δ.
        implied_approach: QUOTED_APPROACH * (hertz_p0 / standard).powi(2),
    }
}

/// Every reading with its p0 [Pa].
fn evaluated_readings(run: &CaseRun) -> Vec<(Reading, f64)> {
    readings(run)
        .into_iter()
        .map(|r| {
            let p0 = r.hertz.peak_pressure(r.approach);
            (r, p0)
        })
        .collect()
}

/// Which readings reproduce the paper's Hertz p0.
pub fn reading_verdict(run: &CaseRun, quoted: &Quoted) -> ReadingVerdict {
    evaluate(&evaluated_readings(run), run, quoted.hertz_p0)
}

/// The section on the paper's own numbers.
pub fn section(run: &CaseRun, quoted: &Quoted) -> Result<Section> {
    let Quoted { hertz_p0, ansys_p0 } = *quoted;
    let rows = evaluated_readings(run);
    let verdict = evaluate(&rows, run, hertz_p0);
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
    let standard_p0 = verdict.standard_p0;
    let verdict = if verdict.matches.is_empty() {
        format!(
            "No reading reproduces {:.0} MPa within its three significant figures; the closest is \"{}\" at {:.1} MPa. \
             Under the standard reading 581 MPa would need δn = {:.2} µm, not 17 µm.",
            hertz_p0 * 1e-6,
            verdict.closest.0,
            verdict.closest.1 * 1e-6,
            verdict.implied_approach * 1e6
        )
    } else {
        format!(
            "{:.0} MPa is reproduced by: {}.",
            hertz_p0 * 1e-6,
            verdict.matches.join("; ")
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
                (ansys_p0 / standard_p0 - 1.0) * 100.0,
                standard_p0 * 1e-6
            ),
        ],
        tables: vec![table],
        figures: vec![],
        folded: true,
    })
}
