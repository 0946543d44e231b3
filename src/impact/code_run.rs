//! The real DEM codes run dynamically over an impact sweep: LAMMPS (`pair_style granular`, one
//! solver per tangential model of the kinematic adapters, `fix nve/sphere`) and YADE
//! (`Law2_ScGeom_MindlinPhys_Mindlin`, `NewtonIntegrator`). Each sweep is one process: the input
//! is generated from the case ([`super::lammps`], [`super::yade`]), run in a fresh folder with
//! the process handling of every external program (`crate::external::program`: timeout, the
//! whole process tree killed, the folder and its log kept on failure), and each sweep point's
//! rows read back ([`super::code_readback`]) into the outcome the built-in laws produce.
//!
//! **Placement** (the same for both codes): body 1 above, body 2 below on the z axis, the gap
//! half a step of approach (first touch inside the first step, interpolated). A **rigid flat is
//! a fixed sphere of radius [`FLAT_RADIUS_FACTOR`] × R1**, not a wall: the codes' sphere–sphere
//! contact is then the one law run in every test, and LAMMPS's `fix wall/gran` is avoided
//! (LAMMPS's `unittest/granular` found a wall model gaining energy at grazing impact). One
//! material (E', ν') for both bodies carries the pair's E* and G*
//! (`crate::dem::lammps::equivalent_material`: a flat is a sphere of 2E and the same ν), since both
//! codes mix two materials differently from Hertz and Mindlin; against a flat, E' is raised by
//! √(R1/R*) = √(1 + 10⁻⁵) so that E*√R* and G*√R* — all Hertz's force, Mindlin's stiffness 8G*a
//! and both codes' damping depend on — are the flat's exactly. What the big sphere still costs:
//! the centres are ~R2 apart, so δ is resolved to ulp(R2) ≈ 2e-16 × 10⁵ R1 (4e-8 of δ_max in
//! tests 2 and 4); and the normal turns by x/R2 over the contact's tangential travel x (≤ 2e-5
//! rad in test 5, ≤ 2e-6 elsewhere). The step is h = t_c / `steps` (t_c Hertz's duration at the point's normal speed),
//! as the built-in laws'; docs/impact.md shows it converged.
//!
//! These runs are the programs the harness drives with input it writes itself (no case names a
//! command): they need no `--allow-commands` (docs/security.md), and a code not installed makes
//! its checks N/A.

use std::path::Path;
use std::time::{Duration, Instant};

use super::budget::{STEP_BUDGET, TRACE_SAMPLES};
use super::case::{ImpactCase, Point, Variant};
use super::closed_form::HertzImpact;
use super::code_readback::{self, Rows};
use super::integrator::Integration;
use super::outcome::Outcome;
use super::run::{SolverRun, Tally};
use crate::dem::lammps::TangentialModel;
use crate::dem::yade::YadeLaw;
use crate::external::process::{Environment, Job};
use crate::external::program;
use crate::external::toolchain::{Tool, Toolchain};
use crate::hertz::Hertz;
use crate::progress;
use crate::solver::SolveError;

/// A rigid flat is a fixed sphere this many times body 1's radius (see the module doc).
pub const FLAT_RADIUS_FACTOR: f64 = 1e5;

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

/// A DEM code as an impact solver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Code {
    /// LAMMPS with one tangential model.
    Lammps(TangentialModel),
    /// YADE's `Law2_ScGeom_MindlinPhys_Mindlin`.
    Yade,
}

impl Code {
    /// The code called `solver`, if any.
    pub fn named(solver: &str) -> Option<Self> {
        TangentialModel::ALL
            .into_iter()
            .find(|m| m.solver_name() == solver)
            .map(Code::Lammps)
            .or_else(|| (solver == YadeLaw::Mindlin.solver_name()).then_some(Code::Yade))
    }

    /// The solver's name.
    pub fn name(self) -> &'static str {
        match self {
            Code::Lammps(model) => model.solver_name(),
            Code::Yade => YadeLaw::Mindlin.solver_name(),
        }
    }

    /// The expected wall time of one process over a sweep of `steps` integration steps in all
    /// [s]: its start-up and its cost a step ([`super::cost`], which multiplies it by the
    /// variants).
    pub fn estimated_seconds(self, steps: f64) -> f64 {
        match self {
            Code::Lammps(_) => LAMMPS_START_UP_S + LAMMPS_STEP_S * steps,
            Code::Yade => YADE_START_UP_S + YADE_STEP_S * steps,
        }
    }

    fn tool(self) -> Tool {
        match self {
            Code::Lammps(_) => Tool::Lammps,
            Code::Yade => Tool::Yade,
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
            Code::Yade => {
                std::fs::write(dir.join(super::yade::POINTS), super::yade::points(placements))?;
                crate::dem::yade::job(
                    &toolchain.yade,
                    dir,
                    super::yade::SCRIPT,
                    super::yade::SCRIPT_TEXT,
                    timeout,
                )
            }
        }
    }
}

/// One sweep point as the codes see it: two spheres on the z axis (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The sweep point's index (its output is `point-<index>.txt`).
    pub index: usize,
    /// Radii; a flat's is [`FLAT_RADIUS_FACTOR`] × R1.
    pub radius: [f64; 2],
    /// Densities; a flat's is body 1's (it is fixed: its mass never enters).
    pub density: [f64; 2],
    /// Centres (x, z): body 2's at (0, −R2), body 1's half a step of approach above contact.
    pub centre: [[f64; 2]; 2],
    /// Centre velocities (v_x, v_z).
    pub velocity: [[f64; 2]; 2],
    /// Spins about the codes' y axis: −ω1 for body 1 (above), +ω2 for body 2 (below).
    pub spin_y: [f64; 2],
    /// Body 2 is fixed (the flat).
    pub fixed: bool,
    /// The one material (E', ν') of both bodies.
    pub young: f64,
    /// Its Poisson ratio ν'.
    pub poisson: f64,
    /// μ.
    pub friction: f64,
    /// The prescribed restitution (1: no damping).
    pub restitution: f64,
    /// The time step h [s].
    pub step: f64,
    /// The most steps the code may take.
    pub max_steps: usize,
    /// Half the side of the simulation box [m].
    pub half_box: f64,
}

impl Placement {
    /// The placement of `point` (sweep index `index`) of `case`.
    pub fn of(case: &ImpactCase, point: &Point, index: usize) -> Self {
        let hertz = Hertz::of(&case.pair());
        let step = HertzImpact::of(point, &hertz).duration / case.steps as f64;
        let r1 = point.body1.body.radius;
        let fixed = point.body2.is_rigid();
        let r2 = if fixed {
            FLAT_RADIUS_FACTOR * r1
        } else {
            point.body2.body.radius
        };
        let density1 = point.body1.density.unwrap_or_default();
        let (young, poisson) = crate::dem::lammps::equivalent_material(&case.pair());
        // E*√R* kept: R* = R1 R2 / (R1 + R2) is the flat's R1 only as R2 → ∞.
        let young = if fixed {
            young * ((r1 + r2) / r2).sqrt()
        } else {
            young
        };
        let gap = 0.5 * point.approach_speed() * step;
        let max_steps = STEP_BUDGET * case.steps + 2;
        let speed = |b: &super::case::ImpactBody| b.velocity[0].hypot(b.velocity[1]);
        let travel = (speed(&point.body1) + speed(&point.body2)) * step * max_steps as f64;
        Self {
            index,
            radius: [r1, r2],
            density: [density1, point.body2.density.unwrap_or(density1)],
            centre: [[0.0, r1 + gap], [0.0, -r2]],
            velocity: [point.body1.velocity, point.body2.velocity],
            spin_y: [-point.body1.spin, point.body2.spin],
            fixed,
            young,
            poisson,
            friction: case.friction,
            restitution: point.restitution,
            step,
            max_steps,
            half_box: 2.0 * (r1 + r2) + travel,
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
                Rows::read(&file)
                    .and_then(|rows| rows.integration(p, stride))
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
