//! Figures 8 and 9 of the paper: P against δn and Q along the path, in panels by family (finite
//! and boundary elements against the corrected reference; closed forms, DEM laws and DEM codes
//! against the half-space reference), each panel over its error plot. A solver with values at
//! some steps only (the external decks solve the path positions) is drawn as markers, joined
//! only between consecutive computed steps.

use anyhow::Result;

use super::path::path_coordinate;
use crate::document::Figure;
use crate::plot::{compose, Axes, LinePlot, Series, Style};
use crate::{
    figures::data_of, figures::histories, figures::history, figures::missing, figures::NORMAL_REFERENCE,
    figures::TANGENTIAL_REFERENCE,
};
use spherecontact_model::domain::models_a_finite_body;
use spherecontact_model::history::{History, Quantity};
use spherecontact_model::solver::Kind;
use spherecontact_verify::bench::CORRECTED_REFERENCE;
use spherecontact_verify::CaseRun;

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

/// The solver families a force figure draws in panels of their own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Family {
    /// Finite and boundary elements, against the corrected reference where the run has it.
    Continuum,
    /// Closed forms, DEM laws and DEM codes (and any other solver), against the half-space
    /// reference (MDR; for P, Hertz).
    Particle,
}

impl Family {
    /// The family of the solver `name` of kind `kind` (the case's own solvers by the kind the
    /// case gives them).
    fn of(name: &str, kind: Option<Kind>) -> Self {
        if name == CORRECTED_REFERENCE || kind.is_some_and(Kind::is_continuum) {
            Family::Continuum
        } else {
            Family::Particle
        }
    }
}

/// One panel of a force figure: the solvers it draws and what they are drawn against.
#[derive(Clone, Debug, PartialEq)]
struct Panel {
    title: &'static str,
    /// The black dashed reference, if it ran.
    reference: Option<String>,
    /// The half-space reference beside a corrected one (grey, short dashes).
    guide: Option<String>,
    /// The solvers drawn in colour, in the case's order.
    members: Vec<String>,
}

/// The panels of a force figure whose half-space reference is `half_space`: finite and boundary
/// elements against the corrected reference (else the half-space one), then closed forms and DEM
/// laws and codes against the half-space reference; a panel with no solver of its own is left
/// out (the second is kept to show the reference alone when nothing else ran).
fn panels(run: &CaseRun, half_space: &str) -> Vec<Panel> {
    let ran: Vec<String> = histories(run).into_iter().map(|(name, _)| name).collect();
    let has = |name: &str| ran.iter().any(|n| n == name);
    let members = |family: Family, except: &str| -> Vec<String> {
        ran.iter()
            .filter(|n| {
                Family::of(n, run.case.solver_kind(n)) == family && *n != except && *n != CORRECTED_REFERENCE
            })
            .cloned()
            .collect()
    };
    let corrected = has(CORRECTED_REFERENCE);
    let continuum = Panel {
        title: "finite and boundary elements",
        reference: [CORRECTED_REFERENCE, half_space]
            .into_iter()
            .find(|n| has(n))
            .map(str::to_owned),
        guide: (corrected && has(half_space)).then(|| half_space.to_owned()),
        members: members(Family::Continuum, ""),
    };
    // One solver, one pen in a figure: beside a corrected reference (black) the half-space
    // reference is grey in both panels.
    let particle = Panel {
        title: "closed forms, DEM laws and DEM codes",
        reference: (has(half_space) && !corrected).then(|| half_space.to_owned()),
        guide: (has(half_space) && corrected).then(|| half_space.to_owned()),
        members: members(Family::Particle, half_space),
    };
    match (continuum.members.is_empty(), particle.members.is_empty()) {
        (false, false) => vec![continuum, particle],
        (false, true) => vec![continuum],
        (true, _) => vec![particle],
    }
}

/// The series of a panel with `quantity`, against `x[step]`: the solvers as lines (every step)
/// or markers (some steps), then the guide and the reference, drawn last, on top.
fn panel_series(run: &CaseRun, panel: &Panel, quantity: Quantity, x: &[f64]) -> Vec<Series> {
    let series = |name: &String, style: Option<Style>| {
        let runs = runs(history(run, name)?, quantity, x);
        let style = style.unwrap_or(if runs.len() == 1 {
            Style::Line
        } else {
            Style::Markers
        });
        (!runs.is_empty()).then(|| Series {
            name: name.clone(),
            runs,
            style,
        })
    };
    let mut list: Vec<Series> = panel.members.iter().filter_map(|n| series(n, None)).collect();
    list.extend(panel.guide.iter().filter_map(|n| series(n, Some(Style::Guide))));
    list.extend(
        panel
            .reference
            .iter()
            .filter_map(|n| series(n, Some(Style::Reference))),
    );
    list
}

/// The reference a member's error is measured against: a finite body against the corrected
/// reference where the panel draws it, every other solver against the half-space reference.
fn error_reference<'a>(panel: &'a Panel, name: &str, half_space: &'a str) -> &'a str {
    match &panel.reference {
        Some(r) if r == CORRECTED_REFERENCE && models_a_finite_body(name) => r,
        _ => half_space,
    }
}

/// |value − reference| / max |reference| at every step where both exist, as runs of consecutive
/// steps with a positive error (a zero error cannot stand on a log axis: it ends a run).
fn error_runs(history: &History, reference: &History, quantity: Quantity, x: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let peak = reference.peak(quantity);
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut previous = None;
    for row in &history.steps {
        let error = quantity
            .of(row)
            .zip(reference.steps.get(row.step).and_then(|r| quantity.of(r)))
            .filter(|_| peak > 0.0)
            .map(|(v, r)| (v - r).abs() / peak)
            .filter(|e| *e > 0.0);
        let Some(error) = error else {
            previous = None;
            continue;
        };
        match runs.last_mut() {
            Some(run) if previous == Some(row.step.wrapping_sub(1)) => run.push((x[row.step], error)),
            _ => runs.push(vec![(x[row.step], error)]),
        }
        previous = Some(row.step);
    }
    runs
}

/// The error series of a panel's solvers (in the order of its force plot), and the solvers whose
/// error is zero at every step (named in the caption, not drawn).
fn panel_errors(
    run: &CaseRun,
    panel: &Panel,
    drawn: &[Series],
    quantity: Quantity,
    half_space: &str,
    x: &[f64],
) -> (Vec<(usize, Series)>, Vec<String>) {
    let (mut series, mut exact) = (Vec::new(), Vec::new());
    let coloured = drawn
        .iter()
        .filter(|s| !matches!(s.style, Style::Reference | Style::Guide));
    for (k, s) in coloured.enumerate() {
        let against = error_reference(panel, &s.name, half_space);
        let (Some(h), Some(r)) = (history(run, &s.name), history(run, against)) else {
            continue;
        };
        let runs = error_runs(h, r, quantity, x);
        if runs.is_empty() {
            exact.push(format!("{} (against {against})", s.name));
        } else {
            let style = if s.style == Style::Line {
                Style::Line
            } else {
                Style::Markers
            };
            series.push((
                k,
                Series {
                    name: format!("{} vs {against}", s.name),
                    runs,
                    style,
                },
            ));
        }
    }
    (series, exact)
}

/// What a force figure draws: the quantity, its reference, its x axis and labels.
struct ForceFigure<'a> {
    id: &'static str,
    quantity: Quantity,
    symbol: &'static str,
    half_space: &'static str,
    x: &'a [f64],
    x_label: &'static str,
    y_label: &'static str,
    what: &'static str,
}

/// Least height of a panel's force plot and of its error plot [px].
const FORCE_HEIGHT: u32 = 380;
const ERROR_HEIGHT: u32 = 250;

/// The height of a plot of `entries` legend rows: at least `least`, and tall enough for its
/// legend (placed 34 px down, 22 px a row and 16 px of padding) to end above the next plot.
fn plot_height(least: u32, entries: usize) -> u32 {
    least.max(34 + 22 * entries as u32 + 16 + 10)
}

/// A force figure in panels by family, each a force plot over its error plot; every solver of
/// the figure keeps one colour-and-variant pair in both of its plots, and no two share one.
fn force_figure(run: &CaseRun, spec: &ForceFigure) -> Result<Option<Figure>> {
    let panels = panels(run, spec.half_space);
    let width = crate::plot::SIZE.0;
    let (mut parts, mut data, mut notes) = (Vec::new(), Vec::new(), Vec::new());
    let mut first_pen = 0;
    let mut y = 0;
    for panel in &panels {
        let series = panel_series(run, panel, spec.quantity, spec.x);
        if series.is_empty() {
            continue;
        }
        let drawn: Vec<&str> = series
            .iter()
            .filter(|s| !matches!(s.style, Style::Reference | Style::Guide))
            .map(|s| s.name.as_str())
            .collect();
        let coloured = drawn.len();
        let note = panel_note(panel, &drawn);
        let pens: Vec<usize> = (first_pen..first_pen + coloured).collect();
        let (errors, exact) = panel_errors(run, panel, &series, spec.quantity, spec.half_space, spec.x);
        let force = LinePlot {
            title: format!("{}: {}", spec.what, panel.title),
            x_label: spec.x_label.into(),
            y_label: spec.y_label.into(),
            series,
            axes: Axes::Linear,
        };
        let height = plot_height(FORCE_HEIGHT, force.series.len());
        parts.push((None, (0, y), force.to_svg_in((width, height), &pens)?));
        y += height;
        data.push((format!("{}: {}", panel.title, spec.symbol), force));
        if !errors.is_empty() {
            let error_pens: Vec<usize> = errors.iter().map(|(k, _)| pens[*k]).collect();
            let plot = LinePlot {
                title: format!("error of {}: {}", spec.symbol, panel.title),
                x_label: spec.x_label.into(),
                y_label: format!("|{0} − {0}_ref| / max |{0}_ref|", spec.symbol),
                series: errors.into_iter().map(|(_, s)| s).collect(),
                axes: Axes::LogY,
            };
            let height = plot_height(ERROR_HEIGHT, plot.series.len());
            parts.push((None, (0, y), plot.to_svg_in((width, height), &error_pens)?));
            y += height;
            data.push((format!("{}: error of {}", panel.title, spec.symbol), plot));
        }
        notes.push(note + &exact_note(&exact));
        first_pen += coloured;
    }
    if parts.is_empty() {
        return Ok(None);
    }
    let all: Vec<Series> = data.iter().flat_map(|(_, p)| p.series.clone()).collect();
    let caption = format!(
        "{} in panels by family, each over its error against its reference (|{s} − {s}_ref| / max |{s}_ref| at every \
         step; finite bodies against {CORRECTED_REFERENCE} where the run has it, half-spaces against {}). {}{}{}",
        spec.what,
        spec.half_space,
        notes.join(" "),
        sparse_note(&all),
        missing(run),
        s = spec.symbol,
    );
    Ok(Some(Figure {
        id: spec.id.into(),
        data: panel_data(&data, spec.x_label, spec.y_label),
        svg: compose((width, y), &parts),
        caption,
    }))
}

/// "Panel "finite and boundary elements": fem-axisym, bem against mdr-domain (black, dashed),
/// hertz beside it (grey, short dashes)": the solvers a panel draws, and against what.
fn panel_note(panel: &Panel, drawn: &[&str]) -> String {
    let mut note = format!("Panel \"{}\": {}", panel.title, drawn.join(", "));
    match (&panel.reference, &panel.guide) {
        (Some(reference), Some(guide)) => note.push_str(&format!(
            " against {reference} (black, dashed), {guide} beside it (grey, short dashes)"
        )),
        (Some(reference), None) => note.push_str(&format!(" against {reference} (black, dashed)")),
        (None, Some(guide)) => note.push_str(&format!(" against {guide} (grey, short dashes)")),
        (None, None) => {}
    }
    note
}

/// "; zero error at every step (not drawn on the log axis): a, b." or ".".
fn exact_note(exact: &[String]) -> String {
    if exact.is_empty() {
        ".".into()
    } else {
        format!(
            "; zero error at every step (not drawn on the log axis): {}.",
            exact.join(", ")
        )
    }
}

/// The long-format table behind a figure of several plots: series, x, y and the plot.
fn panel_data(plots: &[(String, LinePlot)], x: &str, y: &str) -> crate::document::Table {
    let mut table = data_of(&plots[0].1, x, y);
    table.header.push("plot".into());
    table.rows.clear();
    for (name, plot) in plots {
        let mut part = data_of(plot, x, y);
        for row in &mut part.rows {
            row.push(crate::document::Cell::plain(name));
        }
        table.rows.extend(part.rows);
    }
    table
}

/// The caption's note on the solvers drawn as markers, or "".
fn sparse_note(series: &[Series]) -> String {
    let mut sparse: Vec<&str> = series
        .iter()
        .filter(|s| s.style == Style::Markers)
        .map(|s| s.name.as_str())
        .collect();
    sparse.dedup();
    if sparse.is_empty() {
        String::new()
    } else {
        format!(
            " Markers: {} (values at the computed steps only; nothing is drawn between them).",
            sparse.join(", ")
        )
    }
}

/// Figure 8 of the paper: P against δn, in panels by family, Hertz (or the corrected reference)
/// as the reference.
pub fn normal_force(run: &CaseRun) -> Result<Option<Figure>> {
    let delta_n: Vec<f64> = run.case.scene.steps().iter().map(|s| s.delta_n * 1e6).collect();
    force_figure(
        run,
        &ForceFigure {
            id: "normal-force",
            quantity: Quantity::NormalForce,
            symbol: "P",
            half_space: NORMAL_REFERENCE,
            x: &delta_n,
            x_label: "δn [µm]",
            y_label: "P [N]",
            what: "Normal force P against the normal approach δn",
        },
    )
}

/// Figure 9 of the paper: Q along the path, in panels by family, MDR (exact
/// Mindlin–Deresiewicz, or the corrected reference) as the reference.
pub fn tangential_force(run: &CaseRun) -> Result<Option<Figure>> {
    let x = path_coordinate(run);
    force_figure(
        run,
        &ForceFigure {
            id: "tangential-force",
            quantity: Quantity::TangentialForce,
            symbol: "Q",
            half_space: TANGENTIAL_REFERENCE,
            x: &x,
            x_label: "path position",
            y_label: "Q [N]",
            what: "Tangential force Q along the path",
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_model::history::StepResult;

    /// Requirement: finite and boundary elements — built in, external decks, or a case's own
    /// solver the case marks `fe` or `be` — are drawn in the continuum panel; closed forms, DEM
    /// laws and codes (and a case's own of those kinds) in the other.
    #[test]
    fn solvers_fall_into_their_family() {
        let registry = spherecontact_case::registry::registry();
        let kind = |name: &str| registry.iter().find(|s| s.name() == name).map(|s| s.kind());
        for name in [
            "fem-axisym",
            "fem-3d",
            "freefem-axisym",
            "fenicsx-3d",
            "ccx-3d",
            "bem",
        ] {
            assert_eq!(Family::of(name, kind(name)), Family::Continuum, "{name}");
        }
        assert_eq!(
            Family::of(CORRECTED_REFERENCE, kind(CORRECTED_REFERENCE)),
            Family::Continuum
        );
        for name in ["hertz", "mdr", "thornton", "lammps-mindlin", "yade-mindlin"] {
            assert_eq!(Family::of(name, kind(name)), Family::Particle, "{name}");
        }
        assert_eq!(
            Family::of("my-fe-code", Some(Kind::FiniteElement)),
            Family::Continuum
        );
        assert_eq!(Family::of("my-law", Some(Kind::DemLaw)), Family::Particle);
    }

    #[test]
    fn plots_grow_to_hold_their_legend() {
        assert_eq!(plot_height(250, 3), 250);
        // 12 rows: 34 + 12·22 + 16 + 10 = 324 px.
        assert_eq!(plot_height(250, 12), 324);
    }

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
