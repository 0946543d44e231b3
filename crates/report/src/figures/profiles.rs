//! Radial profiles at one path position (the paper's Figures 10 and 11 read along a line): the
//! pressure against Hertz, the frictional traction q_x against MDR (exact Mindlin–Deresiewicz)
//! and Cattaneo–Mindlin, for every solver with surface fields. A map is read along x (the
//! shift) and along y (across it): where the two differ, the field is not axisymmetric.

use anyhow::Result;

use super::surface::{FieldView, HalfAxis};
use crate::document::Figure;
use crate::plot::{Axes, LinePlot, Series, Style};
use crate::{
    figures::fields_at, figures::figure, figures::history, figures::missing, figures::NORMAL_REFERENCE,
    figures::TANGENTIAL_REFERENCE,
};
use spherecontact_reference::cattaneo_mindlin::virgin_traction;
use spherecontact_verify::CaseRun;

/// Samples of the closed-form curves.
const CURVE_POINTS: usize = 241;

/// A field's component along a half-axis up to `reach` [m], as (r [µm], value [MPa]) for the
/// samples that have it.
fn along(
    view: &FieldView,
    axis: HalfAxis,
    reach: f64,
    value: &dyn Fn(&FieldView, usize) -> Option<f64>,
) -> Vec<(f64, f64)> {
    view.along(axis)
        .iter()
        .filter(|probe| probe.r <= reach)
        .filter_map(|probe| Some((probe.r * 1e6, view.at(probe, |i| value(view, i))? * 1e-6)))
        .collect()
}

/// Every solver's profile of `value` up to `reach` [m]: a profile once (axisymmetric), a map
/// along x (a line) and along y (markers alone: where the field is axisymmetric they sit on the
/// line, where it is not they leave it); the solver named `reference` dashed.
fn solver_series(
    fields: &[(String, FieldView)],
    reference: &str,
    reach: f64,
    value: &dyn Fn(&FieldView, usize) -> Option<f64>,
) -> Vec<Series> {
    let mut series = Vec::new();
    for (name, view) in fields {
        let x = along(view, HalfAxis::X, reach, value);
        if x.is_empty() {
            continue;
        }
        if view.is_map() {
            series.push(Series::joined(format!("{name} along x"), x, Style::Line));
            let y = along(view, HalfAxis::Y, reach, value);
            if !y.is_empty() {
                series.push(Series::scattered(format!("{name} along y"), y));
            }
        } else {
            let style = if name == reference {
                Style::Reference
            } else {
                Style::Line
            };
            series.push(Series::joined(name.clone(), x, style));
        }
    }
    series
}

/// The radius the profiles span [m]: the farthest sample of any solver on the x axis.
fn reach(fields: &[(String, FieldView)]) -> f64 {
    fields
        .iter()
        .flat_map(|(_, v)| v.along(HalfAxis::X).into_iter().map(|p| p.r))
        .fold(0.0, f64::max)
}

/// A closed-form curve q(r) [Pa] on [0, reach], as (µm, MPa).
fn curve(reach: f64, value: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
    (0..CURVE_POINTS)
        .map(|k| {
            let r = reach * k as f64 / (CURVE_POINTS - 1) as f64;
            (r * 1e6, value(r) * 1e-6)
        })
        .collect()
}

/// The pressure and traction profiles at `position`, for every solver with surface fields.
pub fn profiles(run: &CaseRun, position: usize) -> Result<Vec<Figure>> {
    let fields = fields_at(run, position);
    if fields.is_empty() {
        return Ok(Vec::new());
    }
    let scene = &run.case.scene;
    let hertz = scene.hertz();
    let Some(step) = scene.steps().into_iter().find(|s| s.position == Some(position)) else {
        return Ok(Vec::new());
    };
    // Beyond the contact every field is zero: show 30 % of c past its edge, no more.
    let c = hertz.contact_radius(step.delta_n);
    let reach = if c > 0.0 {
        reach(&fields).min(1.3 * c)
    } else {
        reach(&fields)
    };
    let mut figures = Vec::new();

    let mut pressure = solver_series(&fields, NORMAL_REFERENCE, reach, &|v, i| Some(v.pressure(i)));
    pressure.push(Series::joined(
        NORMAL_REFERENCE,
        curve(reach, |r| hertz.pressure(step.delta_n, r)),
        Style::Reference,
    ));
    figures.push(profile_figure(
        run,
        position,
        ("pressure-profile", "Contact pressure", "p [MPa]"),
        pressure,
        format!("dashed: {NORMAL_REFERENCE} at δn = {:.4} µm.", step.delta_n * 1e6),
    )?);

    let mut traction = solver_series(&fields, TANGENTIAL_REFERENCE, reach, &|v, i| {
        Some(v.traction(i)?[0])
    });
    let mdr_force = history(run, TANGENTIAL_REFERENCE)
        .and_then(|h| h.at_position(position))
        .and_then(|row| row.tangential_force);
    let guide = match mdr_force {
        Some(q) => {
            traction.push(Series::joined(
                "cattaneo-mindlin (same P, Q)",
                curve(reach, |r| {
                    virgin_traction(&hertz, scene.friction, step.delta_n, q, r)
                }),
                Style::Guide,
            ));
            format!(
                " Grey: Cattaneo–Mindlin's virgin-loading traction for Hertz's P and {TANGENTIAL_REFERENCE}'s Q = {q:.2} N \
                 at this position (it assumes P constant while δt grows, and q parallel to x)."
            )
        }
        None => {
            format!(" Cattaneo–Mindlin is not drawn: it needs {TANGENTIAL_REFERENCE}'s Q, which did not run.")
        }
    };
    if traction.iter().any(|s| s.style != Style::Guide) {
        figures.push(profile_figure(
            run,
            position,
            ("traction-profile", "Frictional traction q_x", "q_x [MPa]"),
            traction,
            format!("dashed: {TANGENTIAL_REFERENCE} (exact Mindlin–Deresiewicz along the path).{guide}"),
        )?);
    }
    Ok(figures)
}

/// One profile figure.
fn profile_figure(
    run: &CaseRun,
    position: usize,
    (id, what, y_label): (&str, &str, &str),
    mut series: Vec<Series>,
    references: String,
) -> Result<Figure> {
    // References on top.
    series.sort_by_key(|s| matches!(s.style, Style::Reference | Style::Guide));
    let caption = format!(
        "{what} at path position {position} against the distance r from the contact centre: along x (the shift) \
         and along y (across it) for maps, once for axisymmetric profiles; {references}{}",
        missing(run)
    );
    let plot = LinePlot {
        title: format!(
            "{}: {} at position {position}",
            run.case.name(),
            what.to_lowercase()
        ),
        x_label: "r [µm]".into(),
        y_label: y_label.into(),
        series,
        axes: Axes::Linear,
    };
    figure(&format!("{id}-{position}"), plot, caption, "r [um]", y_label)
}
