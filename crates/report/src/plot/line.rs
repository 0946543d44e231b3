//! Line plots: series drawn as lines or markers on linear or logarithmic axes, the legend beside
//! the data.

use std::cell::RefCell;

use anyhow::{anyhow, Result};
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::legend::{Entry, Legend, Mark};
use crate::{
    plot::compose, plot::dashes, plot::fonts, plot::pen, plot::register_font, plot::span, plot::text_width,
    plot::tick_label, plot::DATA_STROKE, plot::MARKER_SIZE, plot::TRIANGLE_SIZE,
};

/// Width and height of a line plot [px], legend included, unless the figure sizes it.
pub const SIZE: (u32, u32) = (900, 480);

/// The colour of a guide series.
pub(super) const GUIDE: RGBColor = RGBColor(120, 120, 120);

/// Height of the x label area [px]: tick labels, their gap and the axis title.
const X_LABEL_AREA: u32 = 56;

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// The reference: black, thick, dashed.
    Reference,
    /// A second reference (a closed form beside the reference solver): grey, short dashes.
    Guide,
    /// A solver with values at every step: a coloured line.
    Line,
    /// A solver with values at some points only: a marker at every point, thin lines only
    /// within runs of consecutive computed points (never a chord across a gap).
    Markers,
}

/// One named curve, as runs of points: a line joins the points of a run, never two runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The legend entry.
    pub name: String,
    /// Runs of consecutive points (x, y), in drawing order.
    pub runs: Vec<Vec<(f64, f64)>>,
    /// How it is drawn.
    pub style: Style,
}

impl Series {
    /// A series whose points are all joined.
    pub fn joined(name: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Self {
        Self {
            name: name.into(),
            runs: vec![points],
            style,
        }
    }

    /// Markers only: every point its own run.
    pub fn scattered(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            runs: points.into_iter().map(|p| vec![p]).collect(),
            style: Style::Markers,
        }
    }

    /// Every point, run after run.
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.runs.iter().flatten().copied()
    }
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

/// A series with its colour and variant ([`super::pen`]), ready to draw.
struct Drawn<'a> {
    series: &'a Series,
    colour: RGBColor,
    variant: usize,
    /// Points on a log axis at or below zero are left out (the caller says so in the caption).
    points: Vec<Vec<(f64, f64)>>,
}

impl LinePlot {
    /// The plot as an SVG document: the chart on the left, the legend in its own area on the
    /// right. On a log axis, points ≤ 0 are not drawn (never on an invented floor).
    pub fn to_svg(&self) -> Result<String> {
        self.to_svg_in(SIZE, &[])
    }

    /// The plot in `size` px, the k-th coloured series drawn with the figure's pen `pens[k]`
    /// ([`super::pen`]; `k` itself where `pens` has no entry), so that the panels of one figure
    /// give each solver one colour-and-variant pair and never give one pair to two solvers.
    pub fn to_svg_in(&self, size: (u32, u32), pens: &[usize]) -> Result<String> {
        register_font()?;
        let (log_x, log_y) = match self.axes {
            Axes::Linear => (false, false),
            Axes::LogY => (false, true),
            Axes::LogLog => (true, true),
        };
        let drawable = |&(x, y): &(f64, f64)| (!log_x || x > 0.0) && (!log_y || y > 0.0);
        let mut coloured = 0;
        let drawn: Vec<Drawn> = self
            .series
            .iter()
            .map(|series| {
                let (colour, variant) = match series.style {
                    Style::Reference => (BLACK, 0),
                    Style::Guide => (GUIDE, 0),
                    _ => {
                        coloured += 1;
                        pen(pens.get(coloured - 1).copied().unwrap_or(coloured - 1))
                    }
                };
                (series, colour, variant)
            })
            .map(|(series, colour, variant)| Drawn {
                series,
                colour,
                variant,
                points: series
                    .runs
                    .iter()
                    .map(|run| run.iter().copied().filter(drawable).collect::<Vec<_>>())
                    .filter(|run| !run.is_empty())
                    .collect(),
            })
            .collect();
        let legend = Legend {
            entries: drawn
                .iter()
                .map(|d| Entry {
                    name: d.series.name.clone(),
                    colour: d.colour,
                    variant: d.variant,
                    mark: match d.series.style {
                        Style::Reference => Mark::Dashed,
                        Style::Guide => Mark::Dotted,
                        Style::Line => Mark::Line,
                        Style::Markers if d.series.runs.iter().all(|r| r.len() < 2) => Mark::Point,
                        Style::Markers => Mark::Marker,
                    },
                })
                .collect(),
        };
        let legend_width = if legend.entries.is_empty() {
            0
        } else {
            legend.width()?
        };
        let chart_size = (size.0.saturating_sub(legend_width).max(size.0 / 3), size.1);
        let all = || drawn.iter().flat_map(|d| d.points.iter().flatten());
        let x = span(all().map(|p| p.0), log_x);
        let y = span(all().map(|p| p.1), log_y);
        // Two passes: the first collects the y tick labels, the second sizes their area to them.
        let labels = RefCell::new(Vec::new());
        self.render(chart_size, &drawn, (x, y), 90, &labels)?;
        let widest = labels
            .borrow()
            .iter()
            .map(|l: &String| text_width(l, fonts::TICK))
            .try_fold(0, |m, w| w.map(|w| m.max(w)))?;
        let y_area = widest + 10 + fonts::AXIS_TITLE as u32 + 12;
        let chart = self.render(chart_size, &drawn, (x, y), y_area, &RefCell::new(Vec::new()))?;
        let mut parts = vec![(None, (0, 0), chart)];
        if legend_width > 0 {
            parts.push((Some("legend"), (chart_size.0, 34), legend.to_svg()?));
        }
        Ok(compose(size, &parts))
    }

    /// The chart alone, with a y label area of `y_area` px; records the y tick labels.
    fn render(
        &self,
        size: (u32, u32),
        drawn: &[Drawn],
        (x, y): ((f64, f64), (f64, f64)),
        y_area: u32,
        labels: &RefCell<Vec<String>>,
    ) -> Result<String> {
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
            let range = |(a, b): (f64, f64)| a..b;
            match self.axes {
                Axes::Linear => self.draw(&root, drawn, range(x), range(y), y_area, labels)?,
                Axes::LogY => self.draw(&root, drawn, range(x), range(y).log_scale(), y_area, labels)?,
                Axes::LogLog => self.draw(
                    &root,
                    drawn,
                    range(x).log_scale(),
                    range(y).log_scale(),
                    y_area,
                    labels,
                )?,
            }
            root.present().map_err(|e| anyhow!("{e}"))?;
        }
        Ok(svg)
    }

    fn draw<X, Y>(
        &self,
        root: &DrawingArea<SVGBackend<'_>, Shift>,
        drawn: &[Drawn],
        x: X,
        y: Y,
        y_area: u32,
        labels: &RefCell<Vec<String>>,
    ) -> Result<()>
    where
        X: AsRangedCoord<Value = f64>,
        Y: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let fail = |e: &dyn std::fmt::Display| anyhow!("plot `{}`: {e}", self.title);
        let (log_x, log_y) = (self.axes == Axes::LogLog, self.axes != Axes::Linear);
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", fonts::TITLE))
            .margin(12)
            .x_label_area_size(X_LABEL_AREA)
            .y_label_area_size(y_area)
            .build_cartesian_2d(x, y)
            .map_err(|e| fail(&e))?;
        let (x_range, y_range) = (chart.x_range(), chart.y_range());
        let x_format = |v: &f64| tick_label(*v, (x_range.start, x_range.end), log_x);
        let y_format = |v: &f64| {
            let label = tick_label(*v, (y_range.start, y_range.end), log_y);
            labels.borrow_mut().push(label.clone());
            label
        };
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&x_format)
            .y_label_formatter(&y_format)
            .label_style(("sans-serif", fonts::TICK))
            .axis_desc_style(("sans-serif", fonts::AXIS_TITLE))
            .light_line_style(RGBColor(238, 238, 238))
            .bold_line_style(RGBColor(215, 215, 215))
            .draw()
            .map_err(|e| fail(&e))?;
        for d in drawn {
            for run in &d.points {
                let points = run.iter().copied();
                let joined = run.len() >= 2;
                match d.series.style {
                    Style::Reference if joined => chart
                        .draw_series(DashedLineSeries::new(points, 9, 6, BLACK.stroke_width(3)))
                        .map(|_| ()),
                    Style::Guide if joined => chart
                        .draw_series(DashedLineSeries::new(
                            points,
                            4,
                            4,
                            GUIDE.stroke_width(DATA_STROKE),
                        ))
                        .map(|_| ()),
                    Style::Line if joined => draw_run(&mut chart, run, d, (true, false)),
                    Style::Markers if joined => draw_run(&mut chart, run, d, (true, true)),
                    // A point with no neighbour in its run is a marker whatever the style.
                    _ => draw_run(&mut chart, run, d, (false, true)),
                }
                .map_err(|e| fail(&e))?;
            }
        }
        Ok(())
    }
}

/// A coloured series' run: its line (solid or dashed by its variant) where `line`, its markers
/// (shaped by its variant, as [`super::marker`] shapes them in the legend) where `markers`.
fn draw_run<'a, X, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'a>, Cartesian2d<X, Y>>,
    run: &[(f64, f64)],
    d: &Drawn,
    (line, markers): (bool, bool),
) -> Result<(), DrawingAreaErrorKind<std::io::Error>>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let points = run.iter().copied();
    if line {
        let style = d.colour.stroke_width(DATA_STROKE);
        match dashes(d.variant) {
            None => chart.draw_series(LineSeries::new(points.clone(), style))?,
            Some((on, off)) => chart.draw_series(DashedLineSeries::new(points.clone(), on, off, style))?,
        };
    }
    if markers {
        let style = d.colour.filled();
        let (r, t) = (MARKER_SIZE as i32, TRIANGLE_SIZE as i32);
        match d.variant {
            0 => chart.draw_series(points.map(|p| Circle::new(p, MARKER_SIZE, style)))?,
            1 => chart.draw_series(
                points.map(|p| EmptyElement::at(p) + Rectangle::new([(-r, -r), (r, r)], style)),
            )?,
            _ => chart.draw_series(points.map(|p| TriangleMarker::new(p, t, style)))?,
        };
    }
    Ok(())
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
                    Series::joined("hertz", vec![(1.0, 1.0), (2.0, 2.8)], Style::Reference),
                    Series::joined("a & <b>", vec![(1.0, 1.1), (2.0, 2.9)], Style::Line),
                    Series::scattered("c", vec![(1.5, 2.0)]),
                ],
                axes,
            };
            let svg = plot.to_svg().unwrap();
            well_formed(&svg);
            assert!(svg.contains("a &amp; &lt;b&gt;"), "legend text is escaped");
            assert!(svg.contains("class=\"legend\""));
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
    fn markers_join_only_consecutive_points() {
        // Two runs: a line may join (0,0)-(1,1), never (1,1)-(5,5).
        let series = Series {
            name: "deck".into(),
            runs: vec![vec![(0.0, 0.0), (1.0, 1.0)], vec![(5.0, 5.0)]],
            style: Style::Markers,
        };
        let plot = LinePlot {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![series],
            axes: Axes::Linear,
        };
        let svg = plot.to_svg().unwrap();
        let polylines = svg.matches("<polyline").count();
        let circles = svg.matches("<circle").count();
        assert!(
            circles >= 3,
            "a marker at every point (legend adds one): {circles}"
        );
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let data_lines: Vec<usize> = doc
            .descendants()
            .filter(|n| n.has_tag_name("polyline"))
            .filter(|n| n.attribute("stroke-width") == Some("2"))
            .filter(|n| !n.ancestors().any(|a| a.attribute("class") == Some("legend")))
            .map(|n| n.attribute("points").unwrap().split_whitespace().count())
            .collect();
        assert_eq!(
            data_lines,
            vec![2],
            "one line, within the first run ({polylines} polylines)"
        );
    }

    #[test]
    fn points_at_or_below_zero_are_not_drawn_on_a_log_axis() {
        let plot = LinePlot {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![Series::scattered("e", vec![(1.0, 0.0), (2.0, 1e-3), (3.0, 1e-5)])],
            axes: Axes::LogY,
        };
        let svg = plot.to_svg().unwrap();
        // Two data markers and the legend's.
        assert_eq!(svg.matches("<circle").count(), 3, "{svg}");
    }
}
