//! The sweep table: one row per sweep point, `sweep,value,` then the quantities of
//! [`Quantity::ALL`] (SI; an empty cell where undefined). `run` writes it for every impact
//! solver (`DIR/<solver>.csv`), and a case's own solver gives it back ([`super::own_solver`]):
//! stored in a file, or written by a program. Written in shortest round-trip form; read here,
//! checked against the case's sweep, every message naming the file's line (the header is line 1)
//! and the column.

use std::fmt::Write;
use std::io::Read;
use std::path::Path;

use super::outcome::Outcome;
use super::problem::{Point, Quantity};
use spherecontact_model::limits::MAX_SWEEP_TABLE_BYTES;
use spherecontact_model::number::Short;
use spherecontact_system::input::{self, Links};

/// Reads the sweep table in `file` (a regular file of at most [`MAX_SWEEP_TABLE_BYTES`], links
/// as `links` says) as [`read`] does; the message names the file and never quotes more than a
/// cell of it.
pub fn read_file(file: &Path, sweep: &str, points: &[Point], links: Links) -> Result<Vec<Outcome>, String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", file.display());
    let mut opened = input::open_regular(file, MAX_SWEEP_TABLE_BYTES, links)
        .map_err(|e| at(&format!("cannot read it: {e}")))?;
    let mut text = String::new();
    opened
        .read_to_string(&mut text)
        .map_err(|e| at(&format!("cannot read it as text: {e}")))?;
    read(&text, sweep, points).map_err(|e| at(&e))
}

/// The two columns before the quantities.
const LEAD: [&str; 2] = ["sweep", "value"];

/// A sweep value read back may differ from the case's by this fraction: a program that writes
/// ten significant digits (or converts degrees to radians its own way) is still at the same
/// point, while two points of a shipped sweep differ by far more (1e-3 at least).
const VALUE_MATCH: f64 = 1e-9;

/// The header line (without its newline).
pub fn header() -> String {
    LEAD.into_iter()
        .chain(Quantity::ALL.map(Quantity::name))
        .collect::<Vec<_>>()
        .join(",")
}

/// A number as a cell: empty unless finite, else its shortest round-trip form
/// ([`spherecontact_model::number::cell`], as every results file).
pub use spherecontact_model::number::cell;

/// The row of one sweep point (without its newline): `sweep` names the swept variable ("none"
/// when the case does not sweep); `outcome` is `None` for a point without one.
pub fn row(sweep: &str, value: Option<f64>, outcome: Option<&Outcome>) -> String {
    let mut text = format!("{sweep},{}", cell(value));
    for q in Quantity::ALL {
        let _ = write!(text, ",{}", cell(outcome.and_then(|o| o.get(q))));
    }
    text
}

/// What is wrong with a sweep table.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum TableError {
    /// The header is not the table's.
    #[error("line 1: the header is not a sweep table's (expected `{expected}`){detail}")]
    Header {
        /// The header expected.
        expected: String,
        /// Which column is wrong, in words.
        detail: String,
    },
    /// The table has another number of rows than the sweep has points.
    #[error("{rows} rows after the header, but the case's sweep has {points} points")]
    Rows {
        /// The rows read.
        rows: usize,
        /// The points of the sweep.
        points: usize,
    },
    /// A cell is wrong.
    #[error("line {line}, column {column}: {why}")]
    Cell {
        /// The file's line (the header is line 1).
        line: usize,
        /// The column's name.
        column: String,
        /// What is wrong.
        why: String,
    },
}

/// Reads `text` as the sweep table of `points` (the case's sweep, in order) whose swept variable
/// is `sweep` ("none" without a sweep): each point's outcome.
pub fn read(text: &str, sweep: &str, points: &[Point]) -> Result<Vec<Outcome>, TableError> {
    let mut lines = text.lines().map(|l| l.strip_suffix('\r').unwrap_or(l));
    check_header(lines.next().unwrap_or(""))?;
    let rows: Vec<&str> = lines.collect();
    let rows = match rows.iter().rposition(|r| !r.trim().is_empty()) {
        Some(last) => &rows[..=last],
        None => &rows[..0],
    };
    if rows.len() != points.len() {
        return Err(TableError::Rows {
            rows: rows.len(),
            points: points.len(),
        });
    }
    rows.iter()
        .zip(points)
        .enumerate()
        .map(|(k, (row, point))| read_row(row, k + 2, sweep, point))
        .collect()
}

/// The header, column by column: the first one that differs is named.
fn check_header(line: &str) -> Result<(), TableError> {
    let expected = header();
    if line == expected {
        return Ok(());
    }
    let wanted: Vec<&str> = expected.split(',').collect();
    let given: Vec<&str> = line.split(',').collect();
    let detail = match wanted.iter().zip(&given).position(|(w, g)| w != &g.trim()) {
        Some(k) => format!(
            ": column {} is `{}`, expected `{}`",
            k + 1,
            shown(given[k]),
            wanted[k]
        ),
        None if given.len() < wanted.len() => format!(": no column `{}`", wanted[given.len()]),
        None => format!(": a column too many, `{}`", shown(given[wanted.len()])),
    };
    Err(TableError::Header { expected, detail })
}

/// A cell as a message quotes it: at most 40 characters, control characters dropped.
fn shown(text: &str) -> String {
    text.chars().filter(|c| !c.is_control()).take(40).collect()
}

/// One row, at file line `line`, of `point`.
fn read_row(row: &str, line: usize, sweep: &str, point: &Point) -> Result<Outcome, TableError> {
    let cells: Vec<&str> = row.split(',').map(str::trim).collect();
    let names: Vec<&str> = LEAD
        .into_iter()
        .chain(Quantity::ALL.map(Quantity::name))
        .collect();
    let bad = |column: &str, why: String| TableError::Cell {
        line,
        column: column.to_owned(),
        why,
    };
    if cells.len() != names.len() {
        return Err(bad(
            "—",
            format!("{} cells, expected {}", cells.len(), names.len()),
        ));
    }
    if cells[0] != sweep {
        return Err(bad("sweep", format!("`{}`, expected `{sweep}`", shown(cells[0]))));
    }
    let number = |k: usize| -> Result<Option<f64>, TableError> {
        if cells[k].is_empty() {
            return Ok(None);
        }
        match cells[k].parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            Ok(_) => Err(bad(
                names[k],
                "not a finite number (an undefined value is an empty cell)".into(),
            )),
            Err(_) => Err(bad(names[k], format!("`{}` is not a number", shown(cells[k])))),
        }
    };
    let value = number(1)?;
    let matches = match (value, point.value) {
        (None, None) => true,
        (Some(v), Some(p)) => (v - p).abs() <= VALUE_MATCH * p.abs().max(f64::MIN_POSITIVE),
        _ => false,
    };
    if !matches {
        let expected = point
            .value
            .map_or_else(|| "empty".to_owned(), |p| Short(p).to_string());
        return Err(bad(
            "value",
            format!("{}, expected the sweep's {expected} (SI)", cell(value)),
        ));
    }
    let mut values = [None; 7];
    for (k, slot) in values.iter_mut().enumerate() {
        *slot = number(k + 2)?;
    }
    Ok(Outcome::from_values(values))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::problem::ImpactBody;

    fn points(values: &[f64]) -> Vec<Point> {
        let body = ImpactBody::rigid_flat();
        values
            .iter()
            .map(|&v| Point {
                value: Some(v),
                body1: body,
                body2: body,
                restitution: 1.0,
            })
            .collect()
    }

    /// Requirement: a table written by [`row`] reads back to the same outcomes, bit for bit
    /// (shortest round-trip form), a CRLF file alike.
    #[test]
    fn a_written_table_reads_back_exactly() {
        let outcome = Outcome::from_values([
            Some(1.0 / 3.0),
            Some(2e5),
            None,
            Some(0.98),
            Some(-0.1),
            Some(7.0),
            None,
        ]);
        let text = format!(
            "{}\r\n{}\r\n{}\n",
            header(),
            row("spin", Some(0.1), Some(&outcome)),
            row("spin", Some(0.3), None)
        );
        let read = read(&text, "spin", &points(&[0.1, 0.3])).unwrap();
        assert_eq!(read[0], outcome);
        assert_eq!(read[1], Outcome::from_values([None; 7]));
    }

    /// Requirement: each defect is named with the file's line and the column.
    #[test]
    fn defects_name_line_and_column() {
        let good = row("spin", Some(0.1), None);
        let read_text = |text: String| read(&text, "spin", &points(&[0.1])).unwrap_err().to_string();
        let misspelt = header().replace("max_overlap", "max_overlp");
        assert!(read_text(format!("{misspelt}\n{good}\n"))
            .contains("column 5 is `max_overlp`, expected `max_overlap`"));
        let nan = good.replacen(",,", ",nan,", 1);
        assert_eq!(
            read_text(format!("{}\n{nan}\n", header())),
            "line 2, column contact_duration: not a finite number (an undefined value is an empty cell)"
        );
        assert!(
            read_text(format!("{}\n{}\n", header(), row("spin", Some(0.2), None)))
                .starts_with("line 2, column value: 0.2, expected the sweep's 0.1")
        );
        assert_eq!(
            read_text(format!("{}\n", header())),
            "0 rows after the header, but the case's sweep has 1 points"
        );
    }
}
