//! The paper's Figures 10–12 as maps: pressure, frictional traction (|q|, q_x, q_y) and
//! stick/slip status on the contact plane at one path position, one panel per solver that
//! resolves the plane, drawn by the field's layout, on one colour scale with a colour bar.

use anyhow::Result;

use super::surface::{FieldView, Layout};
use crate::document::{Cell, Figure, Table};
use crate::plot::{Cells, MapPanel, MapPlot, MapValue, Overlay, Scale};
use crate::{figures::fields_at, figures::history, figures::missing, figures::TANGENTIAL_REFERENCE};
use spherecontact_verify::CaseRun;

/// A component of the surface field that a map shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Component {
    Pressure,
    TractionMagnitude,
    TractionX,
    TractionY,
    Status,
}

impl Component {
    /// File stem, words for the caption, and the colour bar's title.
    fn describe(self) -> (&'static str, &'static str, &'static str) {
        match self {
            Component::Pressure => ("pressure-map", "Contact pressure p (Figure 10)", "p [MPa]"),
            Component::TractionMagnitude => (
                "traction-magnitude-map",
                "Frictional traction |q| (Figure 11)",
                "|q| [MPa]",
            ),
            Component::TractionX => (
                "traction-x-map",
                "Frictional traction along the shift, q_x",
                "q_x [MPa]",
            ),
            Component::TractionY => (
                "traction-y-map",
                "Transverse frictional traction q_y (Cattaneo–Mindlin neglects it)",
                "q_y [MPa]",
            ),
            Component::Status => ("status-map", "Contact status (Figure 12)", "status"),
        }
    }

    /// The plotted symbol, for the title.
    fn symbol(self) -> &'static str {
        match self {
            Component::Pressure => "p",
            Component::TractionMagnitude => "|q|",
            Component::TractionX => "q_x",
            Component::TractionY => "q_y",
            Component::Status => "stick/slip",
        }
    }

    /// The value of sample `i` in contact, `None` outside it or where the solver has none (q_y
    /// and |q| need both components resolved).
    fn value(self, view: &FieldView, i: usize) -> Option<MapValue> {
        if !view.in_contact(i) {
            return None;
        }
        let level = |v: f64| Some(MapValue::Level(v * 1e-6));
        match self {
            Component::Pressure => level(view.pressure(i)),
            Component::TractionMagnitude => level(view.traction(i)?[0].hypot(view.traction_y(i)?)),
            Component::TractionX => level(view.traction(i)?[0]),
            Component::TractionY => level(view.traction_y(i)?),
            Component::Status => view.stick(i).map(MapValue::Stick),
        }
    }
}

/// A solver's panel for `component`, by the field's layout; `None` when it has no such values.
fn panel(name: &str, view: &FieldView, component: Component) -> Option<MapPanel> {
    let values: Vec<Option<MapValue>> = (0..view.len()).map(|i| component.value(view, i)).collect();
    if values.iter().all(Option::is_none) {
        return None;
    }
    let cells = match view.layout() {
        Layout::Grid { spacing } => Cells::Squares { side: spacing * 1e6 },
        Layout::Triangles(triangles) => Cells::Triangles(triangles.clone()),
        Layout::Profile => return None,
    };
    Some(MapPanel {
        title: name.into(),
        points: (0..view.len()).map(|i| view.point(i).map(|c| c * 1e6)).collect(),
        values,
        cells,
    })
}

/// The scale of a component: categories, signed values, or magnitudes.
fn scale(component: Component, panels: &[MapPanel]) -> Scale {
    let label = component.describe().2.to_owned();
    let signed = panels
        .iter()
        .flat_map(|p| &p.values)
        .any(|v| v.and_then(MapValue::level).is_some_and(|l| l < 0.0));
    match component {
        Component::Status => Scale::Status,
        Component::TractionY => Scale::Diverging { label },
        _ if signed => Scale::Diverging { label },
        _ => Scale::Sequential { label },
    }
}

/// The reference circles: Hertz's contact radius and MDR's stick radius at the position.
fn overlays(run: &CaseRun, position: usize) -> Vec<Overlay> {
    let scene = &run.case.scene;
    let mut overlays = Vec::new();
    if let Some(step) = scene.steps().into_iter().find(|s| s.position == Some(position)) {
        let c = scene.hertz().contact_radius(step.delta_n);
        if c > 0.0 {
            overlays.push(Overlay {
                radius: c * 1e6,
                label: format!("Hertz c = {:.1} µm", c * 1e6),
            });
        }
    }
    let stick = history(run, TANGENTIAL_REFERENCE)
        .and_then(|h| h.at_position(position))
        .and_then(|row| row.stick_radius)
        .filter(|&r| r > 0.0);
    if let Some(cs) = stick {
        overlays.push(Overlay {
            radius: cs * 1e6,
            label: format!("{TANGENTIAL_REFERENCE} c_s = {:.1} µm", cs * 1e6),
        });
    }
    overlays
}

/// The long-format table (solver, x, y, value) behind a map.
fn data_of(plot: &MapPlot, what: &str) -> Table {
    Table {
        header: vec!["solver".into(), "x [um]".into(), "y [um]".into(), what.into()],
        rows: plot
            .panels
            .iter()
            .flat_map(|panel| {
                panel.points.iter().zip(&panel.values).filter_map(|(p, v)| {
                    let text = match (*v)? {
                        MapValue::Level(l) => format!("{l:.6e}"),
                        MapValue::Stick(s) => if s { "stick" } else { "slip" }.to_owned(),
                    };
                    Some(vec![
                        Cell::plain(&panel.title),
                        Cell::plain(format!("{:.4}", p[0])),
                        Cell::plain(format!("{:.4}", p[1])),
                        Cell::plain(text),
                    ])
                })
            })
            .collect(),
    }
}

/// The maps at `position`: one figure per component, one panel per solver that resolves the
/// plane.
pub fn maps(run: &CaseRun, position: usize) -> Result<Vec<Figure>> {
    let fields: Vec<(String, FieldView)> = fields_at(run, position)
        .into_iter()
        .filter(|(_, v)| v.is_map())
        .collect();
    if fields.is_empty() {
        return Ok(Vec::new());
    }
    let overlays = overlays(run, position);
    let circles = match overlays.len() {
        0 => String::new(),
        _ => {
            let labels: Vec<&str> = overlays.iter().map(|o| o.label.as_str()).collect();
            format!(" Dashed circles: {}.", labels.join("; "))
        }
    };
    let mut figures = Vec::new();
    for component in [
        Component::Pressure,
        Component::TractionMagnitude,
        Component::TractionX,
        Component::TractionY,
        Component::Status,
    ] {
        let panels: Vec<MapPanel> = fields
            .iter()
            .filter_map(|(name, view)| panel(name, view, component))
            .collect();
        if panels.is_empty() {
            continue;
        }
        let (id, what, label) = component.describe();
        let plot = MapPlot {
            title: format!(
                "{}: {} at position {position}",
                run.case.name(),
                component.symbol()
            ),
            scale: scale(component, &panels),
            panels,
            overlays: overlays.clone(),
        };
        let (lo, hi) = plot.range();
        let range = match plot.scale {
            Scale::Status => String::new(),
            _ => format!(" The colour scale spans {lo:.1} to {hi:.1} MPa on every panel."),
        };
        let caption = format!(
            "{what} on the contact plane at path position {position} (x along the shift δt), inside the contact (p > 0), \
             on each solver's own surface (grid panels or mesh triangles).{range}{circles}{}",
            missing(run)
        );
        figures.push(Figure {
            id: format!("{id}-{position}"),
            data: data_of(&plot, label),
            svg: plot.to_svg()?,
            caption,
        });
    }
    Ok(figures)
}
