//! One trait for every way of solving a scene (the registry of solvers by name is
//! `registry` (spherecontact-case)).
//!
//! Every solver — closed form, incremental law, boundary elements, finite elements, or an
//! external program — takes a [`Scene`] and returns a [`History`] with one row per path step.

pub mod kind;
pub mod split;

pub use kind::Kind;

use std::time::Instant;

use crate::history::{History, Quantity};
use crate::path::{Step, PATH_MATCH};
use crate::resolution::ResolutionError;
use crate::scene::Scene;

/// Why a solver gave no history.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// The model does not apply to this scene (e.g. Cattaneo–Mindlin under a varying normal load).
    #[error("not applicable: {0}")]
    NotApplicable(String),
    /// The solver is not installed on this machine (external tools).
    #[error("not available: {0}")]
    Unavailable(String),
    /// The solver ran and failed.
    #[error("failed: {0}")]
    Failed(String),
}

/// A way of solving a scene.
pub trait Solver: Send + Sync {
    /// The name used on the command line and in case files.
    fn name(&self) -> &str;

    /// One line: the model and the method.
    fn description(&self) -> &str;

    /// The kind of model it is: where tables, figures and scoreboards place it.
    fn kind(&self) -> Kind;

    /// Solves the scene along its whole path. Implementations fill the per-step rows and the
    /// metadata's model, resolution and warnings; [`run`] adds name, version and wall time.
    fn solve(&self, scene: &Scene) -> Result<History, SolveError>;

    /// A coarse estimate of the wall time of [`Solver::solve`] on `scene` [s], from its size
    /// ([`crate::cost`]), to announce a long run before it starts ([`crate::progress`]); `None`
    /// where there is no model (the external programs, which run under their own timeouts).
    fn estimated_seconds(&self, _scene: &Scene) -> Option<f64> {
        None
    }

    /// The same solver at a ladder of resolutions for `scene`, coarse to fine (springs, grid,
    /// mesh size — sizes scale with the scene's contact), for convergence and speed-against-error
    /// studies; empty where resolution has no meaning (closed forms, incremental laws whose
    /// resolution is the path's own increments).
    fn resolution_ladder(&self, _scene: &Scene) -> Vec<Box<dyn Solver>> {
        Vec::new()
    }

    /// The same solver at the resolution `value` (a case's `[resolution]` entry or
    /// `--resolution NAME=VALUE`), judged for `scene`; the default: no resolution to choose.
    /// Every value accepted must solve in bounded memory ([`crate::limits`]).
    fn at_resolution(&self, _scene: &Scene, _value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        Err(ResolutionError::NotResolvable {
            solver: self.name().to_owned(),
            with: String::new(),
        })
    }

    /// The same solver on `ranks` MPI ranks, for solvers that run under MPI; `None` for the
    /// others.
    fn with_ranks(&self, _ranks: u32) -> Option<Box<dyn Solver>> {
        None
    }

    /// The same solver with the case's CalculiX settings (`[calculix]`: contact formulation,
    /// penalty, element), for the CalculiX solvers; `None` for the others.
    fn with_calculix(&self, _settings: &crate::calculix_settings::Settings) -> Option<Box<dyn Solver>> {
        None
    }

    /// The same solver with the case's Kratos settings (`[kratos]`: contact formulation, element,
    /// ALM and penalty factors), for `kratos-3d`; `None` for the others.
    fn with_kratos(&self, _settings: &crate::kratos_settings::Settings) -> Option<Box<dyn Solver>> {
        None
    }

    /// The same solver with its stick regularised by `slope` (`[fem-3d] stick_slope`), for
    /// fem-3d; `None` for the others.
    fn with_stick_slope(&self, _slope: crate::stick_slope::StickSlope) -> Option<Box<dyn Solver>> {
        None
    }

    /// The same solver writing its volume or surface fields as VTU files (for ParaView) into
    /// `dir`; `None` for solvers without such fields.
    fn writing_fields_to(&self, _dir: &std::path::Path) -> Option<Box<dyn Solver>> {
        None
    }

    /// The solver as a deck that can be written into a folder, run elsewhere and read back
    /// (`spherecontact deck write|read`, [`split`]); `None` for the others.
    fn split_deck(&self) -> Option<&dyn split::SplitDeck> {
        None
    }

    /// The cores a run of this solver keeps busy (its threads, its MPI ranks): what a schedule
    /// of concurrent runs sets aside for it (`verify --jobs`, `schedule` (spherecontact-verify)). One by
    /// default.
    fn cores(&self) -> usize {
        1
    }
}

/// Runs `solver` on `scene`, timing it and completing the history's metadata.
///
/// A history with a non-finite value, or with a row count that does not match the path, is a
/// failure of the solver: it is reported as such and never printed as a result. So is a panic:
/// see [`solve_catching_panics`].
pub fn run(solver: &dyn Solver, scene: &Scene) -> Result<History, SolveError> {
    let start = Instant::now();
    let mut history = solve_catching_panics(solver, scene)?;
    validate(&history, &scene.steps()).map_err(SolveError::Failed)?;
    let meta = &mut history.metadata;
    meta.wall_time_s = start.elapsed().as_secs_f64();
    meta.solver = solver.name().to_owned();
    if meta.version.is_empty() {
        meta.version = env!("CARGO_PKG_VERSION").to_owned();
    }
    Ok(history)
}

/// [`run`] under `label` (e.g. the case and the solver): announced on stderr when its estimate is
/// long, and metered while it runs ([`crate::progress`]).
pub fn run_reported(solver: &dyn Solver, scene: &Scene, label: &str) -> Result<History, SolveError> {
    crate::progress::metered(
        label,
        solver.estimated_seconds(scene),
        crate::progress::Work::steps(scene.steps().len()),
        || run(solver, scene),
    )
}

/// `solver.solve(scene)`, with a panic turned into a failure of this solver.
///
/// The last line of defence: case validation keeps every derived quantity a normal number so
/// that no solver should panic, but a bug that still does so must fail its own solver only, with
/// the panic's message, and let the others of the run go on. (The panic is still printed by
/// the default hook, with its location, for a bug report.)
pub fn solve_catching_panics(solver: &dyn Solver, scene: &Scene) -> Result<History, SolveError> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| solver.solve(scene))).unwrap_or_else(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".to_owned());
        Err(SolveError::Failed(format!(
            "internal error (a panic, please report it): {message}"
        )))
    })
}

/// Rejects histories that would print NaN or inf in any output column, or misalign with the
/// path `steps`: the rows (a row per step, each on its step: index, position, and δn, δt within
/// [`PATH_MATCH`] of the path's largest) and the surface fields. A solver's live run and a run
/// read back from a run file (`merge` (spherecontact-verify)) are checked alike. Why, else.
pub fn validate(history: &History, steps: &[Step]) -> Result<(), String> {
    if history.steps.len() != steps.len() {
        return Err(format!(
            "{} rows for a path of {} steps",
            history.steps.len(),
            steps.len()
        ));
    }
    let scale = steps
        .iter()
        .map(|s| s.delta_n.abs().max(s.delta_t.abs()))
        .fold(0.0, f64::max);
    let non_finite = |what: &str, at: String| format!("non-finite {what} at {at}");
    for (row, step) in history.steps.iter().zip(steps) {
        let columns = [("delta_n", Some(row.delta_n)), ("delta_t", Some(row.delta_t))];
        let quantities = Quantity::ALL.map(|q| (q.name(), q.of(row)));
        for (name, value) in columns.into_iter().chain(quantities) {
            if value.is_some_and(|v| !v.is_finite()) {
                return Err(non_finite(name, format!("step {}", row.step)));
            }
        }
        let off = |a: f64, b: f64| (a - b).abs() > PATH_MATCH * scale;
        if row.step != step.index
            || row.position != step.position
            || off(row.delta_n, step.delta_n)
            || off(row.delta_t, step.delta_t)
        {
            return Err(format!(
                "row {} is not on the path's step {} (its step, position, delta_n or delta_t differs)",
                row.step, step.index
            ));
        }
    }
    for field in &history.fields {
        let at = || format!("the field of position {}", field.position);
        let points = field.points.iter().flatten();
        let traction = field.traction.iter().flatten().flatten();
        if !points
            .chain(&field.pressure)
            .chain(traction)
            .all(|v| v.is_finite())
        {
            return Err(non_finite("surface field value", at()));
        }
        let lengths = [
            Some(field.pressure.len()),
            field.traction.as_ref().map(Vec::len),
            field.stick.as_ref().map(Vec::len),
        ];
        if lengths.into_iter().flatten().any(|n| n != field.points.len()) {
            return Err(format!("{}: arrays of unequal lengths", at()));
        }
    }
    Ok(())
}

/// A solver at a resolution the user chose: it records the value in its histories' metadata
/// (`chosen_resolution`), which reports show beside the resolution in words.
pub struct Resolved {
    /// The solver, already at that resolution.
    pub inner: Box<dyn Solver>,
    /// The value as the user gave it.
    pub value: String,
}

impl Solver for Resolved {
    fn name(&self) -> &str {
        self.inner.name()
    }

    fn description(&self) -> &str {
        self.inner.description()
    }

    fn kind(&self) -> Kind {
        self.inner.kind()
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let mut history = self.inner.solve(scene)?;
        history.metadata.chosen_resolution = Some(self.value.clone());
        Ok(history)
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        self.inner.estimated_seconds(scene)
    }

    fn resolution_ladder(&self, scene: &Scene) -> Vec<Box<dyn Solver>> {
        self.inner.resolution_ladder(scene)
    }

    fn cores(&self) -> usize {
        self.inner.cores()
    }

    fn split_deck(&self) -> Option<&dyn split::SplitDeck> {
        self.inner.split_deck()
    }

    fn writing_fields_to(&self, dir: &std::path::Path) -> Option<Box<dyn Solver>> {
        self.inner.writing_fields_to(dir).map(|inner| self.around(inner))
    }

    /// The same resolution with other CalculiX settings (a formulation sweep).
    fn with_calculix(&self, settings: &crate::calculix_settings::Settings) -> Option<Box<dyn Solver>> {
        self.inner.with_calculix(settings).map(|inner| self.around(inner))
    }

    /// The same resolution with other Kratos settings (a formulation sweep).
    fn with_kratos(&self, settings: &crate::kratos_settings::Settings) -> Option<Box<dyn Solver>> {
        self.inner.with_kratos(settings).map(|inner| self.around(inner))
    }

    fn with_stick_slope(&self, slope: crate::stick_slope::StickSlope) -> Option<Box<dyn Solver>> {
        self.inner.with_stick_slope(slope).map(|inner| self.around(inner))
    }
}

impl Resolved {
    /// `inner` at this resolution value.
    fn around(&self, inner: Box<dyn Solver>) -> Box<dyn Solver> {
        Box::new(Resolved {
            inner,
            value: self.value.clone(),
        })
    }
}
