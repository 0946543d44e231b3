//! `deck write` and `deck read`: an external deck written into a folder to run elsewhere (a
//! cluster), and its finished run read back into the files `run` writes (docs/external-decks.md,
//! "On a cluster"). The arguments, the plan (the case read, the solver resolved to a deck, the
//! manifest the folder must carry; nothing written) and its execution.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Subcommand;
use spherecontact::case::{Case, ReadRoots};
use spherecontact::external::permission::CommandPermission;
use spherecontact::external::split::{self, FolderError, Manifest};
use spherecontact::report::history_files;
use spherecontact::solver::split::SplitDeck;
use spherecontact::solver::{SolveError, Solver};
use spherecontact::{io, registry, text};

use crate::{claim, load_case, resolution_options, InputError};

/// What `deck` does.
#[derive(Subcommand)]
pub(crate) enum DeckAction {
    /// Mesh a case and write everything a deck needs into DIR without running it, with run.sh
    /// (the command that runs it there), README.txt and manifest.json.
    Write {
        #[command(flatten)]
        deck: DeckOptions,
        /// MPI ranks run.sh starts (fenicsx-3d); default: the case's `ranks`.
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
        ranks: Option<u32>,
        /// Write into a folder that already holds files (those with the deck's names are
        /// replaced; the others, an earlier run's results among them, stay).
        #[arg(long)]
        force: bool,
    },
    /// Read a deck's finished run in DIR (checked against its manifest.json) into
    /// OUT/<solver>.csv, .json and .fields.csv, as `run` writes them.
    Read {
        #[command(flatten)]
        deck: DeckOptions,
        /// Output folder; default: DIR itself.
        #[arg(long, value_name = "OUT")]
        out: Option<PathBuf>,
        /// Write into an OUT that holds files spherecontact did not write.
        #[arg(long)]
        force: bool,
    },
}

/// The case, the deck and its folder: the same for writing and reading.
#[derive(clap::Args)]
pub(crate) struct DeckOptions {
    /// The case file.
    case: PathBuf,
    /// The deck: an external solver (`spherecontact list`) that can run elsewhere.
    #[arg(long, value_name = "NAME")]
    solver: String,
    /// The deck's folder.
    dir: PathBuf,
    /// The deck's resolution, over the case's `[resolution]`, e.g. freefem-axisym=c/20 (the
    /// same for writing and reading).
    #[arg(long = "resolution", value_name = "NAME=VALUE")]
    resolution: Vec<String>,
}

/// A deck command, validated: nothing is written yet.
struct Plan {
    case: Case,
    solver: Box<dyn Solver>,
    /// What the folder holds, or must hold.
    manifest: Manifest,
    dir: PathBuf,
}

impl Plan {
    /// Reads the case (with the command line's resolutions and ranks) and resolves the solver
    /// to a deck.
    fn new(options: DeckOptions, ranks: Option<u32>, roots: &ReadRoots) -> Result<Self, InputError> {
        let resolutions = resolution_options(&options.resolution)?;
        let case = load_case(
            &options.case,
            ranks,
            &resolutions,
            roots,
            &CommandPermission::refused(),
        )?;
        let name = options.solver.as_str();
        let solver = case
            .solver(name)
            .filter(|s| s.split_deck().is_some())
            .ok_or_else(|| not_a_deck(name))?;
        let deck = solver.split_deck().ok_or_else(|| not_a_deck(name))?;
        let chosen = case.resolution.get(name).map(String::as_str);
        let manifest = Manifest::new(&options.case, name, chosen, deck, &case.scene);
        Ok(Plan {
            case,
            solver,
            manifest,
            dir: options.dir,
        })
    }

    /// The deck (the solver is one: [`Plan::new`]).
    fn deck(&self) -> Result<&dyn SplitDeck, InputError> {
        self.solver
            .split_deck()
            .ok_or_else(|| not_a_deck(&self.manifest.solver))
    }
}

/// The error for a solver `name` that is not a deck.
fn not_a_deck(name: &str) -> InputError {
    InputError(format!(
        "--solver: `{}` is not a deck (allowed: {})",
        text::one_line(name),
        decks().join(", ")
    ))
}

/// The solvers of this build that are decks.
fn decks() -> Vec<String> {
    registry::registry()
        .iter()
        .filter(|s| s.split_deck().is_some())
        .map(|s| s.name().to_owned())
        .collect()
}

/// Runs `deck write` or `deck read`.
pub(crate) fn deck(action: DeckAction, roots: &ReadRoots) -> Result<ExitCode, InputError> {
    match action {
        DeckAction::Write { deck, ranks, force } => write(&Plan::new(deck, ranks, roots)?, force),
        DeckAction::Read { deck, out, force } => {
            let plan = Plan::new(deck, None, roots)?;
            let out = out.unwrap_or_else(|| plan.dir.clone());
            read(&plan, &out, force)
        }
    }
}

/// `deck write`: DIR claimed (and refused when it holds files, without `--force`), the deck
/// written into it.
fn write(plan: &Plan, force: bool) -> Result<ExitCode, InputError> {
    let dir = &plan.dir;
    if let Some(entry) = first_entry(dir).filter(|_| !force) {
        return Err(InputError(format!(
            "{}: refused: the folder already holds `{entry}` (allowed: a new or empty folder, so that \
             no earlier run's results are read back with this deck; --force writes there anyway)",
            dir.display()
        )));
    }
    let folder = claim(dir, force)?;
    let name = &plan.manifest.solver;
    match split::write_folder(plan.deck()?, &plan.case.scene, &plan.manifest, folder.path()) {
        Ok(files) => {
            outln!(
                "{name} deck of case {} written to {}: {}",
                plan.case.name(),
                dir.display(),
                files.join(", ")
            );
            outln!(
                "run it there: sh {} (README.txt), which runs",
                dir.join(split::RUN_SCRIPT).display()
            );
            outln!("  {}", plan.manifest.command);
            outln!(
                "then: spherecontact deck read {} --solver {name} {}",
                plan.manifest.case_file,
                dir.display()
            );
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => failure(name, "writing the deck", e),
    }
}

/// `deck read`: the folder's manifest checked, OUT claimed, the run read back and written.
fn read(plan: &Plan, out: &Path, force: bool) -> Result<ExitCode, InputError> {
    let dir = &plan.dir;
    if !dir.is_dir() {
        return Err(InputError(format!(
            "{}: not a folder (allowed: the folder `spherecontact deck write` wrote)",
            dir.display()
        )));
    }
    // The folder is read whole before OUT is claimed: a wrong folder or a failed read leaves
    // nothing written.
    let name = &plan.manifest.solver;
    let history = match split::read_folder(plan.deck()?, &plan.case.scene, &plan.manifest, dir) {
        Ok(history) => history,
        Err(FolderError::Run(e)) => return failure(name, &format!("reading {}", dir.display()), e),
        Err(e) => return Err(InputError(e.to_string())),
    };
    let folder = claim(out, force)?;
    history_files::write(folder.path(), &history)
        .map_err(|e| InputError(format!("--out {}: {e}", out.display())))?;
    for warning in &history.metadata.warnings {
        eprintln!("warning: {name}: {}", text::lines(warning));
    }
    outln!(
        "{name}: {} steps read back from {} into {}",
        history.steps.len(),
        dir.display(),
        out.join(format!("{name}.csv")).display()
    );
    Ok(ExitCode::SUCCESS)
}

/// A deck that cannot be written or read: bad input when the deck does not model the case
/// (exit 2), else printed as the solver's failure (exit 1).
fn failure(name: &str, doing: &str, e: SolveError) -> Result<ExitCode, InputError> {
    match e {
        SolveError::NotApplicable(why) => Err(InputError(format!("--solver {name}: not applicable: {why}"))),
        e => {
            eprintln!("error: {name}: {doing}: {}", text::lines(&e.to_string()));
            Ok(ExitCode::FAILURE)
        }
    }
}

/// The name of an entry of `dir` other than the output marker, if `dir` is a folder that holds
/// one.
fn first_entry(dir: &Path) -> Option<String> {
    std::fs::read_dir(dir)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .find(|name| name != io::MARKER)
}
