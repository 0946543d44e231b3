//! The in-crate finite element solver for frictionless normal contact, axisymmetric
//! (`fem-axisym`).
//!
//! | file | concept |
//! |---|---|
//! | [`mesh`] | meridian mesh of one body and the in-crate graded generator |
//! | [`msh`] | gmsh MSH 4.1 reader |
//! | [`quadrature`] | Gauss rules |
//! | [`element`] | 6-node axisymmetric triangle, r-weighted stiffness |
//! | [`assembly`] | global stiffness, Dirichlet elimination, reaction row |
//! | [`factor`] | sparse Cholesky with a fill-reducing ordering |
//! | [`contact`] | condensed contact-surface compliance and the semi-smooth Newton contact solve |
//! | [`solver`] | the `Solver` implementation |

pub mod assembly;
pub mod element;
pub mod factor;
pub mod mesh;
pub mod quadrature;
pub mod contact;
pub mod pressure;
pub mod model;
pub mod msh;
pub mod output;
pub mod solver;

pub use solver::FemAxisym;
