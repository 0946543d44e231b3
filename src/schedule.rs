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

use crate::history::History;
use crate::plan::{longest_first, Plan};
use crate::solver::SolveError;
use crate::team;
use crate::verify::{self, CaseRun};

/// A finished run.
#[derive(Debug)]
pub struct Finished {
    /// The solver's history, or why it has none.
    pub result: Result<History, SolveError>,
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
                    let result = team::with_threads(given, || verify::run_solver(case, &run.solver));
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

/// The cases of `plan` that have runs, each judged on its finished runs (in plan order).
pub fn judge(plan: Plan, finished: Vec<Finished>) -> Vec<CaseRun> {
    let mut results: Vec<Vec<_>> = plan.cases.iter().map(|_| Vec::new()).collect();
    for (run, done) in plan.runs.into_iter().zip(finished) {
        results[run.case].push((run.solver, done.result));
    }
    plan.cases
        .into_iter()
        .zip(results)
        .filter(|(_, results)| !results.is_empty())
        .map(|(case, results)| verify::judge(case, results))
        .collect()
}
