//! Executing a plan: its runs proceed concurrently within a number of cores
//! ([`crate::cores::within_cores`]), each taking the cores its solver declares
//! ([`crate::solver::Solver::cores`], at most all of them), longest first by the plan's costs.
//! The results come back in plan order, whatever order the runs finished in, so what is printed
//! and written does not depend on the schedule.

use crate::baseline::Baselined;
use crate::cores::{within_cores, Task};
use crate::history::History;
use crate::impact::run::SolverRun;
use crate::impact::ImpactRun;
use crate::judged::Suite;
use crate::plan::{Member, Plan, Run};
use crate::solver::SolveError;
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

/// Runs every run of `plan` within `cores` cores; the results in plan order.
pub fn execute(plan: &Plan, cores: usize) -> Vec<Finished> {
    execute_around(plan, cores, &|_, solve| solve())
}

/// [`execute`], each run inside `around(run, solve)` (e.g. to show it on a progress bar):
/// `around` calls `solve` once and returns what it gives.
pub fn execute_around(
    plan: &Plan,
    cores: usize,
    around: &(dyn Fn(&Run, &dyn Fn() -> Output) -> Output + Sync),
) -> Vec<Finished> {
    let tasks: Vec<Task> = plan
        .runs
        .iter()
        .map(|run| Task::new(run.cores, run.cost_s))
        .collect();
    within_cores(&tasks, cores, |index| {
        let run = &plan.runs[index];
        around(run, &|| Output::of(&plan.cases[run.case], &run.solver))
    })
    .into_iter()
    .map(|(result, wall_s, cores)| Finished {
        result,
        wall_s,
        cores,
    })
    .collect()
}

/// A path case run as `verify` runs it ([`execute_around`] over its solvers, costed by
/// `recorded(solver)` where known), judged: the same [`CaseRun`] as
/// [`verify::run_case`]'s, whatever the cores.
pub fn run_case(
    case: crate::case::Case,
    cores: usize,
    recorded: impl Fn(&str) -> Option<f64>,
    around: &(dyn Fn(&Run, &dyn Fn() -> Output) -> Output + Sync),
) -> CaseRun {
    if case.required_solvers().is_empty() {
        return verify::judge(case, Vec::new());
    }
    let plan = Plan::new(vec![Member::Path(case)], |_, solver| recorded(solver));
    let finished = execute_around(&plan, cores, around);
    match judge(plan, finished).pop() {
        Some(Judged::Path(run)) => run,
        _ => unreachable!("a plan of one path case with runs judges one path case"),
    }
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
