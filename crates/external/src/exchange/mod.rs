//! The files the harness exchanges with programs outside it: a solver that is any command, a
//! stored result computed elsewhere, a DEM code driven through a generated input.
//!
//! - [`scene_file`]: the scene written for such a program (`scene.json`, versioned, SI);
//! - [`results_csv`]: the History CSV read back from it, validated against the path.
//!
//! Both formats are documented in docs/own-solver.md.

pub mod results_csv;
pub mod scene_file;
