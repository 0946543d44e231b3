//! The run file `DIR/run.json` that `verify --out DIR` writes: the cases selected (all of them,
//! also in a shard), the options they were read with, and each finished run with its history
//! (bit for bit: serde_json's `float_roundtrip`) or why it has none. `merge` reads run files
//! back ([`crate::merge`]).
//!
//! ```json
//! {"format": 1, "shard": "2/3", "cases": ["cases/cattaneo.toml", …],
//!  "options": {"ranks": null, "resolutions": [["bem", "128"]]},
//!  "runs": [{"case": 0, "solver": "bem", "cores": 2, "cost_s": 3.0, "wall_s": 2.41,
//!            "result": {"history": {…}}}, {"case": 0, "solver": "yade-mindlin", …,
//!            "result": {"unavailable": "yade not found"}},
//!           {"case": 5, "solver": "mdr", …, "result": {"impact": [{"solver": "mdr",
//!            "variant": "prescribed", "points": [[0.0873, {"Ok": {"values": […]}}], …], …}]}}]}
//! ```

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::history::History;
use crate::impact::run::SolverRun;
use crate::plan::{CaseOptions, Plan, Shard};
use crate::schedule::{Finished, Output};
use crate::solver::SolveError;

/// The run file's name in its folder.
pub const FILE: &str = "run.json";

/// The format written; a reader refuses any other.
pub const FORMAT: u32 = 1;

/// A verification run's (or one shard's) finished runs.
#[derive(Debug, Serialize, Deserialize)]
pub struct RunFile {
    /// [`FORMAT`].
    pub format: u32,
    /// `K/N` for a shard; `None` for a whole run or a merge.
    pub shard: Option<String>,
    /// Every case file selected, in the plan's order.
    pub cases: Vec<PathBuf>,
    /// The options the cases were read with.
    pub options: CaseOptions,
    /// The finished runs of this file.
    pub runs: Vec<RunRecord>,
}

/// One finished run.
#[derive(Debug, Serialize, Deserialize)]
pub struct RunRecord {
    /// The case's index in [`RunFile::cases`].
    pub case: usize,
    /// The solver.
    pub solver: String,
    /// The cores the schedule gave it.
    pub cores: usize,
    /// Its expected wall time in the plan [s].
    pub cost_s: f64,
    /// Its wall time [s].
    pub wall_s: f64,
    /// Its history, or why it has none.
    pub result: RunResult,
}

/// A run's result as stored: a [`SolveError`] kept by kind and message; an impact case's run
/// as its sweep in each variant (without the trace).
#[derive(Debug, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunResult {
    /// The history.
    History(History),
    /// [`SolveError::NotApplicable`].
    NotApplicable(String),
    /// [`SolveError::Unavailable`].
    Unavailable(String),
    /// [`SolveError::Failed`].
    Failed(String),
    /// An impact case's run ([`Output::Impact`]).
    Impact(Vec<SolverRun>),
}

impl RunResult {
    fn of(result: &Output) -> Self {
        match result {
            Output::Path(Ok(history)) => RunResult::History(history.clone()),
            Output::Path(Err(SolveError::NotApplicable(m))) => RunResult::NotApplicable(m.clone()),
            Output::Path(Err(SolveError::Unavailable(m))) => RunResult::Unavailable(m.clone()),
            Output::Path(Err(SolveError::Failed(m))) => RunResult::Failed(m.clone()),
            Output::Impact(runs) => RunResult::Impact(runs.clone()),
        }
    }

    /// True for an impact case's run.
    pub fn is_impact(&self) -> bool {
        matches!(self, RunResult::Impact(_))
    }

    /// The output it stores.
    pub fn into_output(self) -> Output {
        match self {
            RunResult::History(history) => Output::Path(Ok(history)),
            RunResult::NotApplicable(m) => Output::Path(Err(SolveError::NotApplicable(m))),
            RunResult::Unavailable(m) => Output::Path(Err(SolveError::Unavailable(m))),
            RunResult::Failed(m) => Output::Path(Err(SolveError::Failed(m))),
            RunResult::Impact(runs) => Output::Impact(runs),
        }
    }
}

impl RunFile {
    /// The run file of `plan`'s finished runs, its cases read from `files` with `options`.
    pub fn new(
        plan: &Plan,
        finished: &[Finished],
        files: Vec<PathBuf>,
        options: CaseOptions,
        shard: Option<Shard>,
    ) -> Self {
        let runs = plan
            .runs
            .iter()
            .zip(finished)
            .map(|(run, done)| RunRecord {
                case: run.case,
                solver: run.solver.clone(),
                cores: done.cores,
                cost_s: run.cost_s,
                wall_s: done.wall_s,
                result: RunResult::of(&done.result),
            })
            .collect();
        RunFile {
            format: FORMAT,
            shard: shard.map(|s| s.to_string()),
            cases: files,
            options,
            runs,
        }
    }

    /// Writes `dir/run.json` atomically (`dir` is created if missing).
    pub fn write(&self, dir: &Path) -> std::io::Result<()> {
        std::fs::create_dir_all(dir)?;
        let json = serde_json::to_string(self).map_err(std::io::Error::other)?;
        crate::io::write_atomically(&dir.join(FILE), json.as_bytes())
    }
}
