//! Every process a program started, found and killed: its process group, and what left it
//! (`setsid`, `setpgid`, a daemon's double fork) too.
//!
//! The mechanism (Linux):
//! - **the harness is a child subreaper** (`prctl(PR_SET_CHILD_SUBREAPER)`, set before its first
//!   program starts): a process whose parent dies is re-parented to the harness, not to init, so
//!   no descendant leaves the harness's process tree and none can be reaped (and its pid reused)
//!   behind the harness's back once re-parented;
//! - **so is the program itself** (set before its exec, kept across it): while it runs, the
//!   orphans of its own children are re-parented to it and stay in its subtree;
//! - **a marker in the environment**: each run's environment carries [`MARKER`]`=<harness
//!   pid>.<run>`, which every descendant inherits whatever session or group it moves to;
//! - **the program leads its own process group**, held (unreaped) until the sweep is over, so
//!   the group's id cannot be reused meanwhile.
//!
//! A process belongs to the run when its group is the program's, its environment holds the
//! marker, its parent belongs to the run, or it was seen belonging to it earlier in the run
//! ([`Tracker::observe`], every [`OBSERVE_EVERY`], remembers pid and start time: this catches a
//! process that left the group *and* cleared its environment while its parent was still
//! there). Each is killed through a pidfd checked against its start time, so a pid reused by an
//! unrelated process is never signalled; the sweep repeats until no process of the run is left
//! alive, and those re-parented to the harness are reaped.
//!
//! What it cannot see: a process that leaves the group, clears its environment and is orphaned
//! within one [`OBSERVE_EVERY`] before the program itself ends (while the program runs, such an
//! orphan is its child), or one that runs as another user (setuid programs).

use std::collections::BTreeMap;
use std::io::Read;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Once;
use std::time::{Duration, Instant};

/// The environment variable that marks every process of one run.
pub const MARKER: &str = "SPHERECONTACT_JOB";

/// How often the processes of a running program are noted ([`Tracker::observe`]).
pub const OBSERVE_EVERY: Duration = Duration::from_millis(100);

/// The most rounds of a sweep: a process that forks faster than it is killed is caught within a
/// few rounds; a bound keeps a pathological one from holding the harness.
const MAX_SWEEPS: usize = 200;

/// The most of a process's environment read to look for the marker [bytes].
const MAX_ENVIRON_BYTES: u64 = 1 << 20;

/// One process as `/proc/<pid>/stat` shows it.
#[derive(Clone, Copy, Debug)]
struct Proc {
    pid: i32,
    ppid: i32,
    pgid: i32,
    /// `Z` for a zombie (dead, not yet reaped).
    state: char,
    /// Start time since boot [clock ticks]: with the pid, a process's identity.
    start: u64,
}

/// The processes of one run of a program.
pub struct Tracker {
    marker: String,
    leader: i32,
    /// Processes seen belonging to the run: pid and start time.
    known: BTreeMap<i32, u64>,
    observed: Instant,
}

impl Tracker {
    /// A tracker for a run about to start (the harness made a subreaper first).
    pub fn begin() -> Self {
        static SUBREAPER: Once = Once::new();
        // SAFETY: prctl with PR_SET_CHILD_SUBREAPER takes an integer and touches no memory. On
        // failure (not Linux) the marker and the group still find the run's processes.
        SUBREAPER.call_once(|| unsafe {
            libc::prctl(libc::PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0);
        });
        static RUNS: AtomicU64 = AtomicU64::new(0);
        Tracker {
            marker: format!("{}.{}", std::process::id(), RUNS.fetch_add(1, Ordering::Relaxed)),
            leader: 0,
            known: BTreeMap::new(),
            observed: Instant::now(),
        }
    }

    /// The marker's variable and value, for the program's environment.
    pub fn marker(&self) -> (&'static str, &str) {
        (MARKER, &self.marker)
    }

    /// The program started with process id `pid`, leading its own group.
    pub fn started(&mut self, pid: u32) {
        self.leader = i32::try_from(pid).unwrap_or(0);
    }

    /// Notes the run's processes when [`OBSERVE_EVERY`] has passed since the last look.
    pub fn observe(&mut self) {
        if self.observed.elapsed() >= OBSERVE_EVERY {
            let processes = processes();
            self.known = self.members(&processes, false);
            self.observed = Instant::now();
        }
    }

    /// Kills every process of the run but its leader's zombie, round after round until none is
    /// left alive, then reaps those re-parented to the harness (the leader is the caller's to
    /// reap). Returns how many processes were signalled.
    pub fn kill_all(&mut self) -> usize {
        let mut signalled = 0;
        for _ in 0..MAX_SWEEPS {
            let processes = processes();
            self.known = self.members(&processes, true);
            let alive: Vec<&Proc> = processes
                .iter()
                .filter(|p| self.known.contains_key(&p.pid) && !dead(p))
                .collect();
            if alive.is_empty() {
                break;
            }
            for process in alive {
                signalled += usize::from(kill(process.pid, process.start));
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        self.reap_orphans();
        signalled
    }

    /// Reaps the run's dead processes that were re-parented to the harness.
    fn reap_orphans(&self) {
        let harness = i32::try_from(std::process::id()).unwrap_or(0);
        for process in processes() {
            let ours = self.known.get(&process.pid) == Some(&process.start);
            if ours && dead(&process) && process.ppid == harness && process.pid != self.leader {
                // A zombie: WNOHANG reaps it at once (and never waits on a live process).
                let _ = super::reap::reap(process.pid as u32, libc::WNOHANG);
            }
        }
    }

    /// The run's processes among `processes` (see the module doc); with `environ`, also those
    /// whose environment holds the marker.
    fn members(&self, processes: &[Proc], environ: bool) -> BTreeMap<i32, u64> {
        if self.leader <= 1 {
            // Not started: group 0 is the kernel's threads'.
            return BTreeMap::new();
        }
        let entry = format!("{MARKER}={}", self.marker);
        let mut members: BTreeMap<i32, u64> = processes
            .iter()
            .filter(|p| {
                p.pid == self.leader
                    || p.pgid == self.leader
                    || self.known.get(&p.pid) == Some(&p.start)
                    || (environ && holds(p.pid, &entry))
            })
            .map(|p| (p.pid, p.start))
            .collect();
        loop {
            let before = members.len();
            for p in processes {
                if members.contains_key(&p.ppid) {
                    members.entry(p.pid).or_insert(p.start);
                }
            }
            if members.len() == before {
                return members;
            }
        }
    }
}

/// A zombie (dead, not yet reaped) or a process being torn down.
fn dead(process: &Proc) -> bool {
    matches!(process.state, 'Z' | 'X')
}

/// Every process `/proc` lists now (those that vanish while it is read are left out).
fn processes() -> Vec<Proc> {
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    entries
        .flatten()
        .filter_map(|e| e.file_name().to_str()?.parse::<i32>().ok())
        .filter_map(stat)
        .collect()
}

/// Process `pid` as `/proc/<pid>/stat` shows it.
fn stat(pid: i32) -> Option<Proc> {
    let text = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name, in parentheses, may hold spaces and parentheses: fields follow the last.
    let fields: Vec<&str> = text[text.rfind(')')? + 1..].split_whitespace().collect();
    Some(Proc {
        pid,
        state: fields.first()?.chars().next()?,
        ppid: fields.get(1)?.parse().ok()?,
        pgid: fields.get(2)?.parse().ok()?,
        // Field 22 of stat(5); the list starts at field 3.
        start: fields.get(19)?.parse().ok()?,
    })
}

/// Whether the environment of `pid` holds the variable `entry` (`NAME=value`) exactly. Another
/// user's process cannot be read and does not.
fn holds(pid: i32, entry: &str) -> bool {
    let Ok(file) = std::fs::File::open(format!("/proc/{pid}/environ")) else {
        return false;
    };
    let mut bytes = Vec::new();
    if file.take(MAX_ENVIRON_BYTES).read_to_end(&mut bytes).is_err() {
        return false;
    }
    bytes
        .split(|&b| b == 0)
        .any(|variable| variable == entry.as_bytes())
}

/// Sends SIGKILL to process `pid` if it is still the process that started at `start`: through a
/// pidfd, opened, then checked, so that a pid reused in between is never signalled. True when
/// the signal was sent.
fn kill(pid: i32, start: u64) -> bool {
    // SAFETY: pidfd_open takes a pid and flags and returns a new descriptor or -1.
    let fd = unsafe { libc::syscall(libc::SYS_pidfd_open, pid, 0) } as libc::c_int;
    if fd < 0 {
        return false;
    }
    let same = stat(pid).is_some_and(|p| p.start == start);
    // SAFETY: `fd` is the pidfd just opened; a null siginfo is allowed; close takes the fd.
    let sent = same
        && unsafe {
            libc::syscall(
                libc::SYS_pidfd_send_signal,
                fd,
                libc::SIGKILL,
                std::ptr::null::<u8>(),
                0,
            ) == 0
        };
    // SAFETY: closing the descriptor opened above, once.
    unsafe { libc::close(fd) };
    sent
}
