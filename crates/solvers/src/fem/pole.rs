//! The FEM solvers' resolution: a pole element size, chosen as `c/N` or a length within the
//! solver's limits, and the ladder of sizes c_max/N a convergence study walks down. One
//! mechanism for every FEM solver; each names only its limits and its ladder.

use std::path::Path;

use spherecontact_model::resolution::{self, PoleLimits, ResolutionError};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::Solver;

/// A solver whose resolution is its pole element size.
pub trait PoleSized: Solver + Clone + 'static {
    /// The pole sizes this solver can take.
    const LIMITS: PoleLimits;

    /// This solver with pole element size `h` [m].
    fn sized(&self, h: f64) -> Self;

    /// This solver writing its field files into `dir`.
    fn writing_to(&self, dir: &Path) -> Self;
}

/// `solver` at the pole size `value` (`c/N` or a length) for `scene`, within its limits.
pub fn at_resolution<S: PoleSized>(
    solver: &S,
    scene: &Scene,
    value: &str,
) -> Result<Box<dyn Solver>, ResolutionError> {
    let h = resolution::pole_size(solver.name(), scene, value, S::LIMITS)?;
    Ok(Box::new(solver.sized(h)))
}

/// `solver` at the pole sizes c_max / N for each N of `divisions`, coarsest first.
pub fn ladder<S: PoleSized>(solver: &S, scene: &Scene, divisions: &[f64]) -> Vec<Box<dyn Solver>> {
    divisions
        .iter()
        .map(|n| Box::new(solver.sized(scene.max_contact_radius() / n)) as Box<dyn Solver>)
        .collect()
}

/// `solver` writing its field files into `dir`, as [`Solver::writing_fields_to`] returns it.
pub fn writing_fields_to<S: PoleSized>(solver: &S, dir: &Path) -> Option<Box<dyn Solver>> {
    Some(Box::new(solver.writing_to(dir)))
}
