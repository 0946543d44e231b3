//! The run file `DIR/run.json` that `verify --out DIR` writes: the harness that wrote it, the
//! cases selected (all of them, also in a shard) with the digests of their files and paths, the
//! options they were read with, and each finished run with its history (bit for bit:
//! serde_json's `float_roundtrip`) or why it has none. `merge` and `--from` read run files back
//! ([`crate::merge`]): a run file is a file from elsewhere (a shard comes back from a cluster),
//! so it proves what it is before any of its runs is judged — the same harness, the same case
//! files byte for byte, the same paths, and every history on its case's path.
//!
//! ```json
//! {"format": 2, "harness": "spherecontact 0.1.0", "shard": "2/3",
//!  "cases": [{"file": "cases/cattaneo.toml", "digest": "sha256:…", "path_digest": "sha256:…"}, …],
//!  "options": {"ranks": null, "resolutions": [["bem", "128"]]},
//!  "runs": [{"case": 0, "solver": "bem", "cores": 2, "cost_s": 3.0, "wall_s": 2.41,
//!            "result": {"history": {…}}}, {"case": 0, "solver": "yade-mindlin", …,
//!            "result": {"unavailable": "yade not found"}},
//!           {"case": 5, "solver": "mdr", …, "result": {"impact": [{"solver": "mdr",
//!            "variant": "prescribed", "points": [[0.0873, {"Ok": {"values": […]}}], …], …}]}}]}
//! ```

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::plan::{CaseOptions, Member, Plan, Shard};
use crate::schedule::{Finished, Output};
use spherecontact_impact::solver_run::SolverRun;
use spherecontact_model::history::History;
use spherecontact_model::solver::SolveError;

/// The run file's name in its folder.
pub const FILE: &str = "run.json";

/// The format written; a reader refuses any other.
pub const FORMAT: u32 = 2;

/// The harness that writes and reads run files: a run file of another version is refused (its
/// solvers and checks may differ).
pub const HARNESS: &str = concat!("spherecontact ", env!("CARGO_PKG_VERSION"));

/// The largest run file read [bytes] (1 GiB): the CI job's run of every shipped case is 24 MB
/// (measured: `verify --out` of `cases/`), most of it the surface fields of the paper case's
/// runs; the longest path allowed (a million increments) makes a history of some 150 MB of JSON,
/// so a few such runs fit. It is read whole and parsed in memory (about twice its size).
pub const MAX_RUN_FILE_BYTES: u64 = 1 << 30;

/// A verification run's (or one shard's) finished runs.
#[derive(Debug, Serialize, Deserialize)]
pub struct RunFile {
    /// [`FORMAT`].
    pub format: u32,
    /// [`HARNESS`].
    pub harness: String,
    /// `K/N` for a shard; `None` for a whole run or a merge.
    pub shard: Option<String>,
    /// Every case selected, in the plan's order.
    pub cases: Vec<CaseRecord>,
    /// The options the cases were read with.
    pub options: CaseOptions,
    /// The finished runs of this file.
    pub runs: Vec<RunRecord>,
}

/// A case of a run file: its file and what its runs followed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseRecord {
    /// The case file, as the command line named it (relative to the folder `verify` ran in).
    pub file: PathBuf,
    /// The SHA-256 of the case file's bytes as they were read ([`digest`]).
    pub digest: String,
    /// The SHA-256 of what its runs followed ([`path_digest`]).
    pub path_digest: String,
}

impl CaseRecord {
    /// The record of `case`, read from `file` whose bytes were `text`.
    pub fn new(file: PathBuf, text: &str, case: &Member) -> Self {
        CaseRecord {
            file,
            digest: digest(text.as_bytes()),
            path_digest: path_digest(case),
        }
    }
}

/// `sha256:` and the SHA-256 of `bytes` in hexadecimal.
pub fn digest(bytes: &[u8]) -> String {
    use sha2::Digest;
    let hash = sha2::Sha256::digest(bytes);
    let hex: String = hash.iter().map(|b| format!("{b:02x}")).collect();
    format!("sha256:{hex}")
}

/// The [`digest`] of what `case`'s runs follow, bit for bit: a path case's steps (index,
/// position, δn, δt), an impact case's sweep points (value, bodies, restitution) with its steps
/// per contact and springs.
pub fn path_digest(case: &Member) -> String {
    let mut bytes = Vec::new();
    let mut number = |x: f64| bytes.extend(x.to_bits().to_le_bytes());
    match case {
        Member::Path(case) => {
            for step in case.scene.steps() {
                number(step.index as f64);
                number(step.position.map_or(-1.0, |p| p as f64));
                number(step.delta_n);
                number(step.delta_t);
            }
        }
        Member::Impact(case) => {
            number(case.steps as f64);
            number(case.springs as f64);
            for point in case.points() {
                number(point.value.unwrap_or(f64::NAN));
                for body in [&point.body1, &point.body2] {
                    number(body.density.unwrap_or(-1.0));
                    body.velocity.iter().chain([&body.spin]).for_each(|&v| number(v));
                }
                number(point.restitution);
            }
        }
    }
    digest(&bytes)
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
        files: Vec<CaseRecord>,
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
            harness: HARNESS.to_owned(),
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
        spherecontact_system::io::write_atomically(&dir.join(FILE), json.as_bytes())
    }
}
