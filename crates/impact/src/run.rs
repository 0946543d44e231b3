//! Running an impact case: each solver's contact law through the integrator at every sweep
//! point, in each variant (prescribed restitution, and elastic when e < 1). A solver's run over
//! every variant is announced when its estimate ([`super::cost`]) is long and metered in sweep
//! points ([`spherecontact_model::progress`]), as a path run is in steps.

use std::time::Instant;

use super::budget::{STEP_BUDGET, TRACE_SAMPLES};
use super::case::{ImpactCase, Point, Variant};
use super::closed_form::HertzImpact;
use super::code_rule::{self, Rule};
use super::solver_run::SolverRun;
use super::tally::Tally;
use spherecontact_model::hertz::Hertz;
use spherecontact_model::progress::{self, Work};
use spherecontact_reference as analytic;
use spherecontact_reference::impact::integrator::{self, Integration, IntegrationError, Stepping};
use spherecontact_reference::impact::law::{ContactLaw, DemLaw, MdrLaw};
use spherecontact_reference::impact::outcome::Outcome;

/// The name of the exact reference: MDR's spring bed as the contact law.
pub use spherecontact_reference::impact::problem::REFERENCE;

/// The MDR window holds contact radii up to this factor of the elastic impact's largest one
/// (the bed's own 5 % margin comes on top).
const WINDOW_FACTOR: f64 = 1.05;

pub use spherecontact_case::solver_names;

/// The contact law `solver` for `point` (none for an unknown name).
fn law_for(case: &ImpactCase, solver: &str, point: &Point) -> Option<Box<dyn ContactLaw>> {
    let pair = case.pair();
    if code_rule::is_reference(solver) {
        let hertz = Hertz::of(&pair);
        let reach = HertzImpact::of(point, &hertz).max_overlap * WINDOW_FACTOR;
        let radius = hertz.contact_radius(reach);
        return Some(Box::new(MdrLaw::new(&pair, case.friction, radius, case.springs)));
    }
    let law = analytic::dem_laws().into_iter().find(|l| l.name == solver)?;
    Some(Box::new(DemLaw::new(&law, &pair, case.friction)))
}

/// Integrates one impact of `case` with `solver`'s law at `steps` steps per Hertz duration.
pub fn impact(
    case: &ImpactCase,
    solver: &str,
    point: &Point,
    steps: usize,
    traced: bool,
) -> Result<Integration, String> {
    let mut law = law_for(case, solver, point).ok_or_else(|| format!("no impact solver `{solver}`"))?;
    let hertz = Hertz::of(&case.pair());
    let duration = HertzImpact::of(point, &hertz).duration;
    let damping = Rule::of(solver).damping(point.restitution, point.effective_mass(), &hertz);
    let stepping = Stepping {
        step: duration / steps as f64,
        max_steps: STEP_BUDGET * steps,
        stride: if traced {
            (STEP_BUDGET * steps).div_ceil(TRACE_SAMPLES).max(1)
        } else {
            0
        },
    };
    integrator::integrate(point, law.as_mut(), damping.as_ref(), stepping)
        .map_err(|e: IntegrationError| e.to_string())
}

/// Runs `solver` over every sweep point of `case` in `variant` (a DEM code: one process for the
/// sweep, [`super::code_run`]).
pub fn run_solver(case: &ImpactCase, solver: &str, variant: Variant) -> SolverRun {
    run_tallied(case, solver, variant, Tally::alone(case.points().len()))
}

/// [`run_solver`], each point done reported as `tally` places it.
fn run_tallied(case: &ImpactCase, solver: &str, variant: Variant, tally: Tally) -> SolverRun {
    if let Some(code) = super::code_run::Code::named(solver) {
        return super::code_run::run_sweep(case, code, variant, tally);
    }
    if let Some(own) = case.own_solver(solver) {
        let run = super::own_run::run_own(case, own, variant);
        tally.tick(case.points().len());
        return run;
    }
    let start = Instant::now();
    let mut trace = Vec::new();
    let points = case
        .points()
        .iter()
        .enumerate()
        .map(|(index, point)| {
            let point = match variant {
                Variant::Prescribed => *point,
                Variant::Elastic => point.elastic(),
            };
            let result = impact(case, solver, &point, case.steps, index == 0).map(|integration| {
                if index == 0 {
                    trace = integration.trace.clone();
                }
                Outcome::of(&point, &integration)
            });
            tally.tick(index + 1);
            (point.value, result)
        })
        .collect();
    SolverRun {
        solver: solver.to_owned(),
        variant,
        points,
        trace,
        wall_time_s: start.elapsed().as_secs_f64(),
        unavailable: None,
    }
}

/// Every solver the case needs (its list, then those its checks name), in every variant.
pub fn run_case(case: &ImpactCase, solvers: &[String]) -> Vec<SolverRun> {
    solvers
        .iter()
        .flat_map(|solver| run_metered(case, solver))
        .collect()
}

/// `solver` over the sweep in every variant, under the label `CASE SOLVER`: announced when its
/// estimate is long and metered in sweep points ([`progress::metered`]).
fn run_metered(case: &ImpactCase, solver: &str) -> Vec<SolverRun> {
    let points = case.points().len();
    let total = super::cost::points(case);
    let label = format!("{} {solver}", case.name);
    let seconds = super::cost::seconds(case, solver);
    progress::metered(&label, Some(seconds), Work::points(total), || {
        // The rate is counted from the start: there is no set-up to leave out.
        progress::tick(0, total);
        case.variants()
            .into_iter()
            .enumerate()
            .map(|(k, variant)| {
                let tally = Tally::after(k * points, total);
                run_tallied(case, solver, variant, tally)
            })
            .collect()
    })
}
