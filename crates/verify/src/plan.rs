//! A verification plan: the unit of work is one run, a (case, solver) pair with its cost and the
//! cores it takes; a plan is the runs of the cases selected by label, cut into balanced shards
//! when asked, and ordered for a schedule ([`crate::schedule`]).
//!
//! Nothing here runs a solver: a plan is built and checked first, then executed.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use spherecontact_case::labels;
use spherecontact_case::{Case, ReadRoots};
use spherecontact_external::permission::CommandPermission;
use spherecontact_model::cores::longest_first;
use spherecontact_reference::impact::problem::ImpactCase;

/// Why a plan cannot be made (bad command-line input: exit code 2, nothing written).
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// A `--label` or `--skip-label` that is not a known label.
    #[error("{option} {label}: unknown label (allowed: {allowed})", allowed = labels::allowed())]
    UnknownLabel { option: &'static str, label: String },
    /// A `--shard` that is not K/N with 1 ≤ K ≤ N ≤ [`MAX_SHARDS`].
    #[error("--shard {0}: not a shard (allowed: K/N with 1 ≤ K ≤ N ≤ {MAX_SHARDS}, e.g. 2/3)")]
    Shard(String),
    /// A case file that is not valid (boxed: a located error is large).
    #[error(transparent)]
    Case(Box<spherecontact_case::CaseError>),
    /// A `--resolution` that a case's solver does not accept.
    #[error("--resolution {name}={value} (case {}): {error}", case.display())]
    Resolution {
        name: String,
        value: String,
        case: PathBuf,
        error: Box<spherecontact_model::resolution::ResolutionError>,
    },
    /// A case folder that cannot be listed.
    #[error(transparent)]
    List(#[from] spherecontact_case::ListError),
}

impl From<spherecontact_case::CaseError> for PlanError {
    fn from(error: spherecontact_case::CaseError) -> Self {
        PlanError::Case(Box::new(error))
    }
}

/// The most shards a run may be cut into.
pub const MAX_SHARDS: usize = 1000;

/// The command line's choices that change a case as read: MPI ranks and resolutions over the
/// case's own (a run file records them, so that a merge reads the cases back the same).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CaseOptions {
    /// `--ranks`: MPI ranks over each case's `ranks`.
    pub ranks: Option<u32>,
    /// `--resolution SOLVER=VALUE`, split, each solver once.
    pub resolutions: Vec<(String, String)>,
    /// The folders beyond its own tree that a case may read (`--allow-read`): not recorded in a
    /// run file (a merge is given its own).
    #[serde(skip)]
    pub roots: ReadRoots,
    /// Whether the cases' command solvers may run: not recorded (a merge runs nothing).
    #[serde(skip)]
    pub permission: CommandPermission,
}

impl CaseOptions {
    /// The solvers whose resolution the command line chose (`--resolution`): their values are
    /// not compared with the baselines, which belong to the cases' own resolutions.
    pub fn chosen_solvers(&self) -> Vec<String> {
        self.resolutions.iter().map(|(name, _)| name.clone()).collect()
    }

    /// Loads the case at `file`, a path case with these options over its own or an impact case
    /// (whose steps and springs are its own: `--ranks` and `--resolution` do not apply).
    pub fn load_member(&self, file: &Path) -> Result<Member, PlanError> {
        self.parse_member(file, &spherecontact_case::read_case_file(file)?)
    }

    /// [`CaseOptions::load_member`] of the case file `file` whose text is `text`.
    pub fn parse_member(&self, file: &Path, text: &str) -> Result<Member, PlanError> {
        if spherecontact_case::is_impact(text) {
            let mut case = spherecontact_case::parse_impact(file, text)?;
            case.permit_commands(&self.permission);
            Ok(Member::Impact(case))
        } else {
            self.parse(file, text).map(Member::Path)
        }
    }

    /// Loads the path case at `file` with these options over its own.
    pub fn load(&self, file: &Path) -> Result<Case, PlanError> {
        self.parse(file, &spherecontact_case::read_case_file(file)?)
    }

    /// [`CaseOptions::load`] of the case file `file` whose text is `text`.
    pub fn parse(&self, file: &Path, text: &str) -> Result<Case, PlanError> {
        let mut case = Case::parse_with(file, text, &self.roots)?;
        case.permit_commands(&self.permission);
        case.ranks = self.ranks.unwrap_or(case.ranks);
        for (name, value) in &self.resolutions {
            case.set_resolution(name, value)
                .map_err(|error| PlanError::Resolution {
                    name: name.clone(),
                    value: value.clone(),
                    case: file.to_path_buf(),
                    error: Box::new(error),
                })?;
        }
        Ok(case)
    }
}

/// A case of a plan: a path case (a prescribed loading path) or an impact case (rigid-body
/// dynamics with a contact law, [`spherecontact_impact`]). Both are verified alike: runs of (case,
/// solver), checks judged on the finished runs, baselines, shards and merge.
#[derive(Clone, Debug)]
pub enum Member {
    /// A path case.
    Path(Case),
    /// An impact case.
    Impact(ImpactCase),
}

impl Member {
    /// The case's name.
    pub fn name(&self) -> &str {
        match self {
            Member::Path(case) => case.name(),
            Member::Impact(case) => &case.name,
        }
    }

    /// The case's labels.
    pub fn labels(&self) -> &[String] {
        match self {
            Member::Path(case) => &case.labels,
            Member::Impact(case) => &case.labels,
        }
    }

    /// Every solver the case needs, in its order: a run each.
    pub fn required_solvers(&self) -> Vec<String> {
        match self {
            Member::Path(case) => case.required_solvers(),
            Member::Impact(case) => case.required_solvers(),
        }
    }

    /// The cores `solver` keeps busy: an impact run takes one.
    fn cores(&self, solver: &str) -> usize {
        match self {
            Member::Path(case) => case.solver(solver).map_or(1, |s| s.cores().max(1)),
            Member::Impact(_) => 1,
        }
    }

    /// The expected wall time of `solver` with nothing recorded [s]: a path run's by its kind, an
    /// impact run's from its size (steps × springs × sweep points × variants, a DEM code's
    /// start-up and steps: [`spherecontact_impact::cost`]).
    fn default_cost(&self, solver: &str) -> f64 {
        match self {
            Member::Path(_) => default_cost(solver),
            Member::Impact(case) => spherecontact_impact::cost::seconds(case, solver),
        }
    }
}

/// Which cases run: those with any of `labels` (all when empty) and none of `skip`.
#[derive(Clone, Debug, Default)]
pub struct Selection {
    labels: Vec<String>,
    skip: Vec<String>,
}

impl Selection {
    /// The selection of `--label` (`labels`) and `--skip-label` (`skip`), each a known label.
    pub fn new(labels: &[String], skip: &[String]) -> Result<Self, PlanError> {
        for (option, list) in [("--label", labels), ("--skip-label", skip)] {
            if let Some(label) = list.iter().find(|l| !labels::is_known(l)) {
                return Err(PlanError::UnknownLabel {
                    option,
                    label: label.clone(),
                });
            }
        }
        Ok(Selection {
            labels: labels.to_vec(),
            skip: skip.to_vec(),
        })
    }

    /// True when the case is selected.
    pub fn selects(&self, case: &Member) -> bool {
        let labels = case.labels();
        let has = |label: &String| labels.contains(label);
        (self.labels.is_empty() || self.labels.iter().any(has)) && !self.skip.iter().any(has)
    }
}

/// One run: a solver of a case, what it is expected to cost and the cores it takes.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// The case's index in the plan.
    pub case: usize,
    /// The solver's name.
    pub solver: String,
    /// The cores the solver keeps busy ([`spherecontact_model::solver::Solver::cores`]).
    pub cores: usize,
    /// Its expected wall time [s]: recorded with the baselines, else [`default_cost`] (a path
    /// run) or its size ([`spherecontact_impact::cost::seconds`], an impact run).
    pub cost_s: f64,
}

/// The cases selected and their runs: per case, every solver it needs, in the case's order.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The cases, in the order given.
    pub cases: Vec<Member>,
    /// The runs of this plan (all, or one shard's), case by case.
    pub runs: Vec<Run>,
}

impl Plan {
    /// Every run of `cases`, each costed by `recorded(case, solver)` where known.
    pub fn new(cases: Vec<Member>, recorded: impl Fn(&Member, &str) -> Option<f64>) -> Self {
        let runs = cases
            .iter()
            .enumerate()
            .flat_map(|(index, case)| {
                let recorded = &recorded;
                case.required_solvers().into_iter().map(move |solver| Run {
                    case: index,
                    cores: case.cores(&solver),
                    cost_s: recorded(case, &solver).unwrap_or_else(|| case.default_cost(&solver)),
                    solver,
                })
            })
            .collect();
        Plan { cases, runs }
    }

    /// The plan of one shard: the same cases, the runs [`partition`] gives it.
    pub fn shard(mut self, shard: Shard) -> Self {
        let parts = partition(&self.runs, shard.count);
        self.runs = self
            .runs
            .into_iter()
            .zip(parts)
            .filter_map(|(run, part)| (part + 1 == shard.index).then_some(run))
            .collect();
        self
    }
}

/// The shard (0-based) of each run, `count` shards balanced by cost: each run, longest first,
/// goes to the shard with the least cost so far (the lowest-numbered on a tie).
pub fn partition(runs: &[Run], count: usize) -> Vec<usize> {
    let count = count.max(1);
    let mut load = vec![0.0_f64; count];
    let mut parts = vec![0; runs.len()];
    let costs: Vec<f64> = runs.iter().map(|run| run.cost_s).collect();
    for index in longest_first(&costs) {
        let lightest = (0..count)
            .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
            .expect("at least one shard");
        load[lightest] += runs[index].cost_s;
        parts[index] = lightest;
    }
    parts
}

/// The expected wall time of a solver with nothing recorded [s]: the order of magnitude of its
/// kind on this project's two-core machine (release build), enough to start the long runs first.
pub fn default_cost(solver: &str) -> f64 {
    match solver {
        "fem-3d" | "fenicsx-3d" => 30.0,
        "freefem-axisym" | "fenicsx-axisym" | "mdr-domain" | "fem-axisym" => 5.0,
        "bem" => 3.0,
        name if name.starts_with("lammps") || name.starts_with("yade") || name.starts_with("liggghts") => 1.0,
        "hertz"
        | "cattaneo-mindlin"
        | "hertz-mindlin-spring"
        | "hertz-mindlin-total"
        | "thornton"
        | "md-incremental"
        | "walton-braun" => 0.01,
        "mdr" => 0.1,
        // A case's own command or stored results.
        _ => 1.0,
    }
}

/// One part of a sharded run: the `index`-th (1-based) of `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which part, 1 ≤ index ≤ count.
    pub index: usize,
    /// How many parts.
    pub count: usize,
}

impl FromStr for Shard {
    type Err = PlanError;

    /// `K/N` with 1 ≤ K ≤ N ≤ [`MAX_SHARDS`].
    fn from_str(text: &str) -> Result<Self, PlanError> {
        let bad = || PlanError::Shard(text.to_owned());
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count) = (k.parse().map_err(|_| bad())?, n.parse().map_err(|_| bad())?);
        if 1 <= index && index <= count && count <= MAX_SHARDS {
            Ok(Shard { index, count })
        } else {
            Err(bad())
        }
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(cost_s: f64) -> Run {
        Run {
            case: 0,
            solver: "s".into(),
            cores: 1,
            cost_s,
        }
    }

    #[test]
    fn shards_are_balanced_longest_first_and_cover_every_run_once() {
        let runs: Vec<Run> = [5.0, 1.0, 4.0, 3.0, 3.0, 2.0, 0.5].map(run).to_vec();
        let parts = partition(&runs, 3);
        let load = |k: usize| -> f64 {
            runs.iter()
                .zip(&parts)
                .filter(|(_, &p)| p == k)
                .map(|(r, _)| r.cost_s)
                .sum()
        };
        // LPT: 5 → A, 4 → B, 3 → C, 3 → C (6), 2 → B (6), 1 → A (6), 0.5 → A.
        assert_eq!([load(0), load(1), load(2)], [6.5, 6.0, 6.0]);
        assert_eq!(partition(&runs, 1), vec![0; runs.len()]);
    }

    #[test]
    fn a_shard_is_k_of_n() {
        assert_eq!("2/3".parse::<Shard>().unwrap(), Shard { index: 2, count: 3 });
        for bad in ["0/3", "4/3", "3", "a/b", "1/1001", "-1/2"] {
            let error = bad.parse::<Shard>().unwrap_err().to_string();
            assert!(
                error.contains(&format!("--shard {bad}")) && error.contains("1 ≤ K ≤ N"),
                "{error}"
            );
        }
    }

    #[test]
    fn impact_cases_are_runs_of_the_plan_selected_by_their_labels() {
        let case = spherecontact_case::load_impact(
            &spherecontact_model::fixtures::repository().join("cases/impact/chung-ooi-6.toml"),
        )
        .unwrap();
        let member = Member::Impact(case);
        assert!(Selection::new(&["impact".into()], &[]).unwrap().selects(&member));
        assert!(!Selection::new(&[], &["dem".into()]).unwrap().selects(&member));
        let plan = Plan::new(vec![member], |_, solver| (solver == "thornton").then_some(7.0));
        let solvers: Vec<&str> = plan.runs.iter().map(|r| r.solver.as_str()).collect();
        assert_eq!(
            solvers,
            [
                "mdr",
                "hertz-mindlin-spring",
                "thornton",
                "md-incremental",
                "walton-braun",
                // The DEM codes and their rules' references, named by the case's checks.
                "lammps-mindlin",
                "mdr-lammps",
                "lammps-mindlin-rescale",
                "lammps-mindlin-force",
                "lammps-mindlin-rescale-force",
                "yade-mindlin",
                "mdr-yade",
                "liggghts-hertz-history",
                "mdr-liggghts",
                "kratos-hertz-coulomb"
            ]
        );
        assert!(plan.runs.iter().all(|r| r.cores == 1));
        // A recorded cost wins; else the run's size is costed (e = 0.5: two variants).
        assert_eq!(plan.runs[2].cost_s, 7.0);
        let case = match &plan.cases[0] {
            Member::Impact(case) => case,
            Member::Path(_) => unreachable!("an impact case"),
        };
        for run in plan.runs.iter().filter(|r| r.solver != "thornton") {
            assert_eq!(
                run.cost_s,
                spherecontact_impact::cost::seconds(case, &run.solver),
                "{}",
                run.solver
            );
        }
    }

    /// Requirement (issue 42): an impact run with nothing recorded is costed from its size, not
    /// at a fixed 0.3 s: the shipped cases' runs differ with their sweeps and solvers, and a
    /// 200-angle sweep costs ten times a 20-angle one.
    #[test]
    fn an_impact_run_is_costed_from_its_size() {
        let mut costs = Vec::new();
        for file in
            spherecontact_case::case_files(
                &[spherecontact_model::fixtures::repository().join("cases/impact")],
            )
            .unwrap()
        {
            let member = Member::Impact(spherecontact_case::load_impact(&file).unwrap());
            let plan = Plan::new(vec![member], |_, _| None);
            costs.extend(plan.runs.iter().map(|r| (r.solver.clone(), r.cost_s)));
        }
        let mdr: Vec<f64> = costs.iter().filter(|(s, _)| s == "mdr").map(|c| c.1).collect();
        assert_eq!(mdr.len(), 12);
        assert!(mdr.iter().all(|&c| c != 0.3 && c != 0.6), "{mdr:?}");
        let (least, most) = (
            mdr.iter().copied().fold(f64::INFINITY, f64::min),
            mdr.iter().copied().fold(0.0, f64::max),
        );
        // One elastic point (tests 1, 2) to 17 points in two variants (tests 4, 6–8).
        assert!(most / least > 30.0, "{least} … {most}");
        let mut four = spherecontact_case::load_impact(
            &spherecontact_model::fixtures::repository().join("cases/impact/chung-ooi-4.toml"),
        )
        .unwrap();
        let cost =
            |case: &ImpactCase| Plan::new(vec![Member::Impact(case.clone())], |_, _| None).runs[0].cost_s;
        four.sweep.as_mut().unwrap().values = (1..=20).map(|i| f64::from(i) * 0.07).collect();
        let twenty = cost(&four);
        four.sweep.as_mut().unwrap().values = (1..=200).map(|i| f64::from(i) * 0.007).collect();
        assert!(
            (cost(&four) / twenty - 10.0).abs() < 1e-9,
            "{twenty} {}",
            cost(&four)
        );
    }

    #[test]
    fn unknown_labels_are_refused() {
        let error = Selection::new(&["fast".into()], &["haevy".into()])
            .unwrap_err()
            .to_string();
        assert!(
            error.starts_with("--skip-label haevy: unknown label (allowed: fast"),
            "{error}"
        );
    }
}
