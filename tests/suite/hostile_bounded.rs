//! Bounded and reported (issue 27): every accepted resolution solves within the memory budget or
//! is refused before it allocates, and a long run says so before it starts and shows progress.
//! One regression test per finding; each failed before its fix. The cases are in
//! `tests/hostile/bounded/`.
//!
//! Run: `cargo test --test suite hostile_bounded::`.

use crate::common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use spherecontact::limits::MEMORY_BUDGET;

/// A case of `tests/hostile/bounded/`.
fn case(name: &str) -> PathBuf {
    common::root().join("tests/hostile/bounded").join(name)
}

/// `spherecontact ARGS` in `dir`, with `SPHERECONTACT_PROGRESS` set to `progress` (or unset),
/// its output and its peak resident memory [bytes].
fn measured(args: &[&str], dir: &Path, progress: Option<&str>) -> (Output, u64) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_spherecontact"));
    command
        .args(args)
        .current_dir(dir)
        .env_remove("SPHERECONTACT_PROGRESS");
    if let Some(value) = progress {
        command.env("SPHERECONTACT_PROGRESS", value);
    }
    common::peak::output_and_peak(&command)
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

// --- Finding: fem-axisym frictional at c/226 … c/320 aborted the process (4.5 GB, exit 134) -----

#[test]
#[ignore = "heavy: fem-axisym meshed and planned at c_max/320 before its refusal, 10 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn fem_axisym_frictional_at_the_finest_resolution_is_refused_within_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    let file = case("finest-frictional-axisym.toml");
    let out = dir.path().join("out");
    let args = ["run", file.to_str().unwrap(), "--out", out.to_str().unwrap()];
    let (output, peak) = measured(&args, dir.path(), None);
    let message = stderr(&output);
    // The solver's failure (exit 1), not an abort (134) nor a bad input (2): c/320 is accepted.
    assert_eq!(output.status.code(), Some(1), "{message}");
    for needle in [
        "error: fem-axisym: failed: fem-axisym at pole size c_max/320",
        "estimated peak memory",
        "exceeds the budget of 3.221 GB per solver (limits::MEMORY_BUDGET)",
        "refused before allocating",
        "accepted range c_max/320 to c_max/2",
    ] {
        assert!(message.contains(needle), "`{needle}` not in {message}");
    }
    assert!(
        peak < MEMORY_BUDGET,
        "the refusal itself took {peak} bytes, over the budget"
    );
}

// --- The estimate against the measured peak ----------------------------------------------------

/// The memory estimate of `solver` in the JSON `run` wrote into `out`.
fn recorded_estimate(out: &Path, solver: &str) -> f64 {
    let text = std::fs::read_to_string(out.join(format!("{solver}.json"))).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let found = json
        .pointer("/metadata/extra/memory_estimate_bytes")
        .or_else(|| json.pointer("/metadata/memory_estimate_bytes"))
        .and_then(serde_json::Value::as_f64);
    found.unwrap_or_else(|| panic!("no memory_estimate_bytes in {text:.2000}"))
}

/// How far the peak above the process's baseline may lie from the estimate: measured between
/// 0.91 and 1.12 times the estimate on fem-axisym's and fem-3d's ladders (docs/security.md,
/// "Memory and time bounds"); 1.25 leaves room for another allocator or machine.
const ESTIMATE_FACTOR: f64 = 1.25;

#[test]
fn the_memory_estimate_is_within_its_factor_of_the_measured_peak() {
    let dir = tempfile::tempdir().unwrap();
    let file = case("frictional-axisym.toml");
    let file = file.to_str().unwrap();
    let out = dir.path().join("out");
    let out_text = out.to_str().unwrap();
    // The process's own baseline (the program, the case): the same run with a closed form.
    let (baseline_output, baseline) = measured(
        &["run", file, "--solver", "hertz", "--out", out_text],
        dir.path(),
        None,
    );
    assert!(baseline_output.status.success(), "{}", stderr(&baseline_output));
    let args = ["run", file, "--resolution", "fem-axisym=c/80", "--out", out_text];
    let (output, peak) = measured(&args, dir.path(), None);
    assert!(output.status.success(), "{}", stderr(&output));
    let estimate = recorded_estimate(&out, "fem-axisym");
    let ratio = (peak.saturating_sub(baseline)) as f64 / estimate;
    assert!(
        (1.0 / ESTIMATE_FACTOR..=ESTIMATE_FACTOR).contains(&ratio),
        "peak {peak} − baseline {baseline} against the estimate {estimate}: ratio {ratio:.3}"
    );
}

// --- Finding: a valid case ran for half an hour and `run` printed nothing ----------------------

#[test]
fn a_long_run_says_so_before_it_starts() {
    let dir = tempfile::tempdir().unwrap();
    let file = case("million-increments-mdr.toml");
    let mut child = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(["run", file.to_str().unwrap(), "--out", "out"])
        .current_dir(dir.path())
        .env_remove("SPHERECONTACT_PROGRESS")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let lines = BufReader::new(child.stderr.take().unwrap()).lines();
    // The first lines on stderr, up to the announcement (the run itself would take half an hour:
    // it is stopped once it has said so).
    let mut seen = Vec::new();
    for line in lines.take(5) {
        let line = line.unwrap();
        let found = line.starts_with("note: million-increments-mdr mdr: estimated");
        seen.push(line);
        if found {
            break;
        }
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let note = seen.last().cloned().unwrap_or_default();
    assert!(
        note.starts_with("note: million-increments-mdr mdr: estimated"),
        "{seen:?}"
    );
    assert!(note.contains("for 1000001 steps"), "{note}");
    assert!(note.contains(" min") || note.contains(" h"), "{note}");
}

#[test]
fn progress_lines_appear_when_forced_and_change_no_result() {
    let dir = tempfile::tempdir().unwrap();
    let file = case("many-increments-mdr.toml");
    let file = file.to_str().unwrap();
    let run = |out: &str, progress: Option<&str>| {
        let (output, _) = measured(&["run", file, "--out", out], dir.path(), progress);
        assert!(output.status.success(), "{}", stderr(&output));
        stderr(&output)
    };
    // A line every 10 ms at most: forced on, although stderr is a pipe here.
    let forced = run("forced", Some("0.01"));
    let lines: Vec<&str> = forced.lines().filter(|l| l.starts_with("progress:")).collect();
    assert!(!lines.is_empty(), "no progress line in {forced}");
    for line in &lines {
        assert!(line.starts_with("progress: many-increments-mdr mdr: "), "{line}");
        assert!(line.contains("/40001 steps (") && line.contains("left"), "{line}");
    }
    // Not a terminal and not forced: quiet.
    let quiet = run("quiet", None);
    assert!(!quiet.contains("progress:"), "{quiet}");
    // The progress lines only read the walker's counters.
    let csv = |out: &str| std::fs::read(dir.path().join(out).join("mdr.csv")).unwrap();
    assert_eq!(csv("forced"), csv("quiet"));
}
