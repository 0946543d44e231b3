//! The real DEM codes run dynamically over an impact sweep: LAMMPS (`pair_style granular`, one
//! solver per tangential model of the kinematic adapters, `fix nve/sphere`), YADE
//! (`Law2_ScGeom_MindlinPhys_Mindlin`, `NewtonIntegrator`), LIGGGHTS (`pair gran` hertz +
//! tangential history, `fix nve/sphere`, a rigid flat its own `fix wall/gran`) and Kratos
//! (`DEM_D_Hertz_viscous_Coulomb`, symplectic Euler). Each sweep is one process: the input is
//! generated from the case ([`super::lammps`], [`super::yade`], [`super::liggghts`],
//! [`super::kratos`]), run in a fresh folder with
//! the process handling of every external program (`spherecontact_external::program`: timeout, the
//! whole process tree killed, the folder and its log kept on failure), and each sweep point's
//! rows read back ([`super::code_readback`]) into the outcome the built-in laws produce.
//!
//! The codes place the sweep points alike ([`super::placement`]: two spheres on the z axis, a
//! rigid flat a fixed sphere of [`super::placement::FLAT_RADIUS_FACTOR`] × R1, one material for
//! both bodies, the built-in laws' step).
//!
//! These runs are the programs the harness drives with input it writes itself (no case names a
//! command): they need no `--allow-commands` (docs/security.md), and a code not installed makes
//! its checks N/A.

use std::path::Path;
use std::time::{Duration, Instant};

use super::budget::{STEP_BUDGET, TRACE_SAMPLES};
use super::case::{ImpactCase, Point, Variant};
use super::code_readback::{self, Rows};
use super::placement::{points_file, Placement, POINTS};
use super::solver_run::SolverRun;
use super::tally::Tally;
use spherecontact_external::dem::kratos::KratosLaw;
use spherecontact_external::dem::lammps::TangentialModel;
use spherecontact_external::dem::liggghts;
use spherecontact_external::dem::yade::YadeLaw;
use spherecontact_external::program;
use spherecontact_model::progress;
use spherecontact_model::solver::SolveError;
use spherecontact_reference::impact::integrator::Integration;
use spherecontact_reference::impact::outcome::Outcome;
use spherecontact_system::process::{Environment, Job};
use spherecontact_system::toolchain::{Tool, Toolchain};

/// A code's start-up, and the time allowed per step of a sweep (LAMMPS takes ~10 µs a step with
/// its per-step print, YADE ~60 µs through Python; ×50 and more for a loaded machine).
const START_UP: Duration = Duration::from_secs(120);
const PER_STEP: Duration = Duration::from_millis(3);

/// LAMMPS's start-up [s] and its wall time a step of an impact sweep (with its per-step print)
/// [s], for the estimate ([`Code::estimated_seconds`]): measured in a release build on the shared
/// 2-core machine at load 9 (`cargo run --release --example impact_estimate`, docs/impact.md
/// "Speed"): a one-point sweep of 2000 steps 0.73 to 0.87 s wall (0.19 to 0.23 s CPU), test 4's
/// 17 points at 20 000 steps 19 s wall a variant (7.2 s CPU): 5.4e-5 s wall (2.1e-5 s CPU) a
/// step after 0.6 s; the step set between the two, as [`super::cost`] sets its constants. The
/// toolchain's probe (about 5 s once a process, every code) is left out.
pub const LAMMPS_START_UP_S: f64 = 0.6;
/// See [`LAMMPS_START_UP_S`].
pub const LAMMPS_STEP_S: f64 = 4.0e-5;

/// YADE's start-up (its Python and plugins) [s] and its wall time a step of an impact sweep (a
/// Python loop around `O.step()`) [s], measured as [`LAMMPS_START_UP_S`]: a one-point sweep of
/// 2000 steps 3.6 to 4.6 s wall (1.4 to 1.8 s CPU), test 4's 17 points at 20 000 steps 23 s wall
/// a variant (8.7 s CPU): 5.5e-5 s wall (2.1e-5 s CPU) a step after 4 s (1.4 s CPU); both set
/// between wall and CPU.
pub const YADE_START_UP_S: f64 = 3.0;
/// See [`YADE_START_UP_S`].
pub const YADE_STEP_S: f64 = 4.0e-5;

/// Kratos' start-up (its import) [s] and its wall time a step of an impact sweep (its Python
/// solution loop with the script's per-step record) [s]: a one-point sweep of 2717 steps took
/// 1.5 s wall (0.77 s CPU) at load 4, 0.8 s of it the import, on the shared 2-core machine.
pub const KRATOS_START_UP_S: f64 = 0.8;
/// See [`KRATOS_START_UP_S`].
pub const KRATOS_STEP_S: f64 = 2.5e-4;
/// LIGGGHTS's start-up [s] and its wall time a step of an impact sweep (with its per-step
/// thermo row) [s], for the estimate: each point runs its whole step budget (no `fix halt`), so a
/// step is counted four times ([`super::budget`]: the budget is 4 contact durations); measured
/// as [`LAMMPS_START_UP_S`] (docs/impact.md "Speed").
pub const LIGGGHTS_START_UP_S: f64 = 0.6;
/// See [`LIGGGHTS_START_UP_S`].
pub const LIGGGHTS_STEP_S: f64 = 4.0e-5;

/// A DEM code as an impact solver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Code {
    /// LAMMPS with one tangential model.
    Lammps(TangentialModel),
    /// YADE's `Law2_ScGeom_MindlinPhys_Mindlin`.
    Yade,
    /// Kratos with one DEM law.
    Kratos(KratosLaw),
    /// LIGGGHTS' `hertz` + `tangential history`.
    Liggghts,
}

impl Code {
    /// The code called `solver`, if any.
    pub fn named(solver: &str) -> Option<Self> {
        TangentialModel::ALL
            .into_iter()
            .find(|m| m.solver_name() == solver)
            .map(Code::Lammps)
            .or_else(|| (solver == YadeLaw::Mindlin.solver_name()).then_some(Code::Yade))
            .or_else(|| {
                KratosLaw::ALL
                    .into_iter()
                    .find(|law| law.solver_name() == solver)
                    .map(Code::Kratos)
            })
            .or_else(|| (solver == liggghts::NAME).then_some(Code::Liggghts))
    }

    /// The solver's name.
    pub fn name(self) -> &'static str {
        match self {
            Code::Lammps(model) => model.solver_name(),
            Code::Yade => YadeLaw::Mindlin.solver_name(),
            Code::Kratos(law) => law.solver_name(),
            Code::Liggghts => liggghts::NAME,
        }
    }

    /// The expected wall time of one process over a sweep of `steps` integration steps in all
    /// [s]: its start-up and its cost a step ([`super::cost`], which multiplies it by the
    /// variants).
    pub fn estimated_seconds(self, steps: f64) -> f64 {
        match self {
            Code::Lammps(_) => LAMMPS_START_UP_S + LAMMPS_STEP_S * steps,
            Code::Yade => YADE_START_UP_S + YADE_STEP_S * steps,
            Code::Kratos(_) => KRATOS_START_UP_S + KRATOS_STEP_S * steps,
            Code::Liggghts => LIGGGHTS_START_UP_S + LIGGGHTS_STEP_S * STEP_BUDGET as f64 * steps,
        }
    }

    fn tool(self) -> Tool {
        match self {
            Code::Lammps(_) => Tool::Lammps,
            Code::Yade => Tool::Yade,
            Code::Kratos(_) => Tool::KratosDem,
            Code::Liggghts => Tool::Liggghts,
        }
    }

    /// The rows of a point's output `file` (LIGGGHTS: its log's thermo rows).
    fn rows(self, file: &Path) -> Result<Rows, code_readback::ReadbackError> {
        match self {
            Code::Liggghts => super::liggghts::rows(file),
            Code::Lammps(_) | Code::Yade | Code::Kratos(_) => Rows::read(file),
        }
    }

    /// The placement a point's rows are read against (LIGGGHTS' wall: its mirror sphere).
    fn seen(self, placement: &Placement) -> Placement {
        match self {
            Code::Liggghts => super::liggghts::readback(placement),
            Code::Lammps(_) | Code::Yade | Code::Kratos(_) => *placement,
        }
    }

    /// Writes the input for `placements` into `dir`; the job that runs it.
    fn prepare(self, placements: &[Placement], dir: &Path, toolchain: &Toolchain) -> std::io::Result<Job> {
        let steps: usize = placements.iter().map(|p| p.max_steps).sum();
        let timeout = program::time_limit(START_UP, PER_STEP, steps);
        match self {
            Code::Lammps(model) => {
                std::fs::write(
                    dir.join(super::lammps::INPUT),
                    super::lammps::input(model, placements),
                )?;
                Ok(Job {
                    program: toolchain.lammps.clone(),
                    args: ["-in", super::lammps::INPUT, "-log", "none", "-nocite"]
                        .map(String::from)
                        .to_vec(),
                    env: Vec::new(),
                    timeout,
                })
            }
            Code::Liggghts => {
                let input = super::liggghts::input(placements, super::liggghts::WALL_STIFFNESS_FACTOR);
                std::fs::write(dir.join(super::liggghts::INPUT), input)?;
                Ok(Job {
                    program: toolchain.liggghts.clone(),
                    args: ["-in", super::liggghts::INPUT, "-log", "none", "-nocite"]
                        .map(String::from)
                        .to_vec(),
                    env: Vec::new(),
                    timeout,
                })
            }
            Code::Yade => {
                std::fs::write(dir.join(POINTS), points_file(placements))?;
                spherecontact_external::dem::yade::job(
                    &toolchain.yade,
                    dir,
                    super::yade::SCRIPT,
                    super::yade::SCRIPT_TEXT,
                    timeout,
                )
            }
            Code::Kratos(law) => {
                std::fs::write(dir.join(POINTS), points_file(placements))?;
                std::fs::write(dir.join(super::kratos::SCRIPT), super::kratos::script(law))?;
                Ok(Job {
                    program: toolchain.kratos_python.clone(),
                    args: vec![super::kratos::SCRIPT.into()],
                    env: vec![("OMP_NUM_THREADS".into(), "1".into())],
                    timeout,
                })
            }
        }
    }
}

/// The points of `case` in `variant`.
fn variant_points(case: &ImpactCase, variant: Variant) -> Vec<Point> {
    case.points()
        .into_iter()
        .map(|p| match variant {
            Variant::Prescribed => p,
            Variant::Elastic => p.elastic(),
        })
        .collect()
}

/// Runs `code` over every sweep point of `case` in `variant`, in one process, each point done
/// reported as `tally` places it.
pub(super) fn run_sweep(case: &ImpactCase, code: Code, variant: Variant, tally: Tally) -> SolverRun {
    sweep_with(case, code, variant, &Toolchain::default(), tally)
}

/// [`run_sweep`] with the executables of `toolchain`.
pub fn run_sweep_with(case: &ImpactCase, code: Code, variant: Variant, toolchain: &Toolchain) -> SolverRun {
    sweep_with(case, code, variant, toolchain, Tally::alone(case.points().len()))
}

/// [`run_sweep_with`], reported as `tally` places it.
fn sweep_with(
    case: &ImpactCase,
    code: Code,
    variant: Variant,
    toolchain: &Toolchain,
    tally: Tally,
) -> SolverRun {
    let points = variant_points(case, variant);
    let placements: Vec<Placement> = points
        .iter()
        .enumerate()
        .map(|(i, p)| Placement::of(case, p, i))
        .collect();
    // The toolchain probe (once per process, every tool) is not the sweep's time.
    let available = toolchain.require(code.tool()).map_err(SolveError::Unavailable);
    let start = Instant::now();
    let result = available.and_then(|_version| run_in_folder(code, &placements, toolchain, tally));
    let (results, trace, unavailable) = match result {
        Ok(integrations) => {
            let trace = integrations.first().map(|i| i.trace.clone()).unwrap_or_default();
            let outcomes = points
                .iter()
                .zip(&integrations)
                .map(|(p, i)| Ok(Outcome::of(p, i)))
                .collect();
            (outcomes, trace, None)
        }
        Err(SolveError::Unavailable(why)) => (
            vec![Err(format!("not available: {why}")); points.len()],
            Vec::new(),
            Some(why),
        ),
        Err(e) => (vec![Err(e.to_string()); points.len()], Vec::new(), None),
    };
    SolverRun {
        solver: code.name().to_owned(),
        variant,
        points: points.iter().map(|p| p.value).zip(results).collect(),
        trace,
        wall_time_s: start.elapsed().as_secs_f64(),
        unavailable,
    }
}

/// Writes the input, runs the code and reads every point back, in a fresh folder (kept on
/// failure); the points done reported as `tally` places them, while the code runs too
/// ([`watcher`]).
fn run_in_folder(
    code: Code,
    placements: &[Placement],
    toolchain: &Toolchain,
    tally: Tally,
) -> Result<Vec<Integration>, SolveError> {
    program::in_run_folder(code.name(), |dir| {
        let job = code
            .prepare(placements, dir, toolchain)
            .map_err(|e| SolveError::Failed(format!("writing the {} input: {e}", code.tool().name())))?;
        let program_name = code.tool().name();
        let meaning = |_| "the code stopped with an error (see its output)";
        progress::watching(watcher(dir, placements.len(), tally), || {
            program::run_to_success(&job, dir, "code", program_name, meaning, &Environment::Inherited)
        })?;
        tally.tick(placements.len());
        placements
            .iter()
            .map(|p| {
                let file = dir.join(code_readback::file_name(p.index));
                let stride = if p.index == 0 {
                    p.max_steps.div_ceil(TRACE_SAMPLES).max(1)
                } else {
                    0
                };
                code.rows(&file)
                    .and_then(|rows| rows.integration(&code.seen(p), stride))
                    .map_err(|e| SolveError::Failed(format!("{}: {e}", file.display())))
            })
            .collect()
    })
}

/// How far a code is over its sweep of `points` points in `dir` ([`progress::watching`]): each
/// point's output file (`point-<i>.txt`) is created when the point starts (LAMMPS's `fix print`,
/// the YADE script), so the points before the last file there are done.
fn watcher(dir: &Path, points: usize, tally: Tally) -> progress::Watcher {
    let dir = dir.to_path_buf();
    let mut started = 0;
    Box::new(move || {
        let before = started;
        while started < points && dir.join(code_readback::file_name(started)).exists() {
            started += 1;
        }
        (started > before && started > 1).then(|| tally.at(started - 1))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requirement (issue 42): a DEM code's sweep reports its points done while it runs, read
    /// from the point files it has started, each advance once, placed within the whole run.
    #[test]
    fn the_watcher_counts_the_points_a_code_has_finished() {
        let dir = tempfile::tempdir().unwrap();
        let tally = Tally::alone(3);
        let mut watch = watcher(dir.path(), 3, tally);
        let start = |i: usize| std::fs::write(dir.path().join(code_readback::file_name(i)), "").unwrap();
        assert_eq!(watch(), None);
        start(0);
        assert_eq!(watch(), None, "point 0 runs: none done");
        start(1);
        assert_eq!(watch(), Some((1, 3)));
        assert_eq!(watch(), None, "no change, no tick");
        start(2);
        assert_eq!(watch(), Some((2, 3)), "the last point runs until the code ends");
    }
}
