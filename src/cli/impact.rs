//! `spherecontact run` on an impact case, and `spherecontact impact`: plan (the case and the solvers named, validated; the
//! output folder claimed, `OutputFolder`), then execute (run, write the files, print
//! a line per run).

use std::path::{Path, PathBuf};

use spherecontact::case;
use spherecontact::impact::case::ImpactCase;
use spherecontact::impact::own_run;
use spherecontact::impact::run::{self, solver_names};
use spherecontact::impact::{files, ImpactRun};
use spherecontact::io::{self, OutputFolder};
use spherecontact::permission::CommandPermission;

/// A validated `run` of an impact case: nothing is written before it exists.
#[derive(Debug)]
pub struct RunPlan {
    /// The case.
    pub case: ImpactCase,
    /// The solvers to run.
    pub solvers: Vec<String>,
    /// The output folder, claimed (and locked) for this run.
    pub out: OutputFolder,
}

pub use spherecontact::case::is_impact_file;

/// Plans a run: the case validated, each solver named once and known, `out` claimed (`force`:
/// also a folder holding files the harness did not write).
pub fn plan(
    file: &Path,
    solvers: &[String],
    out: &Path,
    force: bool,
    permission: &CommandPermission,
) -> Result<RunPlan, String> {
    let case = load(file, permission)?;
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
        if !solver_names().contains(&name.as_str()) && case.own_solver(name).is_none() {
            let own = case.own_solvers.iter().map(|s| s.name.as_str());
            let allowed: Vec<&str> = solver_names().into_iter().chain(own).collect();
            return Err(format!(
                "--solver: `{name}` cannot run an impact (allowed: {})",
                allowed.join(", ")
            ));
        }
    }
    if solvers.iter().any(|name| case.own_solver(name).is_some()) {
        own_run::command_lines(&case)
            .iter()
            .for_each(|line| eprintln!("{line}"));
    }
    let out = claim(out, force)?;
    Ok(RunPlan { case, solvers, out })
}

impl RunPlan {
    /// Runs the plan, writes its files and prints a line per run; false if a run failed.
    pub fn execute(self) -> Result<bool, String> {
        let out = self.out.path();
        let runs = run::run_case(&self.case, &self.solvers);
        let written = files::write(out, &self.case, &runs)
            .map_err(|e| format!("writing results to {}: {e}", out.display()))?;
        let mut ok = true;
        for (run, path) in runs.iter().zip(&written) {
            for (at, result) in &run.points {
                if let Err(e) = result {
                    ok = false;
                    eprintln!(
                        "error: {} ({}) at {}: {e}",
                        run.solver,
                        run.variant.name(),
                        spherecontact::number::format_value(*at)
                    );
                }
            }
            outln!(
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

/// `spherecontact impact`: plans (every case valid, `out` claimed), runs every case with its
/// checks, writes each case's solver files into `out/<case>/` and the report into `out`, prints
/// the check rows; true when every case passed.
pub fn report(
    files: &[PathBuf],
    out: &Path,
    force: bool,
    permission: &CommandPermission,
) -> Result<bool, String> {
    let files = if files.is_empty() {
        spherecontact::case::case_files(&[PathBuf::from("cases/impact")]).map_err(|e| e.to_string())?
    } else {
        files.to_vec()
    };
    if files.is_empty() {
        return Err("no impact cases to run".into());
    }
    let cases = files
        .iter()
        .map(|f| load(f, permission))
        .collect::<Result<Vec<_>, _>>()?;
    cases
        .iter()
        .flat_map(own_run::command_lines)
        .for_each(|line| eprintln!("{line}"));
    let folder = claim(out, force)?;
    let out = folder.path();
    let runs: Vec<ImpactRun> = cases.into_iter().map(ImpactRun::of).collect();
    for run in &runs {
        let dir = out.join(&run.case.name);
        io::create_folder(&dir).map_err(|e| format!("--out {}: {e}", dir.display()))?;
        files::write(&dir, &run.case, &run.runs).map_err(|e| format!("--out {}: {e}", dir.display()))?;
        out!("{}", run.block());
    }
    let document = spherecontact::report::impact::document(&runs, true)
        .map_err(|e| format!("building the report: {e}"))?;
    document
        .write(out)
        .map_err(|e| format!("--out {}: {e}", out.display()))?;
    outln!("report: {}", out.join("report.html").display());
    Ok(runs.iter().all(ImpactRun::passed))
}

/// The impact case at `file`, its programs allowed to run as `permission` says.
fn load(file: &Path, permission: &CommandPermission) -> Result<ImpactCase, String> {
    let mut case = case::load_impact(file).map_err(|e| e.to_string())?;
    case.permit_commands(permission);
    Ok(case)
}

/// `out` claimed as this run's output folder (refused: `--out DIR: why`).
fn claim(out: &Path, force: bool) -> Result<OutputFolder, String> {
    OutputFolder::claim(out, force).map_err(|e| format!("--out {}: {e}", out.display()))
}
