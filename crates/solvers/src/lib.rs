//! # spherecontact-solvers: the in-crate numerical solvers
//!
//! **Job.** The numerical models the harness builds itself and checks against the exact
//! references: the boundary-element half-space solver ([`bem`]), the axisymmetric and 3D finite
//! elements ([`fem`], with their meshes, [`fem::mesh`], written for gmsh too), the fits and the
//! measures taken on their results ([`fit`], [`profile`], [`map_measure`]) and the VTU files of
//! their surface fields ([`vtu`]).
//!
//! **May depend on.** `spherecontact-model`, `spherecontact-system` (files and gmsh),
//! `spherecontact-contact` (the normal and Coulomb problems) and `spherecontact-reference` (the
//! finite-body corrections they are judged with).
//!
//! **Offers.** `bem::BemSolver`, the FEM solvers, and `solvers()` of each family: every one a
//! `spherecontact_model::solver::Solver`.

pub mod bem;
pub mod fem;
pub mod fit;
pub mod map_measure;
pub mod profile;
pub mod vtu;
