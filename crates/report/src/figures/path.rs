//! Figure 7 of the paper: the loading path.

use anyhow::Result;

use super::figure;
use crate::document::Figure;
use crate::plot::{Axes, LinePlot, Series, Style};
use spherecontact_verify::CaseRun;

/// The x coordinate of every step along the path: position k plus the fraction of its segment.
pub fn path_coordinate(run: &CaseRun) -> Vec<f64> {
    let mut x = vec![0.0];
    for (k, &m) in run.case.scene.path.substeps().iter().enumerate() {
        x.extend((1..=m).map(|j| k as f64 + j as f64 / m as f64));
    }
    x
}

/// Figure 7 of the paper: δn and δt along the path.
pub fn loading_path(run: &CaseRun) -> Result<Figure> {
    let x = path_coordinate(run);
    let steps = run.case.scene.steps();
    let series = |name: &str, value: fn(&spherecontact_model::path::Step) -> f64| {
        Series::joined(
            name,
            steps.iter().map(|s| (x[s.index], value(s) * 1e6)).collect(),
            Style::Line,
        )
    };
    let plot = LinePlot {
        title: format!("{}: loading path", run.case.name()),
        x_label: "path position".into(),
        y_label: "displacement [µm]".into(),
        series: vec![
            series("δn (normal approach)", |s| s.delta_n),
            series("δt (tangential)", |s| s.delta_t),
        ],
        axes: Axes::Linear,
    };
    let caption = format!(
        "Loading path: the total normal approach δn and the relative tangential displacement δt at each of the {} steps; integers on the x axis are the path positions.",
        steps.len()
    );
    figure(
        "loading-path",
        plot,
        caption,
        "path position",
        "displacement [µm]",
    )
}
