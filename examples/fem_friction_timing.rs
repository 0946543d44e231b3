//! The whole paper path (cases/paper-fig7.toml: 1101 steps, normal and tangential) by
//! `fem-axisym` at its default pole size c_max/40, timed side by side with the same solver on the
//! frictionless path (normal only) and with MDR, CPU medians over repeated runs; and Q against
//! the finite-body reference `mdr-domain` and plain MDR at every path position.
//!
//! Run: `cargo run --release --example fem_friction_timing [REPEAT]` (default 7 timed runs each,
//! after a warm-up). Medians are of the running thread's CPU time; the machine is shared, so
//! quote the ratio measured in one run.

use std::path::Path;

use spherecontact::bench::{median, time_solvers};
use spherecontact::case::Case;
use spherecontact::fem::{FemAxisym, MdrDomain};
use spherecontact::solver::{run, Solver};

fn main() {
    let repeat: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(7);
    let case = Case::load(Path::new("cases/paper-fig7.toml")).expect("the paper case");
    let scene = case.scene;
    let mut frictionless = scene.clone();
    frictionless.friction = 0.0;
    let solvers: Vec<Box<dyn Solver>> = vec![Box::new(FemAxisym::default())];
    let mdr: Vec<Box<dyn Solver>> = vec![Box::new(spherecontact::analytic::mdr::Mdr::default())];
    println!(
        "paper path: {} steps, {repeat} timed runs each",
        scene.steps().len()
    );
    for (name, s, solvers) in [
        ("fem-axisym, normal + tangential", &scene, &solvers),
        ("fem-axisym, μ = 0 (normal only)", &frictionless, &solvers),
        ("mdr", &scene, &mdr),
    ] {
        for t in time_solvers(solvers, s, repeat).into_iter().flatten() {
            println!(
                "{name:34} CPU median {:.3} s (min {:.3}, max {:.3}), wall median {:.3} s",
                median(&t.cpu_seconds),
                t.cpu_seconds[0],
                t.cpu_seconds[t.cpu_seconds.len() - 1],
                median(&t.seconds)
            );
        }
    }
    let fem = run(&FemAxisym::default(), &scene).expect("fem-axisym");
    let reference = run(&MdrDomain::default(), &scene).expect("mdr-domain");
    let plain = run(&spherecontact::analytic::mdr::Mdr::default(), &scene).expect("mdr");
    let peak = reference.peak(spherecontact::history::Quantity::TangentialForce);
    println!("position  δn [µm]  δt [µm]  Q fem-axisym  Q mdr-domain  Q mdr [N]  err/peak(mdr-domain)  err/peak(mdr)");
    for ((f, r), m) in fem
        .at_positions()
        .zip(reference.at_positions())
        .zip(plain.at_positions())
    {
        let (q, qr, qm) = (
            f.tangential_force.unwrap_or(0.0),
            r.tangential_force.unwrap_or(0.0),
            m.tangential_force.unwrap_or(0.0),
        );
        println!(
            "P{:<8} {:7.2} {:8.2} {:12.4} {:13.4} {:10.4} {:+20.3e} {:+14.3e}",
            f.position.unwrap_or(0),
            f.delta_n * 1e6,
            f.delta_t * 1e6,
            q,
            qr,
            qm,
            (q - qr) / peak,
            (q - qm) / peak
        );
    }
}
