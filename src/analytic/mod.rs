//! Closed-form and incremental contact models: the references every numerical solver is
//! checked against, and the DEM laws whose distance from them the harness measures.
//!
//! | solver | model | along a general path |
//! |---|---|---|
//! | `hertz` | Hertz normal contact | exact (frictionless normal part) |
//! | `cattaneo-mindlin` | Cattaneo–Mindlin + Masing | only at constant normal load |
//! | `mdr` | method of dimensionality reduction | exact Mindlin–Deresiewicz |
//! | `hertz-mindlin-spring` | no-slip spring with Coulomb cap | approximate (DEM) |

pub mod cattaneo_mindlin;
pub mod hertz;
pub mod hertz_mindlin_spring;
pub mod incremental;
pub mod mdr;

use crate::solver::Solver;
use incremental::IncrementalSolver;

/// The analytic solvers, references first, then the DEM laws.
pub fn solvers() -> Vec<Box<dyn Solver>> {
    vec![
        Box::new(hertz::HertzSolver),
        Box::new(cattaneo_mindlin::CattaneoMindlin),
        Box::new(mdr::Mdr::default()),
        Box::new(IncrementalSolver {
            name: "hertz-mindlin-spring",
            description: "no-slip Hertz–Mindlin spring k_t = 8G*c with a Coulomb cap (LIGGGHTS, YADE)",
            make_law: |scene| Box::new(hertz_mindlin_spring::HertzMindlinSpring::new(scene)),
        }),
    ]
}
