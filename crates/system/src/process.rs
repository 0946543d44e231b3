//! Running an external program: in its own temporary directory, in its own process group, with a
//! timeout; at the timeout, and when the program ends, every process it started is killed,
//! those that left its group or session included ([`super::descendants`]). Its stdout and
//! stderr are streamed into logs of bounded size ([`super::bounded_log`]), never held whole in
//! memory; the excerpt of them it returns has its secrets masked ([`super::mask`]); its exit
//! status is put into words.

use std::io::Read;
use std::os::fd::AsRawFd;
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::{Path, PathBuf};
use std::process::{ChildStderr, ChildStdout, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use super::bounded_log::BoundedLog;
use super::descendants::Tracker;
use super::excerpt;
use super::mask::Mask;
use super::reap::reap;

/// How often a running program is polled for its exit (the longest wait for its output).
const POLL: Duration = Duration::from_millis(10);

/// How long output is still read after every process of the run was killed: the pipes close
/// as soon as the last writer is dead, so this bounds only a writer the sweep could not see.
const DRAIN: Duration = Duration::from_secs(1);

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

/// The variables a program run with [`Environment::Minimal`] gets from the harness's own
/// environment (those that are set): where programs and the user's files are (PATH, HOME, USER,
/// LOGNAME), the locale and time zone (LANG, LC_ALL, LC_CTYPE, LC_NUMERIC, TZ), the temporary
/// folder (TMPDIR), and what a Python or an MPI build needs to find its packages and libraries
/// (PYTHONPATH, PYTHONHOME, PYTHONUSERBASE, VIRTUAL_ENV, CONDA_PREFIX, LD_LIBRARY_PATH) and how
/// many threads to use (OMP_NUM_THREADS). None of them usually holds a secret; tokens, keys and
/// passwords a CI job or a shell sets are left out.
pub const MINIMAL_ENV: [&str; 17] = [
    "PATH",
    "HOME",
    "USER",
    "LOGNAME",
    "LANG",
    "LC_ALL",
    "LC_CTYPE",
    "LC_NUMERIC",
    "TZ",
    "TMPDIR",
    "PYTHONPATH",
    "PYTHONHOME",
    "PYTHONUSERBASE",
    "VIRTUAL_ENV",
    "CONDA_PREFIX",
    "LD_LIBRARY_PATH",
    "OMP_NUM_THREADS",
];

/// What a program's environment starts from (then [`Job::env`] and the run's marker).
#[derive(Clone, Debug, PartialEq)]
pub enum Environment {
    /// The harness's whole environment: for the programs the harness drives with input it wrote
    /// itself (gmsh, the decks, the DEM codes), which may need the toolchain's own variables.
    Inherited,
    /// [`MINIMAL_ENV`] and the variables named here: for programs a case names.
    Minimal(Vec<String>),
}

impl Environment {
    /// Sets `command`'s environment to this one.
    fn apply(&self, command: &mut Command) {
        if let Environment::Minimal(pass) = self {
            command.env_clear();
            let names = MINIMAL_ENV.iter().copied().chain(pass.iter().map(String::as_str));
            for name in names {
                if let Some(value) = std::env::var_os(name) {
                    command.env(name, value);
                }
            }
        }
    }

    /// The mask of a program's output run in this environment: the values of the variables
    /// passed on and of the harness's secret-named variables ([`Mask::of_environment`]).
    pub fn mask(&self) -> Mask {
        match self {
            Environment::Inherited => Mask::of_environment(&[]),
            Environment::Minimal(pass) => Mask::of_environment(pass),
        }
    }
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
    /// Its standard output: the log's excerpt ([`BoundedLog::finish`]), secrets masked.
    pub stdout: String,
    /// Its standard error: the log's excerpt, secrets masked.
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

    /// The last `lines` lines of stderr, or of stdout when stderr is empty, bounded in lines and
    /// bytes ([`excerpt::last_lines`]): what a failure message shows.
    pub fn tail(&self, lines: usize) -> String {
        let text = if self.stderr.trim().is_empty() {
            &self.stdout
        } else {
            &self.stderr
        };
        excerpt::last_lines(text, lines)
    }
}

/// Runs `job` with working directory `dir` and the harness's environment, stdout and stderr
/// going to `dir/<stem>.stdout` and `dir/<stem>.stderr` (see [`run_in`]).
pub fn run(job: &Job, dir: &Path, stem: &str) -> std::io::Result<Run> {
    run_in(job, dir, stem, &Environment::Inherited)
}

/// Runs `job` with working directory `dir` in `environment`, stdout and stderr streamed to the
/// bounded logs `dir/<stem>.stdout` and `dir/<stem>.stderr` (kept there as the program wrote
/// them; their first and last lines returned, with the secrets of `environment` masked).
///
/// The child leads a new process group and carries the run's marker; at the timeout, and when it
/// ends, every process of the run is killed ([`Tracker::kill_all`]): MPI ranks, shells, Python
/// workers, daemons that started a new session. While it waits, it reports the program's
/// progress when a run is metered and watched ([`spherecontact_model::progress::poll`]). An error here means
/// the program could not be started (missing executable, unwritable directory).
pub fn run_in(job: &Job, dir: &Path, stem: &str, environment: &Environment) -> std::io::Result<Run> {
    let log = |stream: &str| BoundedLog::create(&dir.join(format!("{stem}.{stream}")));
    let mut logs = [log("stdout")?, log("stderr")?];
    let mut tracker = Tracker::begin();
    let mut command = Command::new(&job.program);
    command
        .args(&job.args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .process_group(0);
    environment.apply(&mut command);
    // SAFETY: prctl is async-signal-safe (one system call) and touches no memory. The program
    // becomes a subreaper too (kept across exec): the orphans of its own children stay under it,
    // in the tree the sweep walks, for as long as it runs.
    unsafe {
        command.pre_exec(|| {
            libc::prctl(libc::PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0);
            Ok(())
        });
    }
    let (marker, value) = tracker.marker();
    command
        .envs(job.env.iter().map(|(k, v)| (k, v)))
        .env(marker, value);
    let start = Instant::now();
    let mut child = command.spawn()?;
    tracker.started(child.id());
    // Waits for the end or the timeout; on an error of the harness's own (a log that cannot be
    // written), the program is killed and reaped all the same before the error is returned.
    let watched = Pipes::of(child.stdout.take(), child.stderr.take()).and_then(|mut pipes| loop {
        pipes.pump(&mut logs, POLL)?;
        if has_exited(child.id())? {
            return Ok((pipes, false));
        }
        if start.elapsed() >= job.timeout {
            return Ok((pipes, true));
        }
        tracker.observe();
        spherecontact_model::progress::poll();
    });
    // The program is held unreaped while the sweep runs, so that its group stays its own.
    tracker.kill_all();
    let status = reap(child.id(), 0)?.unwrap_or_else(|| ExitStatus::from_raw(0));
    let (mut pipes, timed_out) = watched?;
    let ending = if timed_out {
        Ending::TimedOut
    } else {
        ending_of(status)
    };
    let drained = Instant::now();
    while pipes.open() && drained.elapsed() < DRAIN {
        pipes.pump(&mut logs, POLL)?;
    }
    let [stdout, stderr] = logs;
    let mask = environment.mask();
    Ok(Run {
        ending,
        stdout: mask.apply(&stdout.finish()?).into_owned(),
        stderr: mask.apply(&stderr.finish()?).into_owned(),
        wall_s: start.elapsed().as_secs_f64(),
    })
}

/// A running program's stdout and stderr, read without blocking.
struct Pipes {
    /// stdout, stderr; `None` once closed.
    streams: [Option<Box<dyn ReadFd>>; 2],
    /// Where each read lands on its way to a log.
    buffer: Vec<u8>,
}

/// A pipe end that can be polled.
trait ReadFd: Read + AsRawFd {}
impl ReadFd for ChildStdout {}
impl ReadFd for ChildStderr {}

impl Pipes {
    fn of(stdout: Option<ChildStdout>, stderr: Option<ChildStderr>) -> std::io::Result<Self> {
        let boxed = |s: Option<Box<dyn ReadFd>>| -> std::io::Result<_> {
            if let Some(s) = &s {
                set_nonblocking(s.as_raw_fd())?;
            }
            Ok(s)
        };
        Ok(Pipes {
            streams: [
                boxed(stdout.map(|s| Box::new(s) as Box<dyn ReadFd>))?,
                boxed(stderr.map(|s| Box::new(s) as Box<dyn ReadFd>))?,
            ],
            buffer: vec![0; 64 << 10],
        })
    }

    /// Whether a stream is still open.
    fn open(&self) -> bool {
        self.streams.iter().any(Option::is_some)
    }

    /// Waits up to `wait` for output, then moves all there is into `logs` (stdout, stderr).
    fn pump(&mut self, logs: &mut [BoundedLog; 2], wait: Duration) -> std::io::Result<()> {
        let mut fds: Vec<libc::pollfd> = self
            .streams
            .iter()
            .flatten()
            .map(|s| libc::pollfd {
                fd: s.as_raw_fd(),
                events: libc::POLLIN,
                revents: 0,
            })
            .collect();
        if fds.is_empty() {
            std::thread::sleep(wait);
            return Ok(());
        }
        // SAFETY: `fds` is a valid array of `fds.len()` pollfd structures for the call.
        unsafe {
            libc::poll(
                fds.as_mut_ptr(),
                fds.len() as libc::nfds_t,
                wait.as_millis() as libc::c_int,
            )
        };
        let buffer = &mut self.buffer;
        for (slot, log) in self.streams.iter_mut().zip(logs.iter_mut()) {
            let Some(stream) = slot else { continue };
            loop {
                match stream.read(buffer) {
                    Ok(0) => {
                        *slot = None;
                        break;
                    }
                    Ok(n) => log.write(&buffer[..n])?,
                    Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => break,
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(e),
                }
            }
        }
        Ok(())
    }
}

/// Puts descriptor `fd` into non-blocking mode.
fn set_nonblocking(fd: libc::c_int) -> std::io::Result<()> {
    // SAFETY: fcntl on a descriptor this process owns; F_GETFL/F_SETFL touch no memory.
    let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
    // SAFETY: as above.
    if flags < 0 || unsafe { libc::fcntl(fd, libc::F_SETFL, flags | libc::O_NONBLOCK) } < 0 {
        return Err(std::io::Error::last_os_error());
    }
    Ok(())
}

/// Whether child `pid` has ended, leaving it unreaped (its pid, and its group's id, stay taken).
fn has_exited(pid: u32) -> std::io::Result<bool> {
    // SAFETY: an all-zero siginfo_t is a valid value; waitid only writes into it.
    let mut info: libc::siginfo_t = unsafe { std::mem::zeroed() };
    let options = libc::WEXITED | libc::WNOHANG | libc::WNOWAIT;
    // SAFETY: a valid pointer to a siginfo_t that outlives the call.
    if unsafe { libc::waitid(libc::P_PID, pid as libc::id_t, &mut info, options) } < 0 {
        return Err(std::io::Error::last_os_error());
    }
    // SAFETY: waitid filled `info` (or left it zero: no child has changed state).
    Ok(unsafe { info.si_pid() } != 0)
}

fn ending_of(status: ExitStatus) -> Ending {
    match (status.code(), status.signal()) {
        (Some(code), _) => Ending::Exited(code),
        (None, Some(signal)) => Ending::Signalled(signal),
        (None, None) => Ending::Exited(-1),
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
    fn a_flood_of_output_leaves_a_bounded_log_with_its_head_its_tail_and_a_count() {
        let dir = tempfile::tempdir().unwrap();
        // 20 MiB of `x`, then `END`: 4 MiB + 4 bytes more than the log keeps.
        let run = run(
            &job("head -c 20971520 /dev/zero | tr '\\0' x; echo END", 60_000),
            dir.path(),
            "t",
        )
        .unwrap();
        assert_eq!(run.ending, Ending::Exited(0));
        let log = std::fs::read(dir.path().join("t.stdout")).unwrap();
        let notice = format!("[spherecontact: {} bytes of output dropped here", (4 << 20) + 4);
        let text = String::from_utf8_lossy(&log);
        assert!(text.contains(&notice), "no count of what was dropped");
        assert!(log.len() as u64 <= spherecontact_model::limits::MAX_PROGRAM_LOG_BYTES + 200);
        assert!(log.starts_with(b"xxxx") && log.ends_with(b"xxxxEND\n"));
        // In memory: the log's first and last 64 KiB around a line that names it.
        assert!(run.stdout.len() < 3 * (64 << 10) && run.stdout.ends_with("xxEND\n"));
        assert!(run.stdout.contains("bytes not shown here; the whole log:"));
    }

    #[test]
    fn a_minimal_environment_holds_only_the_listed_variables() {
        let dir = tempfile::tempdir().unwrap();
        let mut j = job("", 10_000);
        (j.program, j.args) = ("env".into(), Vec::new());
        let environment = Environment::Minimal(vec!["CARGO_PKG_NAME".into()]);
        let run = run_in(&j, dir.path(), "t", &environment).unwrap();
        let names: Vec<&str> = run.stdout.lines().filter_map(|l| l.split('=').next()).collect();
        assert!(names.contains(&"SPHERECONTACT_TEST") && names.contains(&super::super::descendants::MARKER));
        for name in names {
            let listed = MINIMAL_ENV.contains(&name)
                || [
                    "SPHERECONTACT_TEST",
                    "CARGO_PKG_NAME",
                    super::super::descendants::MARKER,
                ]
                .contains(&name);
            assert!(listed, "{name} reached the program");
        }
        // The harness's own environment is fuller: the test shows the difference.
        assert!(std::env::vars().any(|(k, _)| !MINIMAL_ENV.contains(&k.as_str())));
    }

    /// The excerpt a run returns has a passed variable's value masked; the program's log in its
    /// folder keeps what the program wrote (docs/security.md, "Programs a case may run").
    #[test]
    fn the_excerpt_masks_a_passed_variable_s_value_and_the_log_keeps_it() {
        let dir = tempfile::tempdir().unwrap();
        let path = std::env::var("PATH").unwrap();
        let environment = Environment::Minimal(vec!["PATH".into()]);
        let run = run_in(
            &job("echo \"x $PATH x\" >&2", 10_000),
            dir.path(),
            "t",
            &environment,
        )
        .unwrap();
        assert_eq!(run.tail(1), "x [masked: PATH] x");
        let log = std::fs::read_to_string(dir.path().join("t.stderr")).unwrap();
        assert_eq!(log, format!("x {path} x\n"));
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
