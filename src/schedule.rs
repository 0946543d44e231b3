//! Executing a plan: its runs proceed concurrently within a number of cores, each taking the
//! cores its solver declares ([`crate::solver::Solver::cores`], at most all of them), longest
//! first ([`crate::plan::longest_first`]); a run whose cores are not free waits, and those after it
//! wait too (no run overtakes a longer one, so the long ones are never starved).
//!
//! A run gets exactly the cores it was given: it runs inside [`team::with_threads`], so the
//! BEM's team has two threads only when the schedule gave it two cores, and one otherwise
//! (`--jobs 1`, or a solver declaring one core). The results come back in plan order, whatever
//! order the runs finished in, so what is printed and written does not depend on the schedule.

use std::sync::mpsc;
use std::time::Instant;

use crate::baseline::Baselined;
use crate::history::History;
use crate::impact::run::SolverRun;
use crate::impact::ImpactRun;
use crate::judged::Suite;
use crate::plan::{longest_first, Member, Plan};
use crate::solver::SolveError;
use crate::team;
use crate::verify::{self, CaseRun};

/// What a run gives: a path case's solver history (or why it has none), or an impact case's
/// solver over the sweep in each variant (a failed sweep point says why within).
#[derive(Debug)]
pub enum Output {
    /// A path case's run.
    Path(Result<History, SolveError>),
    /// An impact case's run: one per variant (prescribed, and elastic when e < 1).
    Impact(Vec<SolverRun>),
}

impl Output {
    /// Runs `solver` of `case`.
    pub fn of(case: &Member, solver: &str) -> Self {
        match case {
            Member::Path(case) => Output::Path(verify::run_solver(case, solver)),
            Member::Impact(case) => Output::Impact(crate::impact::run::run_case(
                case,
                std::slice::from_ref(&solver.to_owned()),
            )),
        }
    }
}

/// A finished run.
#[derive(Debug)]
pub struct Finished {
    /// What the solver gave.
    pub result: Output,
    /// The run's wall time [s], set-up and read-back included.
    pub wall_s: f64,
    /// The cores it was given.
    pub cores: usize,
}

/// The cores of this machine, the default of `verify --jobs`.
pub fn machine_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Runs every run of `plan` within `cores` cores; the results in plan order.
pub fn execute(plan: &Plan, cores: usize) -> Vec<Finished> {
    let cores = cores.max(1);
    let mut finished: Vec<Option<Finished>> = plan.runs.iter().map(|_| None).collect();
    std::thread::scope(|scope| {
        let (sender, receiver) = mpsc::channel();
        let (mut free, mut running) = (cores, 0);
        let mut queue = longest_first(&plan.runs).into_iter().peekable();
        loop {
            while let Some(&index) = queue.peek() {
                let run = &plan.runs[index];
                let given = run.cores.clamp(1, cores);
                if given > free {
                    break;
                }
                queue.next();
                (free, running) = (free - given, running + 1);
                let sender = sender.clone();
                let case = &plan.cases[run.case];
                scope.spawn(move || {
                    let start = Instant::now();
                    let result = team::with_threads(given, || Output::of(case, &run.solver));
                    let wall_s = start.elapsed().as_secs_f64();
                    // The receiver lives until every run has reported.
                    let _ = sender.send((
                        index,
                        Finished {
                            result,
                            wall_s,
                            cores: given,
                        },
                    ));
                });
            }
            if running == 0 {
                break;
            }
            // `solver::run` turns a solver's panic into its failure, so every run reports.
            let (index, done) = receiver.recv().expect("a running run reports before it ends");
            (free, running) = (free + done.cores, running - 1);
            finished[index] = Some(done);
        }
    });
    finished
        .into_iter()
        .map(|f| f.expect("every run of the plan was started and reported"))
        .collect()
}

/// A case judged on its finished runs.
#[derive(Debug)]
pub enum Judged {
    /// A path case.
    Path(CaseRun),
    /// An impact case.
    Impact(ImpactRun),
}

impl Judged {
    /// The case as its baseline sees it.
    pub fn baselined(&self) -> &dyn Baselined {
        match self {
            Judged::Path(run) => run,
            Judged::Impact(run) => run,
        }
    }

    /// The case as its baseline compares it.
    pub fn baselined_mut(&mut self) -> &mut dyn Baselined {
        match self {
            Judged::Path(run) => run,
            Judged::Impact(run) => run,
        }
    }

    /// Its checks as the verification job lists them ([`crate::judged`]).
    pub fn suite(&self) -> Suite {
        match self {
            Judged::Path(run) => crate::report::table::suite(run),
            Judged::Impact(run) => run.suite(),
        }
    }
}

/// The cases of `plan` that have runs, each judged on its finished runs (in plan order). A
/// run's output of the other kind than its case's (which a merge refuses before) is no run.
pub fn judge(plan: Plan, finished: Vec<Finished>) -> Vec<Judged> {
    let mut results: Vec<Vec<_>> = plan.cases.iter().map(|_| Vec::new()).collect();
    for (run, done) in plan.runs.into_iter().zip(finished) {
        results[run.case].push((run.solver, done.result));
    }
    plan.cases
        .into_iter()
        .zip(results)
        .filter(|(_, results)| !results.is_empty())
        .map(|(case, results)| match case {
            Member::Path(case) => {
                let histories = results
                    .into_iter()
                    .filter_map(|(solver, output)| match output {
                        Output::Path(result) => Some((solver, result)),
                        Output::Impact(_) => None,
                    })
                    .collect();
                Judged::Path(verify::judge(case, histories))
            }
            Member::Impact(case) => {
                let runs = results
                    .into_iter()
                    .flat_map(|(_, output)| match output {
                        Output::Impact(runs) => runs,
                        Output::Path(_) => Vec::new(),
                    })
                    .collect();
                Judged::Impact(ImpactRun::judged(case, runs))
            }
        })
        .collect()
}
