//! The History CSV that a program outside the harness writes (or a stored result holds), read
//! back and validated against the path it claims to follow.
//!
//! Columns (SI: m, N, Pa), the same as `spherecontact run` writes:
//!
//! ```text
//! step,position,delta_n,delta_t,normal_force,tangential_force,contact_radius,peak_pressure,stick_radius
//! ```
//! The four path columns come first, in that order; then any of the quantity columns, each at
//! most once, in any order (a column left out, or an empty cell, is a quantity not produced).
//! One row per path step, step 0 first; `position` is the path position a step reaches, empty
//! between positions; `delta_n`, `delta_t` must be the path's own (to [`PATH_MATCH`]), which
//! catches a file of another path, a shifted row or a file in µm or mm.

use std::path::{Path, PathBuf};

use spherecontact_model::history::{Quantity, StepResult};
use spherecontact_model::limits::MAX_STORED_RESULTS_BYTES;
use spherecontact_model::path::{Step, PATH_MATCH};
use spherecontact_system::input;

/// The path columns, first in every History CSV.
pub const PATH_COLUMNS: [&str; 4] = ["step", "position", "delta_n", "delta_t"];

/// Every column of a History CSV, in the order `spherecontact run` writes them.
pub fn columns() -> Vec<&'static str> {
    let mut columns = PATH_COLUMNS.to_vec();
    columns.extend(Quantity::ALL.iter().map(|q| q.name()));
    columns
}

/// A History CSV that cannot be used: the file, the line and column where known, what is wrong
/// and what is allowed.
#[derive(Debug, thiserror::Error)]
pub enum ResultsError {
    /// The file cannot be opened: missing, not a regular file, or too large.
    #[error("{}: cannot read: {source}", file.display())]
    Open {
        /// The file.
        file: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file cannot be read as CSV.
    #[error("{}: cannot read: {source}", file.display())]
    Unreadable {
        /// The file.
        file: PathBuf,
        /// Why.
        source: csv::Error,
    },
    /// The header is not the documented one. What it holds is not repeated (the file may be
    /// anything): the message locates the fault and gives the expected header.
    #[error("{}:1: header: {why} (allowed: {} first, then any of {})",
        file.display(), PATH_COLUMNS.join(","), quantity_names())]
    Header {
        /// The file.
        file: PathBuf,
        /// What is wrong with it, without the file's text.
        why: String,
    },
    /// A row with another number of cells than the header.
    #[error("{}:{line}: {found} cells in a row under a header of {expected} columns", file.display())]
    ColumnCount {
        /// The file.
        file: PathBuf,
        /// The line (1-based).
        line: u64,
        /// Cells found.
        found: usize,
        /// Columns of the header.
        expected: usize,
    },
    /// A cell that is not what its column allows.
    #[error("{}:{line}: column `{column}`: {why}", file.display())]
    Cell {
        /// The file.
        file: PathBuf,
        /// The line (1-based).
        line: u64,
        /// The column's name.
        column: String,
        /// What is wrong and what is allowed.
        why: String,
    },
    /// Not one row per path step.
    #[error("{}: {rows} rows for a path of {steps} steps (allowed: one row per step, step 0 first)",
        file.display())]
    RowCount {
        /// The file.
        file: PathBuf,
        /// Rows read (counting stops one past the path).
        rows: usize,
        /// Steps of the path.
        steps: usize,
    },
}

fn quantity_names() -> String {
    Quantity::ALL.map(Quantity::name).join(", ")
}

/// Reads the History CSV at `file` (a regular file of at most [`MAX_STORED_RESULTS_BYTES`],
/// opened without blocking) and validates it against `steps`: one row per step, the path's
/// positions and displacements, finite values. Messages locate a fault (line, column) without
/// repeating the file's text, except a number that differs from the path's.
pub fn read(file: &Path, steps: &[Step]) -> Result<Vec<StepResult>, ResultsError> {
    let source =
        input::open_regular(file, MAX_STORED_RESULTS_BYTES, input::Links::Follow).map_err(|source| {
            ResultsError::Open {
                file: file.to_path_buf(),
                source,
            }
        })?;
    read_from(source, file, steps)
}

/// [`read`] of a History CSV already opened (`file` names it in errors): a stream, read row by
/// row, never whole.
pub fn read_from(
    input: impl std::io::Read,
    file: &Path,
    steps: &[Step],
) -> Result<Vec<StepResult>, ResultsError> {
    let unreadable = |source| ResultsError::Unreadable {
        file: file.to_path_buf(),
        source,
    };
    let mut reader = csv::ReaderBuilder::new().flexible(true).from_reader(input);
    let header = reader.headers().map_err(unreadable)?.clone();
    let quantities = quantity_columns(file, &header)?;
    let scale = steps
        .iter()
        .flat_map(|s| [s.delta_n.abs(), s.delta_t.abs()])
        .fold(0.0, f64::max);
    let mut rows = Vec::with_capacity(steps.len());
    for record in reader.records() {
        let record = record.map_err(unreadable)?;
        let Some(step) = steps.get(rows.len()) else {
            return Err(ResultsError::RowCount {
                file: file.to_path_buf(),
                rows: rows.len() + 1,
                steps: steps.len(),
            });
        };
        let line = record.position().map_or(0, csv::Position::line);
        if record.len() != header.len() {
            return Err(ResultsError::ColumnCount {
                file: file.to_path_buf(),
                line,
                found: record.len(),
                expected: header.len(),
            });
        }
        let cells = Cells {
            file,
            line,
            record: &record,
        };
        rows.push(cells.row(step, &quantities, PATH_MATCH * scale)?);
    }
    if rows.len() != steps.len() {
        return Err(ResultsError::RowCount {
            file: file.to_path_buf(),
            rows: rows.len(),
            steps: steps.len(),
        });
    }
    Ok(rows)
}

/// The quantity of each column after the path columns.
fn quantity_columns(file: &Path, header: &csv::StringRecord) -> Result<Vec<Quantity>, ResultsError> {
    let bad = |why: String| ResultsError::Header {
        file: file.to_path_buf(),
        why,
    };
    let names: Vec<&str> = header.iter().map(str::trim).collect();
    if names.len() < PATH_COLUMNS.len() || names[..PATH_COLUMNS.len()] != PATH_COLUMNS {
        return Err(bad("the path columns are missing or out of order".into()));
    }
    let mut quantities: Vec<Quantity> = Vec::new();
    for (k, name) in names.iter().enumerate().skip(PATH_COLUMNS.len()) {
        let quantity = Quantity::from_name(name)
            .ok_or_else(|| bad(format!("column {} is not a known column", k + 1)))?;
        if quantities.contains(&quantity) {
            return Err(bad(format!("column {} repeats `{quantity}`", k + 1)));
        }
        quantities.push(quantity);
    }
    Ok(quantities)
}

/// The cells of one record, with where they are for messages.
struct Cells<'a> {
    file: &'a Path,
    line: u64,
    record: &'a csv::StringRecord,
}

impl Cells<'_> {
    fn error(&self, column: &str, why: String) -> ResultsError {
        ResultsError::Cell {
            file: self.file.to_path_buf(),
            line: self.line,
            column: column.to_owned(),
            why,
        }
    }

    fn text(&self, index: usize) -> &str {
        self.record.get(index).map_or("", str::trim)
    }

    /// The finite number in cell `index`, `None` when the cell is empty.
    fn number(&self, index: usize, column: &str) -> Result<Option<f64>, ResultsError> {
        let text = self.text(index);
        if text.is_empty() {
            return Ok(None);
        }
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            Ok(_) => Err(self.error(
                column,
                "not finite (allowed: a finite number in SI units, or empty)".into(),
            )),
            Err(_) => Err(self.error(
                column,
                "not a number (allowed: a finite number in SI units, or empty)".into(),
            )),
        }
    }

    /// The row for path step `step`, its path columns checked against it.
    fn row(&self, step: &Step, quantities: &[Quantity], tolerance: f64) -> Result<StepResult, ResultsError> {
        let index = self.text(0);
        if index.parse::<usize>().ok() != Some(step.index) {
            return Err(self.error(
                "step",
                format!("not the path's step {0} (allowed: {0})", step.index),
            ));
        }
        let position = self.text(1);
        let parsed = (!position.is_empty()).then(|| position.parse::<usize>().ok());
        if parsed.unwrap_or(None) != step.position || parsed == Some(None) {
            let expected = step
                .position
                .map_or_else(|| "empty (between positions)".to_owned(), |p| p.to_string());
            return Err(self.error(
                "position",
                format!(
                    "not the path's position at step {} (allowed: {expected})",
                    step.index
                ),
            ));
        }
        for (index, column, expected) in [(2, "delta_n", step.delta_n), (3, "delta_t", step.delta_t)] {
            let value = self.number(index, column)?;
            match value {
                Some(v) if (v - expected).abs() <= tolerance => {}
                Some(v) => return Err(self.error(column, mismatch(v, expected, step.index))),
                None => {
                    return Err(self.error(
                        column,
                        format!(
                            "empty at step {} (allowed: the path's {expected:e} m)",
                            step.index
                        ),
                    ))
                }
            }
        }
        let mut row = StepResult::at(step);
        for (k, quantity) in quantities.iter().enumerate() {
            let value = self.number(PATH_COLUMNS.len() + k, quantity.name())?;
            match quantity {
                Quantity::NormalForce => row.normal_force = value,
                Quantity::TangentialForce => row.tangential_force = value,
                Quantity::ContactRadius => row.contact_radius = value,
                Quantity::PeakPressure => row.peak_pressure = value,
                Quantity::StickRadius => row.stick_radius = value,
                // Never a column: `Quantity::from_name` gives step quantities only.
                Quantity::PressureProfile
                | Quantity::TractionProfile
                | Quantity::TransverseRatio
                | Quantity::StickSemiAxisX
                | Quantity::StickSemiAxisY => {}
            }
        }
        Ok(row)
    }
}

/// Why a path value differs from the path, with a hint when the factor is a unit's.
fn mismatch(value: f64, expected: f64, step: usize) -> String {
    let ratio = value / expected;
    let unit = [(1e6, "µm"), (1e3, "mm")]
        .into_iter()
        .find(|(factor, _)| expected != 0.0 && (ratio / factor - 1.0).abs() < 1e-3)
        .map(|(_, unit)| format!("; the file looks like {unit}, the columns are SI (m)"))
        .unwrap_or_default();
    format!("{value:e} at step {step} where the path has {expected:e} m{unit}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steps() -> Vec<Step> {
        spherecontact_model::fixtures::test_scene(&[0.0, 10.0, 17.0]).steps()
    }

    /// The CSV of `steps` with a normal force P = 1 N per µm of δn.
    fn text(steps: &[Step], unit: f64) -> String {
        let mut text = "step,position,delta_n,delta_t,normal_force\n".to_owned();
        for s in steps {
            let position = s.position.map_or_else(String::new, |p| p.to_string());
            text.push_str(&format!(
                "{},{position},{:e},{:e},{:e}\n",
                s.index,
                s.delta_n * unit,
                s.delta_t * unit,
                s.delta_n * 1e6
            ));
        }
        text
    }

    fn read_text(text: &str, steps: &[Step]) -> Result<Vec<StepResult>, ResultsError> {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("h.csv");
        std::fs::write(&file, text).unwrap();
        read(&file, steps)
    }

    #[test]
    fn a_valid_file_reads_back_with_absent_quantities_as_none() {
        let steps = steps();
        let rows = read_text(&text(&steps, 1.0), &steps).unwrap();
        assert_eq!(rows.len(), steps.len());
        assert_eq!(rows[4].normal_force, Some(10.0));
        assert_eq!(rows[4].position, Some(1));
        assert_eq!(rows[4].tangential_force, None);
    }

    #[test]
    fn a_file_in_micrometres_is_named_as_such() {
        let steps = steps();
        let e = read_text(&text(&steps, 1e6), &steps).unwrap_err().to_string();
        assert!(
            e.contains("column `delta_n`") && e.contains("looks like µm"),
            "{e}"
        );
    }

    #[test]
    fn faults_are_located() {
        let steps = steps();
        let good = text(&steps, 1.0);
        let lines: Vec<&str> = good.lines().collect();
        let cases = [
            (lines[..5].join("\n"), "4 rows for a path of 9 steps"),
            (
                good.replace("normal_force", "force"),
                "column 5 is not a known column",
            ),
            (good.replacen(",1e1\n", ",1e1,3\n", 1), "6 cells in a row"),
            (good.replacen(",1e1\n", ",NaN\n", 1), "normal_force`: not finite"),
            (good.replacen(",1e1\n", ",x1\n", 1), "normal_force`: not a number"),
            (good.replacen("4,1,", "4,,", 1), "column `position`"),
            (format!("{good}9,,0,0,0\n"), "10 rows for a path of 9 steps"),
        ];
        for (text, expected) in cases {
            let e = read_text(&text, &steps).unwrap_err().to_string();
            assert!(e.contains(expected), "{expected}: {e}");
        }
    }
}
