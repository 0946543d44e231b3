//! Running a case's own impact solver ([`spherecontact_reference::impact::own_solver`]) in one
//! variant: its sweep table read back — from the stored file, or from the file its program
//! wrote — into a [`SolverRun`] that the checks, files, report and run files treat as any
//! solver's.
//!
//! A program runs as a path case's command solver does (`command` (spherecontact-external)):
//! only when allowed, in a fresh temporary folder holding the impact scene file
//! ([`super::own_scene`]), with its process handling, timeout and minimal environment; its
//! table (`{history}`) read as foreign input (a regular file, no link, bounded). On failure the
//! folder is kept and named.

use std::time::Instant;

use super::case::{ImpactCase, Variant};
use super::solver_run::SolverRun;
use spherecontact_external::command::CommandSolver;
use spherecontact_external::exchange::scene_file::HISTORY_FILE;
use spherecontact_external::program;
use spherecontact_model::solver::SolveError;
use spherecontact_reference::impact::outcome::Outcome;
use spherecontact_reference::impact::own_solver::{OwnSolver, Source};
use spherecontact_reference::impact::table;
use spherecontact_system::input::Links;
use spherecontact_system::permission::how_to_allow;

/// `own` over every sweep point of `case` in `variant`.
pub fn run_own(case: &ImpactCase, own: &OwnSolver, variant: Variant) -> SolverRun {
    let start = Instant::now();
    let points = case.points_of(variant);
    let outcomes = match &own.source {
        Source::Stored { prescribed, elastic } => {
            let file = match variant {
                Variant::Prescribed => Some(prescribed),
                Variant::Elastic => elastic.as_ref(),
            };
            match file {
                Some(file) => table::read_file(file, case.sweep_name(), &points, Links::Follow)
                    .map_err(SolveError::Failed),
                None => Err(SolveError::Unavailable(
                    "stored results of the prescribed variant only (an `elastic_file` gives the elastic one)"
                        .into(),
                )),
            }
        }
        Source::Command { .. } => run_program(case, own, variant),
    };
    let (points, unavailable) = match outcomes {
        Ok(outcomes) => (
            points
                .iter()
                .map(|p| p.value)
                .zip(outcomes.into_iter().map(Ok))
                .collect(),
            None,
        ),
        Err(SolveError::Unavailable(why)) => (
            points
                .iter()
                .map(|p| (p.value, Err(format!("not available: {why}"))))
                .collect(),
            Some(why),
        ),
        Err(e) => {
            let why = e.to_string();
            (points.iter().map(|p| (p.value, Err(why.clone()))).collect(), None)
        }
    };
    SolverRun {
        solver: own.name.clone(),
        variant,
        points,
        trace: Vec::new(),
        wall_time_s: start.elapsed().as_secs_f64(),
        unavailable,
    }
}

/// `own` as a path case's command solver, if it is a program: the one mechanism that fills
/// its placeholders, finds its program and shows its command.
fn command_solver(own: &OwnSolver) -> Option<CommandSolver> {
    let Source::Command {
        command,
        timeout,
        case_dir,
        permission,
    } = &own.source
    else {
        return None;
    };
    Some(CommandSolver {
        name: own.name.clone(),
        command: command.clone(),
        timeout: *timeout,
        case_dir: case_dir.clone(),
        description: own.description.clone(),
        kind: own.kind,
        permission: permission.clone(),
    })
}

/// Lines that say which programs a run of `case` would run and whether they may (as a path
/// case's `command_lines`); none when it runs none.
pub fn command_lines(case: &ImpactCase) -> Vec<String> {
    let needed = case.required_solvers();
    let commands: Vec<CommandSolver> = case
        .own_solvers
        .iter()
        .filter(|s| needed.contains(&s.name))
        .filter_map(command_solver)
        .collect();
    spherecontact_external::command::lines(&case.name, &commands.iter().collect::<Vec<_>>())
}

/// Runs `own`'s program on `variant`'s scene file and reads back the table it wrote.
fn run_program(case: &ImpactCase, own: &OwnSolver, variant: Variant) -> Result<Vec<Outcome>, SolveError> {
    let Source::Command { permission, .. } = &own.source else {
        unreachable!("run_program runs programs");
    };
    if !permission.is_allowed() {
        return Err(SolveError::Unavailable(format!(
            "not run: a program the case names ({})",
            how_to_allow()
        )));
    }
    let solver = command_solver(own).expect("a program's source");
    program::in_run_folder(&own.name, |dir| {
        let failed = |what: &str, e: &dyn std::fmt::Display| SolveError::Failed(format!("{what}: {e}"));
        std::fs::write(
            dir.join(super::own_scene::FILE_NAME),
            super::own_scene::to_json(case, variant),
        )
        .map_err(|e| failed("writing the scene file", &e))?;
        let job = solver.job(dir)?;
        let label = job.program.display().to_string();
        program::run_to_success(
            &job,
            dir,
            "command",
            &label,
            |_| "the program's own failure",
            &permission.environment(),
        )?;
        let points = case.points_of(variant);
        table::read_file(&dir.join(HISTORY_FILE), case.sweep_name(), &points, Links::Refuse)
            .map_err(|e| failed("its results", &e))
    })
}
