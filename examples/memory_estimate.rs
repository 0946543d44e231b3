//! Each solver run's estimates against what it took: the peak memory estimated before the
//! factorisations (`spherecontact::memory`, recorded as `memory_estimate_bytes`) against the peak
//! resident memory of the child process that ran it (`ru_maxrss`), and the coarse time estimate
//! (`spherecontact::cost`) against the measured CPU time of the process (on a shared machine the
//! wall time is the CPU time stretched by the load; on a quiet one they agree but for the BEM's
//! two threads). One child process per run, one after
//! the other (the machine is shared: nothing runs side by side).
//!
//! ```sh
//! # the fem-axisym and fem-3d ladders on the paper's path
//! cargo run --release --example memory_estimate
//! # chosen runs (SOLVER=RESOLUTION, or SOLVER alone for its default), on another case
//! cargo run --release --example memory_estimate -- --case cases/cattaneo.toml mdr=100000 bem=128 fem-3d
//! ```
//!
//! A run over the budget is refused before it factors: its row shows the estimate and no peak.

use std::path::Path;
use std::process::Command;

use spherecontact::bench::process_cpu_seconds;
use spherecontact::case::Case;
use spherecontact::memory::{gigabytes, run_measured};
use spherecontact::solver::{self, Solver};

/// The default rungs: fem-axisym's ladder (c/20 … c/160, the largest under the budget and the
/// largest accepted) and fem-3d's (its whole ladder).
const LADDER: &[&str] = &[
    "fem-axisym=c/20",
    "fem-axisym=c/40",
    "fem-axisym=c/80",
    "fem-axisym=c/120",
    "fem-axisym=c/160",
    "fem-axisym=c/226",
    "fem-axisym=c/320",
    "fem-3d=c/4",
    "fem-3d=c/6",
    "fem-3d=c/10",
    "fem-3d=c/14",
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--child") {
        child(&args[1..]);
        return;
    }
    let (case, runs) = match args.iter().position(|a| a == "--case") {
        Some(i) => (
            args.get(i + 1).cloned().expect("--case FILE"),
            args.iter()
                .enumerate()
                .filter(|&(k, _)| k != i && k != i + 1)
                .map(|(_, a)| a.clone())
                .collect(),
        ),
        None => ("cases/paper-fig7.toml".to_owned(), args),
    };
    let runs: Vec<String> = if runs.is_empty() {
        LADDER.iter().map(|s| (*s).to_owned()).collect()
    } else {
        runs
    };
    println!(
        "case {case}; budget {}",
        gigabytes(spherecontact::limits::MEMORY_BUDGET)
    );
    println!(
        "| solver | resolution | estimate | peak RSS | of which at start | (peak − start) / estimate | time estimate [s] | CPU [s] | wall [s] | CPU / estimate |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for run in &runs {
        let (solver, value) = run.split_once('=').unwrap_or((run.as_str(), ""));
        let exe = std::env::current_exe().expect("this example's path");
        let (output, peak) =
            run_measured(Command::new(exe).args(["--child", &case, solver, value])).expect("a child process");
        let text = String::from_utf8_lossy(&output.stdout);
        let shown = if value.is_empty() { "default" } else { value };
        match text.trim().split_once(' ') {
            Some(("ok", numbers)) => {
                let v: Vec<f64> = numbers
                    .split(' ')
                    .map(|x| x.parse().unwrap_or(f64::NAN))
                    .collect();
                let [estimate, start, wall, cpu, guess] = [v[0], v[1], v[2], v[3], v[4]];
                let ratio = if estimate > 0.0 {
                    format!("{:.2}", (peak as f64 - start) / estimate)
                } else {
                    "–".to_owned()
                };
                println!(
                    "| {solver} | {shown} | {} | {} | {} | {ratio} | {guess:.3} | {cpu:.3} | {wall:.3} | {:.2} |",
                    if estimate > 0.0 { gigabytes(estimate as u64) } else { "–".to_owned() },
                    gigabytes(peak),
                    gigabytes(start as u64),
                    cpu / guess
                );
            }
            _ => println!(
                "| {solver} | {shown} | refused or failed: {} | {} | | | | | | |",
                text.trim().replace('|', "/"),
                gigabytes(peak)
            ),
        }
    }
}

/// One run, in this child process: `CASE SOLVER VALUE`; prints `ok ESTIMATE START WALL CPU
/// GUESS` (bytes, bytes, s, s, s) or `error MESSAGE`.
fn child(args: &[String]) {
    let [case, name, value] = args else {
        panic!("--child CASE SOLVER VALUE")
    };
    let case = Case::load(Path::new(case)).expect("the case loads");
    let base = case.solver(name).expect("a solver of this build");
    let solver: Box<dyn Solver> = if value.is_empty() {
        base
    } else {
        base.at_resolution(&case.scene, value)
            .expect("a valid resolution")
    };
    let start = resident("VmRSS");
    let guess = solver.estimated_seconds(&case.scene).unwrap_or(f64::NAN);
    let cpu = process_cpu_seconds();
    let result = solver::run(solver.as_ref(), &case.scene);
    let cpu = process_cpu_seconds() - cpu;
    match result {
        Ok(history) => {
            let estimate = history
                .metadata
                .extra
                .get("memory_estimate_bytes")
                .and_then(serde_json::Value::as_f64)
                .unwrap_or(0.0);
            println!(
                "ok {estimate} {start} {} {cpu} {guess}",
                history.metadata.wall_time_s
            );
        }
        Err(e) => println!("error {e}"),
    }
}

/// A line of /proc/self/status in bytes (e.g. `VmRSS`).
fn resident(key: &str) -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix(key)?.strip_prefix(':'))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(0.0, |kb| kb * 1024.0)
}
