//! The output files of an impact run (docs/impact.md):
//!
//! - `DIR/<solver>.csv`: one row per sweep point, the prescribed variant: `sweep`, `value`, then
//!   the quantities of `Quantity::ALL` (SI; an empty cell where undefined);
//! - `DIR/<solver>-elastic.csv`: the same for the elastic variant, when e < 1;
//! - `DIR/<solver>-trace.csv`: the first sweep point of the prescribed variant against time:
//!   `time`, `overlap`, `normal_force`, `tangential_force`, `approach_rate`, `slip_velocity`,
//!   `spin1`, `spin2`.
//!
//! Numbers are written in their shortest exact form (`Short` (spherecontact-model)); never NaN or ∞
//! (undefined values are empty cells).

use std::path::{Path, PathBuf};

use super::case::{ImpactCase, Variant};
use super::solver_run::SolverRun;
use spherecontact_reference::impact::table::{self as sweep_table, cell};
use spherecontact_system::io::write_atomically;

/// The file of a run's sweep table in `dir`.
pub fn table_path(dir: &Path, run: &SolverRun) -> PathBuf {
    match run.variant {
        Variant::Prescribed => dir.join(format!("{}.csv", run.solver)),
        Variant::Elastic => dir.join(format!("{}-elastic.csv", run.solver)),
    }
}

/// The sweep table of `run` ([`spherecontact_reference::impact::table`]).
pub fn table(case: &ImpactCase, run: &SolverRun) -> String {
    let sweep = case.sweep.as_ref().map_or("none", |s| s.variable.name());
    let mut text = sweep_table::header();
    text.push('\n');
    for (value, result) in &run.points {
        text.push_str(&sweep_table::row(sweep, *value, result.as_ref().ok()));
        text.push('\n');
    }
    text
}

/// The trace of `run`'s first sweep point.
pub fn trace(case: &ImpactCase, run: &SolverRun) -> String {
    let arms = case.points().first().map_or([0.0; 2], |p| p.lever_arms());
    let mut text =
        String::from("time,overlap,normal_force,tangential_force,approach_rate,slip_velocity,spin1,spin2\n");
    for s in &run.trace {
        let cells = [
            s.time,
            s.overlap,
            s.normal_force,
            s.tangential_force,
            s.motion.approach_rate(),
            s.motion.slip(arms),
            s.motion.body1[2],
            s.motion.body2[2],
        ];
        let row: Vec<String> = cells.iter().map(|&v| cell(Some(v))).collect();
        text.push_str(&row.join(","));
        text.push('\n');
    }
    text
}

/// Writes every run's files into `dir` (which exists); returns the tables written.
pub fn write(dir: &Path, case: &ImpactCase, runs: &[SolverRun]) -> std::io::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for run in runs {
        let path = table_path(dir, run);
        write_atomically(&path, table(case, run).as_bytes())?;
        if run.variant == Variant::Prescribed {
            let trace_path = dir.join(format!("{}-trace.csv", run.solver));
            write_atomically(&trace_path, trace(case, run).as_bytes())?;
        }
        written.push(path);
    }
    Ok(written)
}
