//! One trait for every way of solving a scene (the registry of solvers by name is
//! [`crate::registry`]).
//!
//! Every solver — closed form, incremental law, boundary elements, finite elements, or an
//! external program — takes a [`Scene`] and returns a [`History`] with one row per path step.

use std::time::Instant;

use crate::history::{History, Quantity};
use crate::scene::Scene;
use crate::vtu;

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
    fn name(&self) -> &'static str;

    /// One line: the model and the method.
    fn description(&self) -> &'static str;

    /// Solves the scene along its whole path. Implementations fill the per-step rows and the
    /// metadata's model, resolution and warnings; [`run`] adds name, version and wall time.
    fn solve(&self, scene: &Scene) -> Result<History, SolveError>;

    /// The same solver at a ladder of resolutions for `scene`, coarse to fine (springs, grid,
    /// mesh size — sizes scale with the scene's contact), for convergence and speed-against-error
    /// studies; empty where resolution has no meaning (closed forms, incremental laws whose
    /// resolution is the path's own increments).
    fn resolution_ladder(&self, _scene: &Scene) -> Vec<Box<dyn Solver>> {
        Vec::new()
    }

    /// The same solver writing its volume or surface fields as VTU files (for ParaView) into
    /// `dir`; `None` for solvers without such fields.
    fn writing_fields_to(&self, _dir: &std::path::Path) -> Option<Box<dyn Solver>> {
        None
    }
}

/// Runs `solver` on `scene`, timing it and completing the history's metadata.
///
/// A history with a non-finite value, or with a row count that does not match the path, is a
/// failure of the solver: it is reported as such and never printed as a result.
pub fn run(solver: &dyn Solver, scene: &Scene) -> Result<History, SolveError> {
    let start = Instant::now();
    let mut history = solver.solve(scene)?;
    validate(&history, scene.steps().len())?;
    let meta = &mut history.metadata;
    meta.wall_time_s = start.elapsed().as_secs_f64();
    meta.solver = solver.name().to_owned();
    if meta.version.is_empty() {
        meta.version = env!("CARGO_PKG_VERSION").to_owned();
    }
    Ok(history)
}

/// Rejects histories that would print NaN or misalign with the path.
fn validate(history: &History, steps: usize) -> Result<(), SolveError> {
    if history.steps.len() != steps {
        return Err(SolveError::Failed(format!(
            "{} rows for a path of {steps} steps",
            history.steps.len()
        )));
    }
    for row in &history.steps {
        for quantity in Quantity::ALL {
            if quantity.of(row).is_some_and(|v| !v.is_finite()) {
                return Err(SolveError::Failed(format!(
                    "non-finite {quantity} at step {}",
                    row.step
                )));
            }
        }
    }
    Ok(())
}

/// A solver whose surface fields on a grid are also written as VTU files, one per path position
/// (`<dir>/<case>-<solver>-<position>.vtu`).
pub struct SurfaceVtu {
    /// The solver.
    pub inner: Box<dyn Solver>,
    /// Where the files go.
    pub dir: std::path::PathBuf,
}

impl Solver for SurfaceVtu {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn description(&self) -> &'static str {
        self.inner.description()
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let history = self.inner.solve(scene)?;
        for field in &history.fields {
            let Some(grid) = vtu::Grid::of_surface_field(field) else {
                continue;
            };
            let path = self
                .dir
                .join(format!("{}-{}-{}.vtu", scene.name, self.name(), field.position));
            std::fs::create_dir_all(&self.dir)
                .and_then(|()| grid.write(&path).map_err(std::io::Error::other))
                .map_err(|e| SolveError::Failed(format!("writing {}: {e}", path.display())))?;
        }
        Ok(history)
    }
}
