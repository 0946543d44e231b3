//! Speed of the dolfinx 3D deck `fenicsx-3d` on 1 and 2 MPI ranks, side by side with the in-crate
//! `fem-3d` on the same mesh (both mesh the case's body with `external::solid_geo` at the same
//! pole size, default c_max/5; gmsh is deterministic, so the meshes are the same), in one run:
//! one warm-up run each, then REPEATS timed runs (default 3), interleaved; medians of the wall
//! time of the set-up (mesh, assembly, factorisation, condensation) and of the path, the path's
//! time per increment, and the largest difference of P and Q from fem-3d (relative to the peaks).
//! Times print to three significant figures: fem-3d's whole path (its `contact_s`, the walk with
//! every contact solve) takes tens of milliseconds, which a fixed `{:.1}` s column showed as 0.0.
//! The machine may be shared: compare the rows of one run.
//!
//! Run: `cargo run --release --example deck3d_timing [CASE] [REPEATS] [N]` (needs
//! scripts/setup.sh; default case: cases-heavy/paper-fig7-3d.toml, the paper path up to position
//! 5; N: the pole size c_max/N of both meshes, default 5, the deck's default).

use std::path::Path;
use std::time::Instant;

use spherecontact::bench::{median, significant, worst_error};
use spherecontact::case::Case;
use spherecontact::external::fenicsx3d::{Solid3dDeck, DEFAULT_POLE_FRACTION};
use spherecontact::fem::solid3d::solver::FemSolid3d;
use spherecontact::history::{History, Quantity};
use spherecontact::solver::{self, Solver};

/// A number from the metadata [s], or NaN when the solver does not report it.
fn extra(history: &History, key: &str) -> f64 {
    history
        .metadata
        .extra
        .get(key)
        .and_then(serde_json::Value::as_f64)
        .unwrap_or(f64::NAN)
}

/// (set-up, path) wall seconds of a run, and the path's CPU seconds: the deck's own clocks (CPU
/// of rank 0), or fem-3d's phases (its path's CPU is not recorded: NaN).
fn phases(history: &History, wall_s: f64) -> (f64, f64, f64) {
    let deck_path = extra(history, "deck_path_wall");
    if deck_path.is_finite() {
        return (wall_s - deck_path, deck_path, extra(history, "deck_path"));
    }
    let contact = extra(history, "contact_s");
    (wall_s - contact, contact, f64::NAN)
}

/// The row of fem-3d, the reference of the P and Q columns.
const FEM_ROW: usize = 2;

fn main() {
    let mut args = std::env::args().skip(1);
    let case = args
        .next()
        .unwrap_or_else(|| "cases-heavy/paper-fig7-3d.toml".into());
    let repeats: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(3);
    let scene = Case::load(Path::new(&case))
        .expect("a valid case, run from the crate root")
        .scene;
    let fraction = args
        .next()
        .and_then(|a| a.parse::<f64>().ok())
        .filter(|n| *n >= 1.0)
        .map_or(DEFAULT_POLE_FRACTION, |n| 1.0 / n);
    let h = fraction * scene.max_contact_radius();
    let deck = |ranks: u32| {
        let mut deck = Solid3dDeck::new(ranks);
        deck.options.resolution = Some(h);
        Box::new(deck)
    };
    let solvers: Vec<(String, Box<dyn Solver>)> = vec![
        ("fenicsx-3d, 1 rank".into(), deck(1)),
        ("fenicsx-3d, 2 ranks".into(), deck(2)),
        ("fem-3d".into(), Box::new(FemSolid3d::with_pole_size(h))),
    ];
    let increments = scene.steps().len() - 1;
    println!(
        "{case}: {increments} increments, pole size {:.1} µm (c_max/{:.0}); medians of {repeats} runs \
         after a warm-up, interleaved; the machine may be shared",
        h * 1e6,
        1.0 / fraction
    );
    let mut runs: Vec<Vec<(f64, f64, f64)>> = vec![Vec::new(); solvers.len()];
    let mut histories: Vec<Option<History>> = vec![None; solvers.len()];
    for round in 0..=repeats {
        for (k, (name, solver)) in solvers.iter().enumerate() {
            let start = Instant::now();
            match solver::run(solver.as_ref(), &scene) {
                Ok(history) => {
                    if round > 0 {
                        runs[k].push(phases(&history, start.elapsed().as_secs_f64()));
                    }
                    histories[k] = Some(history);
                }
                Err(e) => println!("{name}: {e}"),
            }
        }
    }
    let fem = histories[FEM_ROW].clone();
    println!(
        "{:<20} {:>9} {:>8} {:>14} {:>18} {:>8} {:>8}",
        "solver", "set-up s", "path s", "ms/increment", "CPU ms/increment", "ΔP/peak", "ΔQ/peak"
    );
    for (k, (name, _)) in solvers.iter().enumerate() {
        let (Some(history), false) = (&histories[k], runs[k].is_empty()) else {
            continue;
        };
        let sorted_median = |part: fn(&(f64, f64, f64)) -> f64| {
            let mut values: Vec<f64> = runs[k].iter().map(part).collect();
            values.sort_by(f64::total_cmp);
            median(&values)
        };
        let (setup, path, cpu) = (
            sorted_median(|r| r.0),
            sorted_median(|r| r.1),
            sorted_median(|r| r.2),
        );
        let per_increment = |s: f64| significant(s / increments as f64 * 1e3);
        // fem-3d against itself: nothing to show.
        let against = |q: Quantity| {
            fem.as_ref()
                .filter(|_| k != FEM_ROW)
                .and_then(|f| worst_error(history, f, q, true))
                .map_or_else(|| "—".to_owned(), |e| format!("{e:.1e}"))
        };
        println!(
            "{name:<20} {:>9} {:>8} {:>14} {:>18} {:>8} {:>8}",
            significant(setup),
            significant(path),
            per_increment(path),
            per_increment(cpu),
            against(Quantity::NormalForce),
            against(Quantity::TangentialForce),
        );
    }
}
