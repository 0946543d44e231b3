//! The resolution study behind the claims about the surface fields: each solver that maps the
//! contact plane, run again at the two finest rungs of its resolution ladder on the path cut at
//! the focus position, so that every measured field quantity is stated with how much it still
//! moves under refinement.
//!
//! The increments matter too (the transverse traction depends on the increment size more than
//! the forces do): the study runs `increments` per segment, and the claims compare its rung at
//! the run's own resolution with the run itself (the case's increments).

use super::measure::{MapMeasures, RadialProfile};
use crate::figures::surface::FieldView;
use crate::figures::{fields_at, histories, TANGENTIAL_REFERENCE};
use spherecontact_model::cores::{within_cores, Task};
use spherecontact_model::history::History;
use spherecontact_model::path::LoadingPath;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{self, Solver};
use spherecontact_verify::CaseRun;

/// Increments per path segment in the study: a fifth of the paper case's 100, enough to move
/// the transverse traction by < 1 % (measured at 64²: q_y,max/q_x,max 0.04978 at 20 against
/// 0.05001 at 100).
pub const STUDY_INCREMENTS: usize = 20;

/// One solve of the study.
#[derive(Clone, Debug, PartialEq)]
pub struct Rung {
    /// The solver's resolution, in its own words.
    pub resolution: String,
    /// Increments per path segment.
    pub increments: usize,
    /// The map's measures at the focus position.
    pub measures: MapMeasures,
    /// The contact radius at the focus position [m].
    pub contact_radius: f64,
    /// Wall time of the solve [s].
    pub seconds: f64,
}

/// A solver's study: its rungs, coarse to fine, or why there are none.
#[derive(Clone, Debug, PartialEq)]
pub struct SolverStudy {
    /// The solver.
    pub solver: String,
    /// The rungs that ran.
    pub rungs: Vec<Rung>,
    /// What went wrong, if anything (a rung that failed, no ladder).
    pub problems: Vec<String>,
}

/// The study of every map solver of a run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Study {
    /// One per solver that mapped the plane at the focus position.
    pub solvers: Vec<SolverStudy>,
}

impl Study {
    /// No study: the claims use the run's own fields and say the resolution study did not run.
    pub fn none() -> Self {
        Self::default()
    }

    /// The two finest rungs of each map solver's ladder, `STUDY_INCREMENTS` per segment, run
    /// within `cores` cores.
    pub fn of_ladders(run: &CaseRun, cores: usize) -> Self {
        let scene = &run.case.scene;
        let solvers = map_solvers(run)
            .into_iter()
            .map(|name| {
                let rungs = spherecontact_case::registry::by_name(&name)
                    .map(|s| s.resolution_ladder(scene))
                    .unwrap_or_default();
                let finest = rungs.len().saturating_sub(2);
                (name, rungs.into_iter().skip(finest).collect())
            })
            .collect();
        Self::of(run, solvers, STUDY_INCREMENTS, cores)
    }

    /// The study with the given solvers (by name: the rungs to run), `increments` per segment;
    /// the rungs run concurrently within `cores` cores ([`within_cores`], the costliest first by
    /// their solvers' estimates), each timed alone.
    pub fn of(
        run: &CaseRun,
        solvers: Vec<(String, Vec<Box<dyn Solver>>)>,
        increments: usize,
        cores: usize,
    ) -> Self {
        let focus = run.case.focus;
        let Some(scene) = cut_at(&run.case.scene, focus, increments) else {
            return Self::none();
        };
        let rungs: Vec<(usize, &dyn Solver)> = solvers
            .iter()
            .enumerate()
            .flat_map(|(k, (_, ladder))| ladder.iter().map(move |rung| (k, rung.as_ref())))
            .collect();
        let tasks: Vec<Task> = rungs
            .iter()
            .map(|(_, rung)| Task::new(rung.cores(), rung.estimated_seconds(&scene).unwrap_or(1.0)))
            .collect();
        let solved = within_cores(&tasks, cores, |i| solver::run(rungs[i].1, &scene));
        let mut studies: Vec<SolverStudy> = solvers
            .iter()
            .map(|(name, ladder)| SolverStudy {
                solver: name.clone(),
                rungs: Vec::new(),
                problems: match ladder.is_empty() {
                    true => vec![format!("{name} has no resolution ladder")],
                    false => Vec::new(),
                },
            })
            .collect();
        let (friction, md) = (scene.friction, md_profile(run));
        for ((k, _), (result, seconds, _)) in rungs.iter().zip(solved) {
            let study = &mut studies[*k];
            let name = &study.solver;
            match result {
                Ok(history) => match measure(&history, focus, friction, md.as_ref()) {
                    Some((measures, contact_radius)) => study.rungs.push(Rung {
                        resolution: history.metadata.resolution.clone(),
                        increments,
                        measures,
                        contact_radius,
                        seconds,
                    }),
                    None => study.problems.push(format!("{name}: no map at position {focus}")),
                },
                Err(e) => study.problems.push(format!("{name}: {e}")),
            }
        }
        Self { solvers: studies }
    }

    /// The study of `solver`, if it ran.
    pub fn of_solver(&self, solver: &str) -> Option<&SolverStudy> {
        self.solvers.iter().find(|s| s.solver == solver)
    }
}

/// The solvers of the run with a map (not a profile) at the focus position.
pub fn map_solvers(run: &CaseRun) -> Vec<String> {
    fields_at(run, run.case.focus)
        .into_iter()
        .filter(|(_, view)| view.is_map())
        .map(|(name, _)| name)
        .collect()
}

/// MD's traction at the focus position: the run's MDR profile, if it ran.
pub fn md_profile(run: &CaseRun) -> Option<RadialProfile> {
    fields_at(run, run.case.focus)
        .iter()
        .find(|(name, _)| name == TANGENTIAL_REFERENCE)
        .and_then(|(_, view)| RadialProfile::of(view))
}

/// A history's map measures and contact radius at `position`.
pub fn measure(
    history: &History,
    position: usize,
    friction: f64,
    md: Option<&RadialProfile>,
) -> Option<(MapMeasures, f64)> {
    let contact_radius = history.at_position(position)?.contact_radius?;
    let measures = MapMeasures::of(
        &FieldView::at_position(history, position)?,
        friction,
        contact_radius,
        md,
    )?;
    Some((measures, contact_radius))
}

/// The run's own measures of `solver` at the focus position (the case's resolution and
/// increments).
pub fn measure_run(run: &CaseRun, solver: &str) -> Option<(MapMeasures, f64)> {
    histories(run)
        .into_iter()
        .find(|(name, _)| name == solver)
        .and_then(|(_, h)| {
            measure(
                h,
                run.case.focus,
                run.case.scene.friction,
                md_profile(run).as_ref(),
            )
        })
}

/// The scene with its path cut at `focus`, `increments` per segment; `None` when the path has
/// no such position or it is the start.
fn cut_at(scene: &Scene, focus: usize, increments: usize) -> Option<Scene> {
    let positions = scene.path.positions().get(..=focus)?.to_vec();
    let path = LoadingPath::try_new(positions, vec![increments; focus])?;
    Some(Scene {
        path,
        ..scene.clone()
    })
}
