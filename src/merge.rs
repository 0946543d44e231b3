//! `spherecontact merge DIR...`: the run files of a sharded verification read back and put
//! together into one plan's finished runs, judged as one unsharded run would be.

use std::path::{Path, PathBuf};

use crate::case::ReadRoots;
use crate::plan::{CaseOptions, Member, Plan, PlanError};
use crate::runfile::{RunFile, FILE, FORMAT};
use crate::schedule::Finished;
use crate::text::one_line;

/// Why run files cannot be merged (bad input: exit code 2, nothing written).
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// No folder given.
    #[error("merge: no run folders (allowed: one or more folders written by `verify --out`)")]
    Nothing,
    /// A run file that cannot be read.
    #[error("{}: cannot read the run file: {error}", file.display())]
    Read { file: PathBuf, error: std::io::Error },
    /// A run file that is not one.
    #[error("{}: not a run file of format {FORMAT}: {error}", file.display())]
    Parse { file: PathBuf, error: String },
    /// Run files of different selections or options.
    #[error("{}: {what} differ from {}'s (allowed: shards of one `verify` command)", file.display(), first.display())]
    Mismatch {
        file: PathBuf,
        first: PathBuf,
        what: &'static str,
    },
    /// A run that no file holds.
    #[error(
        "merge: no run of solver `{}` for case {} (is a shard missing?)",
        one_line(solver),
        shown(case)
    )]
    Missing { case: PathBuf, solver: String },
    /// A run whose result is of the other kind than its case (an impact case's run for a path
    /// case, or the reverse: the case file changed since the shard ran).
    #[error("{}: run of solver `{}` for case {} holds {held} (allowed: the case's kind of run; was the case file changed?)", file.display(), one_line(solver), shown(case))]
    Kind {
        file: PathBuf,
        case: PathBuf,
        solver: String,
        held: &'static str,
    },
    /// A run that two files hold, or that the plan does not have.
    #[error("{}: run of solver `{}` for case {} {problem}", file.display(), one_line(solver), shown(case))]
    Extra {
        file: PathBuf,
        case: PathBuf,
        solver: String,
        problem: &'static str,
    },
    /// The cases cannot be read back.
    #[error(transparent)]
    Plan(#[from] PlanError),
}

/// A case file's name as a run file records it, on one line (src/text.rs).
fn shown(case: &Path) -> String {
    one_line(&case.display().to_string()).into_owned()
}

/// Reads `dir/run.json`: a regular file of [`FORMAT`].
fn read(dir: &Path) -> Result<RunFile, MergeError> {
    let file = dir.join(FILE);
    let read_error = |error| MergeError::Read {
        file: file.clone(),
        error,
    };
    if !std::fs::metadata(&file).map_err(read_error)?.is_file() {
        return Err(read_error(std::io::Error::other("not a regular file")));
    }
    let text = std::fs::read_to_string(&file).map_err(read_error)?;
    let parse = |error: String| MergeError::Parse {
        file: file.clone(),
        error,
    };
    let run: RunFile = serde_json::from_str(&text).map_err(|e| parse(e.to_string()))?;
    if run.format != FORMAT {
        return Err(parse(format!("format {}", run.format)));
    }
    Ok(run)
}

/// Run files put together.
pub struct Merged {
    /// The plan of every selected case.
    pub plan: Plan,
    /// Its finished runs, in plan order.
    pub finished: Vec<Finished>,
    /// Per run file, in the order given: its shard (`K/N`, or none) and the sum of its runs'
    /// wall times [s].
    pub shards: Vec<(Option<String>, f64)>,
}

/// The run files of `dirs` as one plan and its finished runs, in plan order. The case files
/// are read again (from the paths recorded, relative to the current folder) with the options
/// recorded; every run of the plan must be in exactly one file.
pub fn merge(dirs: &[PathBuf], roots: &ReadRoots) -> Result<Merged, MergeError> {
    let files = dirs.iter().map(|d| read(d)).collect::<Result<Vec<_>, _>>()?;
    let first = files.first().ok_or(MergeError::Nothing)?;
    for (dir, file) in dirs.iter().zip(&files) {
        let mismatch = |what| MergeError::Mismatch {
            file: dir.join(FILE),
            first: dirs[0].join(FILE),
            what,
        };
        if file.cases != first.cases {
            return Err(mismatch("the cases"));
        }
        if file.options != first.options {
            return Err(mismatch("the options (--ranks, --resolution)"));
        }
    }
    let case_files = first.cases.clone();
    let options = CaseOptions {
        roots: roots.clone(),
        ..first.options.clone()
    };
    let cases = case_files
        .iter()
        .map(|f| options.load_member(f))
        .collect::<Result<Vec<_>, _>>()?;
    let plan = Plan::new(cases, |_, _| None);
    let mut slots: Vec<Option<Finished>> = plan.runs.iter().map(|_| None).collect();
    let mut shards = Vec::new();
    for (dir, file) in dirs.iter().zip(files) {
        shards.push((file.shard, file.runs.iter().map(|r| r.wall_s).sum()));
        for record in file.runs {
            let extra = |problem| MergeError::Extra {
                file: dir.join(FILE),
                case: case_files.get(record.case).cloned().unwrap_or_default(),
                solver: record.solver.clone(),
                problem,
            };
            let slot = plan
                .runs
                .iter()
                .position(|r| r.case == record.case && r.solver == record.solver);
            match slot {
                None => return Err(extra("is not a run of the cases")),
                Some(i) if slots[i].is_some() => return Err(extra("is held by another run file too")),
                Some(_)
                    if record.result.is_impact() != matches!(plan.cases[record.case], Member::Impact(_)) =>
                {
                    return Err(MergeError::Kind {
                        file: dir.join(FILE),
                        case: case_files[record.case].clone(),
                        solver: record.solver.clone(),
                        held: if record.result.is_impact() {
                            "an impact run but the case is a path case"
                        } else {
                            "a path run but the case is an impact case"
                        },
                    })
                }
                Some(i) => {
                    slots[i] = Some(Finished {
                        result: record.result.into_output(),
                        wall_s: record.wall_s,
                        cores: record.cores,
                    })
                }
            }
        }
    }
    let finished = plan
        .runs
        .iter()
        .zip(slots)
        .map(|(run, slot)| {
            slot.ok_or_else(|| MergeError::Missing {
                case: case_files[run.case].clone(),
                solver: run.solver.clone(),
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(Merged {
        plan,
        finished,
        shards,
    })
}
