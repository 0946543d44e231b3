//! Non-regression baselines: every check's computed value as last accepted, stored per case in
//! `reference/baselines/<case>.toml` beside the references, with each solver's version,
//! resolution and wall time. `verify` compares each value with its baseline at the solvers'
//! non-regression tolerance ([`tolerance`]) and reports a change beyond it as DRIFT, a failure;
//! `spherecontact baseline update [CASE...]` rewrites the files, so that a deliberate change is
//! one reviewed diff (Code_Aster's VALE_CALC beside VALE_REFE).
//!
//! ```toml
//! case = "hertz-normal"
//!
//! [solvers."bem"]
//! version = "0.1.0"
//! resolution = "64² panels of 3.49e-6 m over ±1.1 c_max"
//! wall_s = 4.12e-1
//!
//! [[checks]]
//! index = 20
//! check = "bem normal_force at positions [1, 2] vs hertz (relative)"
//! step = 25
//! value = 2.0261e3
//! ```
//!
//! A check without a value (its solver not installed or failed) has no entry, and an absent
//! entry is no drift. A check whose solver now runs at another resolution than the one stored is
//! not compared (a baseline belongs to a resolution). The wall times are the plan's recorded
//! costs ([`crate::plan`]).

use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::plan::Member;
use crate::CaseRun;
use spherecontact_check::{Drift, Histories, Verdict};
use spherecontact_system::input::foreign::{self, ForeignError};

mod impact;
mod shape;
pub use shape::Shape;

/// The baselines' folder, relative to the current folder (as `cases/` is).
pub const DIR: &str = "reference/baselines";

/// Why a baseline file cannot be used (bad input: exit code 2). A baseline is a file from
/// elsewhere (a pull request can add one): it is read by [`spherecontact_system::input::foreign`], and no
/// message quotes it.
#[derive(Debug, thiserror::Error)]
pub enum BaselineError {
    /// The file cannot be read, or is not a baseline.
    #[error("{0}")]
    Foreign(#[from] ForeignError),
    /// A `--baselines` folder that is not one.
    #[error(
        "--baselines {}: not a folder (allowed: a folder of baselines written by `spherecontact baseline \
         update`)",
        .0.display()
    )]
    Folder(PathBuf),
    /// An entry that does not fit its case: the case changed since, or the file was edited.
    #[error(
        "{}: {entry}: {problem} (a baseline holds its case's checks, steps and solvers as `spherecontact \
         baseline update` wrote them: run it again if the case changed)",
        file.display()
    )]
    Stale {
        /// The file.
        file: PathBuf,
        /// The entry, as `checks[3]` or `solvers`.
        entry: String,
        /// What does not fit, and what is allowed.
        problem: String,
    },
}

/// The largest baseline file [bytes] (16 MiB): the shipped ones are under 8 KB, and a baseline
/// of every judged value of the longest shipped path (the paper case: about 600 checks over its
/// 101 steps, some 60 bytes a value) under 4 MB; TOML parsing takes about 30 bytes of memory a
/// byte, 0.5 GB at the limit.
pub const MAX_BASELINE_BYTES: u64 = 16 << 20;

/// The non-regression tolerance of a solver's values (relative) and its reason.
pub fn tolerance(solver: &str) -> (f64, &'static str) {
    match solver {
        "freefem-axisym" | "fenicsx-axisym" | "fenicsx-3d" => (
            1e-9,
            "an external FEM program: FreeFEM's MUMPS_seq differs in the last bits run to run (about \
             1e-14 of P and Q on the same files, external::deck::single_threaded), FEniCSx under MPI sums \
             by rank, and a penalty system amplifies rounding; a change of mesh, penalty or model moves P \
             by 1e-6 or more",
        ),
        name if name.starts_with("ccx") => (
            1e-6,
            "CalculiX: its results are read from the text it prints (.dat and .frd numbers of 7 \
             significant digits), so a rounding change in its SPOOLES solve that moves one printed digit \
             moves the value by up to 1e-6 relative; a change of mesh, penalty or formulation moves P by \
             1e-5 or more (docs/external-decks.md, the penalty sweep)",
        ),
        name if name.starts_with("lammps") || name.starts_with("yade") => (
            1e-9,
            "a DEM code driven through text input and output: positions and forces pass through its \
             own arithmetic and formatting, which another build of the same version may order differently",
        ),
        _ => (
            1e-12,
            "deterministic: the same source on the same machine gives the same bits (the BEM's team too, \
             on one or two threads); 1e-12 leaves four orders over double rounding for another compiler's \
             contractions (FMA)",
        ),
    }
}

/// The largest change accepted for a check: the loosest of its solvers' tolerances.
fn check_tolerance(solvers: &[String]) -> f64 {
    solvers.iter().map(|s| tolerance(s).0).fold(0.0, f64::max)
}

/// A judged check as a baseline sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct Judgement {
    /// The check's index in its case.
    pub index: usize,
    /// The check in words: an entry applies only to the same check at the same index.
    pub key: String,
    /// The solvers it needs.
    pub solvers: Vec<String>,
    /// Where its value was taken: a path's step, an impact's sweep point (its worst).
    pub step: Option<usize>,
    /// Its value there.
    pub value: Option<f64>,
    /// The reference's value there.
    pub reference: Option<f64>,
    /// Its verdict.
    pub verdict: Verdict,
}

/// A judged case whose check values a baseline records and compares: path cases
/// ([`CaseRun`]) and impact cases ([`spherecontact_impact::ImpactRun`]) alike.
pub trait Baselined {
    /// The case's name.
    fn case_name(&self) -> &str;
    /// Each solver that ran: version, resolution and wall time.
    fn solver_records(&self) -> BTreeMap<String, SolverRecord>;
    /// The resolution `solver` ran at now, if it ran.
    fn resolution(&self, solver: &str) -> Option<String>;
    /// The judged checks, in order.
    fn judgements(&self) -> Vec<Judgement>;
    /// The value of the `check`-th judged check at `step` (a baseline's step may not be the
    /// worst one now).
    fn value_at(&self, check: usize, step: usize) -> Option<f64>;
    /// Records the `check`-th judged check's drift and its verdict.
    fn mark(&mut self, check: usize, drift: Drift, verdict: Verdict);
}

impl Baselined for CaseRun {
    fn case_name(&self) -> &str {
        self.case.name()
    }

    fn solver_records(&self) -> BTreeMap<String, SolverRecord> {
        self.histories
            .iter()
            .filter_map(|(name, result)| {
                let meta = &result.as_ref().ok()?.metadata;
                Some((
                    name.clone(),
                    SolverRecord {
                        version: meta.version.clone(),
                        resolution: meta.resolution.clone(),
                        wall_s: two_digits(meta.wall_time_s),
                    },
                ))
            })
            .collect()
    }

    fn resolution(&self, solver: &str) -> Option<String> {
        Some(
            self.histories
                .get(solver)?
                .as_ref()
                .ok()?
                .metadata
                .resolution
                .clone(),
        )
    }

    fn judgements(&self) -> Vec<Judgement> {
        self.outcomes
            .iter()
            .filter_map(|o| {
                Some(Judgement {
                    index: self.case.checks.iter().position(|c| *c == o.spec)?,
                    key: key(&o.spec),
                    solvers: o.spec.solvers().cloned().collect(),
                    step: o.worst_step,
                    value: o.value,
                    reference: o.reference,
                    verdict: o.verdict,
                })
            })
            .collect()
    }

    fn value_at(&self, check: usize, step: usize) -> Option<f64> {
        let outcome = self.outcomes.get(check)?;
        if outcome.worst_step == Some(step) {
            return outcome.value;
        }
        current(&outcome.spec, step, &self.histories)
    }

    fn mark(&mut self, check: usize, drift: Drift, verdict: Verdict) {
        if let Some(outcome) = self.outcomes.get_mut(check) {
            outcome.drift = Some(drift);
            outcome.verdict = verdict;
        }
    }
}

/// A solver's entry.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverRecord {
    /// Its version when the baseline was written.
    pub version: String,
    /// Its resolution, in words.
    pub resolution: String,
    /// Its wall time [s], to two significant digits.
    pub wall_s: f64,
}

/// A check's entry.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckRecord {
    /// The check's index in the case.
    pub index: usize,
    /// The check in words ([`key`]): an entry applies only to the same check at the same index.
    pub check: String,
    /// The step of the value: the check's worst when the baseline was written.
    pub step: usize,
    /// The value computed there.
    pub value: f64,
}

/// The baseline of one case.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Baseline {
    /// The case's name.
    pub case: String,
    /// Per solver that ran.
    #[serde(default)]
    pub solvers: BTreeMap<String, SolverRecord>,
    /// Per check with a value.
    #[serde(default)]
    pub checks: Vec<CheckRecord>,
}

/// A check in words: solver, quantity, where, reference and measure.
pub fn key(spec: &spherecontact_check::CheckSpec) -> String {
    format!(
        "{} {} at {} vs {} ({})",
        spec.solver,
        spec.quantity,
        spec.at,
        spec.reference,
        spec.measure.name()
    )
}

/// What a baseline file is, as its errors say.
const FORM: &str =
    "a baseline written by `spherecontact baseline update`: its case, [solvers.NAME] and [[checks]]";

/// The first line of every baseline file ([`Baseline::to_toml`]).
const HEADER: &str = "# Non-regression baseline of case `";

/// True when `file` is a regular `<case>.toml` file that opens as the harness's baselines do:
/// what a baselines' folder without its marker may hold ([`spherecontact_system::io::OutputFolder::claim_recognising`]).
pub fn is_baseline_file(file: &Path) -> bool {
    let mut head = [0; HEADER.len()];
    file.extension().is_some_and(|e| e == "toml")
        && std::fs::symlink_metadata(file).is_ok_and(|m| m.is_file())
        && std::fs::File::open(file).is_ok_and(|mut f| std::io::Read::read_exact(&mut f, &mut head).is_ok())
        && head == HEADER.as_bytes()
}

/// The file of case `name` under `dir`.
pub fn file(dir: &Path, name: &str) -> PathBuf {
    dir.join(format!("{name}.toml"))
}

impl Baseline {
    /// The baseline of a judged case: every check's value, every solver that ran.
    pub fn of(run: &(impl Baselined + ?Sized)) -> Self {
        let checks = run
            .judgements()
            .into_iter()
            .filter_map(|j| {
                Some(CheckRecord {
                    index: j.index,
                    check: j.key,
                    step: j.step?,
                    value: j.value?,
                })
            })
            .collect();
        Baseline {
            case: run.case_name().to_owned(),
            solvers: run.solver_records(),
            checks,
        }
    }

    /// The baseline of `case` in `dir`, checked against it ([`Shape`]), or `None` when it has
    /// none (nothing at its name: a dangling link is an error, as is any other kind of file).
    pub fn load(dir: &Path, case: &Shape) -> Result<Option<Self>, BaselineError> {
        let file = file(dir, &case.name);
        if std::fs::symlink_metadata(&file).is_err() {
            return Ok(None);
        }
        let text = foreign::read_text(&file, MAX_BASELINE_BYTES)?;
        let baseline: Baseline = foreign::parse_toml(&file, &text, FORM)?;
        case.admits(&baseline)
            .map_err(|(entry, problem)| BaselineError::Stale { file, entry, problem })?;
        Ok(Some(baseline))
    }

    /// The recorded wall time of `solver` [s].
    pub fn wall_s(&self, solver: &str) -> Option<f64> {
        self.solvers.get(solver).map(|s| s.wall_s)
    }

    /// Compares every check of `run` that has an entry: sets its drift, and its verdict to
    /// DRIFT when the change exceeds the tolerance (a NOOK stays NOOK) or when the baseline
    /// records another resolution of one of its solvers than the run's. The checks of a solver
    /// in `chosen` (a resolution chosen on the command line, `--resolution`) are not compared:
    /// a baseline belongs to the case's own resolution.
    pub fn compare(&self, run: &mut (impl Baselined + ?Sized), chosen: &[String]) {
        for (check, judgement) in run.judgements().into_iter().enumerate() {
            let Some(record) = self
                .checks
                .iter()
                .find(|r| r.index == judgement.index && r.check == judgement.key)
            else {
                continue;
            };
            let Some(value) = run.value_at(check, record.step) else {
                continue;
            };
            if judgement.solvers.iter().any(|name| chosen.contains(name)) {
                continue;
            }
            // A solver that did not run now has no resolution: nothing to compare.
            let Some(now) = judgement
                .solvers
                .iter()
                .map(|name| run.resolution(name))
                .collect::<Option<Vec<String>>>()
            else {
                continue;
            };
            let other = judgement
                .solvers
                .iter()
                .zip(&now)
                .find(|(name, now)| self.solvers.get(*name).map(|s| &s.resolution) != Some(now))
                .map(|(name, _)| name);
            let (drift, verdict) = match other {
                Some(solver) => (
                    Drift::OtherResolution {
                        solver: solver.clone(),
                    },
                    Verdict::Drift,
                ),
                None => self.measured(&judgement, record.value, value),
            };
            run.mark(check, drift, verdict);
        }
    }

    /// The drift of `judgement`'s `value` from its baseline's `stored` value, and its verdict.
    fn measured(&self, judgement: &Judgement, stored: f64, value: f64) -> (Drift, Verdict) {
        // Scaled by the magnitude of the quantity judged: for a profile the value is an RMS
        // difference, some 1e-4 of its reference's peak, and scaling by it would amplify the
        // external decks' last-bit noise by that cancellation (measured: FreeFEM's profile
        // RMS moved 4.4e-9 of itself run to run, 1.5e-13 of the peak).
        let reference = judgement.reference.map_or(0.0, f64::abs);
        let (difference, scale) = (
            (value - stored).abs(),
            stored.abs().max(value.abs()).max(reference),
        );
        let change = if difference == 0.0 {
            0.0
        } else {
            difference / scale
        };
        let tolerance = check_tolerance(&judgement.solvers);
        let verdict = if change > tolerance && judgement.verdict != Verdict::Nook {
            Verdict::Drift
        } else {
            judgement.verdict
        };
        let drift = Drift::Measured {
            baseline: stored,
            change,
            tolerance,
        };
        (drift, verdict)
    }

    /// The file's text: a header, the solvers, the checks (values round-trip exact).
    pub fn to_toml(&self) -> String {
        let string = |s: &str| toml::Value::String(s.to_owned()).to_string();
        let mut text = format!(
            "{HEADER}{}`: each check's computed value when last accepted,\n\
             # with each solver's version, resolution and wall time. Written by\n\
             # `spherecontact baseline update`; `verify` reports a change beyond the solvers'\n\
             # tolerance as DRIFT (crates/verify/src/baseline.rs).\ncase = {}\n",
            self.case,
            string(&self.case)
        );
        for (name, solver) in &self.solvers {
            let _ = write!(
                text,
                "\n[solvers.{}]\nversion = {}\nresolution = {}\nwall_s = {:e}\n",
                string(name),
                string(&solver.version),
                string(&solver.resolution),
                solver.wall_s
            );
        }
        for check in &self.checks {
            let _ = write!(
                text,
                "\n[[checks]]\nindex = {}\ncheck = {}\nstep = {}\nvalue = {:e}\n",
                check.index,
                string(&check.check),
                check.step,
                check.value
            );
        }
        text
    }
}

/// A path check's value at `step` other than its worst: the subject's quantity there (a
/// profile's value exists at its position's step only).
fn current(spec: &spherecontact_check::CheckSpec, step: usize, histories: &Histories) -> Option<f64> {
    if spherecontact_solvers::profile::Field::of(spec.quantity).is_some() {
        return None;
    }
    let history = histories.get(&spec.solver)?.as_ref().ok()?;
    spec.value(history, history.steps.get(step)?)
}

/// `x` to two significant digits: a wall time is a cost estimate, and its noise would make every
/// `baseline update` a diff.
pub fn two_digits(x: f64) -> f64 {
    if x > 0.0 {
        let scale = 10_f64.powi(1 - x.log10().floor() as i32);
        (x * scale).round() / scale
    } else {
        0.0
    }
}

/// The baselines in `dir` of `cases`, each checked against its case, by case name. A folder
/// that does not exist is an error (a typo in `--baselines` would turn the check off unseen),
/// except the default [`DIR`] (cases verified outside a repository have none).
pub fn load_all<'a>(
    dir: &Path,
    cases: impl IntoIterator<Item = &'a Member>,
) -> Result<BTreeMap<String, Baseline>, BaselineError> {
    let mut baselines = BTreeMap::new();
    if !dir.is_dir() {
        if dir == Path::new(DIR) && std::fs::symlink_metadata(dir).is_err() {
            return Ok(baselines);
        }
        return Err(BaselineError::Folder(dir.to_path_buf()));
    }
    for case in cases {
        if let Some(baseline) = Baseline::load(dir, &Shape::of(case))? {
            baselines.insert(case.name().to_owned(), baseline);
        }
    }
    Ok(baselines)
}

/// Compares every run with its case's baseline, if any; `chosen` as for [`Baseline::compare`].
pub fn compare_all<'a>(
    baselines: &BTreeMap<String, Baseline>,
    runs: impl IntoIterator<Item = &'a mut dyn Baselined>,
    chosen: &[String],
) {
    for run in runs {
        if let Some(baseline) = baselines.get(run.case_name()) {
            baseline.compare(run, chosen);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_file_reads_back_what_was_written_bit_for_bit() {
        let baseline = Baseline {
            case: "a-case".into(),
            solvers: [(
                "bem".to_owned(),
                SolverRecord {
                    version: "0.1.0".into(),
                    resolution: "64×64 panels \"quoted\"".into(),
                    wall_s: 0.23,
                },
            )]
            .into_iter()
            .collect(),
            checks: vec![CheckRecord {
                index: 3,
                check: "bem normal_force at every step vs hertz (relative)".into(),
                step: 7,
                value: 0.1 + 0.2,
            }],
        };
        let text = baseline.to_toml();
        assert_eq!(toml::from_str::<Baseline>(&text).unwrap(), baseline, "{text}");
    }

    #[test]
    fn wall_times_keep_two_digits() {
        assert_eq!(two_digits(2.34923066e-1), 0.23);
        assert_eq!(two_digits(59.492033547), 59.0);
        assert_eq!(two_digits(0.0), 0.0);
        assert_eq!(format!("{:e}", two_digits(2.952e-6)), "3e-6");
    }
}
