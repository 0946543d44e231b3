//! Decks written and read apart: a deck that runs elsewhere (a cluster, another machine, by
//! hand) is written into a folder by one command and its finished run read back by another
//! (`spherecontact deck write|read`; the folder, its manifest and its README:
//! `split` (spherecontact-external)). The solver's own run is the same two halves with the launch
//! between them, so the files a written folder holds are those the solver runs.
//!
//! A deck takes part by implementing [`SplitDeck`] and answering [`Solver::split_deck`] with
//! `Some(self)`: the command line finds it by solver name, through the case (its resolution,
//! ranks and settings).
//!
//! [`Solver::split_deck`]: super::Solver::split_deck

use std::path::{Path, PathBuf};

use super::SolveError;
use crate::history::History;
use crate::scene::Scene;

/// The program that runs a written deck in its folder: as the solver's own run starts it.
#[derive(Clone, Debug, PartialEq)]
pub struct DeckCommand {
    /// The executable (a name on PATH, or the path found on this machine).
    pub program: PathBuf,
    /// Its arguments (the deck file by its name in the folder).
    pub args: Vec<String>,
    /// The variables it runs with, besides the inherited environment.
    pub env: Vec<(String, String)>,
}

/// A deck that can be written into a folder without running it, and read back from the folder
/// once it ran there.
pub trait SplitDeck: Send + Sync {
    /// What decides the deck's files besides the scene (the pole element size, the solver's
    /// settings): recorded in the folder's manifest and compared when the folder is read back.
    fn settings(&self, scene: &Scene) -> serde_json::Value;

    /// The command that runs the written deck in its folder.
    fn command(&self) -> DeckCommand;

    /// Meshes `scene` and writes everything the deck needs into the existing folder `dir`,
    /// without running it. `NotApplicable` for a scene the deck does not model; `Unavailable`
    /// when the mesher is missing.
    fn write_run(&self, scene: &Scene, dir: &Path) -> Result<(), SolveError>;

    /// The history of the run the deck finished in `dir`, read back as after the solver's own
    /// run (the files checked against `scene`'s path and each other); writes nothing into
    /// `dir`. Missing or garbage output is a `Failed` naming the file.
    fn read_run(&self, scene: &Scene, dir: &Path) -> Result<History, SolveError>;
}
