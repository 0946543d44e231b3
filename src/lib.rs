//! # spherecontact
//!
//! A verification harness for the contact of two elastic spheres: Hertz normal contact and
//! Mindlin–Deresiewicz frictional tangential contact under an arbitrary loading history.
//!
//! The way through the crate follows the data:
//!
//! ```text
//! cases/*.toml ─▶ case::Case ─▶ scene::Scene ─▶ solver::Solver ─▶ history::History ─▶ check ─▶ report
//! ```
//!
//! - [`case`] reads and validates a case file (bodies, friction, loading path, solvers, checks);
//! - [`scene`] is the solver-independent problem it describes, with [`pair`] (effective
//!   properties) and [`path`] (the steps of the loading path);
//! - [`solver`] is the one trait every model implements; [`analytic`] holds the closed forms
//!   (Hertz, Cattaneo–Mindlin), the exact path reference (MDR) and the incremental DEM laws;
//! - [`contact`] is the contact engine of the numerical solvers (normal and incremental Coulomb
//!   problems over a compliance operator); [`driver`] walks a path for every incremental solver
//!   with one rule for an open gap;
//! - [`check`] judges a solver's [`history::History`] against a reference, with a tolerance and
//!   its reason, as OK / NOOK / INFO (on a map's measures, [`map_measure`], as the reports);
//! - [`verify`] runs cases and their checks; [`report`] prints and writes the results;
//!   [`bench`] times solvers side by side.
//!
//! What it is not: a general contact solver or a DEM code. Everything here serves the question
//! "how far is this solver from the right answer for two elastic spheres, and why".
//!
//! Units are SI throughout (m, N, Pa); a case file may give its path in µm or mm and says so.

pub mod analytic;
pub mod baseline;
pub mod bem;
pub mod bench;
pub mod calculix;
pub mod calculix_settings;
pub mod case;
pub mod check;
pub mod conclusion;
pub mod contact;
pub mod cores;
pub mod cost;
pub mod dem;
pub mod domain;
pub mod driver;
pub mod exchange;
pub mod external;
pub mod fem;
pub mod fit;
pub mod fixtures;
pub mod hertz;
pub mod history;
pub mod impact;
pub mod input;
pub mod io;
pub mod judged;
pub mod limits;
pub mod map_measure;
pub mod memory;
pub mod merge;
pub mod mirror;
pub mod number;
pub mod pair;
pub mod path;
pub mod plan;
pub mod profile;
pub mod progress;
pub mod quadrature;
pub mod registry;
pub mod report;
pub mod resolution;
pub mod runfile;
pub mod scene;
pub mod schedule;
pub mod slurm;
pub mod solver;
pub mod stick_slope;
pub mod team;
pub mod text;
pub mod verify;
pub mod vtu;
