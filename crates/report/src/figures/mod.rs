//! The figures and tables that reports draw from a case run: the loading path, P against δn,
//! Q along the path, surface profiles and maps at one position, errors against the references,
//! the check table and the solver table.
//!
//! A solver that failed or is not installed has no series: each caption names it as missing,
//! with the reason, so that it is never drawn as a flat line or a zero.

mod errors;
mod forces;
mod maps;
mod path;
mod profiles;
pub mod surface;
mod tables;

pub use errors::{errors, position_errors};
pub use forces::{normal_force, tangential_force};
pub use maps::maps;
pub use path::{loading_path, path_coordinate};
pub use profiles::profiles;
pub use tables::{check_table, missing_cell, solver_table, verdict_class, warnings, Warning};

use anyhow::Result;

use super::document::{Cell, Figure, Table};
use super::plot::LinePlot;
use spherecontact_model::history::History;
use spherecontact_verify::CaseRun;
use surface::FieldView;

/// The solver every normal quantity is drawn against.
pub const NORMAL_REFERENCE: &str = "hertz";
/// The solver every tangential quantity is drawn against.
pub const TANGENTIAL_REFERENCE: &str = "mdr";

/// The histories that ran, in the case's solver order.
pub fn histories(run: &CaseRun) -> Vec<(String, &History)> {
    run.case
        .required_solvers()
        .into_iter()
        .filter_map(|name| match run.histories.get(&name) {
            Some(Ok(history)) => Some((name, history)),
            _ => None,
        })
        .collect()
}

/// The history of `name`, if it ran.
pub fn history<'a>(run: &'a CaseRun, name: &str) -> Option<&'a History> {
    run.histories.get(name).and_then(|r| r.as_ref().ok())
}

/// " Missing: a (reason); b (reason)." for the solvers that did not run, or "".
fn missing(run: &CaseRun) -> String {
    let gone: Vec<String> = run
        .histories
        .iter()
        .filter_map(|(name, result)| result.as_ref().err().map(|e| format!("{name} ({e})")))
        .collect();
    if gone.is_empty() {
        String::new()
    } else {
        format!(" Missing: {}.", gone.join("; "))
    }
}

/// The surface fields at `position`, by solver, in the case's solver order.
pub fn fields_at(run: &CaseRun, position: usize) -> Vec<(String, FieldView<'_>)> {
    histories(run)
        .into_iter()
        .filter_map(|(name, h)| Some((name, FieldView::at_position(h, position)?)))
        .collect()
}

/// The long-format table (series, x, y) behind a plot.
fn data_of(plot: &LinePlot, x: &str, y: &str) -> Table {
    Table {
        header: vec!["series".into(), x.into(), y.into()],
        rows: plot
            .series
            .iter()
            .flat_map(|s| {
                s.points().map(|(a, b)| {
                    vec![
                        Cell::plain(&s.name),
                        Cell::plain(format!("{a:.8e}")),
                        Cell::plain(format!("{b:.8e}")),
                    ]
                })
            })
            .collect(),
    }
}

/// A figure from a line plot.
pub(crate) fn figure(id: &str, plot: LinePlot, caption: String, x: &str, y: &str) -> Result<Figure> {
    Ok(Figure {
        id: id.into(),
        data: data_of(&plot, x, y),
        svg: plot.to_svg()?,
        caption,
    })
}
