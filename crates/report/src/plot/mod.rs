//! Plots as SVG text: line plots (linear, log-y or log-log) and panels of 2D maps of surface
//! fields with a shared colour scale.
//!
//! Drawn with plotters' SVG backend; text is measured with DejaVu Sans embedded in the binary
//! (the `dejavu` crate), so nothing depends on the system's font libraries. The SVG names its
//! font family and the browser renders the text.
//!
//! Layout rules a reader relies on, and which `tests/plot_layout.rs` checks on every figure:
//! tick labels are short (no float noise) and their label area is sized from the labels
//! themselves, so they never run into the axis titles; legends and colour bars sit in their own
//! area beside the data (an SVG group of class `legend`), never on it; data are drawn with
//! strokes of at least [`DATA_STROKE`] px, decorations (axes, grid, ticks) with thinner ones.

mod legend;
mod line;
mod map;

pub use line::{Axes, LinePlot, Series, Style, SIZE};
pub use map::{Cells, MapPanel, MapPlot, MapValue, Overlay, Scale};

use std::sync::Once;

use anyhow::{anyhow, Result};
use plotters::prelude::*;

/// Font sizes [plotters units]; plotters' SVG backend writes `font-size` = size / 1.24.
pub mod fonts {
    /// Plot titles.
    pub const TITLE: f64 = 17.0;
    /// Axis titles ("δn [µm]").
    pub const AXIS_TITLE: f64 = 15.0;
    /// Tick labels.
    pub const TICK: f64 = 13.0;
    /// Legend entries and colour-bar titles.
    pub const LEGEND: f64 = 14.0;

    /// The `font-size` attribute plotters writes for a font of `size`.
    pub fn in_svg(size: f64) -> f64 {
        size / 1.24
    }
}

/// Data strokes are at least this wide [px]; axes, grid lines and ticks are thinner.
pub const DATA_STROKE: u32 = 2;

/// Distinguishable line colours: Tableau 10, then ten darker or more saturated ones unlike any
/// of them; the reference series is black and a guide grey, so neither is here.
const COLOURS: [RGBColor; 20] = [
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
    RGBColor(0, 0, 128),
    RGBColor(128, 0, 0),
    RGBColor(0, 128, 128),
    RGBColor(128, 128, 0),
    RGBColor(240, 50, 230),
    RGBColor(230, 180, 0),
    RGBColor(0, 90, 0),
    RGBColor(75, 0, 130),
    RGBColor(250, 128, 114),
    RGBColor(90, 60, 20),
];

/// Series drawn in one line style before the next style begins: about as many as a reader tells
/// apart by colour alone.
const PER_STYLE: usize = 10;

/// How the `slot`-th coloured series of a figure is drawn: its colour, and a variant (0 solid
/// line and round markers, 1 dashed and square, 2 dotted and triangular) that changes every
/// [`PER_STYLE`] series. Every colour-and-variant pair differs up to 60 series.
pub fn pen(slot: usize) -> (RGBColor, usize) {
    (COLOURS[slot % COLOURS.len()], (slot / PER_STYLE) % 3)
}

/// A filled marker at `at` in `colour`, its shape by variant: a circle, a square, a triangle.
fn marker<'a, C: Clone + 'a, DB: DrawingBackend + 'a>(
    at: C,
    colour: RGBColor,
    variant: usize,
) -> plotters::element::DynElement<'a, DB, C> {
    use plotters::element::IntoDynElement;
    let style = colour.filled();
    let at = EmptyElement::at(at);
    let (r, t) = (MARKER_SIZE as i32, TRIANGLE_SIZE as i32);
    match variant {
        0 => (at + Circle::new((0, 0), MARKER_SIZE, style)).into_dyn(),
        1 => (at + Rectangle::new([(-r, -r), (r, r)], style)).into_dyn(),
        _ => (at + TriangleMarker::new((0, 0), t, style)).into_dyn(),
    }
}

/// A round or square marker's half-width [px].
const MARKER_SIZE: u32 = 4;
/// A triangular marker's size [px]: a little larger, its area near the others'.
const TRIANGLE_SIZE: u32 = 5;

/// The dash pattern of a variant [px drawn, px skipped], or `None` for a solid line.
fn dashes(variant: usize) -> Option<(u32, u32)> {
    match variant {
        0 => None,
        1 => Some((10, 5)),
        _ => Some((3, 4)),
    }
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

/// The width [px] plotters reserves for `text` in a font of `size` (an over-estimate of what
/// the browser draws, see [`fonts::in_svg`]).
fn text_width(text: &str, size: f64) -> Result<u32> {
    let font = ("sans-serif", size).into_font();
    let ((x0, _), (x1, _)) = font.layout_box(text).map_err(|e| anyhow!("{e}"))?;
    Ok((x1 - x0).unsigned_abs())
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
        // A fifth of a decade of margin: markers at the extremes stay clear of the axes.
        (true, true) => (lo / 1.6, hi * 1.6),
        (true, false) if hi <= lo => (lo - 0.5 * lo.abs().max(1e-30), hi + 0.5 * hi.abs().max(1e-30)),
        (true, false) => {
            let pad = 0.04 * (hi - lo);
            (lo - pad, hi + pad)
        }
    }
}

/// A tick value as people write it.
///
/// Linear axes: as many decimals as the axis span needs (three significant digits of the span),
/// trailing zeros dropped, so 0.30000000000000004 prints "0.3" and 1000.0 prints "1000";
/// beyond 10⁵ or below 10⁻³ in magnitude, scientific ("2.5e6"). Log axes: powers of ten as
/// "10⁻⁵", other ticks as "2×10⁻⁵" (plotters' own labels print 1e-4 as "9.999999999e-5").
pub fn tick_label(value: f64, (lo, hi): (f64, f64), log: bool) -> String {
    if log {
        return power_of_ten_label(value);
    }
    let magnitude = lo.abs().max(hi.abs());
    if magnitude >= 1e5 || (magnitude < 1e-3 && magnitude > 0.0) {
        let text = format!("{value:.2e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        return format!("{}e{exponent}", trim_zeros(mantissa));
    }
    let span = (hi - lo).abs().max(f64::MIN_POSITIVE);
    let decimals = (2.0 - span.log10().floor()).clamp(0.0, 12.0) as usize;
    let text = trim_zeros(&format!("{value:.decimals$}"));
    if text == "-0" {
        "0".into()
    } else {
        text
    }
}

/// "1.50" → "1.5", "2.00" → "2", "300" → "300".
fn trim_zeros(text: &str) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text.to_owned()
    }
}

/// "10⁻⁵" for 1e-5 (within rounding), "2×10⁻⁵" for 2e-5.
fn power_of_ten_label(value: f64) -> String {
    if !(value > 0.0 && value.is_finite()) {
        return format!("{value}");
    }
    // A tick computed as 10^k may land a rounding error below it: nudge before taking the floor.
    let exponent = (value.log10() + 1e-9).floor();
    let mantissa = value / 10f64.powf(exponent);
    let superscript: String = format!("{}", exponent as i64)
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            d => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d.to_digit(10).unwrap_or(0) as usize],
        })
        .collect();
    if (mantissa - 1.0).abs() < 1e-6 {
        format!("10{superscript}")
    } else {
        format!("{}×10{superscript}", trim_zeros(&format!("{mantissa:.2}")))
    }
}

/// One SVG document from parts drawn separately: each part's content is placed at its offset
/// inside a group, with a class where given (`legend` marks a legend or colour bar).
pub fn compose(size: (u32, u32), parts: &[(Option<&str>, (u32, u32), String)]) -> String {
    let mut svg = format!(
        "<svg width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" xmlns=\"http://www.w3.org/2000/svg\">\n",
        w = size.0,
        h = size.1
    );
    for (class, (dx, dy), part) in parts {
        let body = part
            .find('>')
            .map(|start| &part[start + 1..])
            .and_then(|rest| rest.rfind("</svg>").map(|end| &rest[..end]))
            .unwrap_or("");
        let class = class.map(|c| format!(" class=\"{c}\"")).unwrap_or_default();
        svg.push_str(&format!(
            "<g{class} transform=\"translate({dx},{dy})\">{body}</g>\n"
        ));
    }
    svg.push_str("</svg>\n");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_tick_labels_have_no_float_noise() {
        assert_eq!(tick_label(0.1 + 0.2, (0.0, 1.0), false), "0.3");
        assert_eq!(tick_label(1000.0, (0.0, 1000.0), false), "1000");
        assert_eq!(tick_label(-200.0, (-220.0, 170.0), false), "-200");
        assert_eq!(tick_label(-1e-17, (-1.0, 1.0), false), "0");
        assert_eq!(tick_label(2.5e6, (0.0, 3e6), false), "2.5e6");
        assert_eq!(tick_label(0.0125, (0.0, 0.05), false), "0.0125");
    }

    #[test]
    fn log_tick_labels_are_powers_of_ten() {
        assert_eq!(tick_label(9.999999999e-5, (1e-9, 1e-2), true), "10⁻⁴");
        assert_eq!(tick_label(1e-9, (1e-9, 1e-2), true), "10⁻⁹");
        assert_eq!(tick_label(100.0, (1.0, 1e3), true), "10²");
        assert_eq!(tick_label(2e-5, (1e-6, 1e-4), true), "2×10⁻⁵");
    }

    #[test]
    fn every_series_has_its_own_colour_and_variant() {
        // The first 20 differ in colour alone; up to 60 the pairs differ.
        let rgb = |c: RGBColor| (c.0, c.1, c.2);
        let colours: std::collections::HashSet<_> = (0..20).map(|k| rgb(pen(k).0)).collect();
        assert_eq!(colours.len(), 20);
        let pairs: std::collections::HashSet<_> = (0..60).map(|k| (rgb(pen(k).0), pen(k).1)).collect();
        assert_eq!(pairs.len(), 60);
        // The first ten are solid; beyond about ten series a dash pattern as well.
        assert!((0..10).all(|k| pen(k).1 == 0));
        assert!((10..20).all(|k| pen(k).1 == 1 && dashes(1).is_some()));
        // None is the reference's black or the guide's grey.
        assert!((0..20).all(|k| pen(k).0 != BLACK && pen(k).0 != super::line::GUIDE));
    }

    #[test]
    fn compose_places_parts_in_groups() {
        let part =
            "<svg width=\"10\" height=\"10\" xmlns=\"http://www.w3.org/2000/svg\"><rect/></svg>".to_owned();
        let svg = compose(
            (20, 10),
            &[(None, (0, 0), part.clone()), (Some("legend"), (10, 0), part)],
        );
        assert!(svg.contains("<g transform=\"translate(0,0)\"><rect/></g>"));
        assert!(svg.contains("<g class=\"legend\" transform=\"translate(10,0)\"><rect/></g>"));
        assert_eq!(svg.matches("<svg").count(), 1);
    }
}
