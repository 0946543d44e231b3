//! Plots a reader can trust at a glance, checked on the SVG itself:
//! - no tick label's box overlaps an axis title's, or another tick label's;
//! - every text lies inside the figure;
//! - no legend (or colour bar) box covers a data point.
//!
//! Text boxes are estimated from the metrics of DejaVu Sans, the font the report embeds for
//! layout and names in the SVG (and the one Chromium renders `sans-serif` with here): the
//! advance widths of the glyphs at the SVG's `font-size`, the font's ascent and descent, and
//! the anchor (`text-anchor`, `dy`) and rotation plotters writes. Every check is first shown to
//! fail on a figure built to break it.

use crate::common;

use ab_glyph::{Font, FontRef};
use roxmltree::{Document, Node};
use spherecontact::report::document::Figure;
use spherecontact::report::plot::{fonts, Axes, LinePlot, Series, Style, DATA_STROKE};
use spherecontact::verify;

/// A box [x0, x1] × [y0, y1] in the figure's pixels.
#[derive(Clone, Copy, Debug)]
struct Box2 {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Box2 {
    fn overlaps(&self, other: &Box2) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    fn contains(&self, (x, y): (f64, f64)) -> bool {
        x > self.x0 && x < self.x1 && y > self.y0 && y < self.y1
    }

    fn union(self, other: Box2) -> Box2 {
        Box2 {
            x0: self.x0.min(other.x0),
            x1: self.x1.max(other.x1),
            y0: self.y0.min(other.y0),
            y1: self.y1.max(other.y1),
        }
    }
}

/// What a text is, by its font size (the sizes of `plot::fonts`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Title,
    AxisTitle,
    Tick,
    Legend,
}

#[derive(Debug)]
struct Text {
    text: String,
    role: Role,
    in_legend: bool,
    bounds: Box2,
}

/// Everything the checks need from one SVG.
#[derive(Debug)]
struct Layout {
    size: (f64, f64),
    texts: Vec<Text>,
    /// Data points: marker centres, vertices of data lines, centres of filled cells.
    data: Vec<(f64, f64)>,
    /// The box of each legend or colour bar.
    legends: Vec<Box2>,
}

fn number(node: Node, name: &str) -> f64 {
    node.attribute(name)
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("<{}> without a numeric {name}", node.tag_name().name()))
}

/// The sum of the `translate(dx,dy)` of a node's ancestors.
fn offset(node: Node) -> (f64, f64) {
    node.ancestors()
        .filter_map(|a| a.attribute("transform"))
        .filter_map(|t| t.strip_prefix("translate(")?.strip_suffix(')').map(str::to_owned))
        .fold((0.0, 0.0), |(x, y), t| {
            let (dx, dy) = t.split_once(',').expect("translate(x,y)");
            (x + dx.parse::<f64>().unwrap(), y + dy.parse::<f64>().unwrap())
        })
}

fn in_legend(node: Node) -> bool {
    node.ancestors().any(|a| a.attribute("class") == Some("legend"))
}

/// The box of a `<text>` as the browser draws it with DejaVu Sans.
fn text_box(node: Node, font: &FontRef, (ox, oy): (f64, f64)) -> (String, f64, Box2) {
    let text = node.text().unwrap_or("").trim().to_owned();
    let size = number(node, "font-size");
    let em = size / font.units_per_em().expect("units per em") as f64;
    let width: f64 = text
        .chars()
        .map(|c| font.h_advance_unscaled(font.glyph_id(c)) as f64 * em)
        .sum();
    let (ascent, descent) = (
        font.ascent_unscaled() as f64 * em,
        -font.descent_unscaled() as f64 * em,
    );
    let x_height = font
        .outline(font.glyph_id('x'))
        .map(|o| (o.bounds.max.y - o.bounds.min.y).abs() as f64 * em)
        .expect("an outline of x");
    let (x, y) = (number(node, "x"), number(node, "y"));
    let baseline = y + match node.attribute("dy").unwrap_or("0") {
        "0.76em" => 0.76 * size,
        "0.5ex" => 0.5 * x_height,
        "-0.5ex" => -0.5 * x_height,
        other => panic!("unexpected dy {other}"),
    };
    let left = match node.attribute("text-anchor").unwrap_or("start") {
        "start" => x,
        "middle" => x - width / 2.0,
        "end" => x - width,
        other => panic!("unexpected text-anchor {other}"),
    };
    let horizontal = Box2 {
        x0: left,
        x1: left + width,
        y0: baseline - ascent,
        y1: baseline + descent,
    };
    let bounds = match node.attribute("transform") {
        None => horizontal,
        Some(t) => {
            let inner = t
                .strip_prefix("rotate(")
                .and_then(|t| t.strip_suffix(')'))
                .expect("rotate(a, x, y)");
            let v: Vec<f64> = inner.split(',').map(|s| s.trim().parse().unwrap()).collect();
            let (angle, cx, cy) = (v[0].to_radians(), v[1], v[2]);
            let rotate = |(px, py): (f64, f64)| {
                let (dx, dy) = (px - cx, py - cy);
                (
                    cx + dx * angle.cos() - dy * angle.sin(),
                    cy + dx * angle.sin() + dy * angle.cos(),
                )
            };
            let corners = [
                (horizontal.x0, horizontal.y0),
                (horizontal.x1, horizontal.y0),
                (horizontal.x0, horizontal.y1),
                (horizontal.x1, horizontal.y1),
            ]
            .map(rotate);
            Box2 {
                x0: corners.iter().map(|c| c.0).fold(f64::INFINITY, f64::min),
                x1: corners.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max),
                y0: corners.iter().map(|c| c.1).fold(f64::INFINITY, f64::min),
                y1: corners.iter().map(|c| c.1).fold(f64::NEG_INFINITY, f64::max),
            }
        }
    };
    let moved = Box2 {
        x0: bounds.x0 + ox,
        x1: bounds.x1 + ox,
        y0: bounds.y0 + oy,
        y1: bounds.y1 + oy,
    };
    (text, size, moved)
}

/// The vertices of a `points="x,y x,y"` attribute.
fn vertices(node: Node) -> Vec<(f64, f64)> {
    node.attribute("points")
        .unwrap_or("")
        .split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').expect("x,y");
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

fn parse(svg: &str) -> Layout {
    let font = FontRef::try_from_slice(dejavu::sans::regular()).expect("DejaVu Sans");
    let doc = Document::parse(svg).expect("well-formed SVG");
    let root = doc.root_element();
    let size = (number(root, "width"), number(root, "height"));
    let role = |size: f64| {
        let near = |f: f64| (size - fonts::in_svg(f)).abs() < 1e-6;
        [
            (fonts::TITLE, Role::Title),
            (fonts::AXIS_TITLE, Role::AxisTitle),
            (fonts::TICK, Role::Tick),
            (fonts::LEGEND, Role::Legend),
        ]
        .into_iter()
        .find(|(f, _)| near(*f))
        .map(|(_, r)| r)
        .unwrap_or_else(|| panic!("a text of font-size {size} has no role in plot::fonts"))
    };
    let mut layout = Layout {
        size,
        texts: Vec::new(),
        data: Vec::new(),
        legends: Vec::new(),
    };
    let mut legend_boxes: Vec<(Node, Box2)> = Vec::new();
    for node in root.descendants().filter(|n| n.is_element()) {
        let (ox, oy) = offset(node);
        let legend = in_legend(node);
        let mut extent: Option<Box2> = None;
        match node.tag_name().name() {
            "text" => {
                let (text, size, bounds) = text_box(node, &font, (ox, oy));
                extent = Some(bounds);
                layout.texts.push(Text {
                    text,
                    role: role(size),
                    in_legend: legend,
                    bounds,
                });
            }
            "circle" => {
                let (x, y, r) = (
                    number(node, "cx") + ox,
                    number(node, "cy") + oy,
                    number(node, "r"),
                );
                extent = Some(Box2 {
                    x0: x - r,
                    x1: x + r,
                    y0: y - r,
                    y1: y + r,
                });
                if !legend {
                    layout.data.push((x, y));
                }
            }
            "polyline" | "polygon" => {
                let points: Vec<(f64, f64)> = vertices(node).iter().map(|(x, y)| (x + ox, y + oy)).collect();
                let width: f64 = node.attribute("stroke-width").map_or(0.0, |w| w.parse().unwrap());
                let is_data = node.tag_name().name() == "polygon" || width >= DATA_STROKE as f64;
                if !legend && is_data {
                    layout.data.extend(&points);
                }
                extent = points.iter().fold(None, |b: Option<Box2>, &(x, y)| {
                    let p = Box2 {
                        x0: x,
                        x1: x,
                        y0: y,
                        y1: y,
                    };
                    Some(b.map_or(p, |b| b.union(p)))
                });
            }
            "rect" => {
                let (x, y) = (number(node, "x") + ox, number(node, "y") + oy);
                let (w, h) = (number(node, "width"), number(node, "height"));
                extent = Some(Box2 {
                    x0: x,
                    x1: x + w,
                    y0: y,
                    y1: y + h,
                });
                let filled = !matches!(node.attribute("fill"), None | Some("none") | Some("#FFFFFF"));
                if !legend && filled {
                    layout.data.push((x + w / 2.0, y + h / 2.0));
                }
            }
            _ => {}
        }
        if let (true, Some(b)) = (legend, extent) {
            let group = node
                .ancestors()
                .find(|a| a.attribute("class") == Some("legend"))
                .expect("a legend group");
            match legend_boxes.iter_mut().find(|(g, _)| *g == group) {
                Some((_, existing)) => *existing = existing.union(b),
                None => legend_boxes.push((group, b)),
            }
        }
    }
    layout.legends = legend_boxes.into_iter().map(|(_, b)| b).collect();
    layout
}

/// Every defect a reader would stumble over, in words; empty when the layout is clean.
fn defects(name: &str, svg: &str) -> Vec<String> {
    let layout = parse(svg);
    let mut found = Vec::new();
    let ticks: Vec<&Text> = layout
        .texts
        .iter()
        .filter(|t| t.role == Role::Tick && !t.in_legend)
        .collect();
    let titles: Vec<&Text> = layout
        .texts
        .iter()
        .filter(|t| t.role == Role::AxisTitle)
        .collect();
    for tick in &ticks {
        for title in &titles {
            if tick.bounds.overlaps(&title.bounds) {
                found.push(format!(
                    "{name}: tick label {:?} runs into axis title {:?}",
                    tick.text, title.text
                ));
            }
        }
    }
    for (k, a) in ticks.iter().enumerate() {
        for b in &ticks[k + 1..] {
            if a.bounds.overlaps(&b.bounds) {
                found.push(format!(
                    "{name}: tick labels {:?} and {:?} overlap",
                    a.text, b.text
                ));
            }
        }
    }
    let canvas = Box2 {
        x0: -0.5,
        x1: layout.size.0 + 0.5,
        y0: -0.5,
        y1: layout.size.1 + 0.5,
    };
    for t in &layout.texts {
        let b = t.bounds;
        if !(canvas.contains((b.x0, b.y0)) && canvas.contains((b.x1, b.y1))) {
            found.push(format!("{name}: text {:?} leaves the figure ({b:?})", t.text));
        }
    }
    for legend in &layout.legends {
        if let Some(p) = layout.data.iter().find(|&&p| legend.contains(p)) {
            found.push(format!(
                "{name}: the legend {legend:?} covers the data point {p:?}"
            ));
        }
    }
    found
}

/// The report's figures from the paper's case, in-crate solvers, 10 increments a segment
/// (the layout does not depend on the increments; the run takes seconds).
fn report_figures() -> Vec<Figure> {
    let case = common::paper_case_coarse(10);
    let run = verify::run_case(case);
    common::paper_document(&run)
        .sections
        .into_iter()
        .flat_map(|s| s.figures)
        .collect()
}

#[test]
fn no_figure_of_the_paper_report_has_a_layout_defect() {
    let figures = report_figures();
    let ids: Vec<&str> = figures.iter().map(|f| f.id.as_str()).collect();
    for expected in [
        "normal-force",
        "normal-force-error",
        "traction-profile-5",
        "traction-y-map-5",
        "status-map-5",
    ] {
        assert!(ids.contains(&expected), "{expected} missing from {ids:?}");
    }
    let mut all = Vec::new();
    for figure in &figures {
        let layout = parse(&figure.svg);
        // Controls: the checks see the figure's parts.
        assert!(!layout.data.is_empty(), "{}: no data found", figure.id);
        assert!(
            !layout.legends.is_empty(),
            "{}: no legend or colour bar found",
            figure.id
        );
        assert!(
            layout.texts.iter().any(|t| t.role == Role::AxisTitle)
                && layout.texts.iter().any(|t| t.role == Role::Tick),
            "{}: no axis titles or tick labels found",
            figure.id
        );
        all.extend(defects(&figure.id, &figure.svg));
    }
    assert!(all.is_empty(), "{}", all.join("\n"));
}

#[test]
fn log_axes_have_readable_labels_clear_of_the_titles() {
    for axes in [Axes::LogY, Axes::LogLog] {
        let plot = LinePlot {
            title: "speed against error".into(),
            x_label: "median CPU time [ms]".into(),
            y_label: "worst error along the path".into(),
            series: vec![
                Series::joined(
                    "a solver with a long name",
                    vec![(0.1, 1e-9), (10.0, 1e-5), (3000.0, 1e-2)],
                    Style::Markers,
                ),
                Series::scattered("b", vec![(1.0, 1e-4), (20.0, 3e-7)]),
            ],
            axes,
        };
        let svg = plot.to_svg().unwrap();
        let found = defects("log plot", &svg);
        assert!(found.is_empty(), "{}", found.join("\n"));
        let layout = parse(&svg);
        for tick in layout.texts.iter().filter(|t| t.role == Role::Tick) {
            assert!(
                tick.text.chars().count() <= 8,
                "unreadable tick label {:?}",
                tick.text
            );
        }
    }
}

/// The checks fail on a figure built to break them.
#[test]
fn the_checks_catch_what_they_look_for() {
    let tick = fonts::in_svg(fonts::TICK);
    let title = fonts::in_svg(fonts::AXIS_TITLE);
    let svg = format!(
        "<svg width=\"200\" height=\"100\" xmlns=\"http://www.w3.org/2000/svg\">\
         <text x=\"10\" y=\"50\" dy=\"0.5ex\" text-anchor=\"start\" font-size=\"{tick}\">9.999999999e-5</text>\
         <text x=\"40\" y=\"50\" dy=\"0.76em\" text-anchor=\"middle\" font-size=\"{title}\" transform=\"rotate(270, 40, 50)\">error</text>\
         <text x=\"190\" y=\"90\" dy=\"0.5ex\" text-anchor=\"start\" font-size=\"{tick}\">0.001</text>\
         <circle cx=\"150\" cy=\"20\" r=\"4\"/>\
         <g class=\"legend\" transform=\"translate(120,10)\"><rect x=\"0\" y=\"0\" width=\"60\" height=\"30\" fill=\"none\"/></g>\
         </svg>"
    );
    let found = defects("broken", &svg);
    for what in [
        "runs into axis title",
        "leaves the figure",
        "covers the data point",
    ] {
        assert!(
            found.iter().any(|d| d.contains(what)),
            "`{what}` not caught: {found:?}"
        );
    }
}
