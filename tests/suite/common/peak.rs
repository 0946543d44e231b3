//! The peak resident memory of a program the tests run.
//!
//! All integration tests share one process, which may hold a gigabyte at times. On Linux a child
//! forked straight from it starts with this process's high-water mark (the kernel keeps the mark
//! of the memory image a program replaces at exec), so its own `ru_maxrss` would be ours. The
//! program is therefore started by a small Python parent, whose children start small, and which
//! reports their peak.

use std::process::{Command, Output};

/// Runs the program, reaps it and writes its (and its children's) peak RSS [KiB] to argv[1].
const PARENT: &str = "import resource, subprocess, sys
code = subprocess.call(sys.argv[2:])
with open(sys.argv[1], 'w') as f:
    f.write(str(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss))
sys.exit(code if code >= 0 else 128 - code)";

/// Runs `command` (its arguments, folder and environment) and returns its output and the peak
/// resident memory of it and the processes it waited for [bytes].
pub fn output_and_peak(command: &Command) -> (Output, u64) {
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("peak");
    let mut parent = Command::new("python3");
    parent
        .arg("-c")
        .arg(PARENT)
        .arg(&report)
        .arg(command.get_program());
    parent.args(command.get_args());
    if let Some(cwd) = command.get_current_dir() {
        parent.current_dir(cwd);
    }
    for (key, value) in command.get_envs() {
        match value {
            Some(value) => parent.env(key, value),
            None => parent.env_remove(key),
        };
    }
    let output = parent.output().expect("python3 runs");
    let kib: u64 = std::fs::read_to_string(&report)
        .unwrap_or_else(|e| {
            panic!(
                "no peak reported ({e}): {}",
                String::from_utf8_lossy(&output.stderr)
            )
        })
        .trim()
        .parse()
        .unwrap();
    (output, kib * 1024)
}
