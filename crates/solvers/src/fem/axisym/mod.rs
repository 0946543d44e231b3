//! The axisymmetric finite element contact model and its solver (`fem-axisym`).
//!
//! | file | concept |
//! |---|---|
//! | [`model`] | the scene's reduction (symmetric or two bodies), its discrete model and its contact (the shared engine, [`spherecontact_contact`]) |
//! | [`meshing`] | the model's mesh: generated in-crate, read from a file, or gmsh's from the decks' `.geo` |
//! | [`compliance`] | the modelled domain's far-field compliances relative to the half-space |
//! | [`pressure`] | nodal pressure, p0 and c from the contact forces |
//! | [`output`] | displacement and stress fields, VTU files |
//! | [`output_n1`] | the n = 1 displacement amplitudes and the 3D contact surface with its tractions, VTU files |
//! | [`solver`] | the `Solver` implementation |
//! | [`tangential`] | the tangential problem: Fourier mode n = 1, condensed, Coulomb on the shared engine |
//! | [`reference`] | `mdr-domain`: MDR in series with the domain's compliances, the finite-body reference |

pub mod compliance;
pub mod meshing;
pub mod model;
pub mod output;
pub mod output_n1;
/// The profile fits moved to [`crate::fit::profile`], shared with the decks' readback.
pub use crate::fit::profile as pressure;
pub mod reference;
pub mod solver;
pub mod tangential;

pub use reference::MdrDomain;
pub use solver::FemAxisym;
