//! `spherecontact merge DIR...`: the run files of a sharded verification read back and put
//! together into one plan's finished runs, judged as one unsharded run would be; `compare
//! --from` and `reproduce-paper --from` read them the same way.
//!
//! A run file is a file from elsewhere (a shard comes back from a cluster, a folder from a
//! colleague or an earlier job), so before any verdict it must prove what it is
//! ([`crate::runfile`]): read by [`spherecontact_system::input::foreign`]'s rule, written by this harness, its
//! case files the same bytes as those its runs were made of (their SHA-256, checked before a case
//! file is parsed: a run file that names another file learns nothing of it), the same paths, and
//! every stored history on its case's path as a live run's must be ([`spherecontact_model::solver::validate`]):
//! a history cut to one row, another path's values or a stale shard are refused, never judged.

use std::path::{Path, PathBuf};

use crate::plan::{CaseOptions, Member, Plan, PlanError};
use crate::runfile::{self, CaseRecord, RunFile, RunResult, FILE, FORMAT, HARNESS, MAX_RUN_FILE_BYTES};
use crate::schedule::Finished;
use spherecontact_case::ReadRoots;
use spherecontact_impact::solver_run::SolverRun;
use spherecontact_reference::impact::problem::ImpactCase;
use spherecontact_system::input::foreign::{self, ForeignError};
use spherecontact_system::text::one_line;

/// Why run files cannot be merged (bad input: exit code 2, nothing written).
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// No folder given.
    #[error("merge: no run folders (allowed: one or more folders written by `verify --out`)")]
    Nothing,
    /// A run file that cannot be read or is not one.
    #[error("{0}")]
    Foreign(#[from] ForeignError),
    /// A run file of another harness, or whose cases are not the files it names now.
    #[error("{}: {problem} (allowed: a run file of {HARNESS} over the case files as they are: run `verify --out` again)", file.display())]
    Provenance { file: PathBuf, problem: String },
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
    /// A run whose result does not fit its case: of the other kind (an impact case's run for a
    /// path case, or the reverse), or a history off the case's path.
    #[error("{}: run of solver `{}` for case {}: {problem} (allowed: a run of the case as it is: was the case file changed?)", file.display(), one_line(solver), shown(case))]
    Unfit {
        file: PathBuf,
        case: PathBuf,
        solver: String,
        problem: String,
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

/// A case file's name as a run file records it, on one line (crates/system/src/text.rs).
fn shown(case: &Path) -> String {
    one_line(&case.display().to_string()).into_owned()
}

/// Reads `dir/run.json`: a file from elsewhere of [`FORMAT`], written by [`HARNESS`].
fn read(dir: &Path) -> Result<RunFile, MergeError> {
    let file = dir.join(FILE);
    let text = foreign::read_text(&file, MAX_RUN_FILE_BYTES)?;
    #[derive(serde::Deserialize)]
    struct Header {
        format: u32,
        harness: Option<String>,
    }
    let form = "a run file written by `spherecontact verify --out`";
    let header: Header = foreign::parse_json(&file, &text, form)?;
    let provenance = |problem: String| MergeError::Provenance {
        file: file.clone(),
        problem,
    };
    if header.format != FORMAT {
        return Err(provenance(format!(
            "format {} (allowed: {FORMAT})",
            header.format
        )));
    }
    if header.harness.as_deref() != Some(HARNESS) {
        return Err(provenance("written by another version of the harness".into()));
    }
    Ok(foreign::parse_json(&file, &text, form)?)
}

/// Run files put together.
pub struct Merged {
    /// The plan of every selected case.
    pub plan: Plan,
    /// The options the cases were read with.
    pub options: CaseOptions,
    /// Its finished runs, in plan order.
    pub finished: Vec<Finished>,
    /// Per run file, in the order given: its shard (`K/N`, or none) and the sum of its runs'
    /// wall times [s].
    pub shards: Vec<(Option<String>, f64)>,
}

/// The run files of `dirs` as one plan and its finished runs, in plan order. The case files
/// are read again (from the paths recorded, relative to the current folder) with the options
/// recorded, each checked against its digests; every run of the plan must be in exactly one
/// file, and fit its case.
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
    let records = first.cases.clone();
    let case_files: Vec<PathBuf> = records.iter().map(|r| r.file.clone()).collect();
    let recorded_options = first.options.clone();
    let options = CaseOptions {
        roots: roots.clone(),
        ..recorded_options.clone()
    };
    let run_file = dirs[0].join(FILE);
    let cases = records
        .iter()
        .enumerate()
        .map(|(k, record)| load_recorded(&run_file, k, record, &options))
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
                Some(i) => {
                    let fitting = timings_fit(&record)
                        .and_then(|()| fits(&record.result, &plan.cases[record.case], &record.solver));
                    if let Err(problem) = fitting {
                        return Err(MergeError::Unfit {
                            file: dir.join(FILE),
                            case: case_files[record.case].clone(),
                            solver: record.solver.clone(),
                            problem,
                        });
                    }
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
        options: recorded_options,
        finished,
        shards,
    })
}

/// The `k`-th case of the run file `run_file`, read from the file its `record` names: a `.toml`
/// file whose bytes have the recorded SHA-256 (checked before it is parsed), whose path has the
/// recorded digest.
fn load_recorded(
    run_file: &Path,
    k: usize,
    record: &CaseRecord,
    options: &CaseOptions,
) -> Result<Member, MergeError> {
    let shown = shown(&record.file);
    let provenance = |problem: String| MergeError::Provenance {
        file: run_file.to_path_buf(),
        problem: format!("cases[{k}] (`{shown}`): {problem}"),
    };
    if record.file.extension().is_none_or(|e| e != "toml") {
        return Err(provenance(
            "not a case file's name (allowed: a .toml file)".into(),
        ));
    }
    let text = spherecontact_system::input::read_text(&record.file)
        .map_err(|e| provenance(format!("cannot read the case file: {e}")))?;
    if runfile::digest(text.as_bytes()) != record.digest {
        return Err(provenance(
            "the case file is not the one its runs were made of (its SHA-256 differs: the case was edited \
             since, or the run file names another file)"
                .into(),
        ));
    }
    let case = options.parse_member(&record.file, &text)?;
    if runfile::path_digest(&case) != record.path_digest {
        return Err(provenance("its path is not the one its runs followed".into()));
    }
    Ok(case)
}

/// Whether a run's record keeps a run's bounds: finite, non-negative times (their sums are
/// printed and become costs) and at least one core.
fn timings_fit(record: &runfile::RunRecord) -> Result<(), String> {
    let time = |t: f64| t.is_finite() && (0.0..=MAX_RUN_SECONDS).contains(&t);
    if time(record.wall_s) && time(record.cost_s) && record.cores >= 1 {
        Ok(())
    } else {
        Err(format!(
            "its wall_s, cost_s or cores is not a run's (allowed: 0 to {MAX_RUN_SECONDS:e} s, at least one core)"
        ))
    }
}

/// The longest run a run file may record [s]: a year, far beyond any timeout, so that the sums of
/// a merge's times stay finite.
const MAX_RUN_SECONDS: f64 = 3.2e7;

/// Whether the stored `result` of `solver` fits `case`: a path run for a path case, its history
/// on the case's path ([`spherecontact_model::solver::validate`]); an impact run for an impact case, each
/// sweep on the case's points. Why not, else.
fn fits(result: &RunResult, case: &Member, solver: &str) -> Result<(), String> {
    match (result, case) {
        (RunResult::Impact(runs), Member::Impact(case)) => impact_fits(runs, case, solver),
        (RunResult::Impact(_), Member::Path(_)) => Err("an impact run but the case is a path case".into()),
        (_, Member::Impact(_)) => Err("a path run but the case is an impact case".into()),
        (RunResult::History(history), Member::Path(case)) => {
            spherecontact_model::solver::validate(history, &case.scene.steps())
                .map_err(|why| format!("its history: {why}"))
        }
        (RunResult::NotApplicable(_) | RunResult::Unavailable(_) | RunResult::Failed(_), Member::Path(_)) => {
            Ok(())
        }
    }
}

/// Whether the stored impact `runs` of `solver` are sweeps of `case`: each of this solver, in
/// one of the case's variants (once each), over the case's sweep points (their values bit for
/// bit) with finite outcomes.
fn impact_fits(runs: &[SolverRun], case: &ImpactCase, solver: &str) -> Result<(), String> {
    let (points, variants) = (case.points(), case.variants());
    for (k, run) in runs.iter().enumerate() {
        if run.solver != solver {
            return Err(format!("its sweep {k} is another solver's"));
        }
        if !variants.contains(&run.variant) || runs[..k].iter().any(|r| r.variant == run.variant) {
            return Err(format!("its sweep {k} is not one of the case's variants, once"));
        }
        if run.points.len() != points.len() && run.unavailable.is_none() {
            return Err(format!(
                "its sweep {k} has {} points for the case's {}",
                run.points.len(),
                points.len()
            ));
        }
        for (j, ((value, outcome), point)) in run.points.iter().zip(&points).enumerate() {
            if value.map(f64::to_bits) != point.value.map(f64::to_bits) {
                return Err(format!("its sweep {k}'s point {j} is not the case's"));
            }
            if outcome.as_ref().is_ok_and(|o| !o.is_finite()) || !run.wall_time_s.is_finite() {
                return Err(format!("its sweep {k}'s point {j} holds a non-finite value"));
            }
        }
    }
    Ok(())
}
