//! # spherecontact-report: reports
//!
//! **Job.** What people and machines read: the check table on the terminal, per-solver files, JUnit XML, Markdown, HTML with SVG figures, the comparison reports, the DEM scoreboard and the paper reproduced with its claims put to the test.
//!
//! **May depend on.** Every crate below it.
//!
//! **Offers.** `document`, `junit`, `paper`, `compare`, `claims`, `bench`.
//!
//! What people and machines read: the check table on the terminal, per-solver CSV and JSON
//! files, and JUnit XML for CI.

pub mod conclusion;

pub mod bench;
pub mod claims;
pub mod compare;
pub mod dem_scoreboard;
pub mod discretisation;
pub mod document;
pub mod figures;
pub mod glance;
pub mod history_files;
pub mod impact;
pub mod junit;
pub mod paper;
pub mod paper_numbers;
pub mod plot;
pub mod summary;
