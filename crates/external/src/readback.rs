//! Reading back what a deck wrote: its per-step CSV (`steps.csv`, one row per computed step) and
//! its clock (`timing.csv`); the CSV reading the other tables share ([`records`], [`Row`]);
//! [`read_output`], the one way every deck's result file is opened (the contact line's nodal
//! state, `surface.csv`, is read by [`super::surface`]; the field files by
//! [`super::field_files`]); and [`check_path_file`], that a folder read back was written for the
//! steps asked.
//!
//! A deck's folder is foreign input (docs/security.md, "Deck folders"): it comes back from a
//! cluster or a colleague, so each file is read by the rule of files from elsewhere
//! ([`spherecontact_system::input::foreign`]): a regular file in the folder (a link only to a file inside it), of
//! at most its limit (`spherecontact_model::limits`), and a fault is named by file, line and column with the
//! form allowed, never by the file's text. Missing, truncated or non-finite output is such an
//! error, never a panic. A deck's own run reads its private temporary folder by the same rule.
//!
//! Units: the decks work in mm, N, MPa; the rows here are converted to SI.

use std::fmt::Display;
use std::path::Path;

use super::csv_lines;
use super::deck::{path_file, ComputedStep, PATH_FILE};
use spherecontact_model::solver::SolveError;
use spherecontact_system::input::foreign;

/// The columns a deck's `steps.csv` has, in order.
pub const STEP_COLUMNS: [&str; 10] = [
    "step",
    "d_mm",
    "t_mm",
    "P_contact_N",
    "P_top_N",
    "Q_N",
    "iterations_normal",
    "iterations_tangential",
    "outcome",
    "field_file",
];

/// How a deck's contact iteration ended at one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Converged: the residual at round-off, or the contact state repeated after a full step.
    Converged,
    /// The tangential iteration cycled between two contact states (a node at the stick edge
    /// has no consistent state); the iterate with the least residual was kept.
    Cycle,
    /// The iteration cap was hit: the step is flagged.
    Capped,
}

/// One row of a deck's `steps.csv`, in SI.
#[derive(Clone, Debug, PartialEq)]
pub struct DeckRow {
    /// The path step.
    pub step: usize,
    /// The approach of the modelled sphere d = δn/2 [m].
    pub d: f64,
    /// The shift of the modelled sphere's far face t = δt/2 [m].
    pub t: f64,
    /// Normal force from the contact forces [N].
    pub force_contact: f64,
    /// Normal force from the reaction on the loaded face [N] (at path positions only).
    pub force_reaction: Option<f64>,
    /// Tangential force along δt [N] (0 when the tangential mode is not solved).
    pub tangential_force: f64,
    /// Contact iterations of the normal mode (0: the approach did not change).
    pub iterations_normal: u32,
    /// Contact iterations of the tangential mode.
    pub iterations_tangential: u32,
    /// How the iterations ended.
    pub outcome: Outcome,
    /// The field file written at this step (path positions), if any.
    pub field_file: Option<String>,
}

/// Reads `steps.csv` from `text`, expecting the computed steps `expected` in order.
///
/// Fails on a wrong header, fewer or more rows than expected (a truncated run), a step or
/// displacement that is not the one asked for, or a value that is not a finite number.
pub fn parse_steps(text: &str, expected: &[ComputedStep]) -> Result<Vec<DeckRow>, String> {
    let rows = records(text, "steps.csv", &STEP_COLUMNS)?;
    if let Some(extra) = rows.get(expected.len()) {
        return Err(extra.error(format!(
            "a row past the {} computed steps of {PATH_FILE} (allowed: one row per computed step)",
            expected.len()
        )));
    }
    if rows.len() < expected.len() {
        return Err(format!(
            "steps.csv has {} rows, expected {} (truncated output: the deck stopped early)",
            rows.len(),
            expected.len()
        ));
    }
    rows.iter()
        .zip(expected)
        .map(|(row, asked)| parse_row(row, asked))
        .collect()
}

/// The records of a deck's CSV `file` (text `text`), whose header must be `columns`: every
/// record well-formed and with one cell per column, else an error naming the line.
pub fn records<'a>(text: &str, file: &'a str, columns: &'a [&'a str]) -> Result<Vec<Row<'a>>, String> {
    let (input, lines) = csv_lines::counted(text.as_bytes());
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(input);
    let not_csv =
        |line: u64| format!("{file}:{line}: not a CSV record (allowed: comma-separated UTF-8 text)");
    check_header(reader.headers().map_err(|_| not_csv(1))?, file, columns)?;
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| not_csv(lines.of(e.position())))?;
        let row = Row {
            file,
            columns,
            line: lines.of(record.position()),
            record,
        };
        if row.record.len() != columns.len() {
            return Err(row.error(format!(
                "{} cells in a row under a header of {} columns (a truncated line?)",
                row.record.len(),
                columns.len()
            )));
        }
        rows.push(row);
    }
    Ok(rows)
}

/// Checks that `header` is `columns`: the first column that is not, by its position, with the
/// header expected (never the header's own text).
fn check_header(header: &csv::StringRecord, file: &str, columns: &[&str]) -> Result<(), String> {
    let problem = match header
        .iter()
        .zip(columns)
        .position(|(found, name)| found != *name)
    {
        Some(k) => format!("column {} is not `{}`", k + 1, columns[k]),
        None if header.len() != columns.len() => {
            format!("{} columns where {} belong", header.len(), columns.len())
        }
        None => return Ok(()),
    };
    Err(format!(
        "{file}:1: header: {problem} (allowed: the header `{}`)",
        columns.join(",")
    ))
}

/// One record of a deck's CSV with where it lies: its cells read as the column allows, a
/// fault named by file, line and column, never by the cell's text.
pub struct Row<'a> {
    file: &'a str,
    columns: &'a [&'a str],
    line: u64,
    record: csv::StringRecord,
}

impl Row<'_> {
    /// `FILE:LINE: what`.
    pub fn error(&self, what: impl Display) -> String {
        format!("{}:{}: {what}", self.file, self.line)
    }

    /// `FILE:LINE: column `NAME`: why` of cell `i`.
    pub fn cell_error(&self, i: usize, why: impl Display) -> String {
        self.error(format!("column `{}`: {why}", self.columns[i]))
    }

    /// Cell `i`'s text.
    pub fn text(&self, i: usize) -> &str {
        &self.record[i]
    }

    /// Cell `i` as a finite number, times `scale`.
    pub fn finite(&self, i: usize, scale: f64) -> Result<f64, String> {
        match self.text(i).parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v * scale),
            _ => Err(self.cell_error(
                i,
                "not a finite number (allowed: a finite number in the column's unit)",
            )),
        }
    }

    /// Cell `i` as a whole number (`what` it is, for the message).
    pub fn whole<T: std::str::FromStr>(&self, i: usize, what: &str) -> Result<T, String> {
        self.text(i)
            .parse()
            .map_err(|_| self.cell_error(i, format!("not {what} (allowed: a whole number from 0)")))
    }

    /// Cell `i` as the value of one of `choices` (its text, its value).
    pub fn choice<T: Copy>(&self, i: usize, choices: &[(&str, T)]) -> Result<T, String> {
        choices
            .iter()
            .find(|(text, _)| *text == self.text(i))
            .map(|&(_, value)| value)
            .ok_or_else(|| {
                let names: Vec<&str> = choices.iter().map(|(text, _)| *text).collect();
                self.cell_error(i, format!("not an allowed value (allowed: {})", names.join(", ")))
            })
    }
}

/// The row of computed step `asked`, in SI, checked against it (step index, d and t within 1e-9).
fn parse_row(row: &Row, asked: &ComputedStep) -> Result<DeckRow, String> {
    let number = |i: usize, scale: f64| row.finite(i, scale);
    let step = row.whole(0, "a step index")?;
    if step != asked.step {
        return Err(row.cell_error(
            0,
            format!(
                "not the computed step (allowed: {}, the next step of {PATH_FILE})",
                asked.step
            ),
        ));
    }
    let (d, t) = (number(1, 1e-3)?, number(2, 1e-3)?);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-12);
    for (i, found, value) in [(1, d, asked.d), (2, t, asked.t)] {
        if !close(found, value) {
            return Err(row.cell_error(
                i,
                format!(
                    "not the step's (allowed: {:e}, from {PATH_FILE}, within 1e-9)",
                    value * 1e3
                ),
            ));
        }
    }
    Ok(DeckRow {
        step,
        d,
        t,
        force_contact: number(3, 1.0)?,
        force_reaction: if row.text(4).is_empty() {
            None
        } else {
            Some(number(4, 1.0)?)
        },
        tangential_force: number(5, 1.0)?,
        iterations_normal: row.whole(6, "a count")?,
        iterations_tangential: row.whole(7, "a count")?,
        outcome: row.choice(
            8,
            &[
                ("0", Outcome::Capped),
                ("1", Outcome::Converged),
                ("2", Outcome::Cycle),
            ],
        )?,
        field_file: match row.text(9) {
            "-" => None,
            name if is_field_file_name(name) => Some(name.to_owned()),
            _ => {
                return Err(row.cell_error(
                    9,
                    "not a field file's name (allowed: `-`, or the name of a .vtu or .xdmf file in \
                     the deck's folder)",
                ))
            }
        },
    })
}

/// Whether `name` names a field file in its folder itself: one normal component (no folder, no
/// `..`, not absolute) ending `.vtu` or `.xdmf`, the files `scripts/read_fields.py` reads.
pub fn is_field_file_name(name: &str) -> bool {
    is_plain_name(name) && (name.ends_with(".vtu") || name.ends_with(".xdmf"))
}

/// Whether `name` names a file in its folder itself: one normal component (no folder, no `..`,
/// not absolute).
pub fn is_plain_name(name: &str) -> bool {
    let mut components = Path::new(name).components();
    matches!(
        (components.next(), components.next()),
        (Some(std::path::Component::Normal(_)), None)
    )
}

/// The text of the result file `name` of the run directory `dir`, a file from elsewhere of at
/// most `limit` bytes ([`foreign::read_text`]); "output missing" when it is absent.
pub fn read_output(dir: &Path, name: &str, limit: u64) -> Result<String, String> {
    let file = dir.join(name);
    present(&file)?;
    foreign::read_text(&file, limit).map_err(|e| e.to_string())
}

/// [`read_output`] of a file a deck may leave out: `None` when it is absent; a file there that
/// cannot be read (a FIFO, a link out of the folder, too large) is an error.
pub fn read_optional_output(dir: &Path, name: &str, limit: u64) -> Result<Option<String>, String> {
    if is_absent(&dir.join(name)) {
        Ok(None)
    } else {
        read_output(dir, name, limit).map(Some)
    }
}

/// Checks that the run directory `dir` was written for `steps` (of scene `scene`): its
/// [`PATH_FILE`] lists them, as a deck run elsewhere is read back. The file may be no longer
/// than the list expected.
pub fn check_path_file(dir: &Path, steps: &[ComputedStep], scene: &str) -> Result<(), SolveError> {
    let expected = path_file(steps);
    let listed = read_output(dir, PATH_FILE, expected.len() as u64).map_err(SolveError::Failed)?;
    if listed != expected {
        return Err(SolveError::Failed(format!(
            "{}: the steps it lists are not those of scene `{scene}`",
            dir.join(PATH_FILE).display()
        )));
    }
    Ok(())
}

/// `Ok` when something (a file, a link, a FIFO) is at the result file `file`, else its "output
/// missing" error.
pub fn present(file: &Path) -> Result<(), String> {
    match is_absent(file) {
        true => Err(format!(
            "{}: output missing (the deck writes it when it runs)",
            file.display()
        )),
        false => Ok(()),
    }
}

/// Whether nothing, not even a dangling link, is at `file`.
fn is_absent(file: &Path) -> bool {
    matches!(std::fs::symlink_metadata(file), Err(e) if e.kind() == std::io::ErrorKind::NotFound)
}

/// The deck's own clock of its set-up (assembly, factorisation, condensation) and of the path
/// [s] from `timing.csv`; `None` where a value is missing (timings are reported, never judged).
pub fn parse_timing(text: &str) -> (Option<f64>, Option<f64>) {
    let value = |phase: &str| {
        text.lines()
            .filter_map(|l| l.split_once(','))
            .find(|(p, _)| p.trim() == phase)
            .and_then(|(_, v)| v.trim().parse::<f64>().ok())
            .filter(|v| v.is_finite())
    };
    (value("setup"), value("path"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str =
        "step,d_mm,t_mm,P_contact_N,P_top_N,Q_N,iterations_normal,iterations_tangential,outcome,field_file";

    fn asked() -> Vec<ComputedStep> {
        vec![
            ComputedStep {
                step: 4,
                d: 8.5e-6,
                t: 0.0,
                position: None,
            },
            ComputedStep {
                step: 5,
                d: 8.5e-6,
                t: 5e-7,
                position: Some(2),
            },
        ]
    }

    fn two_rows() -> String {
        format!(
            "{HEADER}\n4,0.0085,0,806.56,,0,3,2,1,-\n\
             5,0.0085,0.0005,806.56,806.77,98.8,0,4,2,field_2.vtu\n"
        )
    }

    #[test]
    fn rows_are_read_and_converted_to_si() {
        let rows = parse_steps(&two_rows(), &asked()).unwrap();
        assert_eq!(rows.len(), 2);
        assert!((rows[1].t - 5e-7).abs() < 1e-18);
        assert_eq!(rows[0].force_reaction, None);
        assert_eq!(rows[1].force_reaction, Some(806.77));
        assert_eq!(rows[1].tangential_force, 98.8);
        assert_eq!((rows[0].iterations_normal, rows[1].iterations_tangential), (3, 4));
        assert_eq!(
            (rows[0].outcome, rows[1].outcome),
            (Outcome::Converged, Outcome::Cycle)
        );
        assert_eq!(rows[0].field_file, None);
        assert_eq!(rows[1].field_file.as_deref(), Some("field_2.vtu"));
    }

    #[test]
    fn truncated_output_is_an_error() {
        let text = two_rows();
        let cut = &text[..text.len() - 30];
        let e = parse_steps(cut, &asked()).unwrap_err();
        assert!(
            e.starts_with("steps.csv:3: ") && e.contains("truncated line"),
            "{e}"
        );
        let one_row: String = text.lines().take(2).collect::<Vec<_>>().join("\n");
        let e = parse_steps(&one_row, &asked()).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
    }

    /// Requirement: a bad cell, header or row is named by line and column with the form allowed,
    /// and its text is never quoted.
    #[test]
    fn faults_are_located_and_never_quoted() {
        let cases = [
            (
                two_rows().replace("806.56,,", "SECRET,,"),
                "steps.csv:2: column `P_contact_N`: not a finite number",
            ),
            (
                two_rows().replace("806.56,,", "nan,,"),
                "steps.csv:2: column `P_contact_N`: not a finite number",
            ),
            (
                two_rows().replace(",2,field", ",SECRET,field"),
                "steps.csv:3: column `outcome`: not an allowed value (allowed: 0, 1, 2)",
            ),
            (
                two_rows().replace("\n4,", "\nSECRET,"),
                "steps.csv:2: column `step`: not a step index",
            ),
            (
                two_rows().replace(",3,2,1,", ",SECRET,2,1,"),
                "steps.csv:2: column `iterations_normal`: not a count",
            ),
            (
                two_rows().replace("\n5,", "\n6,"),
                "steps.csv:3: column `step`: not the computed step (allowed: 5",
            ),
            (
                two_rows().replace("0.0005", "0.0006"),
                "steps.csv:3: column `t_mm`: not the step's (allowed: ",
            ),
            (
                "a,SECRET\n1,2\n".to_owned(),
                "steps.csv:1: header: column 1 is not `step`",
            ),
            (
                format!("{HEADER},SECRET\n"),
                "steps.csv:1: header: 11 columns where 10 belong",
            ),
        ];
        for (text, expected) in cases {
            // The same lines in a file of CRLF line ends (Python's csv writes them).
            for text in [text.clone(), text.replace('\n', "\r\n")] {
                let e = parse_steps(&text, &asked()).unwrap_err();
                assert!(e.starts_with(expected), "{e}");
                assert!(
                    !e.contains("SECRET") && !e.contains("nan") && !e.contains("0.0006"),
                    "{e}"
                );
            }
        }
        let e = parse_steps("a,b\n", &asked()).unwrap_err();
        assert!(e.contains(&format!("(allowed: the header `{HEADER}`)")), "{e}");
        let e = parse_steps(&two_rows(), &asked()[..1]).unwrap_err();
        assert!(
            e.starts_with("steps.csv:3: a row past the 1 computed steps"),
            "{e}"
        );
        for name in ["../x.vtu", "/etc/passwd", "a/b.vtu", "field.csv", "SECRET"] {
            let e = parse_steps(&two_rows().replace("field_2.vtu", name), &asked()).unwrap_err();
            assert!(e.contains("column `field_file`: not a field file's name"), "{e}");
            assert!(!e.contains(name), "{e}");
        }
    }

    #[test]
    fn a_missing_output_is_named_and_a_fifo_refused_at_once() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_output(dir.path(), "steps.csv", 100).unwrap_err();
        assert!(e.contains("output missing"), "{e}");
        assert_eq!(read_optional_output(dir.path(), "timing.csv", 100), Ok(None));
        let fifo = dir.path().join("timing.csv");
        rustix::fs::mkfifoat(rustix::fs::CWD, &fifo, rustix::fs::Mode::from_raw_mode(0o600)).unwrap();
        let e = read_optional_output(dir.path(), "timing.csv", 100).unwrap_err();
        assert!(e.contains("a FIFO"), "{e}");
    }

    #[test]
    fn timing_is_read_where_present() {
        assert_eq!(
            parse_timing("phase,seconds\nsetup,12.5\npath,3\n"),
            (Some(12.5), Some(3.0))
        );
        assert_eq!(parse_timing("phase,seconds\nsetup,nan\n"), (None, None));
    }
}
