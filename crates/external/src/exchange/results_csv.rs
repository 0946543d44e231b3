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
//!
//! A fault of the file's form or of its path columns refuses the file; a cell of a quantity that
//! is not a number refuses that quantity only ([`Results::unread`]): its checks fail with the
//! file, line and column, the other quantities are read and judged. Lines are the file's own,
//! 1-based, every line break counted ([`crate::csv_lines`]).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::csv_lines;
use spherecontact_model::history::{Quantity, StepResult};
use spherecontact_model::limits::MAX_STORED_RESULTS_BYTES;
use spherecontact_model::path::{Step, PATH_MATCH};
use spherecontact_system::input;
use spherecontact_system::text::nearest;

/// The path columns, first in every History CSV.
pub const PATH_COLUMNS: [&str; 4] = ["step", "position", "delta_n", "delta_t"];

/// Every column of a History CSV, in the order `spherecontact run` writes them.
pub fn columns() -> Vec<&'static str> {
    let mut columns = PATH_COLUMNS.to_vec();
    columns.extend(Quantity::ALL.iter().map(|q| q.name()));
    columns
}

/// A History CSV read back.
#[derive(Debug)]
pub struct Results {
    /// One row per path step, step 0 first.
    pub steps: Vec<StepResult>,
    /// The quantities left out for a cell that is not a number, and why: the first such cell's
    /// file, line and column (the whole column is left out). The output is at fault: a
    /// program's run folder is kept.
    pub refused: BTreeMap<Quantity, String>,
    /// The quantities whose column is not in the header, and so it says.
    pub absent: BTreeMap<Quantity, String>,
}

impl Results {
    /// Why each quantity is not in the rows, refused or absent: the history's `Metadata::unread`.
    pub fn unread(&self) -> BTreeMap<Quantity, String> {
        let both = self.refused.iter().chain(&self.absent);
        both.map(|(&q, why)| (q, why.clone())).collect()
    }
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
/// positions and displacements; a quantity with a cell that is not a finite number is refused
/// alone ([`Results::refused`]). Messages locate a fault (line, column) without
/// repeating the file's text, except a number that differs from the path's.
pub fn read(file: &Path, steps: &[Step]) -> Result<Results, ResultsError> {
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
pub fn read_from(input: impl std::io::Read, file: &Path, steps: &[Step]) -> Result<Results, ResultsError> {
    let unreadable = |source| ResultsError::Unreadable {
        file: file.to_path_buf(),
        source,
    };
    let (input, lines) = csv_lines::counted(input);
    let mut reader = csv::ReaderBuilder::new().flexible(true).from_reader(input);
    let header = reader.headers().map_err(unreadable)?.clone();
    let quantities = quantity_columns(file, &header)?;
    let scale = steps
        .iter()
        .flat_map(|s| [s.delta_n.abs(), s.delta_t.abs()])
        .fold(0.0, f64::max);
    let mut rows = Vec::with_capacity(steps.len());
    let mut refused: BTreeMap<Quantity, String> = BTreeMap::new();
    for record in reader.records() {
        let record = record.map_err(unreadable)?;
        let line = lines.of(record.position());
        let Some(step) = steps.get(rows.len()) else {
            return Err(ResultsError::RowCount {
                file: file.to_path_buf(),
                rows: rows.len() + 1,
                steps: steps.len(),
            });
        };
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
        let (row, bad) = cells.row(step, &quantities, PATH_MATCH * scale)?;
        for (quantity, e) in bad {
            refused.entry(quantity).or_insert_with(|| {
                format!("{e} (the column is left out; the file's other columns are read)")
            });
        }
        rows.push(row);
    }
    if rows.len() != steps.len() {
        return Err(ResultsError::RowCount {
            file: file.to_path_buf(),
            rows: rows.len(),
            steps: steps.len(),
        });
    }
    for row in &mut rows {
        for &quantity in refused.keys() {
            set(row, quantity, None);
        }
    }
    let shown: Vec<&str> = header.iter().map(str::trim).collect();
    let absent = Quantity::ALL
        .into_iter()
        .filter(|q| !quantities.contains(q))
        .map(|q| {
            let why = format!(
                "{}: no column `{q}` in the header (columns: {})",
                file.display(),
                shown.join(", ")
            );
            (q, why)
        });
    Ok(Results {
        steps: rows,
        refused,
        absent: absent.collect(),
    })
}

/// The quantity of each column after the path columns. A column that is not a quantity's is
/// named by its position, and by its text only when it is a misspelling of a quantity's name
/// (within [`nearest`]'s few edits of it: never a line of the file's data).
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
        let quantity = Quantity::from_name(name).ok_or_else(|| {
            let printable = name.chars().all(|c| c.is_ascii_graphic());
            match nearest(name, Quantity::ALL.map(Quantity::name)) {
                Some(meant) if printable => bad(format!(
                    "column {} `{name}` is not a known column; did you mean `{meant}`?",
                    k + 1
                )),
                _ => bad(format!("column {} is not a known column", k + 1)),
            }
        })?;
        if quantities.contains(&quantity) {
            return Err(bad(format!("column {} repeats `{quantity}`", k + 1)));
        }
        quantities.push(quantity);
    }
    Ok(quantities)
}

/// Sets `quantity` of `row` to `value` (a step quantity: a column).
fn set(row: &mut StepResult, quantity: Quantity, value: Option<f64>) {
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

    /// The row for path step `step`, its path columns checked against it; with each quantity
    /// whose cell is not a number, and why (that quantity is left out of the row).
    fn row(
        &self,
        step: &Step,
        quantities: &[Quantity],
        tolerance: f64,
    ) -> Result<(StepResult, Vec<(Quantity, ResultsError)>), ResultsError> {
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
        let mut bad = Vec::new();
        for (k, &quantity) in quantities.iter().enumerate() {
            match self.number(PATH_COLUMNS.len() + k, quantity.name()) {
                Ok(value) => set(&mut row, quantity, value),
                Err(e) => bad.push((quantity, e)),
            }
        }
        Ok((row, bad))
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

    /// The CSV of `steps` with a normal force P = 1 N per µm of δn and Q = P/10.
    fn text(steps: &[Step], unit: f64) -> String {
        let mut text = "step,position,delta_n,delta_t,normal_force,tangential_force\n".to_owned();
        for s in steps {
            let position = s.position.map_or_else(String::new, |p| p.to_string());
            text.push_str(&format!(
                "{},{position},{:e},{:e},{:e},{:e}\n",
                s.index,
                s.delta_n * unit,
                s.delta_t * unit,
                s.delta_n * 1e6,
                s.delta_n * 1e6 / 10.0
            ));
        }
        text
    }

    fn read_text(text: &str, steps: &[Step]) -> Result<Results, ResultsError> {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("h.csv");
        std::fs::write(&file, text).unwrap();
        read(&file, steps)
    }

    /// Requirement: the rows read back; a quantity without a column is none, and why is named:
    /// the file, the column and the header's columns.
    #[test]
    fn a_valid_file_reads_back_with_absent_quantities_as_none() {
        let steps = steps();
        let read = read_text(&text(&steps, 1.0), &steps).unwrap();
        let rows = &read.steps;
        assert_eq!(rows.len(), steps.len());
        assert_eq!(rows[4].normal_force, Some(10.0));
        assert_eq!(rows[4].tangential_force, Some(1.0));
        assert_eq!(rows[4].position, Some(1));
        assert_eq!(rows[4].contact_radius, None);
        assert!(read.refused.is_empty());
        let why = &read.absent[&Quantity::ContactRadius];
        assert!(
            why.ends_with(
                "h.csv: no column `contact_radius` in the header (columns: step, position, delta_n, \
                 delta_t, normal_force, tangential_force)"
            ),
            "{why}"
        );
        assert!(!read.unread().contains_key(&Quantity::NormalForce));
    }

    /// Requirement: a cell of one quantity that is not a number leaves out that quantity only,
    /// named by the file's own line (1-based, CRLF ends and a blank line counted) and column;
    /// the other quantities are read.
    #[test]
    fn a_bad_cell_leaves_out_its_column_only_and_names_its_line() {
        let steps = steps();
        let good = text(&steps, 1.0);
        let mut lines: Vec<String> = good.lines().map(str::to_owned).collect();
        // Step 6 is on line 8 (header, steps 0-5, then it); a blank line before it makes it 9.
        lines[7] = lines[7].rsplit_once(',').unwrap().0.to_owned() + ",nan";
        lines.insert(3, String::new());
        for end in ["\n", "\r\n"] {
            let read = read_text(&(lines.join(end) + end), &steps).unwrap();
            assert_eq!(read.refused.len(), 1);
            assert!(read.steps.iter().all(|r| r.tangential_force.is_none()));
            assert_eq!(read.steps[6].normal_force, Some(steps[6].delta_n * 1e6));
            let why = &read.refused[&Quantity::TangentialForce];
            assert!(
                why.contains("h.csv:9: column `tangential_force`: not finite")
                    && why.contains("the column is left out"),
                "{why}"
            );
            assert!(!read.unread().contains_key(&Quantity::NormalForce), "{read:?}");
        }
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

    /// Requirement: each fault of the file's form or path is named by its line (the header is
    /// line 1; step k is on line k + 2) and column; a misspelt column by its name and the name
    /// meant, any other by its position only.
    #[test]
    fn faults_are_located() {
        let steps = steps();
        let good = text(&steps, 1.0);
        let lines: Vec<&str> = good.lines().collect();
        let cases = [
            (lines[..5].join("\n"), "4 rows for a path of 9 steps"),
            (
                good.replace("normal_force", "force"),
                "h.csv:1: header: column 5 is not a known column (allowed: ",
            ),
            (
                good.replace("tangential_force", "tangental_force"),
                "h.csv:1: header: column 6 `tangental_force` is not a known column; did you mean \
                 `tangential_force`? (allowed: step,position,delta_n,delta_t first, then any of \
                 normal_force, tangential_force, contact_radius, peak_pressure, stick_radius)",
            ),
            (
                good.replacen(",1e0\n", ",1e0,3\n", 1),
                "h.csv:6: 7 cells in a row",
            ),
            (good.replacen("\n1,,", "\n1,x,", 1), "h.csv:3: column `position`"),
            (good.replacen("4,1,", "4,,", 1), "h.csv:6: column `position`"),
            (
                good.replacen("\n2,", "\n3,", 1),
                "h.csv:4: column `step`: not the path's step 2",
            ),
            (
                format!("{good}9,,0,0,0,0\n"),
                "h.csv: 10 rows for a path of 9 steps",
            ),
        ];
        for (text, expected) in cases {
            for text in [text.clone(), text.replace('\n', "\r\n")] {
                let e = read_text(&text, &steps).unwrap_err().to_string();
                assert!(e.contains(expected), "{expected}: {e}");
            }
        }
    }
}
