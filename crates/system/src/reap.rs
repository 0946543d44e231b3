//! Reaping a child process: `wait4` on it, and the clock of the CPU time (user + system) of every
//! child reaped so far, which benchmarks read. The program a run started is reaped here by
//! [`super::process`], and the descendants re-parented to the harness by [`super::descendants`].

use std::os::unix::process::ExitStatusExt;
use std::process::ExitStatus;
use std::sync::atomic::{AtomicU64, Ordering as AtomicOrdering};

/// CPU time [ns] of every child that [`reap`] has reaped, with the children they waited for.
static CHILD_CPU_NS: AtomicU64 = AtomicU64::new(0);

/// The CPU time (user + system) of all external programs this process has run so far [s]: a
/// clock that benchmarks read before and after a solve, as the thread's own CPU clock.
pub fn child_cpu_seconds() -> f64 {
    CHILD_CPU_NS.load(AtomicOrdering::Relaxed) as f64 * 1e-9
}

/// Waits for `pid` with `wait4` (blocking, or not with `WNOHANG`), adding its CPU time to
/// [`child_cpu_seconds`]; `None` while it still runs.
pub(super) fn reap(pid: u32, options: libc::c_int) -> std::io::Result<Option<ExitStatus>> {
    let mut status: libc::c_int = 0;
    // SAFETY: an all-zero rusage is a valid value; wait4 only writes into it.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: valid pointers to a c_int and an rusage that outlive the call.
    let reaped = unsafe { libc::wait4(pid as libc::pid_t, &mut status, options, &mut usage) };
    match reaped {
        0 => Ok(None),
        r if r < 0 => Err(std::io::Error::last_os_error()),
        _ => {
            let ns = |t: libc::timeval| t.tv_sec as u64 * 1_000_000_000 + t.tv_usec as u64 * 1_000;
            CHILD_CPU_NS.fetch_add(ns(usage.ru_utime) + ns(usage.ru_stime), AtomicOrdering::Relaxed);
            Ok(Some(ExitStatus::from_raw(status)))
        }
    }
}
