//! The figures and tables that reports draw from a case run: the loading path, P against δn,
//! Q along the path, surface profiles and maps at one position, errors against the references,
//! the check table and the solver table.
//!
//! A solver that failed or is not installed has no series: each caption names it as missing,
//! with the reason, so that it is never drawn as a flat line or a zero.

use anyhow::Result;

use super::document::{Cell, Figure, Table};
use super::format_value;
use super::plot::{Axes, LinePlot, MapPlot, MapValue, Series, Style};
use crate::check::Verdict;
use crate::history::{History, Quantity, SurfaceField};
use crate::solver::SolveError;
use crate::verify::CaseRun;

/// The solver every normal quantity is drawn against.
pub const NORMAL_REFERENCE: &str = "hertz";
/// The solver every tangential quantity is drawn against.
pub const TANGENTIAL_REFERENCE: &str = "mdr";

/// The histories that ran, in the case's solver order.
fn histories(run: &CaseRun) -> Vec<(String, &History)> {
    run.case
        .required_solvers()
        .into_iter()
        .filter_map(|name| match run.histories.get(&name) {
            Some(Ok(history)) => Some((name, history)),
            _ => None,
        })
        .collect()
}

/// "Missing: a (reason); b (reason)." for the solvers that did not run, or "".
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

/// The x coordinate of every step along the path: position k plus the fraction of its segment.
pub fn path_coordinate(run: &CaseRun) -> Vec<f64> {
    let mut x = vec![0.0];
    for (k, &m) in run.case.scene.path.substeps().iter().enumerate() {
        x.extend((1..=m).map(|j| k as f64 + j as f64 / m as f64));
    }
    x
}

/// The style of a solver's series: the reference, a line, or markers for sparse data.
fn style(name: &str, reference: &str, present: usize, steps: usize) -> Style {
    if name == reference {
        Style::Reference
    } else if 2 * present < steps {
        Style::Markers
    } else {
        Style::Line
    }
}

/// The long-format table (series, x, y) behind a plot.
fn data_of(plot: &LinePlot, x: &str, y: &str) -> Table {
    Table {
        header: vec!["series".into(), x.into(), y.into()],
        rows: plot
            .series
            .iter()
            .flat_map(|s| {
                s.points.iter().map(|(a, b)| {
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
fn figure(id: &str, plot: LinePlot, caption: String, x: &str, y: &str) -> Result<Figure> {
    Ok(Figure {
        id: id.into(),
        data: data_of(&plot, x, y),
        svg: plot.to_svg()?,
        caption,
    })
}

/// One series per solver with `quantity`, against `x_of(step index, row)`, scaled by `scale`.
fn quantity_series(run: &CaseRun, quantity: Quantity, reference: &str, x: &[f64], scale: f64) -> Vec<Series> {
    let mut series: Vec<Series> = histories(run)
        .into_iter()
        .filter_map(|(name, history)| {
            let points: Vec<(f64, f64)> = history
                .steps
                .iter()
                .filter_map(|r| Some((x[r.step], quantity.of(r)? * scale)))
                .collect();
            (!points.is_empty()).then(|| Series {
                style: style(&name, reference, points.len(), history.steps.len()),
                name,
                points,
            })
        })
        .collect();
    // The reference is drawn last, on top.
    series.sort_by_key(|s| s.style == Style::Reference);
    series
}

/// Figure 7 of the paper: δn and δt along the path.
pub fn loading_path(run: &CaseRun) -> Result<Figure> {
    let x = path_coordinate(run);
    let steps = run.case.scene.steps();
    let series = |name: &str, value: fn(&crate::path::Step) -> f64| Series {
        name: name.into(),
        points: steps.iter().map(|s| (x[s.index], value(s) * 1e6)).collect(),
        style: Style::Line,
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

/// Figure 8 of the paper: P against δn for every solver, Hertz as the reference.
pub fn normal_force(run: &CaseRun) -> Result<Option<Figure>> {
    let delta_n: Vec<f64> = run.case.scene.steps().iter().map(|s| s.delta_n * 1e6).collect();
    let series = quantity_series(run, Quantity::NormalForce, NORMAL_REFERENCE, &delta_n, 1.0);
    if series.is_empty() {
        return Ok(None);
    }
    let plot = LinePlot {
        title: format!("{}: normal force", run.case.name()),
        x_label: "δn [µm]".into(),
        y_label: "P [N]".into(),
        series,
        axes: Axes::Linear,
    };
    let caption = format!(
        "Normal force P against the normal approach δn; dashed: {NORMAL_REFERENCE}.{}",
        missing(run)
    );
    figure("normal-force", plot, caption, "delta_n [um]", "P [N]").map(Some)
}

/// Figure 9 of the paper: Q along the path for every solver and law, MDR as the reference.
pub fn tangential_force(run: &CaseRun) -> Result<Option<Figure>> {
    let x = path_coordinate(run);
    let series = quantity_series(run, Quantity::TangentialForce, TANGENTIAL_REFERENCE, &x, 1.0);
    if series.is_empty() {
        return Ok(None);
    }
    let plot = LinePlot {
        title: format!("{}: tangential force", run.case.name()),
        x_label: "path position".into(),
        y_label: "Q [N]".into(),
        series,
        axes: Axes::Linear,
    };
    let caption = format!(
        "Tangential force Q along the path; dashed: {TANGENTIAL_REFERENCE} (exact Mindlin–Deresiewicz).{}",
        missing(run)
    );
    figure("tangential-force", plot, caption, "path position", "Q [N]").map(Some)
}

/// The samples of a field on the x axis (y = 0, or the row nearest it), x ≥ 0, sorted by x.
fn on_axis(field: &SurfaceField) -> Vec<usize> {
    let nearest = field
        .points
        .iter()
        .map(|p| p[1].abs())
        .fold(f64::INFINITY, f64::min);
    let mut indices: Vec<usize> = (0..field.points.len())
        .filter(|&i| field.points[i][1].abs() == nearest && field.points[i][0] >= 0.0)
        .collect();
    indices.sort_by(|&a, &b| field.points[a][0].total_cmp(&field.points[b][0]));
    indices
}

/// True when a field samples the plane, not only the x axis.
fn is_map(field: &SurfaceField) -> bool {
    field.points.iter().any(|p| p[1] != 0.0)
}

/// The fields at `position`, by solver.
fn fields_at(run: &CaseRun, position: usize) -> Vec<(String, &SurfaceField)> {
    histories(run)
        .into_iter()
        .filter_map(|(name, h)| {
            h.fields
                .iter()
                .find(|f| f.position == position)
                .map(|f| (name, f))
        })
        .collect()
}

/// Pressure and frictional traction along x at `position` (the paper's Figures 10 and 11 as
/// profiles), for every solver that resolves them.
pub fn profiles(run: &CaseRun, position: usize) -> Result<Vec<Figure>> {
    let fields = fields_at(run, position);
    let profile = |value: &dyn Fn(&SurfaceField, usize) -> Option<f64>, reference: &str| -> Vec<Series> {
        fields
            .iter()
            .filter_map(|(name, field)| {
                let points: Vec<_> = on_axis(field)
                    .into_iter()
                    .filter_map(|i| Some((field.points[i][0] * 1e6, value(field, i)? * 1e-6)))
                    .collect();
                (!points.is_empty()).then(|| Series {
                    name: name.clone(),
                    style: if name == reference {
                        Style::Reference
                    } else {
                        Style::Line
                    },
                    points,
                })
            })
            .collect()
    };
    let mut figures = Vec::new();
    let pressure = profile(&|f, i| Some(f.pressure[i]), NORMAL_REFERENCE);
    let traction = profile(&|f, i| Some(f.traction.as_ref()?[i][0]), TANGENTIAL_REFERENCE);
    for (id, series, what, symbol) in [
        ("pressure-profile", pressure, "Contact pressure", "p"),
        (
            "traction-profile",
            traction,
            "Frictional traction along δt",
            "q_x",
        ),
    ] {
        if series.is_empty() {
            continue;
        }
        let plot = LinePlot {
            title: format!(
                "{}: {} at position {position}",
                run.case.name(),
                what.to_lowercase()
            ),
            x_label: "r = x [µm]".into(),
            y_label: format!("{symbol} [MPa]"),
            series,
            axes: Axes::Linear,
        };
        let caption = format!(
            "{what} along the x axis at path position {position}.{}",
            missing(run)
        );
        figures.push(figure(
            &format!("{id}-{position}"),
            plot,
            caption,
            "x [um]",
            &format!("{symbol} [MPa]"),
        )?);
    }
    Ok(figures)
}

/// Maps of pressure, frictional traction and stick/slip status at `position` for the solvers
/// that resolve the plane (the paper's Figures 10–12).
pub fn maps(run: &CaseRun, position: usize) -> Result<Vec<Figure>> {
    let mut figures = Vec::new();
    for (name, field) in fields_at(run, position).into_iter().filter(|(_, f)| is_map(f)) {
        let cell = cell_size(field) * 1e6;
        let points: Vec<[f64; 2]> = field.points.iter().map(|p| [p[0] * 1e6, p[1] * 1e6]).collect();
        let contact = |i: usize| field.pressure[i] > 0.0;
        let mut layers: Vec<(&str, &str, Vec<Option<MapValue>>)> = vec![(
            "pressure",
            "contact pressure p [MPa]",
            (0..points.len())
                .map(|i| contact(i).then_some(MapValue::Level(field.pressure[i] * 1e-6)))
                .collect(),
        )];
        if let Some(traction) = &field.traction {
            let magnitude = |i: usize| traction[i][0].hypot(traction[i][1]) * 1e-6;
            layers.push((
                "traction",
                "frictional traction |q| [MPa]",
                (0..points.len())
                    .map(|i| contact(i).then(|| MapValue::Level(magnitude(i))))
                    .collect(),
            ));
        }
        if let Some(stick) = &field.stick {
            layers.push((
                "status",
                "contact status: blue stick, orange slip",
                (0..points.len())
                    .map(|i| contact(i).then_some(MapValue::Stick(stick[i])))
                    .collect(),
            ));
        }
        for (layer, what, values) in layers {
            let range = level_range(&values);
            let map = MapPlot {
                title: format!("{name}: {what}{range}"),
                points: points.clone(),
                values,
                cell,
            };
            let id = format!("{layer}-map-{name}-{position}");
            let data = Table {
                header: vec!["x [um]".into(), "y [um]".into(), what.into()],
                rows: map
                    .points
                    .iter()
                    .zip(&map.values)
                    .filter_map(|(p, v)| {
                        let text = match (*v)? {
                            MapValue::Level(l) => format!("{l:.6e}"),
                            MapValue::Stick(s) => if s { "stick" } else { "slip" }.to_owned(),
                        };
                        Some(vec![
                            Cell::plain(format!("{:.4}", p[0])),
                            Cell::plain(format!("{:.4}", p[1])),
                            Cell::plain(text),
                        ])
                    })
                    .collect(),
            };
            let caption =
                format!("{name}: {what} on the contact plane at path position {position} (x along δt).");
            figures.push(Figure {
                id,
                svg: map.to_svg()?,
                caption,
                data,
            });
        }
    }
    Ok(figures)
}

/// The smallest positive spacing between sample coordinates: a map's cell size [m].
fn cell_size(field: &SurfaceField) -> f64 {
    let mut xs: Vec<f64> = field.points.iter().map(|p| p[0]).collect();
    xs.sort_by(f64::total_cmp);
    xs.windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min)
}

/// " (0.0–451.5)" for a map of levels, "" otherwise.
fn level_range(values: &[Option<MapValue>]) -> String {
    let levels = super::plot::levels(values);
    if levels.is_empty() {
        return String::new();
    }
    let (lo, hi) = levels
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    format!(" ({lo:.1}–{hi:.1})")
}

/// Each solver's error against its reference at every path position: P against Hertz
/// (relative), Q against MDR (relative to MDR's peak |Q|). Solvers identical to the reference
/// by construction (zero error everywhere) are named in the caption, not drawn.
pub fn errors(run: &CaseRun) -> Result<Vec<Figure>> {
    let all = histories(run);
    let reference_of = |name: &str| all.iter().find(|(n, _)| n == name).map(|(_, h)| *h);
    let mut figures = Vec::new();
    for (quantity, reference, measure) in [
        (Quantity::NormalForce, NORMAL_REFERENCE, "relative"),
        (
            Quantity::TangentialForce,
            TANGENTIAL_REFERENCE,
            "relative to the reference's peak |Q|",
        ),
    ] {
        let Some(reference_history) = reference_of(reference) else {
            continue;
        };
        let peak = reference_history.peak(quantity);
        let (mut series, mut exact) = (Vec::new(), Vec::new());
        for (name, history) in all.iter().filter(|(n, _)| n != reference) {
            let points: Vec<(f64, f64)> = history
                .at_positions()
                .filter_map(|row| {
                    let (v, r) = (
                        quantity.of(row)?,
                        quantity.of(reference_history.steps.get(row.step)?)?,
                    );
                    let scale = if quantity == Quantity::NormalForce {
                        r.abs()
                    } else {
                        peak
                    };
                    let position = row.position? as f64;
                    (scale > 0.0).then(|| (position, (v - r).abs() / scale))
                })
                .collect();
            if points.is_empty() {
                continue;
            }
            if points.iter().all(|p| p.1 == 0.0) {
                exact.push(name.clone());
                continue;
            }
            series.push(Series {
                name: name.clone(),
                points,
                style: Style::Markers,
            });
        }
        if series.is_empty() {
            continue;
        }
        let plot = LinePlot {
            title: format!("{}: {} error against {reference}", run.case.name(), quantity),
            x_label: "path position".into(),
            y_label: format!("|error| ({measure})"),
            series,
            axes: Axes::LogY,
        };
        let mut caption = format!("Error of {quantity} against {reference} at every path position ({measure}); zero errors are not drawn on the log axis.");
        if !exact.is_empty() {
            caption.push_str(&format!(
                " Identical to {reference} by construction: {}.",
                exact.join(", ")
            ));
        }
        caption.push_str(&missing(run));
        figures.push(figure(
            &format!("{}-error", quantity.name().replace('_', "-")),
            plot,
            caption,
            "position",
            "error",
        )?);
    }
    Ok(figures)
}

/// The check table: verdict, what, value, reference, error, tolerance and reason.
pub fn check_table(run: &CaseRun) -> Table {
    let header = [
        "verdict",
        "solver",
        "quantity",
        "where",
        "value",
        "reference",
        "against",
        "error",
        "tolerance",
        "reason",
    ];
    Table {
        header: header.iter().map(|s| s.to_string()).collect(),
        rows: run
            .outcomes
            .iter()
            .map(|o| {
                let class = match o.verdict {
                    Verdict::Ok => "ok",
                    Verdict::Nook => "nook",
                    Verdict::Info => "info",
                    Verdict::Unavailable => "na",
                };
                let unit = o.spec.quantity.unit();
                let at = match o.worst_step {
                    Some(step) => format!("{} (worst: step {step})", o.spec.at),
                    None => o.spec.at.to_string(),
                };
                let mut reason = o.spec.reason.clone();
                if let Some(message) = &o.message {
                    reason = format!("{message}. {reason}");
                }
                vec![
                    Cell::with_class(o.verdict.label(), class),
                    Cell::plain(&o.spec.solver),
                    Cell::plain(o.spec.quantity.name()),
                    Cell::plain(at),
                    Cell::plain(format!("{} {unit}", format_value(o.value))),
                    Cell::plain(format!("{} {unit}", format_value(o.reference))),
                    Cell::plain(o.spec.reference.to_string()),
                    Cell::plain(format!("{} ({})", format_value(o.error), o.spec.measure.name())),
                    Cell::plain(
                        o.spec
                            .tolerance
                            .map_or_else(|| "informational".to_owned(), |t| format_value(Some(t))),
                    ),
                    Cell::plain(reason),
                ]
            })
            .collect(),
    }
}

/// Whether a metadata key is a duration in seconds (`meshing_s`, `solving_s`, …).
fn is_duration(key: &str) -> bool {
    key.ends_with("_s")
}

/// The wall time, with the solver's own split of it (`meshing 1.37 s, …`) where it gives one.
fn wall_time_of(metadata: &crate::history::Metadata) -> String {
    let parts: Vec<String> = metadata
        .extra
        .iter()
        .filter(|(key, _)| is_duration(key))
        .filter_map(|(key, value)| {
            Some(format!(
                "{} {:.3} s",
                key.trim_end_matches("_s").replace('_', " "),
                value.as_f64()?
            ))
        })
        .collect();
    let total = format!("{:.3} ms", metadata.wall_time_s * 1e3);
    if parts.is_empty() {
        total
    } else {
        format!("{total} ({})", parts.join(", "))
    }
}

/// The scalar facts of a solver's metadata (`key = value`), durations excepted (they go with the
/// wall time); lists and long texts are left to the solver's JSON file, and named as such.
fn details_of(extra: &std::collections::BTreeMap<String, serde_json::Value>) -> Vec<String> {
    let mut shown = Vec::new();
    let mut elsewhere = Vec::new();
    for (key, value) in extra.iter().filter(|(key, _)| !is_duration(key)) {
        match value {
            serde_json::Value::Number(n) => match n.as_f64() {
                Some(x) if x.fract() == 0.0 && x.abs() < 1e15 => shown.push(format!("{key} = {x}")),
                Some(x) => shown.push(format!("{key} = {x:.4}")),
                None => shown.push(format!("{key} = {n}")),
            },
            serde_json::Value::String(text) if text.chars().count() <= 80 => {
                shown.push(format!("{key} = {text}"))
            }
            serde_json::Value::Bool(b) => shown.push(format!("{key} = {b}")),
            _ => elsewhere.push(key.as_str()),
        }
    }
    if !elsewhere.is_empty() {
        shown.push(format!("more in solvers/<name>.json: {}", elsewhere.join(", ")));
    }
    shown
}

/// The solver table: what ran, how (model, resolution, version, facts) and how long; what did
/// not run and why.
pub fn solver_table(run: &CaseRun) -> Table {
    let header = [
        "solver",
        "status",
        "model",
        "resolution",
        "version",
        "details",
        "wall time",
    ];
    Table {
        header: header.iter().map(|s| s.to_string()).collect(),
        rows: run
            .case
            .required_solvers()
            .iter()
            .map(|name| match run.histories.get(name) {
                Some(Ok(h)) => {
                    let m = &h.metadata;
                    let details = details_of(&m.extra);
                    vec![
                        Cell::plain(name),
                        Cell::with_class("ran", "ok"),
                        Cell::plain(&m.model),
                        Cell::plain(&m.resolution),
                        Cell::plain(&m.version),
                        Cell::plain(details.join("; ")),
                        Cell::with_class(wall_time_of(m), "timing"),
                    ]
                }
                Some(Err(e)) => {
                    let (status, class) = match e {
                        SolveError::Unavailable(_) => ("missing: not available", "na"),
                        SolveError::NotApplicable(_) => ("missing: not applicable", "na"),
                        SolveError::Failed(_) => ("missing: failed", "nook"),
                    };
                    let mut row = vec![
                        Cell::plain(name),
                        Cell::with_class(status, class),
                        Cell::plain(e.to_string()),
                    ];
                    row.extend((0..4).map(|_| Cell::plain("—")));
                    row
                }
                None => vec![Cell::plain(name), Cell::with_class("not run", "na")]
                    .into_iter()
                    .chain((0..5).map(|_| Cell::plain("—")))
                    .collect(),
            })
            .collect(),
    }
}
