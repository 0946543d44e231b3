//! Speed per increment of the Kratos deck `kratos-3d` beside `fem-3d` and `ccx-3d` on comparable
//! meshes, side by side in one run (issue 40, "Speed"): `cases/kratos-3d-normal.toml` (the paper's
//! spheres, the hemisphere gripped rigidly, Kratos' frictionless ALM) pressed to δn = 10 µm in M
//! increments, the three at the same pole size c_max/N: gmsh meshes the same `.geo` at the same
//! size, so the three solve on the same nodes — Kratos on the corners of the quadratic
//! tetrahedra fem-3d and CalculiX use (Kratos 10.4.4 has mortar contact for linear faces only).
//!
//! Each solver runs once to warm up, then REPEATS times (default 3), round-robin
//! ([`bench::time_solvers`]); printed: the medians of the whole run's wall and CPU time (this
//! process's and the programs it ran: Kratos' Python, ccx, gmsh), each with its ratio to fem-3d's,
//! and from the warm-up run's clocks: the path's time (Kratos' and ccx's whole process, fem-3d's
//! contact walk after assembly and factorisation) per increment, and the median of the solver's
//! own per-increment clock (Kratos' steps after the first, `kratos_step_s`; fem-3d's
//! `increment_median_s`; CalculiX has none), with P at δn = 10 µm (the same problem: the
//! first-order elements' excess shows in Kratos' P). The machine may be shared: compare the rows
//! of one run, and the CPU columns rather than the wall ones.
//!
//! Run: `cargo run --release --example kratos_increment_timing [REPEATS] [N] [M]` (defaults 3,
//! 3, 4; needs gmsh, ccx and Kratos: scripts/setup.sh).

use std::path::Path;

use spherecontact::bench::{self, median, significant, Timing};
use spherecontact::case::Case;
use spherecontact::history::History;
use spherecontact::path::{LoadingPath, Position};
use spherecontact::solver::Solver;

/// The solvers, the last the reference of the ratios.
const SOLVERS: [&str; 3] = ["kratos-3d", "ccx-3d", "fem-3d"];

/// The metadata keys of a run's path time: the decks' whole process, fem-3d's contact walk.
const PATH_KEYS: [&str; 2] = ["solving_s", "contact_s"];

/// A number of the metadata.
fn extra(history: &History, key: &str) -> Option<f64> {
    history
        .metadata
        .extra
        .get(key)
        .and_then(serde_json::Value::as_f64)
}

/// The path's wall time of a run [s], NaN if the solver clocks none.
fn path_seconds(history: &History) -> f64 {
    PATH_KEYS
        .iter()
        .find_map(|key| extra(history, key))
        .unwrap_or(f64::NAN)
}

/// The median of the solver's own per-increment clock [s]: Kratos' steps after the unloaded
/// first, fem-3d's increment median; NaN for a solver without one.
fn own_increment_seconds(history: &History) -> f64 {
    if let Some(steps) = history
        .metadata
        .extra
        .get("kratos_step_s")
        .and_then(|v| v.as_array())
    {
        let mut times: Vec<f64> = steps.iter().skip(1).filter_map(|v| v.as_f64()).collect();
        times.sort_by(f64::total_cmp);
        return if times.is_empty() {
            f64::NAN
        } else {
            median(&times)
        };
    }
    extra(history, "increment_median_s").unwrap_or(f64::NAN)
}

/// The path: δn = 10 µm in `increments`.
fn approach(increments: usize) -> LoadingPath {
    let at = |n: f64| Position {
        delta_n: n * 1e-6,
        delta_t: 0.0,
    };
    LoadingPath::try_new(vec![at(0.0), at(10.0)], vec![increments]).expect("a valid path")
}

/// Prints the table of `timings` (fem-3d last, the reference of the ratios).
fn table(timings: &[Timing], increments: usize) {
    println!(
        "{:<10} {:>8} {:>8} {:>7} {:>7} {:>14} {:>17} {:>10}",
        "solver", "wall s", "CPU s", "× wall", "× CPU", "path ms/incr.", "own ms/increment", "P [N]"
    );
    let Some(reference) = timings.last().filter(|t| t.solver == "fem-3d") else {
        println!("(fem-3d failed: no ratios)");
        return;
    };
    let [wall_ref, cpu_ref] = [median(&reference.seconds), median(&reference.cpu_seconds)];
    for timing in timings {
        let [wall, cpu] = [median(&timing.seconds), median(&timing.cpu_seconds)];
        let history = &timing.history;
        let p = history
            .steps
            .last()
            .and_then(|r| r.normal_force)
            .map_or("—".into(), |p| format!("{p:.2}"));
        println!(
            "{:<10} {:>8} {:>8} {:>7} {:>7} {:>14} {:>17} {:>10}",
            timing.solver,
            significant(wall),
            significant(cpu),
            significant(wall / wall_ref),
            significant(cpu / cpu_ref),
            significant(path_seconds(history) / increments as f64 * 1e3),
            significant(own_increment_seconds(history) * 1e3),
            p
        );
    }
    for timing in timings {
        println!("  {}: {}", timing.solver, timing.history.metadata.resolution);
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut number = |default: usize| {
        args.next()
            .and_then(|a| a.parse().ok())
            .filter(|n| *n >= 1)
            .unwrap_or(default)
    };
    let (repeats, n, increments) = (number(3), number(3), number(4));
    let mut case = Case::load(Path::new("cases/kratos-3d-normal.toml")).expect("run from the crate root");
    case.scene.path = approach(increments);
    let solvers: Vec<Box<dyn Solver>> = SOLVERS
        .iter()
        .map(|name| {
            case.resolution.insert(name.to_string(), format!("c/{n}"));
            case.solver(name).expect("built in")
        })
        .collect();
    println!(
        "{}: δn = 10 µm in {increments} increments, pole size c_max/{n}; medians of {repeats} runs \
         after a warm-up, round-robin; the path's and own clocks from the warm-up run",
        case.name()
    );
    let mut timings = Vec::new();
    for result in bench::time_solvers(&solvers, &case.scene, repeats) {
        match result {
            Ok(timing) => timings.push(timing),
            Err((name, e)) => println!("{name}: {e}"),
        }
    }
    table(&timings, increments);
}
