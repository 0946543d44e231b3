//! Plots as SVG text: line plots (linear, log-y or log-log) and 2D maps of a surface field.
//!
//! Drawn with plotters' SVG backend; text is measured with DejaVu Sans embedded in the binary
//! (the `dejavu` crate), so nothing depends on the system's font libraries. The SVG names its
//! font family and the browser renders the text.

use std::sync::Once;

use anyhow::{anyhow, Result};
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;

/// Width and height of every plot [px].
const SIZE: (u32, u32) = (820, 480);

/// Distinguishable line colours (Tableau 10), the reference series is black.
const COLOURS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// The reference: black, thick, dashed.
    Reference,
    /// A solver with values at every step: a coloured line.
    Line,
    /// A solver with values at a few points only: coloured markers joined by a thin line.
    Markers,
}

/// One named curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The legend entry.
    pub name: String,
    /// The points (x, y), in drawing order.
    pub points: Vec<(f64, f64)>,
    /// How it is drawn.
    pub style: Style,
}

/// Which axes are logarithmic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axes {
    /// Both linear.
    Linear,
    /// Logarithmic y.
    LogY,
    /// Both logarithmic.
    LogLog,
}

/// A line plot.
#[derive(Clone, Debug, PartialEq)]
pub struct LinePlot {
    /// The caption drawn above the plot.
    pub title: String,
    /// The x axis label, with its unit.
    pub x_label: String,
    /// The y axis label, with its unit.
    pub y_label: String,
    /// The curves; a solver with no data has no series (the report says it is missing).
    pub series: Vec<Series>,
    /// Linear or logarithmic axes.
    pub axes: Axes,
}

/// Registers the embedded font once per process.
fn register_font() -> Result<()> {
    static ONCE: Once = Once::new();
    let mut result = Ok(());
    ONCE.call_once(|| {
        result = plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
            .map_err(|_| anyhow!("the embedded DejaVu Sans font could not be read"));
    });
    result
}

/// The range [min, max] of `values`, widened when it is empty or a single value.
fn span(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    match (lo.is_finite(), log) {
        (false, false) => (0.0, 1.0),
        (false, true) => (1e-3, 1.0),
        (true, true) if hi <= lo => (lo / 2.0, hi * 2.0),
        (true, true) => (lo / 1.2, hi * 1.2),
        (true, false) if hi <= lo => (lo - 0.5 * lo.abs().max(1e-30), hi + 0.5 * hi.abs().max(1e-30)),
        (true, false) => {
            let pad = 0.04 * (hi - lo);
            (lo - pad, hi + pad)
        }
    }
}

impl LinePlot {
    /// The plot as an SVG document.
    pub fn to_svg(&self) -> Result<String> {
        register_font()?;
        let (log_x, log_y) = match self.axes {
            Axes::Linear => (false, false),
            Axes::LogY => (false, true),
            Axes::LogLog => (true, true),
        };
        let points = || self.series.iter().flat_map(|s| s.points.iter());
        let (x0, x1) = span(points().map(|p| p.0), log_x);
        let (y0, y1) = span(points().map(|p| p.1), log_y);
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
            root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
            match self.axes {
                Axes::Linear => self.draw(&root, x0..x1, y0..y1)?,
                Axes::LogY => self.draw(&root, x0..x1, (y0..y1).log_scale())?,
                Axes::LogLog => self.draw(&root, (x0..x1).log_scale(), (y0..y1).log_scale())?,
            }
            root.present().map_err(|e| anyhow!("{e}"))?;
        }
        Ok(svg)
    }

    fn draw<X, Y>(&self, root: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>, x: X, y: Y) -> Result<()>
    where
        X: AsRangedCoord<Value = f64>,
        Y: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let fail = |e: &dyn std::fmt::Display| anyhow!("plot `{}`: {e}", self.title);
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(78)
            .build_cartesian_2d(x, y)
            .map_err(|e| fail(&e))?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style(("sans-serif", 13))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(|e| fail(&e))?;
        let mut colour = COLOURS.iter().cycle();
        for series in &self.series {
            let points = series.points.iter().copied();
            let drawn = match series.style {
                Style::Reference => {
                    let style = BLACK.stroke_width(3);
                    let anno = chart
                        .draw_series(DashedLineSeries::new(points, 9, 6, style))
                        .map_err(|e| fail(&e))?;
                    anno.label(&series.name)
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
                    continue;
                }
                Style::Line => {
                    let style = colour.next().expect("cycle").stroke_width(2);
                    (chart.draw_series(LineSeries::new(points, style)), style)
                }
                Style::Markers => {
                    let style = colour.next().expect("cycle").stroke_width(1);
                    let fill = style.color.filled();
                    chart
                        .draw_series(series.points.iter().map(|&p| Circle::new(p, 4, fill)))
                        .map_err(|e| fail(&e))?;
                    (chart.draw_series(LineSeries::new(points, style)), style)
                }
            };
            let (anno, style) = drawn;
            anno.map_err(|e| fail(&e))?
                .label(&series.name)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
        }
        if !self.series.is_empty() {
            chart
                .configure_series_labels()
                .label_font(("sans-serif", 13))
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(180, 180, 180))
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| fail(&e))?;
        }
        Ok(())
    }
}

/// A surface field on the contact plane as coloured cells.
#[derive(Clone, Debug, PartialEq)]
pub struct MapPlot {
    /// The caption.
    pub title: String,
    /// Cell centres (x, y) [µm].
    pub points: Vec<[f64; 2]>,
    /// The cell's value, or `None` where there is nothing to draw (outside the contact).
    pub values: Vec<Option<MapValue>>,
    /// The cell's side [µm].
    pub cell: f64,
}

/// What a map cell shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MapValue {
    /// A magnitude, coloured on a sequential scale between the map's extremes.
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

/// The levels among a map's cells.
pub fn levels(values: &[Option<MapValue>]) -> Vec<f64> {
    values
        .iter()
        .filter_map(|v| v.and_then(MapValue::level))
        .collect()
}

/// A sequential colour scale (dark blue → yellow), `t` in [0, 1].
fn sequential(t: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 4] = [
        (0.0, [68.0, 1.0, 84.0]),
        (0.35, [49.0, 104.0, 142.0]),
        (0.7, [53.0, 183.0, 121.0]),
        (1.0, [253.0, 231.0, 37.0]),
    ];
    let t = t.clamp(0.0, 1.0);
    let k = STOPS
        .iter()
        .rposition(|s| s.0 <= t)
        .unwrap_or(0)
        .min(STOPS.len() - 2);
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    let s = (t - a.0) / (b.0 - a.0);
    let c = |i: usize| (a.1[i] + s * (b.1[i] - a.1[i])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

impl MapPlot {
    /// The map as an SVG document; the title carries the scale's extremes.
    pub fn to_svg(&self) -> Result<String> {
        register_font()?;
        let levels = levels(&self.values);
        let (lo, hi) = span(levels.iter().copied(), false);
        let half = 0.5 * self.cell;
        let (x0, x1) = span(self.points.iter().map(|p| p[0]), false);
        let (y0, y1) = span(self.points.iter().map(|p| p[1]), false);
        let extent = (x1 - x0).max(y1 - y0) / 2.0 + half;
        let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        let fail = |e: &dyn std::fmt::Display| anyhow!("map `{}`: {e}", self.title);
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (560, 520)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| fail(&e))?;
            let mut chart = ChartBuilder::on(&root)
                .caption(&self.title, ("sans-serif", 16))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(cx - extent..cx + extent, cy - extent..cy + extent)
                .map_err(|e| fail(&e))?;
            chart
                .configure_mesh()
                .x_desc("x [µm]")
                .y_desc("y [µm]")
                .disable_mesh()
                .label_style(("sans-serif", 12))
                .draw()
                .map_err(|e| fail(&e))?;
            let cells = self.points.iter().zip(&self.values).filter_map(|(p, v)| {
                let colour = match (*v)? {
                    MapValue::Level(l) => sequential((l - lo) / (hi - lo)),
                    MapValue::Stick(true) => RGBColor(31, 119, 180),
                    MapValue::Stick(false) => RGBColor(255, 127, 14),
                };
                Some(Rectangle::new(
                    [(p[0] - half, p[1] - half), (p[0] + half, p[1] + half)],
                    colour.filled(),
                ))
            });
            chart.draw_series(cells).map_err(|e| fail(&e))?;
            root.present().map_err(|e| fail(&e))?;
        }
        Ok(svg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn well_formed(svg: &str) {
        assert!(
            svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
            "{}",
            &svg[..80.min(svg.len())]
        );
        assert!(!svg.contains("NaN"));
    }

    #[test]
    fn line_plots_render_in_every_axis_kind() {
        for axes in [Axes::Linear, Axes::LogY, Axes::LogLog] {
            let plot = LinePlot {
                title: "P against δn".into(),
                x_label: "δn [µm]".into(),
                y_label: "P [N]".into(),
                series: vec![
                    Series {
                        name: "hertz".into(),
                        points: vec![(1.0, 1.0), (2.0, 2.8)],
                        style: Style::Reference,
                    },
                    Series {
                        name: "a & <b>".into(),
                        points: vec![(1.0, 1.1), (2.0, 2.9)],
                        style: Style::Line,
                    },
                    Series {
                        name: "c".into(),
                        points: vec![(1.5, 2.0)],
                        style: Style::Markers,
                    },
                ],
                axes,
            };
            let svg = plot.to_svg().unwrap();
            well_formed(&svg);
            assert!(svg.contains("a &amp; &lt;b&gt;"), "legend text is escaped");
        }
    }

    #[test]
    fn an_empty_plot_still_renders() {
        let plot = LinePlot {
            title: "nothing".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![],
            axes: Axes::LogY,
        };
        well_formed(&plot.to_svg().unwrap());
    }

    #[test]
    fn maps_render_levels_and_categories() {
        let points: Vec<[f64; 2]> = (0..16).map(|k| [(k % 4) as f64, (k / 4) as f64]).collect();
        let levels = points
            .iter()
            .map(|p| Some(MapValue::Level(p[0] + p[1])))
            .collect();
        let map = MapPlot {
            title: "p".into(),
            points: points.clone(),
            values: levels,
            cell: 1.0,
        };
        well_formed(&map.to_svg().unwrap());
        let status = points
            .iter()
            .map(|p| (p[0] > 0.0).then_some(MapValue::Stick(p[1] > 1.0)))
            .collect();
        let map = MapPlot {
            title: "stick".into(),
            points,
            values: status,
            cell: 1.0,
        };
        well_formed(&map.to_svg().unwrap());
    }
}
