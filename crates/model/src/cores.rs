//! Work that proceeds concurrently within a number of cores: each task takes the cores it
//! declares (at most all of them), the longest start first ([`longest_first`]); a task whose cores
//! are not free waits, and those after it wait too (no task overtakes a longer one, so the long
//! ones are never starved). The verification job's runs (`schedule` (spherecontact-verify)) and the resolution
//! study of `reproduce-paper` (`claims::Study` (spherecontact-report)) both go through [`within_cores`].
//!
//! A task gets exactly the cores it was given: it runs inside [`team::with_threads`], so the
//! BEM's team has two threads only when the task was given two cores, and one otherwise
//! (`--jobs 1`, or a solver declaring one core). Results come back in task order.

use std::panic::{self, AssertUnwindSafe};
use std::sync::mpsc;
use std::time::Instant;

use crate::team;

/// The cores of this machine, the default of `verify --jobs` and `reproduce-paper --jobs`.
pub fn machine_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The indices of `costs`, longest first (ties in the given order): the order a schedule starts
/// its tasks and shards take them, so that the last to finish are short (longest processing time
/// first).
pub fn longest_first(costs: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..costs.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]).then(a.cmp(&b)));
    order
}

/// What [`within_cores`] needs to know of a unit of work before it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Task {
    /// The cores it keeps busy (at least 1; at most all of them are given).
    pub cores: usize,
    /// Its expected wall time [s]: the longest start first.
    pub cost_s: f64,
}

impl Task {
    /// A task taking `cores` cores for about `cost_s` seconds.
    pub fn new(cores: usize, cost_s: f64) -> Self {
        Self { cores, cost_s }
    }
}

/// Runs `work(i)` for every task `i` within `cores` cores (see the module doc: longest first, a
/// task waits for its cores, each runs with exactly the team threads it was given); each task's
/// result, wall time [s] and cores, in task order. A panic of `work` (`solver::run` turns a
/// solver's into its failure) is carried to the caller once the running tasks have ended.
pub fn within_cores<T: Send>(
    tasks: &[Task],
    cores: usize,
    work: impl Fn(usize) -> T + Sync,
) -> Vec<(T, f64, usize)> {
    let cores = cores.max(1);
    let costs: Vec<f64> = tasks.iter().map(|t| t.cost_s).collect();
    let mut finished: Vec<Option<(T, f64, usize)>> = tasks.iter().map(|_| None).collect();
    let mut panicked = None;
    std::thread::scope(|scope| {
        let (sender, receiver) = mpsc::channel();
        let (mut free, mut running) = (cores, 0);
        let mut queue = longest_first(&costs).into_iter().peekable();
        let work = &work;
        loop {
            while let Some(&index) = queue.peek().filter(|_| panicked.is_none()) {
                let given = tasks[index].cores.clamp(1, cores);
                if given > free {
                    break;
                }
                queue.next();
                (free, running) = (free - given, running + 1);
                let sender = sender.clone();
                scope.spawn(move || {
                    let start = Instant::now();
                    let result =
                        panic::catch_unwind(AssertUnwindSafe(|| team::with_threads(given, || work(index))));
                    // The receiver lives until every task has reported.
                    let _ = sender.send((index, result, start.elapsed().as_secs_f64(), given));
                });
            }
            if running == 0 {
                break;
            }
            let (index, result, wall_s, given) = receiver.recv().expect("the loop holds a sender");
            (free, running) = (free + given, running - 1);
            match result {
                Ok(result) => finished[index] = Some((result, wall_s, given)),
                Err(payload) => {
                    panicked.get_or_insert(payload);
                }
            }
        }
    });
    if let Some(payload) = panicked {
        panic::resume_unwind(payload);
    }
    finished
        .into_iter()
        .map(|f| f.expect("every task was started and reported"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Mutex;

    /// Requirement: results come back in task order whatever the finishing order, each with the
    /// cores it was given (clamped to the machine's), and the busy cores never exceed the limit.
    #[test]
    fn results_in_task_order_within_the_cores() {
        let tasks = [
            Task::new(1, 0.1),
            Task::new(2, 3.0),
            Task::new(1, 2.0),
            Task::new(5, 1.0),
        ];
        let (busy, most) = (AtomicUsize::new(0), AtomicUsize::new(0));
        let results = within_cores(&tasks, 2, |i| {
            let given = tasks[i].cores.clamp(1, 2);
            let now = busy.fetch_add(given, Ordering::SeqCst) + given;
            most.fetch_max(now, Ordering::SeqCst);
            std::thread::sleep(std::time::Duration::from_millis(20));
            busy.fetch_sub(given, Ordering::SeqCst);
            i * 10
        });
        let values: Vec<_> = results.iter().map(|(v, _, c)| (*v, *c)).collect();
        assert_eq!(values, [(0, 1), (10, 2), (20, 1), (30, 2)]);
        assert!(most.load(Ordering::SeqCst) <= 2, "busy cores {most:?} over 2");
        assert!(results.iter().all(|(_, wall, _)| *wall >= 0.02));
    }

    /// Requirement: on one core the tasks start longest first, ties in the given order.
    #[test]
    fn one_core_starts_the_longest_first() {
        let tasks = [
            Task::new(1, 1.0),
            Task::new(1, 5.0),
            Task::new(1, 1.0),
            Task::new(1, 3.0),
        ];
        let order = Mutex::new(Vec::new());
        within_cores(&tasks, 1, |i| order.lock().expect("not poisoned").push(i));
        assert_eq!(*order.lock().expect("not poisoned"), [1, 3, 0, 2]);
    }

    /// Requirement: a task's panic reaches the caller (it is not swallowed, nor a deadlock).
    #[test]
    #[should_panic(expected = "task 2 failed")]
    fn a_panicking_task_panics_the_caller() {
        let tasks = [Task::new(1, 1.0); 4];
        within_cores(&tasks, 2, |i| assert!(i != 2, "task {i} failed"));
    }
}
