//! The one place that names every solver family of this build.
//!
//! Everything that needs a solver by name (case validation, the command line, `verify`, `bench`)
//! asks here; the solver families themselves know nothing of each other or of this list.

use crate::solver::Solver;
use crate::{analytic, bem, external, fem};

/// Every solver this build knows, in listing order.
pub fn registry() -> Vec<Box<dyn Solver>> {
    let mut solvers = analytic::solvers();
    solvers.push(Box::new(bem::Bem::default()));
    solvers.push(Box::new(fem::FemAxisym::default()));
    solvers.push(Box::new(fem::MdrDomain::default()));
    solvers.extend(external::solvers());
    solvers
}

/// The solver called `name`, if this build has it.
pub fn by_name(name: &str) -> Option<Box<dyn Solver>> {
    registry().into_iter().find(|s| s.name() == name)
}

/// The names of every solver of this build, in listing order.
pub fn names() -> Vec<&'static str> {
    registry().iter().map(|s| s.name()).collect()
}
