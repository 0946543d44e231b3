//! Executing a plan: its runs proceed concurrently within a number of cores
//! ([`spherecontact_model::cores::within_cores`]), each taking the cores its solver declares
//! ([`spherecontact_model::solver::Solver::cores`], at most all of them), longest first by the plan's costs.
//! The results come back in plan order, whatever order the runs finished in, so what is printed
//! and written does not depend on the schedule.

use crate::baseline::Baselined;
use crate::plan::{Member, Plan, Run};
use crate::{self as case_run, CaseRun};
use spherecontact_check::judged::Suite;
use spherecontact_impact::solver_run::SolverRun;
use spherecontact_impact::ImpactRun;
use spherecontact_model::cores::{within_cores, Task};
use spherecontact_model::history::History;
use spherecontact_model::solver::SolveError;

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
            Member::Path(case) => Output::Path(case_run::run_solver(case, solver)),
            Member::Impact(case) => Output::Impact(spherecontact_impact::run::run_case(
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

/// Path cases run as `verify` runs them: every (case, solver) run of them in one plan,
/// concurrently within `cores` ([`execute_around`], costed by `recorded(case, solver)` where
/// known), each case judged: one [`CaseRun`] a case, in the given order, the same as
/// [`case_run::run_case`]'s whatever the cores (a case without solvers is judged on none).
pub fn run_cases(
    cases: Vec<spherecontact_case::Case>,
    cores: usize,
    recorded: impl Fn(&spherecontact_case::Case, &str) -> Option<f64>,
    around: &(dyn Fn(&Run, &dyn Fn() -> Output) -> Output + Sync),
) -> Vec<CaseRun> {
    // A case without solvers has no run in a plan ([`judge`] leaves it out): judged here.
    let mut planned = Vec::new();
    let slots: Vec<Option<CaseRun>> = cases
        .into_iter()
        .map(|case| match case.required_solvers().is_empty() {
            true => Some(case_run::judge(case, Vec::new())),
            false => {
                planned.push(Member::Path(case));
                None
            }
        })
        .collect();
    let plan = Plan::new(planned, |member, solver| match member {
        Member::Path(case) => recorded(case, solver),
        Member::Impact(_) => None,
    });
    let finished = execute_around(&plan, cores, around);
    let mut judged = judge(plan, finished).into_iter().map(|j| match j {
        Judged::Path(run) => run,
        Judged::Impact(_) => unreachable!("a plan of path cases judges path cases"),
    });
    slots
        .into_iter()
        .map(|slot| slot.unwrap_or_else(|| judged.next().expect("each planned case has runs, so is judged")))
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

    /// Its checks as the verification job lists them ([`spherecontact_check::judged`]).
    pub fn suite(&self) -> Suite {
        match self {
            Judged::Path(run) => crate::table::suite(run),
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
                Judged::Path(case_run::judge(case, histories))
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

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_case::Case;

    fn case(name: &str, solvers: &str) -> Case {
        let text = format!(
            "name = \"{name}\"\nfriction = 0.2\nsolvers = [{solvers}]\n[body1]\nradius = 0.1\nyoung = 70e9\n\
             poisson = 0.3\n[path]\nunit = \"um\"\ndelta_n = [0, 10, 10]\ndelta_t = [0, 0, 1]\nsubsteps = 2\n"
        );
        Case::parse(std::path::Path::new(&format!("{name}.toml")), &text).unwrap()
    }

    /// Requirement: cases run in one schedule come back one judged run a case, in the given
    /// order, each with the histories its own serial run gives (bit for bit: the same solvers on
    /// the same scenes).
    #[test]
    fn cases_in_one_schedule_come_back_in_order_as_their_serial_runs() {
        let cases = || {
            vec![
                case("a", "\"hertz\", \"mdr\""),
                case("b", "\"cattaneo-mindlin\""),
                case("c", "\"hertz\""),
            ]
        };
        let together = run_cases(cases(), 2, |_, _| None, &|_, solve| solve());
        let names: Vec<&str> = together.iter().map(|r| r.case.name()).collect();
        assert_eq!(names, ["a", "b", "c"]);
        for (run, case) in together.iter().zip(cases()) {
            let serial = case_run::run_case(case);
            let solvers: Vec<&String> = run.histories.keys().collect();
            assert_eq!(solvers, serial.histories.keys().collect::<Vec<_>>());
            for (name, history) in &run.histories {
                let (a, b) = (
                    history.as_ref().unwrap(),
                    serial.histories[name].as_ref().unwrap(),
                );
                assert_eq!(a.steps, b.steps, "{name}");
            }
        }
    }
}
