//! Speed against error of the external decks: the mesh ladder h = c/10, c/20, c/40, c/80 at the
//! paper's δn = 17 µm through each deck, wall time split into meshing, solving and reading back
//! (medians of REPEATS runs, default 3), errors against Hertz, and the in-crate `fem-axisym`
//! side by side at its default resolution when this build has it.
//!
//! Run: `cargo run --release --example external_timing [REPEATS]` (needs scripts/setup.sh).

use std::path::Path;

use spherecontact::case::Case;
use spherecontact::external::axisym::AxisymSolver;
use spherecontact::external::deck::Deck;
use spherecontact::external::fenicsx::Fenicsx;
use spherecontact::external::freefem::FreeFem;
use spherecontact::fem::mesh::geo::MeshFiles;
use spherecontact::history::History;
use spherecontact::path::{LoadingPath, Position};
use spherecontact::registry;
use spherecontact::scene::Scene;
use spherecontact::solver::{self, Solver};

/// Elements per contact radius at the pole, coarse to fine.
const LADDER: [f64; 4] = [10.0, 20.0, 40.0, 80.0];

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn seconds(history: &History, key: &str) -> f64 {
    history
        .metadata
        .extra
        .get(key)
        .and_then(|v| v.as_f64())
        .unwrap_or(f64::NAN)
}

/// A duration column: "—" where the solver does not split its time that way (never "NaN").
fn column(seconds: f64) -> String {
    if seconds.is_finite() {
        format!("{seconds:.2}")
    } else {
        "—".to_owned()
    }
}

fn scene() -> Scene {
    let mut scene = Case::load(Path::new("cases/hertz-normal.toml"))
        .expect("run from the crate root")
        .scene;
    let position = |delta_n: f64| Position {
        delta_n,
        delta_t: 0.0,
    };
    scene.path = LoadingPath::try_new(vec![position(0.0), position(17e-6)], vec![17]).expect("a valid path");
    scene
}

fn row(name: &str, resolution: &str, runs: &[History], scene: &Scene) {
    let hertz = scene.hertz();
    let dn = 17e-6;
    let last = runs.last().expect("one run at least");
    let at = last.at_position(1).expect("position 1");
    let err = |v: Option<f64>, r: f64| {
        v.map_or_else(|| "—".to_owned(), |v| format!("{:+.3}", (v / r - 1.0) * 100.0))
    };
    let med = |key: &str| median(runs.iter().map(|h| seconds(h, key)).collect());
    let wall = median(runs.iter().map(|h| h.metadata.wall_time_s).collect());
    println!(
        "{name:<15} {resolution:<30} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8.2}",
        err(at.normal_force, hertz.force(dn)),
        err(at.contact_radius, hertz.contact_radius(dn)),
        err(at.peak_pressure, hertz.peak_pressure(dn)),
        column(med("meshing_s")),
        column(med("solving_s")),
        column(med("reading_back_s")),
        wall
    );
}

fn main() {
    let repeats: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(3);
    let scene = scene();
    let c = scene.max_contact_radius();
    println!(
        "δn = 17 µm, c = {:.4} mm; medians of {repeats} runs; errors vs Hertz in %",
        c * 1e3
    );
    println!(
        "{:<15} {:<30} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8}",
        "solver", "resolution", "P", "c", "p0", "mesh s", "solve s", "read s", "wall s"
    );
    let decks: [&dyn Fn(f64) -> Box<dyn Solver>; 2] = [&|h| boxed(FreeFem, h), &|h| boxed(Fenicsx, h)];
    for make in decks {
        for n in LADDER {
            let solver = make(c / n);
            let runs: Result<Vec<History>, _> = (0..repeats)
                .map(|_| solver::run(solver.as_ref(), &scene))
                .collect();
            match runs {
                Ok(runs) => row(solver.name(), &runs[0].metadata.resolution, &runs, &scene),
                Err(e) => println!("{:<15} c/{n}: {e}", solver.name()),
            }
        }
    }
    // The in-crate FEM through its own ladder (c/5 … c/80), side by side in the same run.
    for fem in registry::by_name("fem-axisym").map_or_else(Vec::new, |s| s.resolution_ladder(&scene)) {
        let runs: Result<Vec<History>, _> = (0..repeats).map(|_| solver::run(fem.as_ref(), &scene)).collect();
        match runs {
            Ok(runs) => row("fem-axisym", &runs[0].metadata.resolution, &runs, &scene),
            Err(e) => println!("fem-axisym: {e}"),
        }
    }
}

fn boxed<D: Deck<Mesh = MeshFiles> + 'static>(deck: D, h: f64) -> Box<dyn Solver> {
    let mut solver = AxisymSolver::new(deck);
    solver.options.resolution = Some(h);
    Box::new(solver)
}
