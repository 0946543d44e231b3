//! Speed against error of `fem-axisym` on the paper's spheres (R 0.1 m, E 70 GPa, ν 0.3).
//!
//! Run: `cargo run --release --example fem_timing`. For each pole element size from 100 µm to
//! 10 µm: DOFs, the errors of P, p0 and c at δn = 17 µm against Hertz, and medians of the wall
//! time of one load step (mesh, assembly, factorisation, condensation, contact) and of the whole
//! 25-step Hertz curve (0 → 25 µm, the same factorisation, contact re-solved per step). Then the
//! Cholesky ordering (AMD against reverse Cuthill–McKee) and the paper's 1100-step path.

use std::time::Instant;

use spherecontact::case::Case;
use spherecontact::fem::factor::Ordering;
use spherecontact::fem::FemAxisym;
use spherecontact::history::History;
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::solver::run;

fn scene(positions_um: &[f64], substeps: Vec<usize>) -> Scene {
    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.3,
        },
    };
    let positions = positions_um
        .iter()
        .map(|&d| Position {
            delta_n: d * 1e-6,
            delta_t: 0.0,
        })
        .collect();
    Scene {
        name: "timing".into(),
        pair: ContactPair {
            body1: body,
            body2: body,
        },
        friction: 0.2,
        path: LoadingPath::try_new(positions, substeps).unwrap(),
        domain: Default::default(),
        fields: Default::default(),
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median wall time of `runs` solves, and the last history.
fn timed(solver: &FemAxisym, scene: &Scene, runs: usize) -> (f64, History) {
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let t = Instant::now();
        let h = run(solver, scene).unwrap();
        times.push(t.elapsed().as_secs_f64());
        last = Some(h);
    }
    (median(times), last.unwrap())
}

fn extra(h: &History, key: &str) -> f64 {
    h.metadata.extra[key].as_f64().unwrap()
}

fn main() {
    let one_step = scene(&[0.0, 17.0], vec![1]);
    let curve = scene(&[0.0, 25.0], vec![25]);
    let hertz = one_step.hertz();
    let d = 17e-6;
    println!("paper spheres, δn = 17 µm (one sphere on a rigid plane at δn/2); errors against Hertz");
    println!("| pole size | DOFs | P err | p0 err | c err | factor | condense | one step (median) | 25-step curve (median) | per step |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for h_um in [100.0, 50.0, 25.0, 20.0, 15.0, 10.0] {
        let solver = FemAxisym::with_pole_size(h_um * 1e-6);
        let runs = if h_um >= 20.0 { 7 } else { 3 };
        let (t1, h1) = timed(&solver, &one_step, runs);
        let (tc, hc) = timed(&solver, &curve, runs);
        let row = h1.at_position(1).unwrap();
        let err = |v: Option<f64>, r: f64| format!("{:+.3} %", 100.0 * (v.unwrap() / r - 1.0));
        println!(
            "| {h_um} µm | {} | {} | {} | {} | {:.3} s | {:.3} s | {:.3} s | {:.3} s | {:.2} ms |",
            extra(&h1, "dofs"),
            err(row.normal_force, hertz.force(d)),
            err(row.peak_pressure, hertz.peak_pressure(d)),
            err(row.contact_radius, hertz.contact_radius(d)),
            extra(&h1, "factor_s"),
            extra(&h1, "condense_s"),
            t1,
            tc,
            1e3 * extra(&hc, "contact_s") / 26.0,
        );
    }
    println!("\nCholesky ordering (factor time, entries of L):");
    for h_um in [25.0, 10.0] {
        for ordering in [Ordering::Amd, Ordering::ReverseCuthillMcKee] {
            let solver = FemAxisym {
                ordering: Some(ordering),
                ..FemAxisym::with_pole_size(h_um * 1e-6)
            };
            let times: Vec<f64> = (0..3)
                .map(|_| extra(&run(&solver, &one_step).unwrap(), "factor_s"))
                .collect();
            let h = run(&solver, &one_step).unwrap();
            println!(
                "  {h_um} µm {ordering:?}: {:.3} s, {} entries",
                median(times),
                extra(&h, "factor_entries")
            );
        }
    }
    match Case::load(std::path::Path::new("cases/paper-fig7.toml")) {
        Ok(case) => {
            let solver = FemAxisym::default();
            let (t, h) = timed(&solver, &case.scene, 3);
            println!(
                "\npaper-fig7 path ({} steps), default pole size {:.1} µm, {} DOFs: {:.3} s median, contact {:.3} s, {} semi-smooth Newton iterations",
                h.steps.len(),
                1e6 * extra(&h, "pole_size_m"),
                extra(&h, "dofs"),
                t,
                extra(&h, "contact_s"),
                extra(&h, "iterations_total")
            );
        }
        Err(e) => println!("paper-fig7: {e}"),
    }
}
