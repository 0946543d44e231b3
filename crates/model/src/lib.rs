//! # spherecontact-model: the problem and its answer
//!
//! **Job.** What every other crate talks about, and nothing else: two bodies and their effective
//! properties ([`pair`]), the loading path and its steps ([`path`]), the problem a solver is given
//! ([`scene`], with its finite [`domain`]), what a solver answers ([`history`]: forces, energies
//! and surface fields at every step), Hertz's normal contact ([`hertz`]), and the one trait every
//! model implements ([`solver::Solver`]), with the resolutions, costs, limits and progress a run
//! is described by, and the one path walker every incremental model steps with ([`driver`]: an
//! open gap forgets, a path that never closes is zeros).
//!
//! **May depend on.** No crate of the workspace; no I/O beyond a child's resource usage
//! ([`memory`]).
//!
//! **Offers.** The types of the flow
//!
//! ```text
//! case ─▶ scene::Scene ─▶ solver::Solver ─▶ history::History ─▶ check ─▶ report
//! ```
//!
//! and [`fixtures`]: the paper's pair and scenes, for the tests of every crate.
//!
//! Units are SI throughout (m, N, Pa).

pub mod calculix_settings;
pub mod choice;
pub mod cores;
pub mod cost;
pub mod domain;
pub mod driver;
pub mod fixtures;
pub mod hertz;
pub mod history;
pub mod kratos_settings;
pub mod limits;
pub mod memory;
pub mod mirror;
pub mod number;
pub mod pair;
pub mod path;
pub mod progress;
pub mod quadrature;
pub mod resolution;
pub mod scene;
pub mod solver;
pub mod stick_slope;
pub mod team;
