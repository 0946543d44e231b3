//! A deck's folder for a run elsewhere (`spherecontact deck write|read`; docs/external-decks.md,
//! "On a cluster"): everything the deck needs, written by [`write_folder`] into a claimed output
//! folder, with
//!
//! - [`RUN_SCRIPT`]: the command that runs the deck in its folder, the solver's own command
//!   (program, arguments, environment), its output logged to `deck.stdout` and `deck.stderr` as
//!   the solver's own run logs it;
//! - [`README`]: what the folder is and the commands to run it and to read it back;
//! - [`MANIFEST`]: the case, the solver, the resolution and settings, the scene and the version
//!   that wrote it, so that [`read_folder`] reads back only the folder of the same case, solver
//!   and resolution ([`Manifest::check_found`]).
//!
//! The deck side of the split is [`SplitDeck`]; a folder is read back through the same checks as
//! the solver's own run ([`spherecontact_model::solver::run`]: rows against the path, finite values).

use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::deck::{Deck, LOG_STEM};
use spherecontact_model::history::History;
use spherecontact_model::limits::MAX_INPUT_BYTES;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::split::{DeckCommand, SplitDeck};
use spherecontact_model::solver::Kind;
use spherecontact_model::solver::{self, SolveError, Solver};
use spherecontact_system::input::foreign;
use spherecontact_system::toolchain::Toolchain;

/// The version a history read back from a folder records (the tool's version on the other
/// machine is not known here).
pub const RUN_ELSEWHERE: &str = "(run elsewhere)";

/// The manifest's file name.
pub const MANIFEST: &str = "manifest.json";

/// The README's file name.
pub const README: &str = "README.txt";

/// The run script's file name.
pub const RUN_SCRIPT: &str = "run.sh";

/// The manifest's `format`: what kind of file it is, and its layout's version.
const FORMAT: &str = "spherecontact deck folder 1";

/// The command that runs `deck`, written into its folder, there: the job of the solver's own run
/// (`toolchain`'s program, the deck file by its name, the environment), without its time limit.
pub fn deck_command(deck: &impl Deck, toolchain: &Toolchain) -> DeckCommand {
    let job = deck.job(toolchain, Path::new(deck.file_name()), Duration::ZERO);
    DeckCommand {
        program: job.program,
        args: job.args,
        env: job.env,
    }
}

/// What a deck folder was written for.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// [`FORMAT`].
    pub format: String,
    /// The version of spherecontact that wrote the folder.
    pub spherecontact: String,
    /// The case's name.
    pub case: String,
    /// The case file, as given to `deck write`.
    pub case_file: String,
    /// The solver.
    pub solver: String,
    /// The resolution chosen for the solver (`--resolution` or the case's `[resolution]`), or
    /// `None` for its default.
    pub resolution: Option<String>,
    /// What decides the deck's files besides the scene ([`SplitDeck::settings`]).
    pub settings: Value,
    /// The scene: the spheres, the path, the domain.
    pub scene: Value,
    /// The command [`RUN_SCRIPT`] runs.
    pub command: String,
}

/// Why a folder cannot be read back.
#[derive(Debug, thiserror::Error)]
pub enum FolderError {
    /// The manifest is missing or is not one.
    #[error("{}: {why}", file.display())]
    Manifest {
        /// The manifest's path.
        file: PathBuf,
        /// What is wrong.
        why: String,
    },
    /// The folder was written for another case, solver, resolution or scene.
    #[error(
        "{}: the folder was written for {field} {found}, but this read is for {expected} (allowed: \
         the case file, --solver and --resolution the deck was written with)",
        file.display()
    )]
    Mismatch {
        /// The manifest's path.
        file: PathBuf,
        /// What differs.
        field: String,
        /// The manifest's value.
        found: String,
        /// The value of this read.
        expected: String,
    },
    /// The case's scene is not the one the folder was written for.
    #[error(
        "{}: the deck was written for case `{case}` with another scene (its `{key}` differs): the \
         case changed since; write the deck again",
        file.display()
    )]
    SceneChanged {
        /// The manifest's path.
        file: PathBuf,
        /// The case.
        case: String,
        /// The first part of the scene that differs.
        key: String,
    },
    /// The run's files are missing or garbage (or the deck does not model the scene).
    #[error("{0}")]
    Run(SolveError),
}

impl Manifest {
    /// The manifest of `deck` (the solver `solver`, at the resolution chosen as `resolution`)
    /// written for the case `case_file` whose scene is `scene`.
    pub fn new(
        case_file: &Path,
        solver: &str,
        resolution: Option<&str>,
        deck: &dyn SplitDeck,
        scene: &Scene,
    ) -> Self {
        Manifest {
            format: FORMAT.into(),
            spherecontact: env!("CARGO_PKG_VERSION").into(),
            case: scene.name.clone(),
            case_file: case_file.display().to_string(),
            solver: solver.into(),
            resolution: resolution.map(str::to_owned),
            settings: deck.settings(scene),
            scene: serde_json::to_value(scene).unwrap_or(Value::Null),
            command: command_line(&deck.command()),
        }
    }

    /// Checks the manifest `found` in `dir` against this one (the case, solver, resolution,
    /// settings and scene of this read): the warnings it leaves (another version wrote it).
    pub fn check_found(&self, found: &Manifest, dir: &Path) -> Result<Vec<String>, FolderError> {
        let file = dir.join(MANIFEST);
        let differs = |field: &str, found: String, expected: String| FolderError::Mismatch {
            file: file.clone(),
            field: field.into(),
            found,
            expected,
        };
        let quoted = |s: &str| format!("`{s}`");
        let resolution = |r: &Option<String>| r.as_deref().map_or("the default resolution".into(), quoted);
        if found.solver != self.solver {
            return Err(differs("solver", quoted(&found.solver), quoted(&self.solver)));
        }
        if found.case != self.case {
            return Err(differs("case", quoted(&found.case), quoted(&self.case)));
        }
        if found.settings != self.settings || found.resolution != self.resolution {
            return Err(differs(
                "resolution",
                format!("{} ({})", resolution(&found.resolution), found.settings),
                format!("{} ({})", resolution(&self.resolution), self.settings),
            ));
        }
        if let Some(key) = first_difference(&found.scene, &self.scene) {
            return Err(FolderError::SceneChanged {
                file,
                case: found.case.clone(),
                key,
            });
        }
        Ok((found.spherecontact != self.spherecontact)
            .then(|| {
                format!(
                    "the deck was written by spherecontact {} and read back by {}",
                    found.spherecontact, self.spherecontact
                )
            })
            .into_iter()
            .collect())
    }
}

/// The first top-level key whose value differs between two scenes (the whole scene if they are
/// not both objects).
fn first_difference(found: &Value, expected: &Value) -> Option<String> {
    match (found, expected) {
        (Value::Object(a), Value::Object(b)) => {
            let keys = a.keys().chain(b.keys());
            keys.into_iter().find(|k| a.get(*k) != b.get(*k)).cloned()
        }
        _ => (found != expected).then(|| "scene".to_owned()),
    }
}

/// Meshes and writes `deck` for `scene` into the claimed folder `out`, with [`RUN_SCRIPT`],
/// [`README`] and [`MANIFEST`] (the manifest last: a folder with one is complete). The deck is
/// written in a private temporary folder first, each file then copied atomically: a deck that
/// cannot be written leaves nothing in `out`. The files written, by name.
pub fn write_folder(
    deck: &dyn SplitDeck,
    scene: &Scene,
    manifest: &Manifest,
    out: &Path,
) -> Result<Vec<String>, SolveError> {
    let work = tempfile::Builder::new()
        .prefix("spherecontact-deck-")
        .tempdir()
        .map_err(|e| SolveError::Failed(format!("no temporary folder: {e}")))?;
    deck.write_run(scene, work.path())?;
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    let entries = std::fs::read_dir(work.path()).map_err(|e| SolveError::Failed(e.to_string()))?;
    for entry in entries {
        let path = entry.map_err(|e| SolveError::Failed(e.to_string()))?.path();
        let bytes =
            std::fs::read(&path).map_err(|e| SolveError::Failed(format!("{}: {e}", path.display())))?;
        files.push((
            path.file_name().unwrap_or_default().to_string_lossy().into(),
            bytes,
        ));
    }
    files.sort();
    let mut names: Vec<String> = files.iter().map(|(name, _)| name.clone()).collect();
    names.extend([RUN_SCRIPT, README, MANIFEST].map(String::from));
    let manifest_text =
        serde_json::to_string_pretty(manifest).map_err(|e| SolveError::Failed(format!("{MANIFEST}: {e}")))?;
    files.push((
        RUN_SCRIPT.into(),
        run_script(manifest, &deck.command()).into_bytes(),
    ));
    files.push((README.into(), readme(manifest, &names, out).into_bytes()));
    files.push((MANIFEST.into(), manifest_text.into_bytes()));
    for (name, bytes) in &files {
        let target = out.join(name);
        spherecontact_system::io::write_atomically(&target, bytes)
            .map_err(|e| SolveError::Failed(format!("writing {}: {e}", target.display())))?;
    }
    Ok(names)
}

/// The manifest of the deck folder `dir`, read as a file from elsewhere
/// ([`spherecontact_system::input::foreign`]: a regular file, a link only inside the folder, at most
/// [`MAX_INPUT_BYTES`], as large as the case file whose scene it holds; a parse error quotes
/// nothing of it). Once it parses with this [`FORMAT`] it is taken for the harness's own file:
/// [`Manifest::check_found`] names the case, solver and resolution it was written for.
pub fn read_manifest(dir: &Path) -> Result<Manifest, FolderError> {
    let file = dir.join(MANIFEST);
    let error = |why: String| FolderError::Manifest {
        file: file.clone(),
        why,
    };
    let allowed = format!("a folder written by `spherecontact deck write`, which holds {MANIFEST}");
    if std::fs::symlink_metadata(&file).is_err() {
        return Err(error(format!("missing (allowed: {allowed})")));
    }
    let text = foreign::read_text(&file, MAX_INPUT_BYTES).map_err(|e| error(e.problem))?;
    let manifest: Manifest = foreign::parse_json(&file, &text, "a deck manifest").map_err(|e| {
        let at = e.location.map_or_else(String::new, |(line, column)| {
            format!(" at line {line}, column {column}")
        });
        error(format!("not a deck manifest{at}: {}", e.problem))
    })?;
    if manifest.format != FORMAT {
        return Err(error(format!(
            "not a deck manifest: its `format` is not `{FORMAT}` (allowed: {allowed})"
        )));
    }
    Ok(manifest)
}

/// Reads back the run `deck` finished in `dir`, after checking the folder's manifest against
/// `expected` ([`Manifest::check_found`]): its history, as the solver's own run gives it, with
/// the manifest's warnings.
pub fn read_folder(
    deck: &dyn SplitDeck,
    scene: &Scene,
    expected: &Manifest,
    dir: &Path,
) -> Result<History, FolderError> {
    let warnings = expected.check_found(&read_manifest(dir)?, dir)?;
    let reading = ReadBack {
        name: &expected.solver,
        deck,
        dir,
    };
    let mut history = solver::run(&reading, scene).map_err(FolderError::Run)?;
    history.metadata.chosen_resolution = expected.resolution.clone();
    history.metadata.warnings.extend(warnings);
    Ok(history)
}

/// A folder's run read back, as a solver: so that it goes through [`solver::run`]'s checks.
struct ReadBack<'a> {
    name: &'a str,
    deck: &'a dyn SplitDeck,
    dir: &'a Path,
}

impl Solver for ReadBack<'_> {
    fn name(&self) -> &str {
        self.name
    }

    fn kind(&self) -> Kind {
        Kind::FiniteElement
    }

    fn description(&self) -> &str {
        "a deck's run read back from its folder"
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        self.deck.read_run(scene, self.dir)
    }
}

/// `command` as one shell line: its variables, the program as this machine's toolchain names it
/// (a name looked up on PATH, or a path: `/usr/bin/python3`, Debian's, where dolfinx is), its
/// arguments; each word quoted where the shell would split it.
pub fn command_line(command: &DeckCommand) -> String {
    let program = command.program.display().to_string();
    let env = command.env.iter().map(|(k, v)| format!("{k}={}", quote(v)));
    let words = std::iter::once(quote(&program)).chain(command.args.iter().map(|a| quote(a)));
    env.chain(words).collect::<Vec<_>>().join(" ")
}

/// `word` quoted for a POSIX shell where it holds anything but letters, digits and `_./=+-`.
fn quote(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_./=+-".contains(c);
    if !word.is_empty() && word.chars().all(plain) {
        word.to_owned()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

/// The run script: into its own folder, the deck's command with its logs, its exit code.
fn run_script(manifest: &Manifest, command: &DeckCommand) -> String {
    let exports: String = command
        .env
        .iter()
        .map(|(k, v)| format!("export {k}={}\n", quote(v)))
        .collect();
    let bare = DeckCommand {
        env: Vec::new(),
        ..command.clone()
    };
    format!(
        "#!/bin/sh\n\
         # The {solver} deck of case `{case}`, written by spherecontact {version} ({README}).\n\
         # Runs it in this folder; stdout and stderr go to {LOG_STEM}.stdout and {LOG_STEM}.stderr.\n\
         cd \"$(dirname \"$0\")\" || exit 2\n\
         {exports}\
         status=0\n\
         {line} >{LOG_STEM}.stdout 2>{LOG_STEM}.stderr || status=$?\n\
         if [ \"$status\" -ne 0 ]; then\n\
         \x20 echo \"{solver}: the deck exited with code $status; the end of {LOG_STEM}.stderr:\" >&2\n\
         \x20 tail -n 12 {LOG_STEM}.stderr >&2\n\
         fi\n\
         exit \"$status\"\n",
        solver = manifest.solver,
        case = one_line(&manifest.case),
        version = manifest.spherecontact,
        line = command_line(&bare),
    )
}

/// The README of the folder `out` holding `files`.
fn readme(manifest: &Manifest, files: &[String], out: &Path) -> String {
    let resolution = manifest
        .resolution
        .as_ref()
        .map_or_else(String::new, |r| format!(" --resolution {}={r}", manifest.solver));
    format!(
        "The {solver} deck of case `{case}` ({case_file}), resolution {chosen} ({settings}),\n\
         written by spherecontact {version} (`spherecontact deck write`).\n\n\
         Files: {files}.\n\n\
         1. Run it, in this folder, wherever its program is installed (copy the whole folder; \
         where the program lies elsewhere than on this machine, edit its path in {RUN_SCRIPT}):\n\n\
         \x20   sh {RUN_SCRIPT}\n\n\
         \x20  which runs\n\n\
         \x20   {command} >{LOG_STEM}.stdout 2>{LOG_STEM}.stderr\n\n\
         \x20  (the same command as `spherecontact run --solver {solver}`; under a batch system, put \
         that line in the job script).\n\
         2. Bring the folder back, as it is, and read it where the case is:\n\n\
         \x20   spherecontact deck read {case_file} --solver {solver}{resolution} {dir} --out OUT\n\n\
         \x20  which checks {MANIFEST} (case, solver, resolution, scene) and the run's files, and \
         writes OUT/{solver}.csv, .json and .fields.csv as `spherecontact run` does.\n\
         3. To check and report them beside the other solvers, a case names the CSV as stored \
         results (`[[stored_results]]`, with a name of its own and `file` inside the case's folder \
         or an --allow-read folder): docs/external-decks.md, \"On a cluster\".\n",
        solver = manifest.solver,
        case = one_line(&manifest.case),
        case_file = one_line(&manifest.case_file),
        chosen = manifest.resolution.as_deref().map_or("default", |r| r),
        settings = manifest.settings,
        version = manifest.spherecontact,
        files = files.join(", "),
        command = manifest.command,
        dir = one_line(&out.display().to_string()),
    )
}

/// `text` on one line (control characters escaped), for the script's comments and the README.
fn one_line(text: &str) -> String {
    spherecontact_system::text::one_line(text).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_are_quoted_where_the_shell_would_split_them() {
        assert_eq!(quote("deck.edp"), "deck.edp");
        assert_eq!(quote("a b"), "'a b'");
        assert_eq!(quote("it's"), r"'it'\''s'");
        assert_eq!(quote(""), "''");
        let command = DeckCommand {
            program: "/usr/bin/FreeFem++".into(),
            args: vec!["-v".into(), "0".into(), "deck.edp".into()],
            env: vec![("OMP_NUM_THREADS".into(), "1".into())],
        };
        assert_eq!(
            command_line(&command),
            "OMP_NUM_THREADS=1 /usr/bin/FreeFem++ -v 0 deck.edp"
        );
    }

    #[test]
    fn the_first_differing_key_of_a_scene_is_named() {
        let a = serde_json::json!({"name": "x", "friction": 0.2, "path": [1, 2]});
        let b = serde_json::json!({"name": "x", "friction": 0.2, "path": [1, 3]});
        assert_eq!(first_difference(&a, &b).as_deref(), Some("path"));
        assert_eq!(first_difference(&a, &a), None);
    }
}
