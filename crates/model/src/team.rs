//! A persistent team of threads for fork–join passes of tens of microseconds.
//!
//! The BEM's FFT products cost 50–200 µs at 128² panels and run in three passes, each of which
//! splits into independent parts (blocks of rows, ranges of columns). A general-purpose pool
//! hands work over at about the cost of such a pass: with rayon on this project's two-core
//! machine the paper path at 128² took 2.7 s wall and 3.6 s CPU on two threads inside its pool,
//! and 3.5 s called from outside it, against 2.2 s on one thread. Its idle workers fall asleep
//! within microseconds and every pass woke them with a system call.
//!
//! This team's workers instead spin on an atomic for [`SPIN`] after a pass, so that the next pass
//! of a solve (the next product comes a few tens of microseconds later) finds them awake; only
//! then do they park, so an idle team costs nothing (OpenMP runtimes wait the same way by
//! default). Parts are claimed from a shared counter by the caller as well: a part that no worker
//! has taken when the caller finishes its own is run by the caller, so a sleeping or descheduled
//! worker delays a pass by no more than the claims.
//!
//! One team serves the process ([`with_team`]); a caller that finds it busy (another thread's
//! product) runs its parts alone. What this is not: a scheduler. There is no nesting, no
//! stealing between workers, and at most one pass in flight.

use std::cell::{Cell, RefCell};
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicPtr, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock, TryLockError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long an idle worker spins before it parks: longer than the gap between two products of an
/// iterative contact solve (the engine's loops between products take 50–100 µs at 128²), shorter
/// than anything a user would notice as a busy CPU.
const SPIN: Duration = Duration::from_micros(200);

/// Threads of the process's team: two at most. Measured on two cores only; more threads are not
/// measured and not used.
const MAX_THREADS: usize = 2;

/// A team of threads: the caller and `threads − 1` workers.
pub struct Team {
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
    /// The last pass's epoch.
    epoch: Cell<u32>,
}

/// What the caller and the workers share.
struct Shared {
    /// The pass: epoch (bits 32–63), parts (16–31) and the next unclaimed part (0–15).
    state: AtomicU64,
    /// Parts finished in this pass.
    finished: AtomicUsize,
    /// The pass's job: a `&F` and the trampoline that calls it (`call::<F>`).
    data: AtomicPtr<()>,
    call: AtomicPtr<()>,
    /// A part run by a worker panicked.
    panicked: AtomicBool,
    /// Per worker, parked or about to park.
    sleeping: Vec<AtomicBool>,
    shutdown: AtomicBool,
}

fn pack(epoch: u32, parts: usize, next: usize) -> u64 {
    (u64::from(epoch) << 32) | ((parts as u64) << 16) | next as u64
}

fn unpack(state: u64) -> (u32, usize, usize) {
    (
        (state >> 32) as u32,
        ((state >> 16) & 0xffff) as usize,
        (state & 0xffff) as usize,
    )
}

/// Calls the job `F` behind `data` on part `part`.
///
/// # Safety
/// `data` points to a live `F`.
unsafe fn call<F: Fn(usize) + Sync>(data: *const (), part: usize) {
    // SAFETY: the caller of `Team::execute` keeps its `&F` alive until every part has finished.
    unsafe { (*(data as *const F))(part) }
}

impl Shared {
    /// Claims the next part of pass `epoch`, if any is left.
    fn claim(&self, epoch: u32) -> Option<usize> {
        let mut state = self.state.load(Ordering::Acquire);
        loop {
            let (e, parts, next) = unpack(state);
            if e != epoch || next >= parts {
                return None;
            }
            match self.state.compare_exchange_weak(
                state,
                pack(e, parts, next + 1),
                Ordering::AcqRel,
                Ordering::Acquire,
            ) {
                Ok(_) => return Some(next),
                Err(actual) => state = actual,
            }
        }
    }

    /// Runs the claimed part `part` of the current job; its panic, if any.
    fn run(&self, part: usize) -> std::thread::Result<()> {
        let data = self.data.load(Ordering::Relaxed) as *const ();
        // SAFETY: `call` was stored from a `call::<F>` function pointer with `data` its `&F`,
        // both before the pass was published; the part is claimed, so the pass is not over and
        // the job is alive.
        let job = self.call.load(Ordering::Relaxed) as *const ();
        let job: unsafe fn(*const (), usize) = unsafe { std::mem::transmute(job) };
        let outcome = catch_unwind(AssertUnwindSafe(|| unsafe { job(data, part) }));
        // The flag before the count: whoever sees the pass finished sees its panic.
        if outcome.is_err() {
            self.panicked.store(true, Ordering::Release);
        }
        self.finished.fetch_add(1, Ordering::Release);
        outcome
    }

    /// A worker: waits for each pass, claims and runs parts until none is left.
    fn work(&self, index: usize) {
        let mut seen = unpack(self.state.load(Ordering::Acquire)).0;
        loop {
            seen = self.wait(index, seen);
            if self.shutdown.load(Ordering::Acquire) {
                return;
            }
            while let Some(part) = self.claim(seen) {
                // A panic is flagged by `run`, for the caller to raise.
                let _ = self.run(part);
            }
        }
    }

    /// Spins until a pass after `seen` is published (or shutdown), parking after [`SPIN`].
    fn wait(&self, index: usize, seen: u32) -> u32 {
        let mut start = Instant::now();
        let mut spins = 0_u32;
        loop {
            let epoch = unpack(self.state.load(Ordering::Acquire)).0;
            if epoch != seen || self.shutdown.load(Ordering::Acquire) {
                return epoch;
            }
            spins = spins.wrapping_add(1);
            if spins.is_multiple_of(64) && start.elapsed() > SPIN {
                // Announce the sleep, then look again: a pass published in between is seen here,
                // or its publisher sees the flag and unparks (both sides SeqCst).
                self.sleeping[index].store(true, Ordering::SeqCst);
                if unpack(self.state.load(Ordering::SeqCst)).0 == seen
                    && !self.shutdown.load(Ordering::SeqCst)
                {
                    std::thread::park();
                }
                self.sleeping[index].store(false, Ordering::SeqCst);
                start = Instant::now();
            } else {
                std::hint::spin_loop();
            }
        }
    }
}

impl Team {
    /// A team of `threads` (the caller and `threads − 1` workers; 0 counts as 1, and fewer when
    /// the system refuses a thread).
    pub fn new(threads: usize) -> Self {
        let workers = threads.max(1) - 1;
        let shared = Arc::new(Shared {
            state: AtomicU64::new(0),
            finished: AtomicUsize::new(0),
            data: AtomicPtr::new(std::ptr::null_mut()),
            call: AtomicPtr::new(std::ptr::null_mut()),
            panicked: AtomicBool::new(false),
            sleeping: (0..workers).map(|_| AtomicBool::new(false)).collect(),
            shutdown: AtomicBool::new(false),
        });
        // A worker the system refuses to start is done without: the team is smaller.
        let workers = (0..workers)
            .map_while(|index| {
                let shared = Arc::clone(&shared);
                std::thread::Builder::new()
                    .name(format!("spherecontact-team-{}", index + 1))
                    .spawn(move || shared.work(index))
                    .ok()
            })
            .collect();
        Self {
            shared,
            workers,
            epoch: Cell::new(0),
        }
    }

    /// The caller alone.
    pub fn alone() -> Self {
        Self::new(1)
    }

    /// Threads, the caller's included.
    pub fn threads(&self) -> usize {
        self.workers.len() + 1
    }

    /// Calls `task(i, &mut parts[i])` for every part, spread over the team, and returns when all
    /// are done. A panic in a part is raised here once every part has finished.
    ///
    /// # Panics
    /// With more than 65 535 parts.
    pub fn run<P: Send>(&self, parts: &mut [P], task: impl Fn(usize, &mut P) + Sync) {
        if self.workers.is_empty() || parts.len() <= 1 {
            parts.iter_mut().enumerate().for_each(|(i, p)| task(i, p));
            return;
        }
        assert!(parts.len() <= 0xffff, "at most 65 535 parts a pass");
        let base = PartsPtr(parts.as_mut_ptr());
        let job = move |i: usize| {
            // SAFETY: every index below `parts.len()` is claimed exactly once, so each `&mut P`
            // is unique, and `execute` returns only after every part has finished.
            let part = unsafe { &mut *base.at(i) };
            task(i, part);
        };
        self.execute(parts.len(), &job);
    }

    /// Publishes the job, runs the parts the caller claims, waits for the others.
    fn execute<F: Fn(usize) + Sync>(&self, parts: usize, job: &F) {
        let shared = &*self.shared;
        let epoch = self.epoch.get().wrapping_add(1);
        self.epoch.set(epoch);
        shared.finished.store(0, Ordering::Relaxed);
        shared.data.store(job as *const F as *mut (), Ordering::Relaxed);
        shared
            .call
            .store(call::<F> as *const () as *mut (), Ordering::Relaxed);
        shared.state.store(pack(epoch, parts, 0), Ordering::SeqCst);
        for (worker, sleeping) in self.workers.iter().zip(&shared.sleeping) {
            if sleeping.load(Ordering::SeqCst) {
                worker.thread().unpark();
            }
        }
        let mut own_panic = None;
        while let Some(part) = shared.claim(epoch) {
            if let Err(payload) = shared.run(part) {
                own_panic = Some(payload);
            }
        }
        let mut spins = 0_u32;
        while shared.finished.load(Ordering::Acquire) < parts {
            spins = spins.wrapping_add(1);
            if spins.is_multiple_of(1024) {
                // The worker may have been descheduled: let it run.
                std::thread::yield_now();
            } else {
                std::hint::spin_loop();
            }
        }
        if shared.panicked.swap(false, Ordering::AcqRel) {
            match own_panic {
                Some(payload) => resume_unwind(payload),
                None => panic!("a part run by a team worker panicked"),
            }
        }
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        let shared = &*self.shared;
        shared.shutdown.store(true, Ordering::SeqCst);
        shared
            .state
            .store(pack(self.epoch.get().wrapping_add(1), 0, 0), Ordering::SeqCst);
        for worker in self.workers.drain(..) {
            worker.thread().unpark();
            // A worker that panicked outside a part has nothing left to report.
            let _ = worker.join();
        }
    }
}

/// The parts of a pass, shared with the workers.
struct PartsPtr<P>(*mut P);

impl<P> PartsPtr<P> {
    /// Part `i` (a method, so that closures capture the whole wrapper and its `Sync`).
    fn at(&self, i: usize) -> *mut P {
        // SAFETY: `i` is below the slice's length (claimed from its part count).
        unsafe { self.0.add(i) }
    }
}

// SAFETY: the pointer is only turned into a `&mut P` for a part claimed exactly once, and the
// parts are `Send`.
unsafe impl<P: Send> Sync for PartsPtr<P> {}

/// The process's team, created at first use with [`default_threads`].
fn team() -> &'static Mutex<Team> {
    static TEAM: OnceLock<Mutex<Team>> = OnceLock::new();
    TEAM.get_or_init(|| Mutex::new(Team::new(default_threads())))
}

/// The threads of the process's team by default: the cores available, at most [`MAX_THREADS`].
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get().min(MAX_THREADS))
}

thread_local! {
    /// The team of the run on this thread, set by [`with_threads`]; `None`: the process's.
    static RUN_TEAM: RefCell<Option<Team>> = const { RefCell::new(None) };
}

/// Calls `f` with the team of the calling thread's run ([`with_threads`]) if it has one, else
/// with the process's team, or with the caller alone while another thread uses it.
pub fn with_team<R>(f: impl FnOnce(&Team) -> R) -> R {
    RUN_TEAM.with(|run| match run.try_borrow() {
        Ok(team) if team.is_some() => f(team.as_ref().expect("checked")),
        _ => with_process_team(f),
    })
}

/// Runs `f` with a team of its own of `threads` (at most [`MAX_THREADS`]) for every product
/// made on this thread: a run that a schedule gave `threads` cores uses exactly that many,
/// whatever other runs of the process do at the same time (`verify --jobs`).
pub fn with_threads<R>(threads: usize, f: impl FnOnce() -> R) -> R {
    /// Puts the thread's previous team back, also when `f` panics.
    struct Restore(Option<Team>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            RUN_TEAM.with(|run| *run.borrow_mut() = previous);
        }
    }
    let team = Team::new(threads.min(MAX_THREADS));
    let _restore = Restore(RUN_TEAM.with(|run| run.replace(Some(team))));
    f()
}

/// Calls `f` with the process's team, or with the caller alone while another thread uses it.
fn with_process_team<R>(f: impl FnOnce(&Team) -> R) -> R {
    match team().try_lock() {
        Ok(team) => f(&team),
        // A panic in an earlier pass left the team consistent (a pass ends only when its parts
        // have).
        Err(TryLockError::Poisoned(poisoned)) => f(&poisoned.into_inner()),
        Err(TryLockError::WouldBlock) => f(&Team::alone()),
    }
}

/// Replaces the process's team by one of `threads` (e.g. 1 to time a solver on one thread);
/// waits while another thread uses it.
pub fn set_threads(threads: usize) {
    let mut team = team().lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    *team = Team::new(threads);
}

/// `len` units cut into `parts` contiguous ranges of sizes differing by at most one.
pub fn ranges(len: usize, parts: usize) -> impl Iterator<Item = std::ops::Range<usize>> {
    let parts = parts.max(1);
    (0..parts).map(move |i| (i * len / parts)..((i + 1) * len / parts))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_uses_the_threads_it_was_given_and_then_the_process_team_again() {
        // A schedule gives a run one core: its products run on one thread, whatever the
        // process's team holds; nested, the inner count applies; after, the thread's team is
        // the process's again.
        let threads = || with_team(|team| team.threads());
        with_threads(1, || {
            assert_eq!(threads(), 1);
            with_threads(2, || assert_eq!(threads(), 2));
            assert_eq!(threads(), 1);
        });
        assert!(RUN_TEAM.with(|run| run.borrow().is_none()));
    }

    #[test]
    fn every_part_runs_once_on_any_team() {
        // Requirement: each part is handed to exactly one thread, in every pass, whatever the
        // team's size and the number of parts (fewer, as many, more than the threads).
        for threads in [1, 2, 3] {
            let team = Team::new(threads);
            assert_eq!(team.threads(), threads);
            for pass in 0..500_usize {
                let count = 1 + pass % 7;
                let mut parts: Vec<(usize, usize)> = vec![(0, 0); count];
                team.run(&mut parts, |i, part| {
                    part.0 += 1;
                    part.1 = i * 10 + pass;
                });
                for (i, &(runs, value)) in parts.iter().enumerate() {
                    assert_eq!(
                        (runs, value),
                        (1, i * 10 + pass),
                        "threads {threads}, pass {pass}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_team_woken_from_its_sleep_still_runs_every_part() {
        // Requirement: a worker parked after its spin is woken by the next pass (no lost
        // wake-up), and the pass completes.
        let team = Team::new(2);
        for _ in 0..3 {
            std::thread::sleep(SPIN * 5);
            let mut parts = vec![0_u32; 4];
            team.run(&mut parts, |i, part| *part = i as u32 + 1);
            assert_eq!(parts, [1, 2, 3, 4]);
        }
    }

    #[test]
    fn a_panic_in_a_part_reaches_the_caller_and_the_team_goes_on() {
        // Requirement: a panicking part is reported to the caller (never lost, never a hang), and
        // the team serves the next pass.
        let team = Team::new(2);
        for faulty in [0, 1, 3] {
            let outcome = catch_unwind(AssertUnwindSafe(|| {
                let mut parts = vec![0_u8; 4];
                team.run(&mut parts, |i, _| assert_ne!(i, faulty, "part {i} fails"));
            }));
            assert!(outcome.is_err(), "part {faulty}'s panic was lost");
            let mut parts = vec![0_u8; 4];
            team.run(&mut parts, |_, part| *part = 7);
            assert_eq!(parts, [7; 4]);
        }
    }

    #[test]
    fn ranges_cover_the_units_in_order() {
        let cut: Vec<_> = ranges(10, 3).collect();
        assert_eq!(cut, [0..3, 3..6, 6..10]);
        assert_eq!(ranges(2, 4).map(|r| r.len()).sum::<usize>(), 2);
    }
}
