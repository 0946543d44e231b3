//! Reading back what a deck wrote: its per-step CSV (`steps.csv`, one row per computed step), its
//! clock (`timing.csv`), and the surface pressure p(r) of its field files, extracted through meshio
//! by `scripts/read_fields.py` run as a subprocess (the contact line's nodal state, `surface.csv`,
//! is read by [`super::surface`]). Missing, truncated or non-finite output is an error with a
//! message that names the file, the row and the column, never a panic.
//!
//! Units: the decks work in mm, N, MPa; the rows here are converted to SI.

use std::path::{Path, PathBuf};
use std::time::Duration;

use super::deck::ComputedStep;
use super::process::{self, Job};
use super::toolchain::Toolchain;

/// The glue script, compiled in and written beside the field files when needed.
pub const READ_FIELDS_PY: &str = include_str!("../../scripts/read_fields.py");

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
    let records = records(text, "steps.csv", &STEP_COLUMNS)?;
    let mut rows = Vec::new();
    for (k, record) in records.iter().enumerate() {
        let row = parse_row(record).map_err(|e| format!("steps.csv row {}: {e}", k + 1))?;
        let Some(asked) = expected.get(k) else {
            return Err(format!(
                "steps.csv row {}: more rows than the {} steps asked for",
                k + 1,
                expected.len()
            ));
        };
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-12);
        if row.step != asked.step || !close(row.d, asked.d) || !close(row.t, asked.t) {
            return Err(format!(
                "steps.csv row {}: step {} at d = {:e} m, t = {:e} m; expected step {} at d = {:e} m, t = {:e} m",
                k + 1,
                row.step,
                row.d,
                row.t,
                asked.step,
                asked.d,
                asked.t
            ));
        }
        rows.push(row);
    }
    if rows.len() != expected.len() {
        return Err(format!(
            "steps.csv has {} rows, expected {} (truncated output: the deck stopped early)",
            rows.len(),
            expected.len()
        ));
    }
    Ok(rows)
}

/// The records of a deck's CSV `file` (text `text`), whose header must be `columns`: every
/// record well-formed and with one field per column, else an error naming the row.
pub fn records(text: &str, file: &str, columns: &[&str]) -> Result<Vec<csv::StringRecord>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header = reader.headers().map_err(|e| format!("{file}: {e}"))?;
    if header.iter().ne(columns.iter().copied()) {
        return Err(format!(
            "{file}: header is `{}`, expected `{}`",
            header.iter().collect::<Vec<_>>().join(","),
            columns.join(",")
        ));
    }
    reader
        .records()
        .enumerate()
        .map(|(k, record)| {
            let record = record.map_err(|e| format!("{file} row {}: {e}", k + 1))?;
            if record.len() != columns.len() {
                return Err(format!(
                    "{file} row {}: {} fields, expected {} (truncated line?)",
                    k + 1,
                    record.len(),
                    columns.len()
                ));
            }
            Ok(record)
        })
        .collect()
}

/// Field `i` of `record` (columns `columns`) as a finite number, times `scale`.
pub fn finite(record: &csv::StringRecord, columns: &[&str], i: usize, scale: f64) -> Result<f64, String> {
    match record[i].parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v * scale),
        _ => Err(format!(
            "{} = `{}` is not a finite number",
            columns[i], &record[i]
        )),
    }
}

fn parse_row(record: &csv::StringRecord) -> Result<DeckRow, String> {
    let number = |i: usize, scale: f64| finite(record, &STEP_COLUMNS, i, scale);
    let count = |i: usize| -> Result<u32, String> {
        record[i]
            .parse()
            .map_err(|_| format!("{} = `{}` is not a count", STEP_COLUMNS[i], &record[i]))
    };
    let outcome = match &record[8] {
        "1" => Outcome::Converged,
        "2" => Outcome::Cycle,
        "0" => Outcome::Capped,
        other => return Err(format!("outcome = `{other}` is not 0, 1 or 2")),
    };
    Ok(DeckRow {
        step: record[0]
            .parse()
            .map_err(|_| format!("step = `{}` is not a step index", &record[0]))?,
        d: number(1, 1e-3)?,
        t: number(2, 1e-3)?,
        force_contact: number(3, 1.0)?,
        force_reaction: if record[4].is_empty() {
            None
        } else {
            Some(number(4, 1.0)?)
        },
        tangential_force: number(5, 1.0)?,
        iterations_normal: count(6)?,
        iterations_tangential: count(7)?,
        outcome,
        field_file: match &record[9] {
            "-" => None,
            name if is_plain_name(name) => Some(name.to_owned()),
            name => {
                return Err(format!(
                    "field_file = `{name}` is not a file name (allowed: a name in the run folder, or -)"
                ))
            }
        },
    })
}

/// Whether `name` names a file in its folder itself: one normal component (no folder, no `..`,
/// not absolute).
fn is_plain_name(name: &str) -> bool {
    let mut components = Path::new(name).components();
    matches!(
        (components.next(), components.next()),
        (Some(std::path::Component::Normal(_)), None)
    )
}

/// Reads the file `name` of the run directory `dir` ("output missing" when absent).
pub fn read_output(dir: &Path, name: &str) -> Result<String, String> {
    let file = dir.join(name);
    std::fs::read_to_string(&file).map_err(|e| format!("{}: output missing ({e})", file.display()))
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

/// One point of the spherical surface in a field file, SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Radius r [m].
    pub r: f64,
    /// Contact pressure [Pa].
    pub pressure: f64,
    /// Height of the deformed surface above the contact plane, z + u_z [m] (negative inside the
    /// contact by the penalty's penetration p/k).
    pub gap: f64,
}

/// The surface of one field file, sorted by r.
pub type Profile = Vec<SurfacePoint>;

/// Extracts p(r) on the spherical surface (radius `radius_mm`, r ≤ `window_mm`) from each field
/// file in `dir`, through meshio (`scripts/read_fields.py` run by the toolchain's Python). The
/// script, its output and its logs live in a private temporary folder: nothing is written into
/// `dir` (a run folder read back by `deck read` stays as the deck left it).
pub fn read_profiles(
    dir: &Path,
    files: &[String],
    radius_mm: f64,
    window_mm: f64,
    toolchain: &Toolchain,
    timeout: Duration,
) -> Result<Vec<Profile>, String> {
    let work = tempfile::Builder::new()
        .prefix("spherecontact-meshio-")
        .tempdir()
        .map_err(|e| format!("meshio: no temporary folder: {e}"))?;
    let script = work.path().join("read_fields.py");
    std::fs::write(&script, READ_FIELDS_PY).map_err(|e| format!("{}: {e}", script.display()))?;
    let out: PathBuf = work.path().join("profiles.csv");
    let dir = std::path::absolute(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let paths: Vec<String> = files.iter().map(|f| dir.join(f).display().to_string()).collect();
    let mut args = vec![
        script.display().to_string(),
        "--radius".into(),
        radius_mm.to_string(),
        "--window".into(),
        window_mm.to_string(),
        "--out".into(),
        out.display().to_string(),
    ];
    args.extend(paths.iter().cloned());
    let job = Job {
        program: toolchain.python.clone(),
        args,
        env: vec![],
        timeout,
    };
    let run = process::run(&job, work.path(), "read_fields").map_err(|e| format!("meshio: {e}"))?;
    if let Some(failure) = run
        .ending
        .failure("python (meshio)", timeout, |_| "reading the field files failed")
    {
        return Err(format!("{failure}; {}", run.tail(4)));
    }
    let text =
        std::fs::read_to_string(&out).map_err(|e| format!("{}: output missing ({e})", out.display()))?;
    parse_profiles(&text, &paths)
}

/// Splits `read_fields.py`'s CSV (file, r [mm], p [MPa], gap [mm]) into one SI profile per file.
pub fn parse_profiles(text: &str, files: &[String]) -> Result<Vec<Profile>, String> {
    let mut profiles = vec![Profile::new(); files.len()];
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    for (k, record) in reader.records().enumerate() {
        let record = record.map_err(|e| format!("profiles.csv row {}: {e}", k + 1))?;
        let values: Option<Vec<f64>> = (record.len() == 4)
            .then(|| (1..4).map(|i| record[i].parse::<f64>().ok()).collect())
            .flatten()
            .filter(|v: &Vec<f64>| v.iter().all(|x| x.is_finite()));
        let Some(v) = values else {
            return Err(format!(
                "profiles.csv row {}: not a finite (r, p, gap) triple",
                k + 1
            ));
        };
        let Some(i) = files.iter().position(|f| f == &record[0]) else {
            return Err(format!(
                "profiles.csv row {}: unknown file `{}`",
                k + 1,
                &record[0]
            ));
        };
        profiles[i].push(SurfacePoint {
            r: v[0] * 1e-3,
            pressure: v[1] * 1e6,
            gap: v[2] * 1e-3,
        });
    }
    if let Some(i) = profiles.iter().position(Vec::is_empty) {
        return Err(format!("no surface pressure read from {}", files[i]));
    }
    Ok(profiles)
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
        assert!(e.contains("row 2"), "{e}");
        let one_row: String = text.lines().take(2).collect::<Vec<_>>().join("\n");
        let e = parse_steps(&one_row, &asked()).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
    }

    #[test]
    fn nan_wrong_step_and_bad_outcome_are_errors() {
        let text = two_rows().replace("806.56,,", "nan,,");
        let e = parse_steps(&text, &asked()).unwrap_err();
        assert!(e.contains("P_contact_N") && e.contains("finite"), "{e}");
        let mut other = asked();
        other[1].t = 6e-7;
        let e = parse_steps(&two_rows(), &other).unwrap_err();
        assert!(e.contains("expected step 5"), "{e}");
        let e = parse_steps(&two_rows().replace(",2,field", ",7,field"), &asked()).unwrap_err();
        assert!(e.contains("outcome"), "{e}");
        let e = parse_steps("a,b\n1,2\n", &asked()).unwrap_err();
        assert!(e.contains("header"), "{e}");
        let e = parse_steps(&two_rows(), &asked()[..1]).unwrap_err();
        assert!(e.contains("more rows"), "{e}");
        for name in ["../x.vtu", "/etc/passwd", "a/b.vtu"] {
            let e = parse_steps(&two_rows().replace("field_2.vtu", name), &asked()).unwrap_err();
            assert!(e.contains("field_file") && e.contains("not a file name"), "{e}");
        }
    }

    #[test]
    fn missing_output_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_output(dir.path(), "steps.csv").unwrap_err();
        assert!(e.contains("output missing"), "{e}");
    }

    #[test]
    fn timing_is_read_where_present() {
        assert_eq!(
            parse_timing("phase,seconds\nsetup,12.5\npath,3\n"),
            (Some(12.5), Some(3.0))
        );
        assert_eq!(parse_timing("phase,seconds\nsetup,nan\n"), (None, None));
    }

    #[test]
    fn profiles_split_by_file_and_reject_nan() {
        let files = vec!["a.vtu".to_string(), "b.vtu".to_string()];
        let text =
            "file,r,pressure,gap\na.vtu,0.0,450.0,-1e-8\nb.vtu,0.0,550.0,-1e-8\nb.vtu,0.5,300.0,-1e-8\n";
        let p = parse_profiles(text, &files).unwrap();
        assert_eq!(p[0].len(), 1);
        assert_eq!(p[0][0].pressure, 450e6);
        assert_eq!(p[1].len(), 2);
        assert!(parse_profiles("file,r,pressure,gap\na.vtu,0.0,nan,0\n", &files).is_err());
        let e = parse_profiles("file,r,pressure,gap\na.vtu,0.0,1.0,0\n", &files).unwrap_err();
        assert!(e.contains("b.vtu"), "{e}");
    }
}
