//! Legends and colour bars, drawn in their own area beside the data.

use anyhow::{anyhow, Result};
use plotters::prelude::*;

use crate::{plot::dashes, plot::fonts, plot::marker, plot::text_width, plot::DATA_STROKE};

/// Height of one legend row [px].
const ROW: u32 = 22;
/// Width of an entry's sample (line, dashes or marker) [px].
const SAMPLE: u32 = 26;
/// Padding inside the box [px].
const PAD: u32 = 8;

/// How an entry's sample is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mark {
    /// A thick dashed black line (the reference).
    Dashed,
    /// A grey line of short dashes (a guide).
    Dotted,
    /// A coloured line.
    Line,
    /// A filled marker (with a short line: markers are joined within runs).
    Marker,
    /// A filled marker alone (points never joined).
    Point,
    /// A filled square (a category of a map).
    Swatch,
}

/// One legend row.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// The text.
    pub name: String,
    /// The sample's colour.
    pub colour: RGBColor,
    /// Its line's dashes and its marker's shape ([`super::pen`]).
    pub variant: usize,
    /// The sample.
    pub mark: Mark,
}

/// A boxed list of entries.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    /// The rows, top to bottom.
    pub entries: Vec<Entry>,
}

impl Legend {
    /// The width the legend needs [px], box and margins included.
    pub fn width(&self) -> Result<u32> {
        let widest = self
            .entries
            .iter()
            .map(|e| text_width(&e.name, fonts::LEGEND))
            .try_fold(0, |m, w| w.map(|w| m.max(w)))?;
        Ok(widest + SAMPLE + 3 * PAD + 2 * PAD)
    }

    /// The height it needs [px].
    pub fn height(&self) -> u32 {
        self.entries.len() as u32 * ROW + 2 * PAD
    }

    /// The legend as an SVG document of its own size, the box inset by `PAD` on the left.
    pub fn to_svg(&self) -> Result<String> {
        let (w, h) = (self.width()?, self.height());
        let fail = |e: &dyn std::fmt::Display| anyhow!("legend: {e}");
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
            let (x0, x1) = (PAD as i32, (w - PAD) as i32);
            root.draw(&Rectangle::new(
                [(x0, 0), (x1, h as i32 - 1)],
                ShapeStyle::from(&RGBColor(190, 190, 190)).stroke_width(1),
            ))
            .map_err(|e| fail(&e))?;
            for (k, entry) in self.entries.iter().enumerate() {
                let y = (PAD + k as u32 * ROW + ROW / 2) as i32;
                let (a, b) = (x0 + PAD as i32, x0 + (PAD + SAMPLE) as i32);
                match entry.mark {
                    Mark::Dashed => {
                        for s in (a..b).step_by(10) {
                            root.draw(&PathElement::new(
                                vec![(s, y), ((s + 6).min(b), y)],
                                BLACK.stroke_width(3),
                            ))
                            .map_err(|e| fail(&e))?;
                        }
                    }
                    Mark::Dotted => {
                        for s in (a..b).step_by(8) {
                            root.draw(&PathElement::new(
                                vec![(s, y), ((s + 4).min(b), y)],
                                entry.colour.stroke_width(DATA_STROKE),
                            ))
                            .map_err(|e| fail(&e))?;
                        }
                    }
                    Mark::Line | Mark::Marker => {
                        // The line's dashes as the data draw them: the same lengths on and off.
                        let (on, off) = dashes(entry.variant).unwrap_or((SAMPLE, 0));
                        for s in (a..b).step_by((on + off) as usize) {
                            root.draw(&PathElement::new(
                                vec![(s, y), ((s + on as i32).min(b), y)],
                                entry.colour.stroke_width(DATA_STROKE),
                            ))
                            .map_err(|e| fail(&e))?;
                        }
                        if entry.mark == Mark::Marker {
                            root.draw(&marker(((a + b) / 2, y), entry.colour, entry.variant))
                                .map_err(|e| fail(&e))?;
                        }
                    }
                    Mark::Point => {
                        root.draw(&marker(((a + b) / 2, y), entry.colour, entry.variant))
                            .map_err(|e| fail(&e))?;
                    }
                    Mark::Swatch => {
                        root.draw(&Rectangle::new(
                            [(a, y - 7), (a + 14, y + 7)],
                            entry.colour.filled(),
                        ))
                        .map_err(|e| fail(&e))?;
                    }
                }
                root.draw(&Text::new(
                    entry.name.as_str(),
                    (b + PAD as i32, y),
                    ("sans-serif", fonts::LEGEND)
                        .into_font()
                        .into_text_style(&root)
                        .pos(plotters::style::text_anchor::Pos::new(
                            plotters::style::text_anchor::HPos::Left,
                            plotters::style::text_anchor::VPos::Center,
                        )),
                ))
                .map_err(|e| fail(&e))?;
            }
            root.present().map_err(|e| fail(&e))?;
        }
        Ok(svg)
    }
}
