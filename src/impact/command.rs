//! `spherecontact run` on an impact case: plan (the case and the solvers named, validated; the
//! output folder checked), then execute (run, write the files, print a line per run).

use std::path::{Path, PathBuf};

use super::case::ImpactCase;
use super::run::{self, solver_names};
use super::{files, ImpactRun};
use crate::case;

/// A validated `run` of an impact case: nothing is written before it exists.
#[derive(Debug)]
pub struct RunPlan {
    /// The case.
    pub case: ImpactCase,
    /// The solvers to run.
    pub solvers: Vec<String>,
    /// The output folder.
    pub out: PathBuf,
}

/// True when `file` holds an impact case (`kind = "impact"`); false when it cannot be read (the
/// path-case loader then reports why).
pub fn is_impact_file(file: &Path) -> bool {
    case::input::read_text(file).is_ok_and(|text| case::is_impact(&text))
}

/// Plans a run: the case validated, each solver named once and known, `out` writable.
pub fn plan(file: &Path, solvers: &[String], out: &Path) -> Result<RunPlan, String> {
    let case = case::load_impact(file).map_err(|e| e.to_string())?;
    let solvers = if solvers.is_empty() {
        case.solvers.clone()
    } else {
        solvers.to_vec()
    };
    for (i, name) in solvers.iter().enumerate() {
        if solvers[..i].contains(name) {
            return Err(format!(
                "--solver: `{name}` is named twice (allowed: each solver once)"
            ));
        }
        if !solver_names().contains(&name.as_str()) {
            return Err(format!(
                "--solver: `{name}` cannot run an impact (allowed: {})",
                solver_names().join(", ")
            ));
        }
    }
    crate::io::check_output_folder(out).map_err(|e| format!("--out {}: {e}", out.display()))?;
    Ok(RunPlan {
        case,
        solvers,
        out: out.to_path_buf(),
    })
}

impl RunPlan {
    /// Runs the plan, writes its files and prints a line per run; false if a run failed.
    pub fn execute(self) -> Result<bool, String> {
        std::fs::create_dir_all(&self.out).map_err(|e| format!("--out {}: {e}", self.out.display()))?;
        let runs = run::run_case(&self.case, &self.solvers);
        let written = files::write(&self.out, &self.case, &runs)
            .map_err(|e| format!("writing results to {}: {e}", self.out.display()))?;
        let mut ok = true;
        for (run, path) in runs.iter().zip(&written) {
            for (at, result) in &run.points {
                if let Err(e) = result {
                    ok = false;
                    eprintln!(
                        "error: {} ({}) at {}: {e}",
                        run.solver,
                        run.variant.name(),
                        crate::report::format_value(*at)
                    );
                }
            }
            println!(
                "{:<22} {:<10} {:>9.3} ms  -> {}",
                run.solver,
                run.variant.name(),
                run.wall_time_s * 1e3,
                path.display()
            );
        }
        Ok(ok)
    }
}

/// Loads and runs an impact case with its checks, for `verify`.
pub fn verify(file: &Path) -> Result<ImpactRun, String> {
    let case = case::load_impact(file).map_err(|e| e.to_string())?;
    Ok(ImpactRun::of(case))
}
