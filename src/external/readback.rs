//! Reading back what a deck wrote: its per-step CSV (`steps.csv`, one row per approach), and the
//! surface pressure p(r) of its field files, extracted through meshio by `scripts/read_fields.py`
//! run as a subprocess. Missing, truncated or non-finite output is an error with a message that
//! names the file, the row and the column, never a panic.
//!
//! Units: the decks work in mm, N, MPa; the rows here are converted to SI.

use std::path::{Path, PathBuf};
use std::time::Duration;

use super::process::{self, Job};
use super::toolchain::Toolchain;

/// The glue script, compiled in and written beside the field files when needed.
pub const READ_FIELDS_PY: &str = include_str!("../../scripts/read_fields.py");

/// The columns a deck's `steps.csv` has, in order.
pub const STEP_COLUMNS: [&str; 10] = [
    "index",
    "d_mm",
    "P_contact_N",
    "P_top_N",
    "p0_MPa",
    "p0_method",
    "contact_radius_mm",
    "iterations",
    "converged",
    "field_file",
];

/// One row of a deck's per-step CSV, in SI.
#[derive(Clone, Debug, PartialEq)]
pub struct DeckRow {
    /// The approach of the modelled sphere d = δn/2 [m].
    pub d: f64,
    /// Normal force from the contact traction [N].
    pub force_contact: f64,
    /// Normal force from the reaction on the loaded face [N].
    pub force_reaction: f64,
    /// Peak pressure [Pa].
    pub p0: f64,
    /// How the deck obtained p0.
    pub p0_method: String,
    /// Contact radius [m].
    pub contact_radius: f64,
    /// Contact iterations (active-set or Newton).
    pub iterations: u32,
    /// Whether the iteration met its tolerance.
    pub converged: bool,
    /// The field file the deck wrote for this row.
    pub field_file: String,
}

/// Reads `steps.csv` from `text`, expecting the approaches `d` [m] in order.
///
/// Fails on a wrong header, fewer or more rows than expected (a truncated run), an approach that
/// is not the one asked for, or a value that is not a finite number.
pub fn parse_steps(text: &str, d: &[f64]) -> Result<Vec<DeckRow>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header = reader.headers().map_err(|e| format!("steps.csv: {e}"))?;
    if header.iter().ne(STEP_COLUMNS) {
        return Err(format!(
            "steps.csv: header is `{}`, expected `{}`",
            header.iter().collect::<Vec<_>>().join(","),
            STEP_COLUMNS.join(",")
        ));
    }
    let mut rows = Vec::new();
    for (k, record) in reader.records().enumerate() {
        let record = record.map_err(|e| format!("steps.csv row {}: {e}", k + 1))?;
        let row = parse_row(&record).map_err(|e| format!("steps.csv row {}: {e}", k + 1))?;
        let expected = d.get(k).copied().unwrap_or(f64::NAN);
        if (row.d - expected).abs() > 1e-9 * expected.abs() {
            return Err(format!(
                "steps.csv row {}: approach {:e} m, expected {expected:e} m",
                k + 1,
                row.d
            ));
        }
        rows.push(row);
    }
    if rows.len() != d.len() {
        return Err(format!(
            "steps.csv has {} rows, expected {} (truncated output: the deck stopped early)",
            rows.len(),
            d.len()
        ));
    }
    Ok(rows)
}

fn parse_row(record: &csv::StringRecord) -> Result<DeckRow, String> {
    if record.len() != STEP_COLUMNS.len() {
        return Err(format!(
            "{} fields, expected {} (truncated line?)",
            record.len(),
            STEP_COLUMNS.len()
        ));
    }
    let number = |i: usize, scale: f64| -> Result<f64, String> {
        let text = &record[i];
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v * scale),
            _ => Err(format!("{} = `{text}` is not a finite number", STEP_COLUMNS[i])),
        }
    };
    let integer = |i: usize| -> Result<u32, String> {
        record[i]
            .parse()
            .map_err(|_| format!("{} = `{}` is not a count", STEP_COLUMNS[i], &record[i]))
    };
    Ok(DeckRow {
        d: number(1, 1e-3)?,
        force_contact: number(2, 1.0)?,
        force_reaction: number(3, 1.0)?,
        p0: number(4, 1e6)?,
        p0_method: record[5].to_owned(),
        contact_radius: number(6, 1e-3)?,
        iterations: integer(7)?,
        converged: integer(8)? == 1,
        field_file: record[9].to_owned(),
    })
}

/// Reads `dir/steps.csv` (see [`parse_steps`]).
pub fn read_steps(dir: &Path, d: &[f64]) -> Result<Vec<DeckRow>, String> {
    let file = dir.join("steps.csv");
    let text =
        std::fs::read_to_string(&file).map_err(|e| format!("{}: output missing ({e})", file.display()))?;
    parse_steps(&text, d)
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

/// Points up to this fraction of the contact radius beyond its edge enter the edge fit.
pub const EDGE_FIT_BAND: f64 = 0.2;

/// The contact radius from the gap just outside the contact.
///
/// At the edge of a smooth frictionless non-adhesive contact the pressure falls as √(c − r) and
/// the gap opens as g ≈ A (r − c)^{3/2} (Johnson 1985, §4.2 and eq. 3.42 for Hertz; the same
/// exponent holds for any smooth profile), so g^{2/3} is linear in r and vanishes at c. A least
/// squares line through g^{2/3} of the open surface points within [`EDGE_FIT_BAND`]·r of the last
/// point in contact gives c as its zero, kept within the band (the nodes just past the edge of a
/// discrete solution may be open by a mere 1e-7 of the gap further out). On Hertz's
/// exact gap this errs by ≤ 1.5e-4 c (unit test); on a finite element solution the edge itself
/// is resolved only to about an element, and the fit averages the nodes' scatter there. Taking
/// the last node in contact (or a linear zero crossing of g, which the penalty's tiny negative
/// gap pins to that node) errs by up to one node spacing.
///
/// `None` when no point is in contact or fewer than two open points lie in the band.
pub fn contact_radius(profile: &[SurfacePoint]) -> Option<f64> {
    // After the last point in contact: a P2 gap may wiggle above zero inside the contact.
    let last = profile.iter().rposition(|p| p.gap <= 0.0)?;
    let last_closed = profile[last].r;
    let band: Vec<(f64, f64)> = profile[last + 1..]
        .iter()
        .take_while(|p| p.r - last_closed <= EDGE_FIT_BAND * last_closed)
        .map(|p| (p.r, p.gap.powf(2.0 / 3.0)))
        .collect();
    let line = crate::fit::Line::fit(&band)?;
    let c = line.zero()?;
    (line.slope > 0.0 && c.is_finite()).then(|| c.clamp(last_closed, band[band.len() - 1].0))
}

/// Extracts p(r) on the spherical surface (radius `radius_mm`, r ≤ `window_mm`) from each field
/// file in `dir`, through meshio (`scripts/read_fields.py` run by the toolchain's Python).
pub fn read_profiles(
    dir: &Path,
    files: &[String],
    radius_mm: f64,
    window_mm: f64,
    toolchain: &Toolchain,
    timeout: Duration,
) -> Result<Vec<Profile>, String> {
    let script = dir.join("read_fields.py");
    std::fs::write(&script, READ_FIELDS_PY).map_err(|e| format!("{}: {e}", script.display()))?;
    let out: PathBuf = dir.join("profiles.csv");
    let mut args = vec![
        script.display().to_string(),
        "--radius".into(),
        radius_mm.to_string(),
        "--window".into(),
        window_mm.to_string(),
        "--out".into(),
        out.display().to_string(),
    ];
    args.extend(files.iter().cloned());
    let job = Job {
        program: toolchain.python.clone(),
        args,
        env: vec![],
        timeout,
    };
    let run = process::run(&job, dir, "read_fields").map_err(|e| format!("meshio: {e}"))?;
    if !run.succeeded() {
        return Err(format!(
            "reading the field files through meshio failed ({:?}): {}",
            run.ending,
            run.tail(4)
        ));
    }
    let text =
        std::fs::read_to_string(&out).map_err(|e| format!("{}: output missing ({e})", out.display()))?;
    parse_profiles(&text, files)
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
        "index,d_mm,P_contact_N,P_top_N,p0_MPa,p0_method,contact_radius_mm,iterations,converged,field_file";

    fn two_rows() -> String {
        format!(
            "{HEADER}\n0,0.0085,806.56,806.77,448.1,minus-szz-pole,0.919,2,1,field_0.vtu\n\
             1,0.0125,1439.7,1440.1,544.3,minus-szz-pole,1.118,1,1,field_1.vtu\n"
        )
    }

    #[test]
    fn rows_are_read_and_converted_to_si() {
        let rows = parse_steps(&two_rows(), &[8.5e-6, 12.5e-6]).unwrap();
        assert_eq!(rows.len(), 2);
        assert!((rows[0].p0 - 448.1e6).abs() < 1.0);
        assert!((rows[1].contact_radius - 1.118e-3).abs() < 1e-12);
        assert_eq!(rows[0].iterations, 2);
        assert!(rows[1].converged);
        assert_eq!(rows[1].field_file, "field_1.vtu");
    }

    #[test]
    fn truncated_output_is_an_error() {
        let text = two_rows();
        let cut = &text[..text.len() - 30];
        let e = parse_steps(cut, &[8.5e-6, 12.5e-6]).unwrap_err();
        assert!(e.contains("row 2"), "{e}");
        let one_row: String = text.lines().take(2).collect::<Vec<_>>().join("\n");
        let e = parse_steps(&one_row, &[8.5e-6, 12.5e-6]).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
    }

    #[test]
    fn nan_and_wrong_approach_are_errors() {
        let text = two_rows().replace("806.56", "nan");
        let e = parse_steps(&text, &[8.5e-6, 12.5e-6]).unwrap_err();
        assert!(e.contains("P_contact_N") && e.contains("finite"), "{e}");
        let e = parse_steps(&two_rows(), &[8.5e-6, 13e-6]).unwrap_err();
        assert!(e.contains("expected"), "{e}");
        let e = parse_steps("a,b\n1,2\n", &[8.5e-6]).unwrap_err();
        assert!(e.contains("header"), "{e}");
    }

    #[test]
    fn missing_output_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_steps(dir.path(), &[1e-6]).unwrap_err();
        assert!(e.contains("output missing"), "{e}");
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

    /// Hertz's gap outside the contact (Johnson 1985, eq. 3.42 with 4.22), in units a = 1,
    /// with the penalty's small negative gap inside: the edge fit recovers c = a to well below
    /// the node spacing, where the last node in contact errs by up to one spacing.
    #[test]
    fn the_edge_fit_recovers_hertz_contact_radius() {
        let hertz_gap = |r: f64| {
            if r <= 1.0 {
                -1e-6
            } else {
                ((2.0 - r * r) * (1.0 / r).asin() + (r * r - 1.0).sqrt()) / std::f64::consts::PI
                    - (1.0 - r * r / 2.0) // gap = r²/2 + u(r) − δ in units a²/R = 1, δ = 1
            }
        };
        for h in [0.05, 0.025, 0.0125] {
            for offset in (1..20).map(|k| f64::from(k) / 20.0) {
                let profile: Profile = (0..100)
                    .map(|i| {
                        let r = (i as f64 + offset) * h;
                        SurfacePoint {
                            r,
                            pressure: 0.0,
                            gap: hertz_gap(r),
                        }
                    })
                    .collect();
                let c = contact_radius(&profile).unwrap();
                // Measured: |c − a| ≤ 1.5e-4 a at these spacings (the next term of the gap's
                // expansion over the band); the last node in contact errs by up to h.
                assert!((c - 1.0).abs() < 2e-4, "h {h} offset {offset}: c = {c}");
            }
        }
    }
}
