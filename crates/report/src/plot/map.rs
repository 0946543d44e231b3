//! Maps of a surface field on the contact plane: one panel per solver, side by side on the same
//! axes and the same colour scale, with a colour bar (or the stick/slip legend) beside them.
//!
//! A panel draws its field by the field's layout: grid panels as squares, a surface mesh as
//! triangles, so a solver with a new layout needs no new figure code.

use anyhow::{anyhow, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::legend::{Entry, Legend, Mark};
use crate::{plot::compose, plot::fonts, plot::register_font, plot::text_width, plot::tick_label};

/// One panel's size [px].
const PANEL: (u32, u32) = (380, 400);
/// A panel's margin [px] (more on one side where the plotting area is made square).
const MARGIN: u32 = 10;
/// Height of a panel's x label area [px].
const X_AREA: u32 = 50;
/// Height of the title strip above the panels [px].
const TITLE_STRIP: u32 = 34;
/// Width of the colour bar's gradient [px].
const BAR: u32 = 18;
/// Colours of stick and slip.
const STICK: RGBColor = RGBColor(31, 119, 180);
const SLIP: RGBColor = RGBColor(255, 127, 14);

/// What a map cell shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MapValue {
    /// A magnitude, coloured on the plot's scale.
    Level(f64),
    /// Stick (true) or slip (false), coloured by category.
    Stick(bool),
}

impl MapValue {
    /// The magnitude of a level cell.
    pub fn level(self) -> Option<f64> {
        match self {
            MapValue::Level(l) => Some(l),
            MapValue::Stick(_) => None,
        }
    }
}

/// How a panel's samples cover the plane.
#[derive(Clone, Debug, PartialEq)]
pub enum Cells {
    /// A square of side `side` [µm] centred on each sample (a grid of panels).
    Squares {
        /// The side [µm].
        side: f64,
    },
    /// Triangles over the samples (a surface mesh), by sample index: a triangle takes the mean
    /// of its corners' levels, or the status most of its corners have; it is drawn when all
    /// three corners have a value.
    Triangles(Vec<[usize; 3]>),
}

/// One solver's field.
#[derive(Clone, Debug, PartialEq)]
pub struct MapPanel {
    /// The panel's title (the solver).
    pub title: String,
    /// Sample points (x, y) [µm].
    pub points: Vec<[f64; 2]>,
    /// The value at each sample, `None` where there is nothing to draw (outside the contact).
    pub values: Vec<Option<MapValue>>,
    /// How the samples cover the plane.
    pub cells: Cells,
}

/// The colour scale shared by the panels.
#[derive(Clone, Debug, PartialEq)]
pub enum Scale {
    /// Magnitudes from 0 to the largest: dark blue → yellow.
    Sequential {
        /// The colour bar's title, with the unit.
        label: String,
    },
    /// Signed values, symmetric about 0: blue → white → red.
    Diverging {
        /// The colour bar's title, with the unit.
        label: String,
    },
    /// Stick and slip.
    Status,
}

/// A dashed circle about the origin drawn on every panel (a reference radius).
#[derive(Clone, Debug, PartialEq)]
pub struct Overlay {
    /// The radius [µm].
    pub radius: f64,
    /// Its legend entry (status maps) or caption wording.
    pub label: String,
}

/// Panels side by side with their colour bar.
#[derive(Clone, Debug, PartialEq)]
pub struct MapPlot {
    /// The title above the panels.
    pub title: String,
    /// The panels, left to right.
    pub panels: Vec<MapPanel>,
    /// The shared scale.
    pub scale: Scale,
    /// Reference circles.
    pub overlays: Vec<Overlay>,
}

/// A sequential colour scale (dark blue → yellow), `t` in [0, 1].
fn sequential(t: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 4] = [
        (0.0, [68.0, 1.0, 84.0]),
        (0.35, [49.0, 104.0, 142.0]),
        (0.7, [53.0, 183.0, 121.0]),
        (1.0, [253.0, 231.0, 37.0]),
    ];
    interpolate(&STOPS, t)
}

/// A diverging colour scale (blue → white → red), `t` in [0, 1] with 0.5 white.
fn diverging(t: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 3] = [
        (0.0, [49.0, 54.0, 149.0]),
        (0.5, [247.0, 247.0, 247.0]),
        (1.0, [165.0, 0.0, 38.0]),
    ];
    interpolate(&STOPS, t)
}

/// Piecewise-linear interpolation between colour stops.
fn interpolate(stops: &[(f64, [f64; 3])], t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let k = stops
        .iter()
        .rposition(|s| s.0 <= t)
        .unwrap_or(0)
        .min(stops.len() - 2);
    let (a, b) = (stops[k], stops[k + 1]);
    let s = (t - a.0) / (b.0 - a.0);
    let c = |i: usize| (a.1[i] + s * (b.1[i] - a.1[i])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

impl MapPlot {
    /// The levels of every panel.
    fn levels(&self) -> impl Iterator<Item = f64> + '_ {
        self.panels
            .iter()
            .flat_map(|p| p.values.iter())
            .filter_map(|v| v.and_then(MapValue::level))
    }

    /// The range the colours span: [0, max] for magnitudes, [−m, m] for signed values.
    pub fn range(&self) -> (f64, f64) {
        let largest = self.levels().fold(0.0, |m: f64, v| m.max(v.abs()));
        let top = if largest > 0.0 { largest } else { 1.0 };
        match self.scale {
            Scale::Diverging { .. } => (-top, top),
            _ => (0.0, top),
        }
    }

    /// The colour of a value.
    fn colour(&self, value: MapValue, (lo, hi): (f64, f64)) -> RGBColor {
        match (value, &self.scale) {
            (MapValue::Stick(true), _) => STICK,
            (MapValue::Stick(false), _) => SLIP,
            (MapValue::Level(l), Scale::Diverging { .. }) => diverging((l - lo) / (hi - lo)),
            (MapValue::Level(l), _) => sequential((l - lo) / (hi - lo)),
        }
    }

    /// Half the side of the square every panel shows [µm]: the samples with a value (the
    /// contact), and the overlays, with a margin.
    fn extent(&self) -> f64 {
        let reach = self
            .panels
            .iter()
            .flat_map(|p| {
                let half = match p.cells {
                    Cells::Squares { side } => side / 2.0,
                    Cells::Triangles(_) => 0.0,
                };
                p.points
                    .iter()
                    .zip(&p.values)
                    .filter(|(_, v)| v.is_some())
                    .map(move |(q, _)| q[0].abs().max(q[1].abs()) + half)
            })
            .chain(self.overlays.iter().map(|o| o.radius))
            .fold(0.0, f64::max);
        if reach > 0.0 {
            1.08 * reach
        } else {
            1.0
        }
    }

    /// The plot as an SVG document.
    pub fn to_svg(&self) -> Result<String> {
        register_font()?;
        let range = self.range();
        let extent = self.extent();
        let key = self.key(range)?;
        let key_width = key.as_ref().map_or(0, |(w, _)| *w);
        let width = PANEL.0 * self.panels.len().max(1) as u32 + key_width;
        let height = TITLE_STRIP + PANEL.1;
        let mut parts = vec![(None, (0, 0), self.title_strip(width)?)];
        for (k, panel) in self.panels.iter().enumerate() {
            parts.push((
                None,
                (k as u32 * PANEL.0, TITLE_STRIP),
                self.panel_svg(panel, range, extent)?,
            ));
        }
        if let Some((w, svg)) = key {
            parts.push((Some("legend"), (width - w, TITLE_STRIP + 40), svg));
        }
        Ok(compose((width, height), &parts))
    }

    /// The title strip.
    fn title_strip(&self, width: u32) -> Result<String> {
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (width, TITLE_STRIP)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
            root.titled(&self.title, ("sans-serif", fonts::TITLE))
                .map_err(|e| anyhow!("map `{}`: {e}", self.title))?;
            root.present().map_err(|e| anyhow!("{e}"))?;
        }
        Ok(svg)
    }

    /// One panel with its axes.
    fn panel_svg(&self, panel: &MapPanel, range: (f64, f64), extent: f64) -> Result<String> {
        let fail = |e: &dyn std::fmt::Display| anyhow!("map `{}` / {}: {e}", self.title, panel.title);
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, PANEL).into_drawing_area();
            root.fill(&WHITE).map_err(|e| fail(&e))?;
            let axis = (-extent, extent);
            let widest = [-extent, extent, 0.0]
                .iter()
                .map(|v| text_width(&tick_label(*v, axis, false), fonts::TICK))
                .try_fold(0, |m, w| w.map(|w| m.max(w)))?;
            let y_area = widest + 40 + fonts::AXIS_TITLE as u32;
            // A square plotting area, so that a circle looks round: the extra width or height
            // goes to the right or bottom margin.
            let (right, bottom) = square_margins(&panel.title, y_area)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(&panel.title, ("sans-serif", fonts::AXIS_TITLE))
                .margin_top(MARGIN)
                .margin_left(MARGIN)
                .margin_right(right)
                .margin_bottom(bottom)
                .x_label_area_size(X_AREA)
                .y_label_area_size(y_area)
                .build_cartesian_2d(-extent..extent, -extent..extent)
                .map_err(|e| fail(&e))?;
            let format = |v: &f64| tick_label(*v, axis, false);
            chart
                .configure_mesh()
                .x_desc("x [µm]")
                .y_desc("y [µm]")
                .x_labels(5)
                .y_labels(5)
                .x_label_formatter(&format)
                .y_label_formatter(&format)
                .disable_mesh()
                .label_style(("sans-serif", fonts::TICK))
                .axis_desc_style(("sans-serif", fonts::AXIS_TITLE))
                .draw()
                .map_err(|e| fail(&e))?;
            self.draw_cells(&mut chart, panel, range).map_err(|e| fail(&e))?;
            for overlay in &self.overlays {
                chart
                    .draw_series(dashed_circle(overlay.radius))
                    .map_err(|e| fail(&e))?;
            }
            root.present().map_err(|e| fail(&e))?;
        }
        Ok(svg)
    }

    /// The panel's cells, by layout.
    fn draw_cells(
        &self,
        chart: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        panel: &MapPanel,
        range: (f64, f64),
    ) -> Result<()> {
        let fail = |e: &dyn std::fmt::Display| anyhow!("{e}");
        match &panel.cells {
            Cells::Squares { side } => {
                let half = side / 2.0;
                let squares = panel.points.iter().zip(&panel.values).filter_map(|(p, v)| {
                    Some(Rectangle::new(
                        [(p[0] - half, p[1] - half), (p[0] + half, p[1] + half)],
                        self.colour((*v)?, range).filled(),
                    ))
                });
                chart.draw_series(squares).map_err(|e| fail(&e))?;
            }
            Cells::Triangles(triangles) => {
                let shapes = triangles.iter().filter_map(|t| {
                    let corners = t.map(|i| panel.values.get(i).copied().flatten());
                    let value = merge(&corners)?;
                    Some(Polygon::new(
                        t.iter()
                            .map(|&i| (panel.points[i][0], panel.points[i][1]))
                            .collect::<Vec<_>>(),
                        self.colour(value, range).filled(),
                    ))
                });
                chart.draw_series(shapes).map_err(|e| fail(&e))?;
            }
        }
        Ok(())
    }

    /// The colour bar, or the stick/slip legend, with its width; `None` without panels.
    fn key(&self, (lo, hi): (f64, f64)) -> Result<Option<(u32, String)>> {
        if self.panels.is_empty() {
            return Ok(None);
        }
        let label = match &self.scale {
            Scale::Status => {
                let mut entries = vec![
                    Entry {
                        name: "stick".into(),
                        colour: STICK,
                        mark: Mark::Swatch,
                        variant: 0,
                    },
                    Entry {
                        name: "slip".into(),
                        colour: SLIP,
                        mark: Mark::Swatch,
                        variant: 0,
                    },
                ];
                entries.extend(self.overlays.iter().map(|o| Entry {
                    name: o.label.clone(),
                    colour: BLACK,
                    mark: Mark::Dashed,
                    variant: 0,
                }));
                let legend = Legend { entries };
                return Ok(Some((legend.width()?, legend.to_svg()?)));
            }
            Scale::Sequential { label } | Scale::Diverging { label } => label,
        };
        let ticks: Vec<f64> = (0..=4).map(|k| lo + (hi - lo) * k as f64 / 4.0).collect();
        let labels: Vec<String> = ticks.iter().map(|&t| tick_label(t, (lo, hi), false)).collect();
        let widest = labels
            .iter()
            .map(|l| text_width(l, fonts::TICK))
            .try_fold(0, |m, w| w.map(|w| m.max(w)))?;
        let title = text_width(label, fonts::LEGEND)?;
        let width = (BAR + 14 + widest).max(title) + 24;
        let bar_height = PANEL.1 - 140;
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (width, bar_height + 40)).into_drawing_area();
            let fail = |e: &dyn std::fmt::Display| anyhow!("colour bar: {e}");
            let text = |size| {
                ("sans-serif", size).into_font().into_text_style(&root).pos(
                    plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Left,
                        plotters::style::text_anchor::VPos::Center,
                    ),
                )
            };
            root.draw(&Text::new(label.as_str(), (8, 10), text(fonts::LEGEND)))
                .map_err(|e| fail(&e))?;
            let (top, x0) = (30, 12);
            let steps = 64;
            for k in 0..steps {
                let t = 1.0 - (k as f64 + 0.5) / steps as f64;
                let colour = self.colour(MapValue::Level(lo + t * (hi - lo)), (lo, hi));
                let y = |j: u32| top + (j * bar_height / steps) as i32;
                root.draw(&Rectangle::new(
                    [(x0, y(k)), (x0 + BAR as i32, y(k + 1))],
                    colour.filled(),
                ))
                .map_err(|e| fail(&e))?;
            }
            for (k, l) in labels.iter().enumerate() {
                let y = top + (bar_height as f64 * (1.0 - k as f64 / 4.0)).round() as i32;
                let right = x0 + BAR as i32;
                root.draw(&PathElement::new(
                    vec![(right, y), (right + 4, y)],
                    BLACK.stroke_width(1),
                ))
                .map_err(|e| fail(&e))?;
                root.draw(&Text::new(l.as_str(), (right + 8, y), text(fonts::TICK)))
                    .map_err(|e| fail(&e))?;
            }
            root.present().map_err(|e| fail(&e))?;
        }
        Ok(Some((width, svg)))
    }
}

/// The right and bottom margins [px] that make a panel's plotting area square, measured on a
/// throw-away drawing with equal margins.
fn square_margins(title: &str, y_area: u32) -> Result<(u32, u32)> {
    let mut scratch = String::new();
    let root = SVGBackend::with_string(&mut scratch, PANEL).into_drawing_area();
    let chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", fonts::AXIS_TITLE))
        .margin(MARGIN)
        .x_label_area_size(X_AREA)
        .y_label_area_size(y_area)
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(|e| anyhow!("map panel `{title}`: {e}"))?;
    let (w, h) = chart.plotting_area().dim_in_pixel();
    Ok((MARGIN + w.saturating_sub(h), MARGIN + h.saturating_sub(w)))
}

/// A triangle's value from its corners': the mean level, or the status most corners have;
/// `None` unless all three have one of the same kind.
fn merge(corners: &[Option<MapValue>; 3]) -> Option<MapValue> {
    let values: Vec<MapValue> = corners.iter().copied().collect::<Option<_>>()?;
    if let Some(levels) = values.iter().map(|v| v.level()).collect::<Option<Vec<f64>>>() {
        return Some(MapValue::Level(levels.iter().sum::<f64>() / 3.0));
    }
    let sticks = values
        .iter()
        .filter(|v| matches!(v, MapValue::Stick(true)))
        .count();
    let statuses = values.iter().filter(|v| matches!(v, MapValue::Stick(_))).count();
    (statuses == 3).then_some(MapValue::Stick(sticks >= 2))
}

/// A dashed circle of `radius` about the origin, as short segments.
fn dashed_circle(radius: f64) -> impl Iterator<Item = PathElement<(f64, f64)>> {
    const DASHES: usize = 48;
    (0..DASHES).map(move |k| {
        let arc = |s: f64| {
            let angle = std::f64::consts::TAU * (k as f64 + s) / DASHES as f64;
            (radius * angle.cos(), radius * angle.sin())
        };
        PathElement::new(vec![arc(0.0), arc(0.3), arc(0.6)], BLACK.stroke_width(2))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid_panel(title: &str, value: impl Fn([f64; 2]) -> Option<MapValue>) -> MapPanel {
        let points: Vec<[f64; 2]> = (0..64)
            .map(|k| [(k % 8) as f64 - 3.5, (k / 8) as f64 - 3.5])
            .collect();
        MapPanel {
            title: title.into(),
            values: points.iter().map(|&p| value(p)).collect(),
            points,
            cells: Cells::Squares { side: 1.0 },
        }
    }

    fn well_formed(svg: &str) {
        roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("{e}"));
        assert!(!svg.contains("NaN"));
    }

    #[test]
    fn panels_share_one_scale_and_a_colour_bar() {
        let plot = MapPlot {
            title: "|q|".into(),
            panels: vec![
                grid_panel("a", |p| Some(MapValue::Level(p[0].abs()))),
                grid_panel("b", |p| Some(MapValue::Level(2.0 * p[1].abs()))),
            ],
            scale: Scale::Sequential {
                label: "|q| [MPa]".into(),
            },
            overlays: vec![],
        };
        assert_eq!(plot.range(), (0.0, 7.0), "the largest level of either panel");
        let svg = plot.to_svg().unwrap();
        well_formed(&svg);
        assert!(svg.contains("class=\"legend\"") && svg.contains("|q| [MPa]"));
        assert!(svg.contains(">\n7\n</text>") || svg.contains(">7</text>") || svg.contains("\n7\n"));
    }

    #[test]
    fn signed_fields_are_symmetric_about_zero() {
        let plot = MapPlot {
            title: "q_y".into(),
            panels: vec![grid_panel("a", |p| Some(MapValue::Level(p[0] * p[1] / 10.0)))],
            scale: Scale::Diverging {
                label: "q_y [MPa]".into(),
            },
            overlays: vec![],
        };
        let (lo, hi) = plot.range();
        assert_eq!(lo, -hi);
        assert_eq!(diverging(0.5), RGBColor(247, 247, 247), "zero is white");
        well_formed(&plot.to_svg().unwrap());
    }

    #[test]
    fn triangles_take_their_corners_values() {
        let points = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
        let panel = MapPanel {
            title: "fem".into(),
            points,
            values: vec![
                Some(MapValue::Stick(true)),
                Some(MapValue::Stick(true)),
                Some(MapValue::Stick(false)),
                None,
            ],
            cells: Cells::Triangles(vec![[0, 1, 2], [1, 3, 2]]),
        };
        assert_eq!(
            merge(&[panel.values[0], panel.values[1], panel.values[2]]),
            Some(MapValue::Stick(true))
        );
        assert_eq!(merge(&[panel.values[1], panel.values[3], panel.values[2]]), None);
        let plot = MapPlot {
            title: "status".into(),
            panels: vec![panel],
            scale: Scale::Status,
            overlays: vec![Overlay {
                radius: 0.5,
                label: "c_s (MDR)".into(),
            }],
        };
        let svg = plot.to_svg().unwrap();
        well_formed(&svg);
        assert_eq!(
            svg.matches("<polygon").count(),
            1,
            "one triangle has all its corners"
        );
    }
}
