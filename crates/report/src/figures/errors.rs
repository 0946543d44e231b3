//! Each solver's error against its reference at every path position, on a log axis. An error
//! that is exactly zero cannot be drawn there: the caption says where, no point stands on an
//! invented floor.

use anyhow::Result;

use crate::document::Figure;
use crate::plot::{Axes, LinePlot, Series};
use crate::{
    figures::data_of, figures::histories, figures::missing, figures::NORMAL_REFERENCE,
    figures::TANGENTIAL_REFERENCE,
};
use spherecontact_model::domain::models_a_finite_body;
use spherecontact_model::history::{History, Quantity};
use spherecontact_verify::bench::CORRECTED_REFERENCE;
use spherecontact_verify::CaseRun;

/// |value − reference| at every path position where both exist and the scale is positive:
/// relative to the reference for P, to the reference's peak |Q| for Q.
pub fn position_errors(quantity: Quantity, history: &History, reference: &History) -> Vec<(usize, f64)> {
    let peak = reference.peak(quantity);
    history
        .at_positions()
        .filter_map(|row| {
            let value = quantity.of(row)?;
            let expected = quantity.of(reference.steps.get(row.step)?)?;
            let scale = if quantity == Quantity::NormalForce {
                expected.abs()
            } else {
                peak
            };
            let position = row.position?;
            (scale > 0.0).then(|| (position, (value - expected).abs() / scale))
        })
        .collect()
}

/// "a (positions 0, 11); b (position 3)".
fn zero_list(zeros: &[(String, Vec<usize>)]) -> String {
    zeros
        .iter()
        .map(|(name, at)| {
            let list: Vec<String> = at.iter().map(|p| p.to_string()).collect();
            let word = if at.len() == 1 { "position" } else { "positions" };
            format!("{name} ({word} {})", list.join(", "))
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The error figures: P against Hertz (relative), Q against MDR (relative to MDR's peak |Q|);
/// finite bodies also against `mdr-domain` when the run has it.
/// Solvers identical to the reference at every position are named in the caption, not drawn.
pub fn errors(run: &CaseRun) -> Result<Vec<Figure>> {
    let all = histories(run);
    let mut figures = Vec::new();
    for (quantity, symbol, reference, measure, y_label) in [
        (
            Quantity::NormalForce,
            "P",
            NORMAL_REFERENCE,
            "relative",
            format!("|P − P_{NORMAL_REFERENCE}| / P_{NORMAL_REFERENCE}"),
        ),
        (
            Quantity::TangentialForce,
            "Q",
            TANGENTIAL_REFERENCE,
            "relative to the reference's peak |Q|",
            format!("|Q − Q_{TANGENTIAL_REFERENCE}| / max |Q_{TANGENTIAL_REFERENCE}|"),
        ),
    ] {
        let Some(reference_history) = all.iter().find(|(n, _)| n == reference).map(|(_, h)| *h) else {
            continue;
        };
        // Finite bodies are scored against the corrected reference when the run has it, and
        // drawn raw against the half-space beside it: the discretisation and the domain effect.
        let corrected = all
            .iter()
            .find(|(n, _)| n == CORRECTED_REFERENCE)
            .map(|(_, h)| *h);
        let (mut series, mut exact, mut zeros) = (Vec::new(), Vec::new(), Vec::new());
        let mut add = |label: String, points: Vec<(usize, f64)>| {
            if points.is_empty() {
                return;
            }
            let zero_at: Vec<usize> = points.iter().filter(|p| p.1 == 0.0).map(|p| p.0).collect();
            if zero_at.len() == points.len() {
                exact.push(label);
                return;
            }
            if !zero_at.is_empty() {
                zeros.push((label.clone(), zero_at));
            }
            let drawn = points
                .iter()
                .filter(|p| p.1 > 0.0)
                .map(|&(k, e)| (k as f64, e))
                .collect();
            series.push(Series::scattered(label, drawn));
        };
        for (name, history) in all.iter().filter(|(n, _)| n != reference) {
            let finite = corrected.filter(|_| models_a_finite_body(name));
            let label = if finite.is_some() {
                format!("{name} raw")
            } else {
                name.clone()
            };
            add(label, position_errors(quantity, history, reference_history));
            if let Some(corrected) = finite {
                add(
                    format!("{name} vs {CORRECTED_REFERENCE}"),
                    position_errors(quantity, history, corrected),
                );
            }
        }
        let scored = corrected.is_some() && all.iter().any(|(n, _)| models_a_finite_body(n));
        if series.is_empty() {
            continue;
        }
        let mut caption = format!(
            "Error of {symbol} against {reference} at every path position ({measure}); the solvers' markers \
             are set side by side around each position so that equal errors do not hide each other."
        );
        if scored {
            caption.push_str(&format!(
                " Finite-body solvers (FEM, decks) are drawn twice: against {CORRECTED_REFERENCE} (Mindlin–Deresiewicz \
                 in series with the case's domain, docs/finite-body.md), which is their discretisation error, and \
                 \"raw\" against {reference}, which adds the domain effect."
            ));
        }
        if !exact.is_empty() {
            caption.push_str(&format!(
                " Identical to {reference} at every position (zero error, not drawn on the log axis): {}.",
                exact.join(", ")
            ));
        }
        if !zeros.is_empty() {
            caption.push_str(&format!(
                " Zero error (not drawn on the log axis) at: {}.",
                zero_list(&zeros)
            ));
        }
        caption.push_str(&missing(run));
        // The data keep the positions; the drawing sets the solvers side by side around them.
        let data = LinePlot {
            title: format!("{}: {symbol} error against {reference}", run.case.name()),
            x_label: "path position".into(),
            y_label,
            series,
            axes: Axes::LogY,
        };
        let mut plot = data.clone();
        let count = plot.series.len() as f64;
        for (k, series) in plot.series.iter_mut().enumerate() {
            let shift = 0.5 * (k as f64 - (count - 1.0) / 2.0) / count;
            series.runs.iter_mut().flatten().for_each(|p| p.0 += shift);
        }
        figures.push(Figure {
            id: format!("{}-error", quantity.name().replace('_', "-")),
            data: data_of(&data, "position", "error"),
            svg: plot.to_svg()?,
            caption,
        });
    }
    Ok(figures)
}
