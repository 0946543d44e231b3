//! A solver an impact case defines itself (`[[stored_results]]`, `[[command_solvers]]`): the
//! user's own law or code, whose outcomes the harness reads (a stored sweep table, or the one a
//! program writes) instead of integrating them, and judges with the same checks against the
//! exact reference. Validated by `load_impact` (spherecontact-case); run by spherecontact-impact
//! (`own_run`); the sweep table's format is [`super::table`].

use std::path::PathBuf;
use std::time::Duration;

use spherecontact_model::solver::Kind;
use spherecontact_system::permission::CommandPermission;

/// A solver an impact case defines itself.
#[derive(Clone, Debug, PartialEq)]
pub struct OwnSolver {
    /// Its name in the case (a plain name: it names output files).
    pub name: String,
    /// The kind of model it is, as the case says (a DEM law is ranked beside the built-in ones).
    pub kind: Kind,
    /// The description shown in reports.
    pub description: String,
    /// Where its outcomes come from.
    pub source: Source,
}

/// Where an own solver's outcomes come from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// Sweep tables stored in files inside the case's tree: the prescribed variant's, and the
    /// elastic variant's for a case with e < 1 (without it, that variant is not available).
    Stored {
        /// The prescribed variant's table.
        prescribed: PathBuf,
        /// The elastic variant's table, if stored.
        elastic: Option<PathBuf>,
    },
    /// A program given the impact scene file of one variant, writing its sweep table.
    Command {
        /// The program and its arguments, placeholders not yet filled.
        command: Vec<String>,
        /// Wall-clock limit of one run (one variant).
        timeout: Duration,
        /// The case file's folder: `{case_dir}`, and the anchor of relative program paths.
        case_dir: PathBuf,
        /// Whether it may run (refused until the command line says so).
        permission: CommandPermission,
    },
}

impl OwnSolver {
    /// How it gives its results, in words: "a program" or "stored results".
    pub fn origin(&self) -> &'static str {
        match self.source {
            Source::Command { .. } => "a program",
            Source::Stored { .. } => "stored results",
        }
    }
}
