//! Timing solvers side by side: each solver runs the same scene several times in one process,
//! interleaved round by round so that machine noise hits all alike, and the median is reported.
//! Both wall time and the thread's CPU time are kept: on a shared, loaded machine the wall time
//! also counts the time the thread waited for a core, the CPU time does not.
//!
//! Speed is measured and reported here, never asserted in tests: the machines are shared.

use std::time::Instant;

use crate::scene::Scene;
use crate::solver::{self, SolveError, Solver};

/// The times of repeated runs of one solver.
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    /// The solver's name.
    pub solver: String,
    /// Wall times [s], sorted.
    pub seconds: Vec<f64>,
    /// CPU times of the running thread [s], sorted.
    pub cpu_seconds: Vec<f64>,
}

/// The median of sorted values.
pub fn median(sorted: &[f64]) -> f64 {
    let n = sorted.len();
    if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    }
}

/// The CPU time consumed so far by the calling thread [s].
fn thread_cpu_time() -> f64 {
    let mut now = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `now` is a valid, writable timespec; CLOCK_THREAD_CPUTIME_ID exists on Linux.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut now) };
    now.tv_sec as f64 + now.tv_nsec as f64 * 1e-9
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
                    cpu_seconds: Vec::new(),
                })
                .map_err(|e| (s.name().to_owned(), e))
        })
        .collect();
    for _ in 0..repeat.max(1) {
        for (solver, result) in solvers.iter().zip(results.iter_mut()) {
            if let Ok(timing) = result {
                let (start, cpu_start) = (Instant::now(), thread_cpu_time());
                let outcome = solver.solve(scene);
                timing.cpu_seconds.push(thread_cpu_time() - cpu_start);
                timing.seconds.push(start.elapsed().as_secs_f64());
                std::hint::black_box(outcome.ok());
            }
        }
    }
    for timing in results.iter_mut().flatten() {
        timing.seconds.sort_by(f64::total_cmp);
        timing.cpu_seconds.sort_by(f64::total_cmp);
    }
    results
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[1.0, 2.0, 10.0]), 2.0);
        assert_eq!(median(&[1.0, 2.0, 3.0, 10.0]), 2.5);
    }

    #[test]
    fn thread_cpu_time_advances_with_work() {
        let start = thread_cpu_time();
        let mut x = 0.0_f64;
        for i in 0..2_000_000 {
            x = std::hint::black_box(x + (i as f64).sqrt());
        }
        assert!(thread_cpu_time() > start, "{x}");
    }
}
