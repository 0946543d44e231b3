//! Bounded and reported (issue 27): every accepted resolution solves within the memory budget or
//! is refused before it allocates, and a long run says so before it starts and shows progress;
//! an impact run too (issue 42), in sweep points. One regression test per finding; each failed
//! before its fix. The cases are in `tests/hostile/bounded/`.
//!
//! Run: `cargo test --test suite hostile_bounded::`.

use crate::common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::{mpsc, Arc, Mutex};
use std::time::Duration;

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

/// How long [`stderr_until`] waits for its line before it stops the program: a guard, not an
/// assertion (a run that never announces itself would otherwise hold the test for hours; it is
/// stopped, and the test fails on what it printed).
const SILENCE_GUARD: Duration = Duration::from_secs(300);

/// The first lines `spherecontact ARGS` (in `dir`, `SPHERECONTACT_PROGRESS` unset) prints on
/// stderr, up to the first that starts with `wanted` (at most `limit`); then it is stopped.
fn stderr_until(args: &[&str], dir: &Path, wanted: &str, limit: usize) -> Vec<String> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(args)
        .current_dir(dir)
        .env_remove("SPHERECONTACT_PROGRESS")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let lines = BufReader::new(child.stderr.take().unwrap()).lines();
    // The child is killed through the lock only (a reaped child is not signalled again).
    let child = Arc::new(Mutex::new(child));
    let (done, finished) = mpsc::channel::<()>();
    let guarded = Arc::clone(&child);
    let guard = std::thread::spawn(move || {
        if finished.recv_timeout(SILENCE_GUARD).is_err() {
            let _ = guarded.lock().unwrap().kill();
        }
    });
    let mut seen = Vec::new();
    for line in lines.take(limit) {
        let line = line.unwrap();
        let found = line.starts_with(wanted);
        seen.push(line);
        if found {
            break;
        }
    }
    let _ = done.send(());
    let mut child = child.lock().unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    drop(child);
    guard.join().unwrap();
    seen
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
    // The first lines on stderr, up to the announcement (the run itself would take half an hour:
    // it is stopped once it has said so).
    let args = ["run", file.to_str().unwrap(), "--out", "out"];
    let seen = stderr_until(
        &args,
        dir.path(),
        "note: million-increments-mdr mdr: estimated",
        5,
    );
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

// --- Finding (issue 42): a valid 200-angle impact sweep ran for hours in silence ----------------

/// Requirement: `verify` announces an impact run estimated long before it runs, with its
/// estimate (integration steps × springs × sweep points × variants) and its points, in a CI log
/// too (stderr not a terminal). The sweep would take a day and a half: it is stopped once it has
/// said so.
#[test]
fn a_long_impact_sweep_is_announced_with_its_estimate_before_it_runs() {
    let dir = tempfile::tempdir().unwrap();
    let file = case("impact-200-angles.toml");
    let none = dir.path().join("no-baselines");
    // An empty baselines folder: a missing one is an error (a typo would hide the check).
    std::fs::create_dir(&none).unwrap();
    let args = [
        "verify",
        file.to_str().unwrap(),
        "--baselines",
        none.to_str().unwrap(),
    ];
    let seen = stderr_until(&args, dir.path(), "note: impact-200-angles mdr:", 5);
    let note = seen.last().cloned().unwrap_or_default();
    // 400 points (200 angles, damped and elastic) of 10⁵ steps over 10⁶ springs: 33.3 h.
    assert_eq!(
        note,
        "note: impact-200-angles mdr: estimated 33.3 h for 400 points (a coarse estimate, within a \
         factor of about 3); progress is shown on a terminal, or with SPHERECONTACT_PROGRESS=on",
        "{seen:?}"
    );
}

/// `spherecontact run CASE --solver SOLVER --out OUT` in `dir` with `SPHERECONTACT_PROGRESS` set
/// to `progress` (or unset): its stderr.
fn impact_run(dir: &Path, solver: &str, out: &str, progress: Option<&str>) -> String {
    let file = common::root().join("cases/impact/chung-ooi-4.toml");
    let args = ["run", file.to_str().unwrap(), "--solver", solver, "--out", out];
    let (output, _) = measured(&args, dir, progress);
    assert!(output.status.success(), "{}", stderr(&output));
    stderr(&output)
}

/// The points done that the progress lines of `label` report, in order.
fn points_reported(stderr: &str, label: &str) -> Vec<usize> {
    let prefix = format!("progress: {label}: ");
    stderr
        .lines()
        .filter(|l| l.starts_with("progress:"))
        .map(|line| {
            let rest = line.strip_prefix(&prefix).unwrap_or_else(|| panic!("{line}"));
            let (done, rest) = rest.split_once('/').unwrap_or_else(|| panic!("{line}"));
            assert!(
                rest.starts_with("34 points (") && rest.contains(" left"),
                "{line}"
            );
            done.parse().unwrap()
        })
        .collect()
}

/// Requirement: an impact run shows the progress lines of a path run, in sweep points
/// (`k/n points`), when `SPHERECONTACT_PROGRESS` says so (here every point: `0` s apart), none
/// when stderr is not a terminal and it is unset; its results are the same bit for bit.
#[test]
fn an_impact_run_shows_its_progress_in_points_and_the_same_results() {
    let dir = tempfile::tempdir().unwrap();
    // Test 4: 17 angles, e = 0.98: 34 points over both variants, about a second.
    let forced = impact_run(dir.path(), "mdr", "forced", Some("0"));
    let points = points_reported(&forced, "chung-ooi-4 mdr");
    assert_eq!(points, (1..=34).collect::<Vec<_>>(), "{forced}");
    let quiet = impact_run(dir.path(), "mdr", "quiet", None);
    assert!(!quiet.contains("progress:"), "{quiet}");
    for name in ["mdr.csv", "mdr-elastic.csv", "mdr-trace.csv"] {
        let file = |out: &str| std::fs::read(dir.path().join(out).join(name)).unwrap();
        assert_eq!(file("forced"), file("quiet"), "{name}");
    }
}

/// Requirement: a DEM code that runs a whole sweep in one process (LAMMPS) shows its progress
/// while it runs, point by point within a variant, not only when each variant's process ends.
#[test]
#[ignore = "heavy: a LAMMPS impact sweep, 5 s (two test threads); .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn a_dem_codes_sweep_shows_its_progress_while_the_code_runs() {
    let probe = spherecontact::toolchain::Toolchain::default().probe(spherecontact::toolchain::Tool::Lammps);
    if !probe.available() {
        eprintln!("skipped: {} (run scripts/setup.sh)", probe.line());
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let forced = impact_run(dir.path(), "lammps-mindlin", "forced", Some("0"));
    let points = points_reported(&forced, "chung-ooi-4 lammps-mindlin");
    assert!(points.windows(2).all(|w| w[0] < w[1]), "{forced}");
    // Points within a variant's process (neither 17 nor 34, its ends), from its files.
    assert!(points.iter().any(|&k| k != 17 && k != 34), "{forced}");
    assert_eq!(points.last(), Some(&34), "{forced}");
}
