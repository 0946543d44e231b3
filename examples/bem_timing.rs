//! Speed against error of the `bem` solver on grids from 32² to 512² (medians of repeated runs).
//!
//! Run in release: `cargo run --release --example bem_timing` (add `quick` to skip 512²; name
//! sections `normal`, `cattaneo`, `path` to run only those; `n=128,256` chooses the grids, e.g.
//! `cargo run --release --example bem_timing -- cattaneo path n=128,256`).
//! Times are the thread's CPU time (the machine is shared), medians of repeated runs.
//!
//! 1. Normal Hertz contact of the paper's spheres at δn = 17 µm: errors of P, p0, c.
//! 2. One Cattaneo partial-slip increment at δn = 17 µm, δt = 0 → 2 µm (Q/μP ≈ 0.63): stick radius
//!    (c √(N_stick/N_contact), `fit::stick`, and the mean of the stick zone's second-moment
//!    semi-axes) against c(1 − Q/μP)^{1/3} with BEM's own c, Q and P, and Q against
//!    Cattaneo–Mindlin; the time of the tangential solve alone and of the whole solve (grid
//!    set-up, normal, tangential).
//! 3. The paper's path (cases/paper-fig7.toml) with 20 substeps a segment (220 increments): the
//!    time and the largest tangential-force error against MDR over the positions.

use cpu::Instant;
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
    println!("| grid | h/c | P err | p0 err | c err | CG its | median CPU |");
    println!("|---|---|---|---|---|---|---|");
    for &n in ladder {
        let bem = Bem::with_grid(n);
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..repeats(n) {
            let start = Instant::now();
            let history = bem.solve(&scene).expect("normal solve");
            times.push(start.elapsed().as_secs_f64());
            last = Some(history);
        }
        let history = last.expect("at least one run");
        let row = &history.steps[0];
        let rel = |v: Option<f64>, r: f64| (v.unwrap_or(f64::NAN) - r) / r;
        println!(
            "| {n}² | {:.4} | {:+.3e} | {:+.3e} | {:+.3e} | {} | {:.2} ms |",
            history.metadata.extra["panel_size_m"].as_f64().unwrap_or(0.0) / c,
            rel(row.normal_force, p),
            rel(row.peak_pressure, p0),
            rel(row.contact_radius, c),
            history.metadata.extra["normal_cg_iterations"],
            1e3 * median(times)
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
    println!("| grid | Q err (vs C–M) | stick radius err | stick semi-axes err | tangential its | median tangential | median whole solve |");
    println!("|---|---|---|---|---|---|---|");
    let c_max = path_scene.max_contact_radius();
    for &n in ladder {
        let bem = Bem::with_grid(n);
        let grid = Grid::covering(n, bem.window * c_max);
        let (mut tangential, mut whole) = (Vec::new(), Vec::new());
        let mut outcome = None;
        for _ in 0..repeats(n) {
            let start = Instant::now();
            let mut state = ContactState::new(&path_scene, grid, bem.tolerances);
            state.advance(17e-6, 0.0).expect("normal");
            let split = Instant::now();
            let cost = state.advance(17e-6, 2e-6).expect("tangential");
            let end = Instant::now();
            tangential.push((end - split).as_secs_f64());
            whole.push((end - start).as_secs_f64());
            outcome = Some((state.snapshot().clone(), cost));
        }
        let (s, cost) = outcome.expect("at least one run");
        let (q, p) = (s.tangential_force(), s.normal_force());
        let expected = s.contact_radius() * (1.0 - q / (scene.friction * p)).cbrt();
        let fitted = s
            .stick_zone()
            .map_or(f64::NAN, |z| 0.5 * (z.semi_axes[0] + z.semi_axes[1]));
        println!(
            "| {n}² | {:+.3e} | {:+.3e} | {:+.3e} | {} | {:.1} ms | {:.1} ms |",
            (q - q_ref) / q_ref,
            (s.stick_radius() - expected) / expected,
            (fitted - expected) / expected,
            cost.tangential_iterations,
            1e3 * median(tangential),
            1e3 * median(whole)
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
    println!("| grid | max Ft err / peak | normal CG its | tangential its | median CPU |");
    println!("|---|---|---|---|---|");
    for &n in ladder {
        let bem = Bem::with_grid(n);
        let runs = if n <= 64 { 5 } else { 3 };
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..runs {
            let start = Instant::now();
            last = Some(bem.solve(&scene).expect("path"));
            times.push(start.elapsed().as_secs_f64());
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
            "| {n}² | {error:.3e} | {} | {} | {:.3} s |",
            history.metadata.extra["normal_cg_iterations"],
            history.metadata.extra["tangential_apg_iterations"],
            median(times)
        );
    }
}

/// Arguments: `quick` (skip 512²), sections `normal`, `cattaneo`, `path` (all when none), and
/// `n=128,256` to choose the grids.
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let chosen: Option<Vec<usize>> = args.iter().find_map(|a| a.strip_prefix("n=")).map(|list| {
        list.split(',')
            .map(|v| v.parse().expect("n=grid,grid,…"))
            .collect()
    });
    let quick = args.iter().any(|a| a == "quick");
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

/// The thread's CPU time, with the interface of `std::time::Instant` (the machine is shared:
/// wall time also counts the waits for a core).
mod cpu {
    #[derive(Clone, Copy)]
    pub struct Instant(f64);
    pub struct Span(f64);
    impl Span {
        pub fn as_secs_f64(&self) -> f64 {
            self.0
        }
    }
    fn thread_seconds() -> f64 {
        let mut now = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut now) };
        now.tv_sec as f64 + now.tv_nsec as f64 * 1e-9
    }
    impl Instant {
        pub fn now() -> Self {
            Instant(thread_seconds())
        }
        pub fn elapsed(&self) -> Span {
            Span(thread_seconds() - self.0)
        }
    }
    impl std::ops::Sub for Instant {
        type Output = Span;
        fn sub(self, other: Instant) -> Span {
            Span(self.0 - other.0)
        }
    }
}
