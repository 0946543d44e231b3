//! The command line's commands that need more than a function of `main.rs` (binary only).

pub mod deck;
pub mod impact;
pub mod report;
pub mod verify;

/// The `--jobs` of the commands that run solvers concurrently (`verify`, `baseline update`,
/// `compare`, `reproduce-paper`).
#[derive(clap::Args, Clone, Copy, Debug, Default)]
pub struct Jobs {
    /// Cores for concurrent runs (each solver takes the cores it declares); default: the
    /// machine's.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    jobs: Option<u32>,
}

impl Jobs {
    /// The cores given: `--jobs`, else the machine's.
    pub fn cores(self) -> usize {
        self.jobs
            .map_or_else(spherecontact::cores::machine_cores, |n| n as usize)
    }
}
