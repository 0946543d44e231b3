//! The command line's commands that need more than a function of `main.rs` (binary only).

pub mod deck;
pub mod report;
pub mod verify;
