//! Reading a DEM code's rows along the path back, the same for LAMMPS and LIGGGHTS: one row a
//! printed step, `step δn P Q` (LIGGGHTS adds its contact area), checked against the path (the
//! step sequence and the code's own δn), the first row of each step kept: a `run`'s set-up
//! prints the step before it again, with the set-up's forces.

use std::path::Path;

use spherecontact_model::history::StepResult;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::SolveError;

/// How far the δn a code reports may be from the path's, relative to the largest |δn|.
///
/// Reason: sphere 2 sits at z ≈ R1 + R2, where one ulp is about 3e-17 m for 0.1 m spheres,
/// 2e-12 of a 17 µm approach; its z is set (LIGGGHTS) or recomputed from its start (LAMMPS
/// `fix move`) each step, so the error stays at a few ulps. 1e-9 is far above that and far
/// below one substep of any path.
pub const DELTA_N_MATCH: f64 = 1e-9;

/// One printed row: P [N], Q [N], and the values after them (its step and δn checked).
pub struct Row {
    /// P [N].
    pub normal_force: f64,
    /// Q [N].
    pub tangential_force: f64,
    /// Further columns (LIGGGHTS: its contact area [m²]).
    pub rest: Vec<f64>,
}

/// The rows of `file` with `columns` numbers each (at least 4) against `scene`'s path, one per
/// step, and the largest |δn − δn_path| [m]. Lines for which `is_data` is false are the code's
/// other output and skipped (LAMMPS: comments; LIGGGHTS: its log around the thermo rows).
pub fn read(
    file: &Path,
    scene: &Scene,
    columns: usize,
    is_data: impl Fn(&str) -> bool,
) -> Result<(Vec<Row>, f64), SolveError> {
    let text =
        std::fs::read_to_string(file).map_err(|e| SolveError::Failed(format!("{}: {e}", file.display())))?;
    let path = scene.steps();
    let scale = path.iter().map(|s| s.delta_n.abs()).fold(0.0, f64::max);
    let mut rows: Vec<Row> = Vec::with_capacity(path.len());
    let mut worst: f64 = 0.0;
    for (number, line) in text.lines().enumerate() {
        if !is_data(line) {
            continue;
        }
        let bad = |why: &str| {
            SolveError::Failed(format!(
                "{}:{}: {why}: `{}`",
                file.display(),
                number + 1,
                line.chars().take(200).collect::<String>()
            ))
        };
        let values: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|_| bad(&format!("not {columns} numbers")))?;
        if values.len() != columns {
            return Err(bad(&format!("not {columns} numbers")));
        }
        if !values.iter().all(|v| v.is_finite()) {
            return Err(bad("a value is not finite"));
        }
        let step = values[0] as usize;
        if step < rows.len() {
            continue; // the set-up of the next `run` prints the last step again
        }
        let Some(expected) = path.get(step).filter(|_| step == rows.len()) else {
            return Err(bad("step out of sequence"));
        };
        let deviation = (values[1] - expected.delta_n).abs();
        if deviation > DELTA_N_MATCH * scale {
            return Err(bad(&format!(
                "the code's δn is not the path's {:e} m",
                expected.delta_n
            )));
        }
        worst = worst.max(deviation);
        rows.push(Row {
            normal_force: values[2],
            tangential_force: values[3],
            rest: values[4..].to_vec(),
        });
    }
    if rows.len() != path.len() {
        return Err(SolveError::Failed(format!(
            "{}: {} steps for a path of {}",
            file.display(),
            rows.len(),
            path.len()
        )));
    }
    Ok((rows, worst))
}

/// The history rows of `rows` on `scene`'s path: P and Q (and what `more` adds from a row).
pub fn steps(scene: &Scene, rows: &[Row], more: impl Fn(&Row, &mut StepResult)) -> Vec<StepResult> {
    scene
        .steps()
        .iter()
        .zip(rows)
        .map(|(expected, row)| {
            let mut step = StepResult {
                normal_force: Some(row.normal_force),
                tangential_force: Some(row.tangential_force),
                ..StepResult::at(expected)
            };
            more(row, &mut step);
            step
        })
        .collect()
}
