//! Figures 8 and 9 of the paper: P against δn and Q along the path, every solver against its
//! reference. A solver with values at some steps only (the external decks solve the path
//! positions) is drawn as markers, joined only between consecutive computed steps.

use anyhow::Result;

use super::path::path_coordinate;
use super::{figure, histories, missing, NORMAL_REFERENCE, TANGENTIAL_REFERENCE};
use crate::history::{History, Quantity};
use crate::report::document::Figure;
use crate::report::plot::{Axes, LinePlot, Series, Style};
use crate::verify::CaseRun;

/// A history's `quantity` as runs of consecutive steps, against `x[step]`.
fn runs(history: &History, quantity: Quantity, x: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut previous = None;
    for row in &history.steps {
        let Some(value) = quantity.of(row) else {
            continue;
        };
        let point = (x[row.step], value);
        match runs.last_mut() {
            Some(run) if previous == Some(row.step.wrapping_sub(1)) => run.push(point),
            _ => runs.push(vec![point]),
        }
        previous = Some(row.step);
    }
    runs
}

/// One series per solver with `quantity`, against `x[step]`: the reference dashed, a solver
/// with every step as a line, a solver with gaps as markers.
fn quantity_series(run: &CaseRun, quantity: Quantity, reference: &str, x: &[f64]) -> Vec<Series> {
    let mut series: Vec<Series> = histories(run)
        .into_iter()
        .filter_map(|(name, history)| {
            let runs = runs(history, quantity, x);
            let style = match (name == reference, runs.len()) {
                (_, 0) => return None,
                (true, _) => Style::Reference,
                (false, 1) => Style::Line,
                (false, _) => Style::Markers,
            };
            Some(Series { name, runs, style })
        })
        .collect();
    // The reference is drawn last, on top.
    series.sort_by_key(|s| s.style == Style::Reference);
    series
}

/// The caption's note on the solvers drawn as markers, or "".
fn sparse_note(series: &[Series]) -> String {
    let sparse: Vec<&str> = series
        .iter()
        .filter(|s| s.style == Style::Markers)
        .map(|s| s.name.as_str())
        .collect();
    if sparse.is_empty() {
        String::new()
    } else {
        format!(
            " Markers: {} (values at the path positions only; nothing is drawn between them).",
            sparse.join(", ")
        )
    }
}

/// Figure 8 of the paper: P against δn for every solver, Hertz as the reference.
pub fn normal_force(run: &CaseRun) -> Result<Option<Figure>> {
    let delta_n: Vec<f64> = run.case.scene.steps().iter().map(|s| s.delta_n * 1e6).collect();
    let series = quantity_series(run, Quantity::NormalForce, NORMAL_REFERENCE, &delta_n);
    if series.is_empty() {
        return Ok(None);
    }
    let caption = format!(
        "Normal force P against the normal approach δn; dashed: {NORMAL_REFERENCE}.{}{}",
        sparse_note(&series),
        missing(run)
    );
    let plot = LinePlot {
        title: format!("{}: normal force", run.case.name()),
        x_label: "δn [µm]".into(),
        y_label: "P [N]".into(),
        series,
        axes: Axes::Linear,
    };
    figure("normal-force", plot, caption, "delta_n [um]", "P [N]").map(Some)
}

/// Figure 9 of the paper: Q along the path for every solver and law, MDR as the reference.
pub fn tangential_force(run: &CaseRun) -> Result<Option<Figure>> {
    let x = path_coordinate(run);
    let series = quantity_series(run, Quantity::TangentialForce, TANGENTIAL_REFERENCE, &x);
    if series.is_empty() {
        return Ok(None);
    }
    let caption = format!(
        "Tangential force Q along the path; dashed: {TANGENTIAL_REFERENCE} (exact Mindlin–Deresiewicz).{}{}",
        sparse_note(&series),
        missing(run)
    );
    let plot = LinePlot {
        title: format!("{}: tangential force", run.case.name()),
        x_label: "path position".into(),
        y_label: "Q [N]".into(),
        series,
        axes: Axes::Linear,
    };
    figure("tangential-force", plot, caption, "path position", "Q [N]").map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::history::StepResult;

    #[test]
    fn gaps_split_runs() {
        let row = |step: usize, force: Option<f64>| StepResult {
            step,
            normal_force: force,
            ..StepResult::default()
        };
        let history = History {
            steps: vec![
                row(0, Some(0.0)),
                row(1, Some(1.0)),
                row(2, None),
                row(3, Some(3.0)),
                row(4, None),
                row(5, Some(5.0)),
            ],
            ..History::default()
        };
        let x: Vec<f64> = (0..6).map(|k| k as f64).collect();
        assert_eq!(
            runs(&history, Quantity::NormalForce, &x),
            vec![vec![(0.0, 0.0), (1.0, 1.0)], vec![(3.0, 3.0)], vec![(5.0, 5.0)]]
        );
    }
}
