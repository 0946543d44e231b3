//! Half-space boundary elements for the normal and frictional contact of two elastic spheres
//! along a loading path, with pressure, traction and stick/slip maps (the `bem` solver).
//!
//! When the contact radius is small against the radii the two spheres are two elastic
//! half-spaces loaded over the contact. The contact plane is cut into a square [`grid`] of
//! constant-traction panels over a window sized from the path's largest Hertz contact radius;
//! [`influence`] gives the Boussinesq and Cerruti coefficients of a panel in closed form;
//! [`convolution`] applies them by zero-padded FFT, and [`operator`] makes them the compliances of
//! the shared contact engine ([`spherecontact_contact`]: the normal problem with exact non-penetration,
//! Kalker's incremental Coulomb problem with memory); [`state`] carries the fields from one
//! increment to the next and [`solver`] runs the path with the shared walker ([`spherecontact_model::driver`]).
//!
//! Outputs: per step the History quantities (P, Q, contact radius from the pressure edge, peak
//! pressure, stick radius c √(N_stick / N_contact) by every solver's measure, [`crate::fit::stick`]); at every path
//! position a `SurfaceField` over the whole grid (pressure, traction (q_x, q_y), stick/slip).
//! [`Bem::solve_with_fields`] also returns the grid and the slip accumulated since each panel
//! came into contact, for a grid writer (VTU).
//!
//! Normal–tangential coupling is neglected: it vanishes for elastically similar bodies
//! (Dundurs β = 0, e.g. identical spheres) and the solver warns when β ≠ 0.

pub mod convolution;
pub mod grid;
pub mod influence;
pub mod operator;
pub mod solver;
pub mod state;

pub use solver::Bem;
