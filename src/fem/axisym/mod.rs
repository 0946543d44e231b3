//! The axisymmetric finite element contact model and its solver (`fem-axisym`).
//!
//! | file | concept |
//! |---|---|
//! | [`model`] | the scene's reduction (symmetric or two bodies), its discrete model and its contact (the shared engine, [`crate::contact`]) |
//! | [`pressure`] | nodal pressure, p0 and c from the contact forces |
//! | [`output`] | displacement and stress fields, VTU files |
//! | [`solver`] | the `Solver` implementation |

pub mod model;
pub mod output;
pub mod pressure;
pub mod solver;

pub use solver::FemAxisym;
