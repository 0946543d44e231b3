//! Speed against error of the `bem` solver on grids from 32² to 512² (medians of repeated runs).
//!
//! Run in release: `cargo run --release --example bem_timing` (add `quick` to skip 512²; name
//! sections `normal`, `cattaneo`, `path` to run only those; `n=128,256` chooses the grids, e.g.
//! `cargo run --release --example bem_timing -- cattaneo path n=128,256`; `threads=1` runs the
//! FFT products on one thread, [`spherecontact::team`]).
//! Times are medians of repeated runs, each as the process's CPU time (all threads) and the wall
//! time; on a shared machine the CPU time is the steadier, the wall time what a user waits.
//!
//! 1. Normal Hertz contact of the paper's spheres at δn = 17 µm: errors of P, p0, c.
//! 2. One Cattaneo partial-slip increment at δn = 17 µm, δt = 0 → 2 µm (Q/μP ≈ 0.63): stick radius
//!    (c √(N_stick/N_contact), `fit::stick`, and the mean of the stick zone's second-moment
//!    semi-axes) against c(1 − Q/μP)^{1/3} with BEM's own c, Q and P, and Q against
//!    Cattaneo–Mindlin; the time of the tangential solve alone and of the whole solve (grid
//!    set-up, normal, tangential).
//! 3. The paper's path (cases/paper-fig7.toml) with 20 substeps a segment (220 increments): the
//!    time and the largest tangential-force error against MDR over the positions.

use clock::{Clock, Span};
use std::path::Path;

use spherecontact::analytic::cattaneo_mindlin::CattaneoMindlin;
use spherecontact::analytic::mdr::Mdr;
use spherecontact::bem::state::ContactState;
use spherecontact::bem::{grid::Grid, Bem};
use spherecontact::case::Case;
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::solver::Solver;

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// "CPU / wall" of the median of each, in `unit` (1e3: ms) with `digits` decimals.
fn medians(spans: &[Span], unit: f64, digits: usize) -> String {
    let cpu = median(spans.iter().map(|s| s.cpu).collect());
    let wall = median(spans.iter().map(|s| s.wall).collect());
    format!("{:.digits$} / {:.digits$}", unit * cpu, unit * wall)
}

fn case(name: &str) -> Case {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases").join(name);
    Case::load(&file).unwrap_or_else(|e| panic!("{e}"))
}

fn with_path(scene: &Scene, delta_n: &[f64], delta_t: &[f64], substeps: usize) -> Scene {
    let positions = delta_n
        .iter()
        .zip(delta_t)
        .map(|(&n, &t)| Position {
            delta_n: n * 1e-6,
            delta_t: t * 1e-6,
        })
        .collect::<Vec<_>>();
    let segments = positions.len() - 1;
    Scene {
        path: LoadingPath::try_new(positions, vec![substeps; segments]).expect("valid path"),
        domain: Default::default(),
        ..scene.clone()
    }
}

fn repeats(n: usize) -> usize {
    match n {
        0..=64 => 21,
        65..=128 => 11,
        129..=256 => 5,
        _ => 3,
    }
}

fn normal(scene: &Scene, ladder: &[usize]) {
    let scene = with_path(scene, &[17.0], &[0.0], 1);
    let hertz = scene.hertz();
    let (p, c, p0) = (
        hertz.force(17e-6),
        hertz.contact_radius(17e-6),
        hertz.peak_pressure(17e-6),
    );
    println!("\n## Normal Hertz, δn = 17 µm (P = {p:.3} N, c = {c:.5e} m, p0 = {p0:.4e} Pa)");
    println!("| grid | h/c | P err | p0 err | c err | CG its | median CPU / wall [ms] |");
    println!("|---|---|---|---|---|---|---|");
    for &n in ladder {
        let bem = Bem::with_grid(n);
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..repeats(n) {
            let start = Clock::now();
            let history = bem.solve(&scene).expect("normal solve");
            times.push(start.elapsed());
            last = Some(history);
        }
        let history = last.expect("at least one run");
        let row = &history.steps[0];
        let rel = |v: Option<f64>, r: f64| (v.unwrap_or(f64::NAN) - r) / r;
        println!(
            "| {n}² | {:.4} | {:+.3e} | {:+.3e} | {:+.3e} | {} | {} |",
            history.metadata.extra["panel_size_m"].as_f64().unwrap_or(0.0) / c,
            rel(row.normal_force, p),
            rel(row.peak_pressure, p0),
            rel(row.contact_radius, c),
            history.metadata.extra["normal_cg_iterations"],
            medians(&times, 1e3, 2)
        );
    }
}

fn cattaneo(scene: &Scene, ladder: &[usize]) {
    let path_scene = with_path(scene, &[17.0, 17.0], &[0.0, 2.0], 1);
    let reference = CattaneoMindlin.solve(&path_scene).expect("closed form");
    let q_ref = reference.steps[1].tangential_force.unwrap_or(f64::NAN);
    let mu_p = scene.friction * scene.hertz().force(17e-6);
    println!(
        "\n## Cattaneo partial slip, δn = 17 µm, δt = 0 → 2 µm in one increment (Q/μP = {:.3})",
        q_ref / mu_p
    );
    println!("| grid | Q err (vs C–M) | stick radius err | stick semi-axes err | tangential its | median tangential CPU / wall [ms] | median whole solve CPU / wall [ms] |");
    println!("|---|---|---|---|---|---|---|");
    let c_max = path_scene.max_contact_radius();
    for &n in ladder {
        let bem = Bem::with_grid(n);
        let grid = Grid::covering(n, bem.window * c_max);
        let (mut tangential, mut whole) = (Vec::new(), Vec::new());
        let mut outcome = None;
        for _ in 0..repeats(n) {
            let start = Clock::now();
            let mut state = ContactState::new(&path_scene, grid, bem.tolerances);
            state.advance(17e-6, 0.0).expect("normal");
            let split = Clock::now();
            let cost = state.advance(17e-6, 2e-6).expect("tangential");
            let end = Clock::now();
            tangential.push(end - split);
            whole.push(end - start);
            outcome = Some((state.snapshot().clone(), cost));
        }
        let (s, cost) = outcome.expect("at least one run");
        let (q, p) = (s.tangential_force(), s.normal_force());
        let expected = s.contact_radius() * (1.0 - q / (scene.friction * p)).cbrt();
        let fitted = s
            .stick_zone()
            .map_or(f64::NAN, |z| 0.5 * (z.semi_axes[0] + z.semi_axes[1]));
        println!(
            "| {n}² | {:+.3e} | {:+.3e} | {:+.3e} | {} | {} | {} |",
            (q - q_ref) / q_ref,
            (s.stick_radius() - expected) / expected,
            (fitted - expected) / expected,
            cost.tangential_iterations,
            medians(&tangential, 1e3, 1),
            medians(&whole, 1e3, 1)
        );
    }
}

fn paper_path(scene: &Scene, ladder: &[usize]) {
    let scene = Scene {
        path: scene.path.clone(),
        domain: Default::default(),
        ..scene.clone()
    };
    let mdr = Mdr::default().solve(&scene).expect("mdr");
    let peak = mdr
        .at_positions()
        .filter_map(|r| r.tangential_force)
        .fold(0.0, |m: f64, q| m.max(q.abs()));
    println!(
        "\n## Paper path, {} increments: Ft against MDR at the positions (relative to peak |Ft| = {peak:.3} N)",
        scene.steps().len() - 1
    );
    println!("| grid | max Ft err / peak | normal CG its | tangential its | median CPU / wall [s] |");
    println!("|---|---|---|---|---|");
    for &n in ladder {
        let bem = Bem::with_grid(n);
        let runs = if n <= 64 { 5 } else { 3 };
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..runs {
            let start = Clock::now();
            last = Some(bem.solve(&scene).expect("path"));
            times.push(start.elapsed());
        }
        let history = last.expect("at least one run");
        let error = history
            .at_positions()
            .zip(mdr.at_positions())
            .map(|(b, m)| {
                (b.tangential_force.unwrap_or(f64::NAN) - m.tangential_force.unwrap_or(f64::NAN)).abs()
            })
            .fold(0.0, f64::max)
            / peak;
        println!(
            "| {n}² | {error:.3e} | {} | {} | {} |",
            history.metadata.extra["normal_cg_iterations"],
            history.metadata.extra["tangential_apg_iterations"],
            medians(&times, 1.0, 3)
        );
    }
}

/// Arguments: `quick` (skip 512²), sections `normal`, `cattaneo`, `path` (all when none),
/// `n=128,256` to choose the grids, and `threads=1` (or 2) for the team of the FFT products.
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let chosen: Option<Vec<usize>> = args.iter().find_map(|a| a.strip_prefix("n=")).map(|list| {
        list.split(',')
            .map(|v| v.parse().expect("n=grid,grid,…"))
            .collect()
    });
    let quick = args.iter().any(|a| a == "quick");
    if let Some(threads) = args.iter().find_map(|a| a.strip_prefix("threads=")) {
        spherecontact::team::set_threads(threads.parse().expect("threads=count"));
    }
    let ladder: Vec<usize> = chosen.clone().unwrap_or_else(|| {
        if quick {
            vec![32, 64, 128, 256]
        } else {
            vec![32, 64, 128, 256, 512]
        }
    });
    let sections = ["normal", "cattaneo", "path"];
    let run = |s: &str| !args.iter().any(|a| sections.contains(&a.as_str())) || args.iter().any(|a| a == s);
    let hertz = case("hertz-normal.toml").scene;
    if run("normal") {
        normal(&hertz, &ladder);
    }
    if run("cattaneo") {
        cattaneo(&hertz, &ladder);
    }
    if run("path") {
        let mut paper = case("paper-fig7.toml").scene;
        paper.path = LoadingPath::try_new(paper.path.positions().to_vec(), vec![20; 11]).expect("valid");
        let ladder = if chosen.is_some() {
            &ladder[..]
        } else {
            &ladder[..ladder.len().min(3)]
        };
        paper_path(&paper, ladder);
    }
}

/// The process's CPU time (every thread) and the wall time, read together.
mod clock {
    /// A reading of both clocks.
    #[derive(Clone, Copy)]
    pub struct Clock {
        cpu: f64,
        wall: std::time::Instant,
    }

    /// The time between two readings [s].
    #[derive(Clone, Copy)]
    pub struct Span {
        pub cpu: f64,
        pub wall: f64,
    }

    impl Clock {
        pub fn now() -> Self {
            Clock {
                cpu: spherecontact::bench::process_cpu_seconds(),
                wall: std::time::Instant::now(),
            }
        }

        pub fn elapsed(&self) -> Span {
            Clock::now() - *self
        }
    }

    impl std::ops::Sub for Clock {
        type Output = Span;
        fn sub(self, other: Clock) -> Span {
            Span {
                cpu: self.cpu - other.cpu,
                wall: (self.wall - other.wall).as_secs_f64(),
            }
        }
    }
}
