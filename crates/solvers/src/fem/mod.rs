//! The in-crate finite element solvers.
//!
//! | module | concept |
//! |---|---|
//! | [`element`] | element kinds: the 6-node axisymmetric triangle (n = 0) |
//! | [`mesh`] | meshes: the meridian mesh of one body and its graded generator, the gmsh MSH reader |
//! | [`spherecontact_model::quadrature`] | Gauss rules (top level: the surface measures of [`crate::fit`] use them too) |
//! | [`assembly`] | global stiffness of a meridian mesh, Dirichlet elimination, reaction row |
//! | [`factor`] | sparse Cholesky with a fill-reducing ordering |
//! | [`ordering`] | the elimination order with the contact DOFs last (their Schur complement is the factor's trailing block) |
//! | [`condense`] | the dense compliance of a factored body at its contact DOFs |
//! | [`nodal`] | element values (stresses) averaged at the nodes, for the VTU fields |
//! | [`pole`] | the resolution of a FEM solver: a pole element size (`c/N` or a length) and its ladder |
//! | [`axisym`] | the axisymmetric contact model and the `fem-axisym` solver |
//! | [`solid3d`] | the 3D contact model (10-node tetrahedra, condensed contact surface) and the `fem-3d` solver |
//!
//! The stiffness is assembled and factored once per mesh; the compliance of the candidate
//! contact nodes is computed once by solves with the factor; each path step then re-solves only
//! the small condensed contact problem, on the shared engine ([`spherecontact_contact`]). Verification: `tests/fem_element.rs` (patch test,
//! manufactured-solution rates), `tests/fem_hertz.rs` (Hertz, convergence), `tests/fem_msh.rs`,
//! `tests/fem_hard_cases.rs`; the 3D model: `tests/fem3d_element.rs`, `tests/fem3d_surface.rs`,
//! `tests/fem3d_mesh.rs`, `tests/fem3d_hertz.rs`; speed: `examples/fem_timing.rs`, `examples/fem3d_timing.rs`.

pub mod assembly;
pub mod axisym;
pub mod condense;
pub mod element;
pub mod factor;
pub mod mesh;
pub mod nodal;
pub mod ordering;
pub mod pole;
pub mod solid3d;

pub use axisym::{FemAxisym, MdrDomain};
pub use solid3d::FemSolid3d;
