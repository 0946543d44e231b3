//! A command solver: any program named by a case, given the scene file and read back through the
//! History CSV (docs/own-solver.md; docs/security.md, "Programs a case may run").
//!
//! It runs only when allowed ([`super::permission`]): otherwise it is not available, with the
//! reason and the command it would run. The run: a fresh temporary folder; `scene.json` written
//! there ([`crate::exchange::scene_file`]); the command run there with the decks' process
//! handling ([`spherecontact_system::process`]: own process group, every process it started killed at the
//! timeout and when it ends, stdout and stderr streamed to bounded logs `command.stdout` /
//! `command.stderr`) in a minimal environment; `history.csv` read back (a regular file, no
//! link, at most [`MAX_HISTORY_BYTES`]) and validated against the path
//! ([`crate::exchange::results_csv`]); optionally `metadata.json` (the same checks, at most
//! [`MAX_METADATA_BYTES`]) read for the version, model, resolution and warnings the program
//! wants shown, each masked and bounded as its output is ([`spherecontact_system::mask`], [`spherecontact_system::excerpt`]).
//! On any failure the folder is kept and named in the message, and so it is when a column of the
//! results is refused for a bad cell (that quantity alone: `results_csv`); otherwise it is removed.
//!
//! Placeholders in the command: `{case_dir}` (the case file's folder), `{scene}` and `{history}`
//! (the absolute paths of the two files), filled under the rule of [`super::placeholder`]. A
//! program given as a relative path with a `/` is resolved against the case file's folder; a
//! bare name is looked up on PATH.
//!
//! A program that is not there is a failure of that solver, not "not available": the case names
//! it explicitly, and a typo must not pass as a missing optional tool.

use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::Deserialize;

use super::permission::{how_to_allow, CommandPermission};
use super::placeholder::{self, Values};
use super::program;
use crate::exchange::results_csv::{self, Results};
use crate::exchange::scene_file;
use spherecontact_model::history::{History, Metadata};
use spherecontact_model::limits::{MAX_HISTORY_BYTES, MAX_METADATA_BYTES, MAX_SHOWN_LINES};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_system::excerpt;
use spherecontact_system::input::{self, Links};
use spherecontact_system::mask::Mask;
use spherecontact_system::process::{Environment, Job};
use spherecontact_system::toolchain::which;

/// The file a command may write beside its History CSV to describe itself.
pub const METADATA_FILE: &str = "metadata.json";

/// What a command may say about itself in [`METADATA_FILE`] (every key optional).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CommandMetadata {
    /// The program's version.
    pub version: Option<String>,
    /// The model it solves.
    pub model: Option<String>,
    /// Its resolution, in words.
    pub resolution: Option<String>,
    /// Warnings a reader must see.
    #[serde(default)]
    pub warnings: Vec<String>,
}

impl CommandMetadata {
    /// What of it the harness shows and keeps: each text with the values of `mask` masked, then
    /// bounded as an excerpt of a program's output ([`excerpt::last_lines`]).
    fn shown(self, mask: &Mask) -> Self {
        let shown = |text: String| excerpt::last_lines(&mask.apply(&text), MAX_SHOWN_LINES);
        CommandMetadata {
            version: self.version.map(shown),
            model: self.model.map(shown),
            resolution: self.resolution.map(shown),
            warnings: self.warnings.into_iter().map(shown).collect(),
        }
    }
}

/// A program named by a case as a solver.
#[derive(Clone, Debug, PartialEq)]
pub struct CommandSolver {
    /// The solver's name in the case (a plain name: it names output files).
    pub name: String,
    /// The program and its arguments, placeholders not yet filled.
    pub command: Vec<String>,
    /// Wall-clock limit; at the limit the program and its children are killed.
    pub timeout: Duration,
    /// The case file's folder: `{case_dir}`, and the anchor of relative program paths.
    pub case_dir: PathBuf,
    /// The description shown by `list` and in reports.
    pub description: String,
    /// The kind of model the program is, as the case says.
    pub kind: Kind,
    /// Whether it may run ([`CommandPermission::refused`] until the command line says so).
    pub permission: CommandPermission,
}

impl Solver for CommandSolver {
    fn name(&self) -> &str {
        &self.name
    }

    fn kind(&self) -> Kind {
        self.kind
    }

    fn description(&self) -> &str {
        &self.description
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        if !self.permission.is_allowed() {
            return Err(SolveError::Unavailable(format!(
                "not run: a program the case names ({})",
                how_to_allow()
            )));
        }
        program::in_run_folder_kept_if(&self.name, |dir| {
            let job = self.job(dir)?;
            let label = job.program.display().to_string();
            let environment = self.permission.environment();
            let (mut results, told, wall_s) = run_exchange(scene, dir, &job, &label, &environment)?;
            // A column refused for a bad cell keeps the folder, and says so.
            let keep = !results.refused.is_empty();
            for why in results.refused.values_mut() {
                *why = format!("{why} {}", program::kept_in(dir));
            }
            let mut metadata = Metadata {
                version: told.version.unwrap_or_else(|| "command".into()),
                model: told
                    .model
                    .unwrap_or_else(|| format!("command: {}", self.command.join(" "))),
                resolution: told.resolution.unwrap_or_default(),
                warnings: told.warnings,
                unread: results.unread(),
                ..Metadata::default()
            };
            metadata
                .extra
                .insert("command".into(), serde_json::json!(self.command));
            metadata
                .extra
                .insert("command_wall_s".into(), serde_json::json!(wall_s));
            let history = History {
                metadata,
                steps: results.steps,
                fields: Vec::new(),
            };
            Ok((history, keep))
        })
    }
}

impl CommandSolver {
    /// The case file's folder, absolute.
    fn case_dir(&self) -> PathBuf {
        std::path::absolute(&self.case_dir).unwrap_or_else(|_| self.case_dir.clone())
    }

    /// The command as it would run, `{case_dir}` filled and `{scene}`, `{history}` left as they
    /// are (their folder is made at the run), each argument quoted where it needs it; or why it
    /// would be refused.
    pub fn shown(&self) -> String {
        let case_dir = self.case_dir();
        let values = Values {
            case_dir: &case_dir,
            run_dir: None,
        };
        match self
            .command
            .iter()
            .map(|a| values.fill(a).map(|a| placeholder::shown(&a)))
            .collect::<Result<Vec<_>, _>>()
        {
            Ok(arguments) => arguments.join(" "),
            Err(e) => format!("nothing: {e}"),
        }
    }

    /// The program and arguments with the placeholders filled (their values also in the
    /// environment), the program resolved.
    pub fn job(&self, run_dir: &Path) -> Result<Job, SolveError> {
        let case_dir = self.case_dir();
        let run_dir = std::path::absolute(run_dir).unwrap_or_else(|_| run_dir.to_path_buf());
        let values = Values {
            case_dir: &case_dir,
            run_dir: Some(&run_dir),
        };
        let filled = self
            .command
            .iter()
            .map(|a| values.fill(a))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| SolveError::Failed(format!("not run: {e}")))?;
        let Some((program, args)) = filled.split_first() else {
            return Err(SolveError::Failed("empty command".into()));
        };
        let program = PathBuf::from(program);
        let program = if program.is_relative() && program.components().count() > 1 {
            case_dir.join(program)
        } else {
            program
        };
        let resolved = which(&program).ok_or_else(|| {
            SolveError::Failed(format!(
                "program `{}` not found (a bare name is looked up on PATH, a relative path in the case file's folder {})",
                program.display(),
                case_dir.display()
            ))
        })?;
        Ok(Job {
            program: resolved,
            args: args.to_vec(),
            env: values.environment(),
            timeout: self.timeout,
        })
    }
}

/// Lines that say which of `commands` a run of the case `case` would run and whether they may:
/// for `verify`, `list` and `doctor`; none without commands.
pub fn lines(case: &str, commands: &[&CommandSolver]) -> Vec<String> {
    let Some(first) = commands.first() else {
        return Vec::new();
    };
    let mut lines = vec![format!("{case}: command solvers {}", first.permission.state())];
    let runs = if first.permission.is_allowed() {
        "runs"
    } else {
        "would run"
    };
    lines.extend(commands.iter().map(|c| {
        format!(
            "  {} {runs} (timeout {} s): {}",
            c.name,
            c.timeout.as_secs_f64(),
            c.shown()
        )
    }));
    lines
}

/// Writes the scene file into `dir`, runs `job` there in `environment` and reads back the History
/// CSV it wrote (validated against the path; a quantity refused alone, [`Results`]) and its
/// optional [`METADATA_FILE`] (masked and bounded: `CommandMetadata::shown`); also its wall time
/// [s].
pub fn run_exchange(
    scene: &Scene,
    dir: &Path,
    job: &Job,
    program: &str,
    environment: &Environment,
) -> Result<(Results, CommandMetadata, f64), SolveError> {
    let failed = |what: &str, e: &dyn std::fmt::Display| SolveError::Failed(format!("{what}: {e}"));
    std::fs::write(
        dir.join(scene_file::FILE_NAME),
        scene_file::SceneFile::of(scene).to_json(),
    )
    .map_err(|e| failed("writing the scene file", &e))?;
    let run = program::run_to_success(
        job,
        dir,
        "command",
        program,
        |_| "the program's own failure",
        environment,
    )?;
    let history = dir.join(scene_file::HISTORY_FILE);
    let file = input::open_regular(&history, MAX_HISTORY_BYTES, Links::Refuse)
        .map_err(|e| failed(&format!("its results: {}: cannot read", history.display()), &e))?;
    let results =
        results_csv::read_from(file, &history, &scene.steps()).map_err(|e| failed("its results", &e))?;
    let told = read_metadata(&dir.join(METADATA_FILE))?.shown(&environment.mask());
    Ok((results, told, run.wall_s))
}

/// The command's own description of itself, if it wrote one.
fn read_metadata(file: &Path) -> Result<CommandMetadata, SolveError> {
    let failed = |e: &dyn std::fmt::Display| SolveError::Failed(format!("{}: {e}", file.display()));
    let mut opened = match input::open_regular(file, MAX_METADATA_BYTES, Links::Refuse) {
        Ok(opened) => opened,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(CommandMetadata::default()),
        Err(e) => return Err(failed(&e)),
    };
    let mut text = String::new();
    std::io::Read::read_to_string(&mut opened, &mut text).map_err(|e| failed(&e))?;
    serde_json::from_str(&text).map_err(|e| {
        failed(&format!(
            "{e} (allowed keys: version, model, resolution, warnings)"
        ))
    })
}
