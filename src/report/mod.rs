//! What people and machines read: the check table on the terminal, per-solver CSV and JSON
//! files, and JUnit XML for CI.

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
