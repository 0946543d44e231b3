//! Running an external program: in its own temporary directory, in its own process group, with a
//! timeout that kills the whole group (the program and every child it started), its stdout and
//! stderr kept in files, and its exit status put into words.

use std::fs::File;
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus};
use std::sync::atomic::{AtomicU64, Ordering as AtomicOrdering};
use std::time::{Duration, Instant};

/// How often a running program is polled for its exit.
const POLL: Duration = Duration::from_millis(10);

/// A program to run: executable, arguments, extra environment, time limit.
#[derive(Clone, Debug)]
pub struct Job {
    /// The executable (a path, or a name looked up on PATH).
    pub program: PathBuf,
    /// Its arguments.
    pub args: Vec<String>,
    /// Extra environment variables.
    pub env: Vec<(String, String)>,
    /// Wall-clock limit; at the limit the process group is killed.
    pub timeout: Duration,
}

/// How a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Ending {
    /// Exited with this code (0 is success).
    Exited(i32),
    /// Killed by this signal (not by us).
    Signalled(i32),
    /// Killed, with its children, at the timeout.
    TimedOut,
}

/// What a finished run left: how it ended, its output, its wall time.
#[derive(Clone, Debug)]
pub struct Run {
    /// How it ended.
    pub ending: Ending,
    /// Its standard output.
    pub stdout: String,
    /// Its standard error.
    pub stderr: String,
    /// Wall time [s].
    pub wall_s: f64,
}

impl Ending {
    /// Why a run that ended this way failed, in words, or `None` for exit code 0. `program`
    /// names the program; `meaning` puts its own exit codes into words.
    pub fn failure(
        &self,
        program: &str,
        timeout: Duration,
        meaning: impl Fn(i32) -> &'static str,
    ) -> Option<String> {
        match self {
            Ending::Exited(0) => None,
            Ending::Exited(code) => Some(format!("{program} exited with code {code}: {}", meaning(*code))),
            Ending::Signalled(signal) => Some(format!("{program} crashed with {}", signal_name(*signal))),
            Ending::TimedOut => Some(format!(
                "{program} did not finish within {} s: killed with its children",
                timeout.as_secs_f64()
            )),
        }
    }
}

impl Run {
    /// True when the program exited with code 0.
    pub fn succeeded(&self) -> bool {
        self.ending == Ending::Exited(0)
    }

    /// The last `lines` lines of stderr, or of stdout when stderr is empty: what a failure
    /// message shows.
    pub fn tail(&self, lines: usize) -> String {
        let text = if self.stderr.trim().is_empty() {
            &self.stdout
        } else {
            &self.stderr
        };
        let all: Vec<&str> = text.lines().collect();
        all[all.len().saturating_sub(lines)..].join("\n")
    }
}

/// Runs `job` with working directory `dir`, stdout and stderr going to `dir/<stem>.stdout` and
/// `dir/<stem>.stderr` (kept there for inspection, and returned).
///
/// The child leads a new process group, so at the timeout `SIGKILL` to the group ends the
/// program and any process it spawned (MPI ranks, shells, Python workers). An error here means
/// the program could not be started (missing executable, unwritable directory).
pub fn run(job: &Job, dir: &Path, stem: &str) -> std::io::Result<Run> {
    let (out_path, err_path) = (
        dir.join(format!("{stem}.stdout")),
        dir.join(format!("{stem}.stderr")),
    );
    let start = Instant::now();
    let child = Command::new(&job.program)
        .args(&job.args)
        .envs(job.env.iter().map(|(k, v)| (k, v)))
        .current_dir(dir)
        .stdin(std::process::Stdio::null())
        .stdout(File::create(&out_path)?)
        .stderr(File::create(&err_path)?)
        .process_group(0)
        .spawn()?;
    let ending = loop {
        if let Some(status) = reap(child.id(), libc::WNOHANG)? {
            break ending_of(status);
        }
        if start.elapsed() >= job.timeout {
            kill_group(child.id());
            reap(child.id(), 0)?;
            break Ending::TimedOut;
        }
        std::thread::sleep(POLL);
    };
    // The group may hold children that outlived a finished leader: end them too.
    kill_group(child.id());
    let read = |p: &Path| String::from_utf8_lossy(&std::fs::read(p).unwrap_or_default()).into_owned();
    Ok(Run {
        ending,
        stdout: read(&out_path),
        stderr: read(&err_path),
        wall_s: start.elapsed().as_secs_f64(),
    })
}

/// CPU time [ns] of every child that [`run`] has reaped, with the children they waited for.
static CHILD_CPU_NS: AtomicU64 = AtomicU64::new(0);

/// The CPU time (user + system) of all external programs this process has run so far [s]: a
/// clock that benchmarks read before and after a solve, as the thread's own CPU clock.
pub fn child_cpu_seconds() -> f64 {
    CHILD_CPU_NS.load(AtomicOrdering::Relaxed) as f64 * 1e-9
}

/// Waits for `pid` with `wait4` (blocking, or not with `WNOHANG`), adding its CPU time to
/// [`child_cpu_seconds`]; `None` while it still runs.
fn reap(pid: u32, options: libc::c_int) -> std::io::Result<Option<ExitStatus>> {
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

fn ending_of(status: ExitStatus) -> Ending {
    match (status.code(), status.signal()) {
        (Some(code), _) => Ending::Exited(code),
        (None, Some(signal)) => Ending::Signalled(signal),
        (None, None) => Ending::Exited(-1),
    }
}

/// Sends SIGKILL to the process group led by `pid` (ESRCH, an already empty group, is fine).
fn kill_group(pid: u32) {
    if let Ok(pid) = libc::pid_t::try_from(pid) {
        // SAFETY: kill(2) with a negative pid signals the process group; it touches no memory.
        unsafe {
            libc::kill(-pid, libc::SIGKILL);
        }
    }
}

/// The name of a signal number, for messages.
pub fn signal_name(signal: i32) -> &'static str {
    match signal {
        libc::SIGSEGV => "SIGSEGV (segmentation fault)",
        libc::SIGABRT => "SIGABRT (abort)",
        libc::SIGKILL => "SIGKILL (killed, e.g. out of memory)",
        libc::SIGBUS => "SIGBUS (bus error)",
        libc::SIGFPE => "SIGFPE (arithmetic error)",
        libc::SIGTERM => "SIGTERM",
        _ => "a signal",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job(script: &str, timeout_ms: u64) -> Job {
        Job {
            program: "sh".into(),
            args: vec!["-c".into(), script.into()],
            env: vec![("SPHERECONTACT_TEST".into(), "42".into())],
            timeout: Duration::from_millis(timeout_ms),
        }
    }

    #[test]
    fn keeps_output_exit_code_and_environment() {
        let dir = tempfile::tempdir().unwrap();
        let run = run(
            &job("echo out $SPHERECONTACT_TEST; echo err >&2; exit 3", 10_000),
            dir.path(),
            "t",
        )
        .unwrap();
        assert_eq!(run.ending, Ending::Exited(3));
        assert_eq!(run.stdout.trim(), "out 42");
        assert_eq!(run.tail(5), "err");
        assert!(dir.path().join("t.stderr").exists());
    }

    #[test]
    fn reports_a_crash_by_signal() {
        let dir = tempfile::tempdir().unwrap();
        let run = run(&job("kill -SEGV $$", 10_000), dir.path(), "t").unwrap();
        assert_eq!(run.ending, Ending::Signalled(libc::SIGSEGV));
    }

    #[test]
    fn a_hanging_program_and_its_children_are_killed_at_the_timeout() {
        let dir = tempfile::tempdir().unwrap();
        // The shell starts a background child, records its pid, and both hang.
        let run = run(
            &job("sleep 30 & echo $! > child.pid; sleep 30", 300),
            dir.path(),
            "t",
        )
        .unwrap();
        assert_eq!(run.ending, Ending::TimedOut);
        assert!(run.wall_s < 10.0, "killed late: {} s", run.wall_s);
        let child: i32 = std::fs::read_to_string(dir.path().join("child.pid"))
            .unwrap()
            .trim()
            .parse()
            .unwrap();
        // The child may linger as a zombie of init for a moment; it must not be running.
        let alive = || {
            std::fs::read_to_string(format!("/proc/{child}/stat"))
                .map(|s| !s.contains(") Z"))
                .unwrap_or(false)
        };
        let deadline = Instant::now() + Duration::from_secs(5);
        while alive() && Instant::now() < deadline {
            std::thread::sleep(POLL);
        }
        assert!(!alive(), "child {child} of the killed program still runs");
    }

    #[test]
    fn a_missing_program_is_an_error_not_a_panic() {
        let dir = tempfile::tempdir().unwrap();
        let mut j = job("", 1000);
        j.program = "/nonexistent/spherecontact-no-such-tool".into();
        assert!(run(&j, dir.path(), "t").is_err());
    }
}
