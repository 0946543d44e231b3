//! The 3D finite element contact model (10-node tetrahedra) and its solver (`fem-3d`).
//!
//! | file | concept |
//! |---|---|
//! | [`system`] | DOFs (far face gripped, u_y = 0 on the symmetry plane) and the assembled stiffness |
//! | [`surface`] | the contact candidate surface and its sub-triangulated contact rule |
//! | [`condense`] | the condensed normal and tangential compliances from the factorisation |
//! | [`contact`] | the contact problem on the shared engine: pressure multipliers, symmetric weights |
//! | [`model`] | the whole set-up of one body |
//! | [`meshing`] | the body's mesh from the scene: sizes from the largest contact radius, gmsh |
//! | [`measures`] | the contact radius, peak pressure and stick zone from the nodal values (`crate::fit::surface`, shared with the 3D deck) |
//! | [`solver`] | `fem-3d`: the model of the scene's domain, the engine's settings, the metadata |
//! | [`walk`] | the path walked on the engine: P, Q, c, p0, the stick zone, fields, VTU |
//! | [`output`] | displacement and stress of a contact state; VTU of the volume and the contact surface |

pub mod condense;
pub mod contact;
pub use crate::fit::surface as measures;
pub mod meshing;
pub mod model;
pub mod output;
pub mod solver;
pub mod surface;
pub mod system;
pub mod walk;

pub use solver::FemSolid3d;
