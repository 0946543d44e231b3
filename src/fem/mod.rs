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
//! | [`pressure`] | nodal pressure, p0 and c from the contact forces |
//! | [`model`] | the scene's reduction (symmetric or two bodies) and its discrete model |
//! | [`output`] | displacement and stress fields, VTU files |
//! | [`solver`] | the `Solver` implementation |
//!
//! The stiffness is assembled and factored once per mesh; the compliance of the candidate
//! contact nodes is computed once by solves with the factor; each path step then re-solves only
//! the small condensed contact problem. Verification: `tests/fem_element.rs` (patch test,
//! manufactured-solution rates), `tests/fem_hertz.rs` (Hertz, convergence), `tests/fem_msh.rs`,
//! `tests/fem_hard_cases.rs`; speed: `examples/fem_timing.rs`.

pub mod assembly;
pub mod contact;
pub mod element;
pub mod factor;
pub mod mesh;
pub mod model;
pub mod msh;
pub mod output;
pub mod pressure;
pub mod quadrature;
pub mod solver;

pub use solver::FemAxisym;
