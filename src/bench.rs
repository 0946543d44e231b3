//! Timing solvers side by side: each solver runs the same scene several times in one process,
//! interleaved round by round so that machine noise hits all alike, and the median is reported.
//!
//! Speed is measured and reported here, never asserted in tests: the machines are shared.

use std::time::Instant;

use crate::scene::Scene;
use crate::solver::{self, SolveError, Solver};

/// The wall times of repeated runs of one solver.
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    /// The solver's name.
    pub solver: String,
    /// Wall times [s], sorted.
    pub seconds: Vec<f64>,
}

impl Timing {
    /// The median wall time [s].
    pub fn median(&self) -> f64 {
        let n = self.seconds.len();
        if n % 2 == 1 {
            self.seconds[n / 2]
        } else {
            0.5 * (self.seconds[n / 2 - 1] + self.seconds[n / 2])
        }
    }
}

/// Runs every solver `repeat` times (≥ 1) on `scene`, round-robin, after one warm-up run each.
/// A solver that fails is reported with its error and left out of the timings.
pub fn time_solvers(
    solvers: &[Box<dyn Solver>],
    scene: &Scene,
    repeat: usize,
) -> Vec<Result<Timing, (String, SolveError)>> {
    let mut results: Vec<_> = solvers
        .iter()
        .map(|s| {
            solver::run(s.as_ref(), scene)
                .map(|_| Timing {
                    solver: s.name().to_owned(),
                    seconds: Vec::new(),
                })
                .map_err(|e| (s.name().to_owned(), e))
        })
        .collect();
    for _ in 0..repeat.max(1) {
        for (solver, result) in solvers.iter().zip(results.iter_mut()) {
            if let Ok(timing) = result {
                let start = Instant::now();
                let outcome = solver.solve(scene);
                timing.seconds.push(start.elapsed().as_secs_f64());
                std::hint::black_box(outcome.ok());
            }
        }
    }
    for timing in results.iter_mut().flatten() {
        timing.seconds.sort_by(f64::total_cmp);
    }
    results
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        let t = |s: &[f64]| Timing {
            solver: String::new(),
            seconds: s.to_vec(),
        };
        assert_eq!(t(&[1.0, 2.0, 10.0]).median(), 2.0);
        assert_eq!(t(&[1.0, 2.0, 3.0, 10.0]).median(), 2.5);
    }
}
