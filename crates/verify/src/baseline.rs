//! Non-regression baselines: every value each check judged as last accepted (every step or sweep
//! point it covers), stored per case in `reference/baselines/<case>.toml` beside the references,
//! with each solver's version, resolution and wall time. `verify` compares each value with its
//! baseline at the solvers' non-regression tolerance ([`tolerance`]), names the first step that
//! moved beyond it and the largest change, and reports such a check as DRIFT, a failure;
//! `spherecontact baseline update [CASE...]` rewrites the files, so that a deliberate change is
//! one reviewed diff (Code_Aster's VALE_CALC beside VALE_REFE; MOOSE's CSVDiff compares every
//! row, LAMMPS' unit tests store whole YAML references).
//!
//! ```toml
//! format = 2
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
//! values = [
//!   [25, 2.0261041411427e3],
//!   [50, 5.730707133906211e3],
//! ]
//! ```
//!
//! Every value, not a digest: a digest (a hash per step) would name the first step that moved
//! but not by how much, nor the largest change; the values cost some 30 bytes each (the longest
//! shipped case, paper-fig7, about 1 MB), and a deliberate change reads as a diff of the steps
//! it moved. Values are written in their shortest round-trip form (`{:e}`), so a value reads back
//! bit for bit and the tolerance is round-off, not the file's digits.
//!
//! A check without a value (its solver not installed or failed) has no entry, and an absent
//! entry is no drift. A check whose solver now runs at another resolution than the one stored
//! fails (a baseline belongs to a resolution). A file without `format = 2` (the one value per
//! check of before) is refused, saying to run `baseline update`. The wall times are the plan's
//! recorded costs ([`crate::plan`]).

use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::plan::Member;
use crate::CaseRun;
use spherecontact_check::{drift, Drift, JudgedValue, Verdict};
use spherecontact_system::input::foreign::{self, ForeignError};
use tolerance::check_tolerance;
pub use tolerance::tolerance;

mod impact;
mod shape;
mod tolerance;
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
    /// A baseline of another format than this harness's (the one value per check of before).
    #[error(
        "{}: {problem}: a baseline records every judged value since format 2 (allowed: `format = {FORMAT}`; \
         run `spherecontact baseline update` to rewrite it)",
        file.display()
    )]
    OtherFormat {
        /// The file.
        file: PathBuf,
        /// What it holds instead.
        problem: String,
    },
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

/// The largest baseline file [bytes] (16 MiB): every judged value of the longest shipped case
/// (paper-fig7: 56 checks, most over its 1101 steps, about 30 bytes a value) is about 1 MB; TOML
/// parsing takes about 30 bytes of memory a byte, 0.5 GB at the limit.
pub const MAX_BASELINE_BYTES: u64 = 16 << 20;

/// The format of the baselines this harness writes and reads: 2, every judged value (1, never
/// written as a key, held one value per check).
pub const FORMAT: u32 = 2;

/// A judged check as a baseline sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct Judgement {
    /// The check's index in its case.
    pub index: usize,
    /// The check in words: an entry applies only to the same check at the same index.
    pub key: String,
    /// The solvers it needs.
    pub solvers: Vec<String>,
    /// Every value it judged, in step order: a path's steps, an impact's sweep points.
    pub values: Vec<JudgedValue>,
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
    /// What a judged value's step is called: "step" (a path), "sweep point" (an impact).
    fn unit(&self) -> &'static str;
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
                    values: o.judged.clone(),
                    verdict: o.verdict,
                })
            })
            .collect()
    }

    fn unit(&self) -> &'static str {
        "step"
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
    /// Every value it judged when the baseline was written: (step, value), in step order (a
    /// sweep point's index for an impact case).
    pub values: Vec<(usize, f64)>,
}

/// The baseline of one case.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Baseline {
    /// The format ([`FORMAT`]).
    pub format: u32,
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
    "a baseline written by `spherecontact baseline update`: its format, case, [solvers.NAME] and [[checks]]";

/// What a file must say of itself before it is read as a baseline: its format (a file of the
/// old format has none). Other keys are left to [`Baseline`]'s own reading.
#[derive(Deserialize)]
struct Probe {
    format: Option<i64>,
}

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
            .filter(|j| !j.values.is_empty())
            .map(|j| CheckRecord {
                index: j.index,
                check: j.key,
                values: j.values.iter().map(|v| (v.step, v.value)).collect(),
            })
            .collect();
        Baseline {
            format: FORMAT,
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
        let probe: Probe = foreign::parse_toml(&file, &text, FORM)?;
        let problem = match probe.format {
            Some(f) if f == i64::from(FORMAT) => None,
            Some(f) => Some(format!("format {f}, not this harness's")),
            None => Some("no `format`: a baseline of one value per check".to_owned()),
        };
        if let Some(problem) = problem {
            return Err(BaselineError::OtherFormat { file, problem });
        }
        let baseline: Baseline = foreign::parse_toml(&file, &text, FORM)?;
        case.admits(&baseline)
            .map_err(|(entry, problem)| BaselineError::Stale { file, entry, problem })?;
        Ok(Some(baseline))
    }

    /// The recorded wall time of `solver` [s].
    pub fn wall_s(&self, solver: &str) -> Option<f64> {
        self.solvers.get(solver).map(|s| s.wall_s)
    }

    /// Compares every check of `run` that has an entry, value by value: sets its drift, and
    /// its verdict to DRIFT when a value moved beyond the tolerance, a step is judged on one side
    /// only, or the baseline records another resolution of one of its solvers than the run's (a
    /// NOOK stays NOOK). A check without a value now (a solver not installed or failed) is not
    /// compared. The checks of a solver in `chosen` (a resolution chosen on the command line,
    /// `--resolution`) are not compared: a baseline belongs to the case's own resolution.
    pub fn compare(&self, run: &mut (impl Baselined + ?Sized), chosen: &[String]) {
        let unit = run.unit();
        for (check, judgement) in run.judgements().into_iter().enumerate() {
            let Some(record) = self
                .checks
                .iter()
                .find(|r| r.index == judgement.index && r.check == judgement.key)
            else {
                continue;
            };
            if judgement.values.is_empty() || judgement.solvers.iter().any(|name| chosen.contains(name)) {
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
            let drift = match other {
                Some(solver) => Drift::OtherResolution {
                    solver: solver.clone(),
                },
                None => drift::compare(
                    unit,
                    &judgement.values,
                    &record.values,
                    check_tolerance(&judgement.solvers),
                ),
            };
            let verdict = if drift.fails() && judgement.verdict != Verdict::Nook {
                Verdict::Drift
            } else {
                judgement.verdict
            };
            run.mark(check, drift, verdict);
        }
    }

    /// The file's text: a header, the solvers, the checks (values round-trip exact).
    pub fn to_toml(&self) -> String {
        let string = |s: &str| toml::Value::String(s.to_owned()).to_string();
        let mut text = format!(
            "{HEADER}{}`: every value each check judged when last accepted\n\
             # ([step, value], a sweep point's index for an impact case), with each solver's version,\n\
             # resolution and wall time. Written by `spherecontact baseline update`; `verify` reports\n\
             # a change beyond the solvers' tolerance as DRIFT, naming the first step that moved\n\
             # (crates/verify/src/baseline.rs).\nformat = {}\ncase = {}\n",
            self.case,
            self.format,
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
                "\n[[checks]]\nindex = {}\ncheck = {}\nvalues = [\n",
                check.index,
                string(&check.check),
            );
            for (step, value) in &check.values {
                let _ = writeln!(text, "  [{step}, {value:e}],");
            }
            text.push_str("]\n");
        }
        text
    }
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

/// How baselines are read: to compare runs with them, or to be replaced (`baseline update`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reading {
    /// Every baseline must be of this format and fit its case.
    Compare,
    /// Only their recorded wall times are used (to order the runs): a baseline of another format
    /// or that no longer fits its case is left out, as `baseline update` rewrites it.
    Replace,
}

/// The baselines in `dir` of `cases`, each checked against its case, by case name. A folder
/// that does not exist is an error (a typo in `--baselines` would turn the check off unseen),
/// except the default [`DIR`] (cases verified outside a repository have none).
pub fn load_all<'a>(
    dir: &Path,
    cases: impl IntoIterator<Item = &'a Member>,
    reading: Reading,
) -> Result<BTreeMap<String, Baseline>, BaselineError> {
    let mut baselines = BTreeMap::new();
    if !dir.is_dir() {
        if dir == Path::new(DIR) && std::fs::symlink_metadata(dir).is_err() {
            return Ok(baselines);
        }
        return Err(BaselineError::Folder(dir.to_path_buf()));
    }
    for case in cases {
        match (Baseline::load(dir, &Shape::of(case)), reading) {
            (Ok(Some(baseline)), _) => {
                baselines.insert(case.name().to_owned(), baseline);
            }
            (Ok(None), _) => {}
            (Err(BaselineError::OtherFormat { .. } | BaselineError::Stale { .. }), Reading::Replace) => {}
            (Err(e), _) => return Err(e),
        }
    }
    Ok(baselines)
}

/// Compares every run with its case's baseline, if any; `chosen` as for [`Baseline::compare`].
/// Returns the names of the cases that have none, which `verify` says (and fails with
/// `--require-baselines`).
pub fn compare_all<'a>(
    baselines: &BTreeMap<String, Baseline>,
    runs: impl IntoIterator<Item = &'a mut dyn Baselined>,
    chosen: &[String],
) -> Vec<String> {
    let mut without = Vec::new();
    for run in runs {
        match baselines.get(run.case_name()) {
            Some(baseline) => baseline.compare(run, chosen),
            None => without.push(run.case_name().to_owned()),
        }
    }
    without
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_file_reads_back_what_was_written_bit_for_bit() {
        let baseline = Baseline {
            format: FORMAT,
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
                values: vec![
                    (0, 0.1 + 0.2),
                    (7, -0.0),
                    (8, 5e-324),
                    (9, 1.7976931348623157e308),
                ],
            }],
        };
        let text = baseline.to_toml();
        let read = toml::from_str::<Baseline>(&text).unwrap();
        assert_eq!(read, baseline, "{text}");
        let bits = |b: &Baseline| {
            b.checks[0]
                .values
                .iter()
                .map(|v| v.1.to_bits())
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&read), bits(&baseline), "bit for bit, -0 included: {text}");
    }

    #[test]
    fn wall_times_keep_two_digits() {
        assert_eq!(two_digits(2.34923066e-1), 0.23);
        assert_eq!(two_digits(59.492033547), 59.0);
        assert_eq!(two_digits(0.0), 0.0);
        assert_eq!(format!("{:e}", two_digits(2.952e-6)), "3e-6");
    }
}
