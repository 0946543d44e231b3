//! Timing solvers side by side, and their speed against their error.
//!
//! Every timed solver (or every rung of its resolution ladder) runs the same scene several times
//! in one process, interleaved round by round so that machine noise hits all alike, and the
//! median is reported. Both wall time and the process's CPU time (all its threads) are kept: on a
//! shared, loaded machine the wall time also counts the time spent waiting for a core, the CPU
//! time does not; on an idle one a solver that used several cores would take less wall than CPU
//! time.
//!
//! Errors are measured against the references every report uses: P against Hertz (relative, at
//! every step in contact), Q against MDR on a bed far finer than any rung (relative to its peak
//! |Q|). A model of a finite body (a FEM solver or deck) is scored against `mdr-domain`, MDR in
//! series with the case's domain, so that its error is its discretisation's; its raw offsets from
//! Hertz and MDR (the domain effect on top) are kept beside. Speed is measured and reported here, never asserted in tests: the machines are shared.

use std::time::Instant;

use spherecontact_case::registry;
use spherecontact_case::{Case, CaseSolver};
use spherecontact_model::history::{History, Quantity};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{self, SolveError, Solver};
use spherecontact_reference::hertz::HertzSolver;
use spherecontact_reference::mdr::Mdr;
use spherecontact_solvers::fem::MdrDomain;

/// Springs of the MDR bed that serves as the tangential reference: 4× the finest rung of MDR's
/// own ladder, so its own error (~(Δx/c)²) is ≥ 16× below any rung's.
pub const REFERENCE_SPRINGS: usize = 64_000;

/// The times of repeated runs of one solver, and the history of its first run.
#[derive(Clone, Debug)]
pub struct Timing {
    /// The solver's name.
    pub solver: String,
    /// Wall times [s], sorted.
    pub seconds: Vec<f64>,
    /// CPU times of the process (every thread) and the external programs it ran [s], sorted.
    pub cpu_seconds: Vec<f64>,
    /// The history of the first (untimed, warm-up) run.
    pub history: History,
}

/// The median of sorted values.
pub fn median(sorted: &[f64]) -> f64 {
    let n = sorted.len();
    if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    }
}

/// `value` to three significant figures ("0.0143", "6.04", "130"), "—" when not a number: the
/// timing tables' cells, whose values span milliseconds to minutes.
pub fn significant(value: f64) -> String {
    if !value.is_finite() {
        return "—".to_owned();
    }
    if value == 0.0 {
        return "0".to_owned();
    }
    let digits = (2 - value.abs().log10().floor() as i32).max(0) as usize;
    format!("{value:.digits$}")
}

/// The CPU time consumed so far by this process, every thread [s].
pub fn process_cpu_seconds() -> f64 {
    let mut now = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `now` is a valid, writable timespec; CLOCK_PROCESS_CPUTIME_ID exists on Linux.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut now) };
    now.tv_sec as f64 + now.tv_nsec as f64 * 1e-9
}

/// The CPU time consumed so far by this process (every thread) and by the external programs it
/// has run (gmsh, FreeFem++, python3: external solvers do their work in child processes) [s].
/// Solvers are timed one at a time, so the process's time is the timed solver's.
fn cpu_time() -> f64 {
    process_cpu_seconds() + spherecontact_system::reap::child_cpu_seconds()
}

/// Runs every solver `repeat` times (≥ 1) on `scene`, round-robin, after one warm-up run each.
/// A solver that fails is reported with its error and left out of the timings.
pub fn time_solvers(
    solvers: &[Box<dyn Solver>],
    scene: &Scene,
    repeat: usize,
) -> Vec<Result<Timing, (String, SolveError)>> {
    let mut results: Vec<_> = solvers
        .iter()
        .map(|s| {
            solver::run(s.as_ref(), scene)
                .map(|history| Timing {
                    solver: s.name().to_owned(),
                    seconds: Vec::new(),
                    cpu_seconds: Vec::new(),
                    history,
                })
                .map_err(|e| (s.name().to_owned(), e))
        })
        .collect();
    for _ in 0..repeat.max(1) {
        for (solver, result) in solvers.iter().zip(results.iter_mut()) {
            if let Ok(timing) = result {
                let (start, cpu_start) = (Instant::now(), cpu_time());
                let outcome = solver::solve_catching_panics(solver.as_ref(), scene);
                timing.cpu_seconds.push(cpu_time() - cpu_start);
                timing.seconds.push(start.elapsed().as_secs_f64());
                std::hint::black_box(outcome.ok());
            }
        }
    }
    for timing in results.iter_mut().flatten() {
        timing.seconds.sort_by(f64::total_cmp);
        timing.cpu_seconds.sort_by(f64::total_cmp);
    }
    results
}

/// A measured rung, or the solver and why it gave no history.
pub type RungResult = Result<Rung, (String, SolveError)>;

/// One measured rung of a solver's resolution ladder.
#[derive(Clone, Debug)]
pub struct Rung {
    /// The timing and history.
    pub timing: Timing,
    /// The references its errors are measured against: "hertz" and "mdr", or for a model of a
    /// finite body [`CORRECTED_REFERENCE`] (MDR in series with the case's domain).
    pub reference: &'static str,
    /// max |P − P_ref| / P_ref over the steps in contact; `None` for Hertz itself or a solver
    /// without P.
    pub normal_error: Option<f64>,
    /// max |Q − Q_ref| / max |Q_ref|; `None` without Q, or on a frictionless path.
    pub tangential_error: Option<f64>,
    /// For a finite body scored against the corrected reference, its raw offsets from Hertz
    /// and from MDR (the domain effect plus the discretisation); `None` otherwise.
    pub raw: Option<(Option<f64>, Option<f64>)>,
}

/// The reference of finite-body solvers: Mindlin–Deresiewicz in series with the case's domain.
pub const CORRECTED_REFERENCE: &str = "mdr-domain";

/// The references of a sweep: Hertz, MDR on [`REFERENCE_SPRINGS`] springs, and `mdr-domain`
/// when a solver of the sweep models a finite body.
pub struct References {
    hertz: History,
    mdr: History,
    corrected: Option<History>,
}

impl References {
    /// Computes the references for `scene`; the corrected one only when `finite_body`.
    pub fn of(scene: &Scene, finite_body: bool) -> Result<Self, SolveError> {
        // Where the corrected reference cannot be computed (a scene it does not apply to), the
        // finite bodies are scored raw, and each rung names the reference it was scored on.
        let corrected = finite_body
            .then(|| solver::run(&MdrDomain::default(), scene).ok())
            .flatten();
        Ok(Self {
            hertz: solver::run(&HertzSolver, scene)?,
            mdr: solver::run(
                &Mdr {
                    springs: REFERENCE_SPRINGS,
                },
                scene,
            )?,
            corrected,
        })
    }

    /// The errors of `history` against Hertz (P) and MDR (Q).
    fn raw_errors(&self, history: &History) -> (Option<f64>, Option<f64>) {
        let normal = (history.metadata.solver != "hertz")
            .then(|| worst_error(history, &self.hertz, Quantity::NormalForce, false))
            .flatten();
        (
            normal,
            worst_error(history, &self.mdr, Quantity::TangentialForce, true),
        )
    }

    /// `history` scored as a rung: a finite body against the corrected reference with its raw
    /// offsets beside, any other solver against Hertz and MDR.
    pub fn score(&self, timing: Timing) -> Rung {
        let raw = self.raw_errors(&timing.history);
        match &self.corrected {
            Some(corrected) if spherecontact_model::domain::models_a_finite_body(&timing.solver) => Rung {
                reference: CORRECTED_REFERENCE,
                normal_error: worst_error(&timing.history, corrected, Quantity::NormalForce, false),
                tangential_error: worst_error(&timing.history, corrected, Quantity::TangentialForce, true),
                raw: Some(raw),
                timing,
            },
            _ => Rung {
                reference: "hertz, mdr",
                normal_error: raw.0,
                tangential_error: raw.1,
                raw: None,
                timing,
            },
        }
    }
}

/// The worst error of `quantity` against `reference` over the steps: relative to each step's
/// reference value (steps with a zero reference skipped), or to the reference's peak.
pub fn worst_error(history: &History, reference: &History, quantity: Quantity, to_peak: bool) -> Option<f64> {
    let peak = reference.peak(quantity);
    let errors = history
        .steps
        .iter()
        .zip(&reference.steps)
        .filter_map(|(row, reference)| {
            let (v, r) = (quantity.of(row)?, quantity.of(reference)?);
            let scale = if to_peak { peak } else { r.abs() };
            (scale > 0.0).then(|| (v - r).abs() / scale)
        });
    errors.fold(None, |m: Option<f64>, e| Some(m.map_or(e, |m| m.max(e))))
}

/// Times every solver's resolution ladder (or the solver alone, without one) on `scene`,
/// interleaved, and measures each rung's errors.
pub fn sweep(
    solvers: &[Box<dyn Solver>],
    scene: &Scene,
    repeat: usize,
) -> Result<Vec<RungResult>, SolveError> {
    let finite_body = solvers
        .iter()
        .any(|s| spherecontact_model::domain::models_a_finite_body(s.name()));
    let references = References::of(scene, finite_body)?;
    let rungs: Vec<Box<dyn Solver>> = solvers
        .iter()
        .flat_map(|s| {
            let ladder = s.resolution_ladder(scene);
            if ladder.is_empty() {
                registry::by_name(s.name()).into_iter().collect()
            } else {
                ladder
            }
        })
        .collect();
    Ok(time_solvers(&rungs, scene, repeat)
        .into_iter()
        .map(|result| result.map(|timing| references.score(timing)))
        .collect())
}

/// A solver that `bench` cannot sweep.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// A solver the case defines, named on the command line.
    #[error(
        "--solver `{name}`: {what} defined by the case has no resolutions to sweep and no timing \
         of its own (allowed: a solver of this build, see `spherecontact list`; `verify` and \
         `compare` check it)"
    )]
    CaseDefined {
        /// Its name.
        name: String,
        /// What it is, in words.
        what: &'static str,
    },
    /// Nothing left to sweep.
    #[error(
        "{case}: every solver of the case is defined by the case ({names}), none can be swept \
         (allowed: `--solver NAME` with a solver of this build, see `spherecontact list`)"
    )]
    Nothing {
        /// The case's name.
        case: String,
        /// The solvers left out.
        names: String,
    },
}

/// The solvers of `plan` that `bench` sweeps: this build's. A solver the case defines (stored
/// results, a command) has no resolution ladder and is not in the registry: named on the
/// command line (`named`) it is refused; from the case's own list it is left out, and its name
/// is returned among those left out.
pub fn sweepable(
    case: &Case,
    plan: Vec<Box<dyn Solver>>,
    named: bool,
) -> Result<(Vec<Box<dyn Solver>>, Vec<String>), PlanError> {
    let mut kept = Vec::new();
    let mut left_out = Vec::new();
    for solver in plan {
        let Some(own) = case.own_solvers.iter().find(|s| s.name() == solver.name()) else {
            kept.push(solver);
            continue;
        };
        if named {
            return Err(PlanError::CaseDefined {
                name: own.name().to_owned(),
                what: match own {
                    CaseSolver::Command(_) => "a command",
                    CaseSolver::Stored(_) => "stored results",
                },
            });
        }
        left_out.push(own.name().to_owned());
    }
    if kept.is_empty() {
        return Err(PlanError::Nothing {
            case: case.name().to_owned(),
            names: left_out.join(", "),
        });
    }
    Ok((kept, left_out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_model::path::{LoadingPath, Position};

    #[test]
    fn significant_keeps_three_figures_from_milliseconds_to_minutes_and_never_prints_nan() {
        assert_eq!(significant(0.014_32), "0.0143");
        assert_eq!(significant(6.04), "6.04");
        assert_eq!(significant(130.4), "130");
        assert_eq!(significant(779_242.3), "779242");
        assert_eq!(significant(0.0), "0");
        assert_eq!(significant(f64::NAN), "—");
        assert_eq!(significant(f64::INFINITY), "—");
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[1.0, 2.0, 10.0]), 2.0);
        assert_eq!(median(&[1.0, 2.0, 3.0, 10.0]), 2.5);
    }

    #[test]
    fn cpu_time_counts_the_process_and_the_external_programs() {
        let start = cpu_time();
        let mut x = 0.0_f64;
        for i in 0..2_000_000 {
            x = std::hint::black_box(x + (i as f64).sqrt());
        }
        assert!(cpu_time() > start, "{x}");
        // An external program that burns CPU, run as external solvers run theirs.
        let dir = tempfile::tempdir().unwrap();
        let job = spherecontact_system::process::Job {
            program: "sh".into(),
            args: vec![
                "-c".into(),
                "i=0; while [ $i -lt 200000 ]; do i=$((i+1)); done".into(),
            ],
            env: Vec::new(),
            timeout: std::time::Duration::from_secs(60),
        };
        let before = cpu_time();
        let run = spherecontact_system::process::run(&job, dir.path(), "burn").unwrap();
        assert!(run.succeeded());
        let spent = cpu_time() - before;
        assert!(spent > 0.01, "the program's CPU time is not counted: {spent}");
    }

    #[test]
    fn the_mdr_ladder_converges_towards_the_reference() {
        // Requirement: along MDR's ladder (250 → 16 000 springs, 64× finer) both errors fall at
        // second order, 4096× (measured: P 4600×, Q 4000×); asserted 1000×, for where the
        // contact and stick edges fall within their cells at the few sampled steps.
        let position = |n: f64, t: f64| Position {
            delta_n: n * 1e-6,
            delta_t: t * 1e-6,
        };
        let scene = Scene {
            name: "sweep".into(),
            pair: spherecontact_model::fixtures::paper_pair(),
            friction: 0.2,
            path: LoadingPath::try_new(
                vec![position(0.0, 0.0), position(17.0, 0.0), position(17.0, 3.0)],
                vec![17, 30],
            )
            .unwrap(),
            domain: Default::default(),
            fields: Default::default(),
        };
        let rungs = sweep(&[Box::new(Mdr::default())], &scene, 1).unwrap();
        let rungs: Vec<Rung> = rungs.into_iter().map(|r| r.unwrap()).collect();
        assert_eq!(rungs.len(), 7);
        let (first, last) = (&rungs[0], &rungs[6]);
        let fall = |e: fn(&Rung) -> Option<f64>| e(first).unwrap() / e(last).unwrap();
        assert!(
            fall(|r| r.normal_error) > 1000.0,
            "P falls {}×",
            fall(|r| r.normal_error)
        );
        assert!(
            fall(|r| r.tangential_error) > 1000.0,
            "Q falls {}×",
            fall(|r| r.tangential_error)
        );
    }
}
