//! Per-increment time of the CalculiX decks beside the in-crate FEM on the same meshes, side by
//! side in one run (issue 28, "Speed"):
//!
//! - **3D**: `cases/ccx-3d.toml` (the paper's spheres pressed to δn = 17 µm, then shifted to
//!   δt = 3 µm, one increment each), `ccx-3d`, `fem-3d` and `fenicsx-3d` (1 rank) all at the
//!   pole size c_max/N (default N = 2, the case's; gmsh meshes the same `.geo` at the same size,
//!   so the three solve on the same nodes);
//! - **axisymmetric**: `cases/ccx-axisym.toml` (δn = 17 and 25 µm, gmsh's meridian mesh at
//!   c_max/20), `ccx-axisym` against `fem-axisym` on the same mesh.
//!
//! Each solver runs once to warm up, then REPEATS times (default 3), interleaved round by round;
//! the medians of: the whole run's wall time, its CPU time (this process's and the external
//! programs' it ran: ccx, gmsh, python3), the path's wall time (what each solver clocks as its
//! path: ccx's whole process for the CalculiX decks, as CalculiX has no clock of its own, so
//! reading the deck and ordering the matrix are in it; the dolfinx deck's own path clock;
//! fem-3d's and fem-axisym's contact walk after assembly, factorisation and condensation), and
//! per increment (3D: computed steps after the unloaded first; axisymmetric: path positions),
//! each with its ratio to the in-crate solver's. The machine may be shared: compare the rows
//! of one run, and the CPU columns rather than the wall ones.
//!
//! Run: `cargo run --release --example ccx_increment_timing [REPEATS] [N]` (needs gmsh, ccx and
//! FEniCSx: scripts/setup.sh).

use std::path::Path;
use std::time::Instant;

use spherecontact::bench::{median, process_cpu_seconds, significant};
use spherecontact::case::Case;
use spherecontact::history::History;
use spherecontact::reap::child_cpu_seconds;
use spherecontact::scene::Scene;
use spherecontact::solver::{self, Solver};

/// The metadata keys of a run's path time, in order of preference: the dolfinx decks' own path
/// clock, the CalculiX decks' ccx process, the in-crate solvers' contact walk.
const PATH_KEYS: [&str; 3] = ["deck_path_s", "solving_s", "contact_s"];

/// The path's wall time of a run [s], NaN if the solver clocks none.
fn path_seconds(history: &History) -> f64 {
    PATH_KEYS
        .iter()
        .find_map(|key| {
            history
                .metadata
                .extra
                .get(*key)
                .and_then(serde_json::Value::as_f64)
        })
        .unwrap_or(f64::NAN)
}

/// One timed run: (wall, CPU, path) seconds.
type Sample = [f64; 3];

/// Runs `solvers` on `scene`: a warm-up, then `repeats` rounds; the samples of each (empty for a
/// solver that failed, whose error is printed).
fn time(solvers: &[(String, Box<dyn Solver>)], scene: &Scene, repeats: usize) -> Vec<Vec<Sample>> {
    let mut samples = vec![Vec::new(); solvers.len()];
    let mut failed = vec![false; solvers.len()];
    for round in 0..=repeats {
        for (k, (name, solver)) in solvers.iter().enumerate() {
            if failed[k] {
                continue;
            }
            let (cpu, child, start) = (process_cpu_seconds(), child_cpu_seconds(), Instant::now());
            match solver::run(solver.as_ref(), scene) {
                Ok(history) if round > 0 => samples[k].push([
                    start.elapsed().as_secs_f64(),
                    process_cpu_seconds() - cpu + child_cpu_seconds() - child,
                    path_seconds(&history),
                ]),
                Ok(_) => {}
                Err(e) => {
                    println!("{name}: {e}");
                    failed[k] = true;
                }
            }
        }
    }
    samples
}

/// The median of one column of `samples`.
fn column(samples: &[Sample], k: usize) -> f64 {
    let mut values: Vec<f64> = samples.iter().map(|s| s[k]).collect();
    values.sort_by(f64::total_cmp);
    median(&values)
}

/// Times `solvers` (the last is the in-crate reference of the ratios) and prints the table.
fn table(
    title: &str,
    solvers: &[(String, Box<dyn Solver>)],
    scene: &Scene,
    increments: usize,
    repeats: usize,
) {
    println!("\n{title}: {increments} increments; medians of {repeats} runs after a warm-up, interleaved");
    println!(
        "{:<12} {:>9} {:>9} {:>9} {:>14} {:>14} {:>9} {:>9}",
        "solver", "wall s", "CPU s", "path s", "ms/increment", "CPU ms/incr.", "× path", "× CPU"
    );
    let samples = time(solvers, scene, repeats);
    let Some(reference) = samples.last().filter(|s| !s.is_empty()) else {
        println!("(the in-crate solver failed: no ratios)");
        return;
    };
    let (reference_path, reference_cpu) = (column(reference, 2), column(reference, 1));
    for ((name, _), runs) in solvers.iter().zip(&samples) {
        if runs.is_empty() {
            continue;
        }
        let [wall, cpu, path] = [0, 1, 2].map(|k| column(runs, k));
        let per = |s: f64| significant(s / increments as f64 * 1e3);
        println!(
            "{name:<12} {:>9} {:>9} {:>9} {:>14} {:>14} {:>9} {:>9}",
            significant(wall),
            significant(cpu),
            significant(path),
            per(path),
            per(cpu),
            significant(path / reference_path),
            significant(cpu / reference_cpu),
        );
    }
}

/// The solvers called `names` of `case`, at the pole size `resolution` when given (over the
/// case's `[resolution]`).
fn solvers(case: &mut Case, names: &[&str], resolution: Option<&str>) -> Vec<(String, Box<dyn Solver>)> {
    names
        .iter()
        .map(|name| {
            if let Some(value) = resolution {
                case.resolution.insert(name.to_string(), value.to_owned());
            }
            (name.to_string(), case.solver(name).expect("built in"))
        })
        .collect()
}

fn main() {
    let mut args = std::env::args().skip(1);
    let repeats: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(3).max(1);
    let n: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(2);
    let load = |file: &str| Case::load(Path::new(file)).expect("run from the crate root");
    let mut solid = load("cases/ccx-3d.toml");
    let size = format!("c/{n}");
    table(
        &format!("{} (3D, pole size c_max/{n})", solid.name()),
        &solvers(&mut solid, &["ccx-3d", "fenicsx-3d", "fem-3d"], Some(&size)),
        &solid.scene,
        solid.scene.steps().len() - 1,
        repeats,
    );
    let mut axisym = load("cases/ccx-axisym.toml");
    table(
        &format!("{} (axisymmetric, the case's mesh)", axisym.name()),
        &solvers(&mut axisym, &["ccx-axisym", "fem-axisym"], None),
        &axisym.scene,
        axisym.scene.path.positions().len() - 1,
        repeats,
    );
}
