//! The whole paper path (cases/paper-fig7.toml: 1101 steps, normal and tangential) by
//! `fem-axisym` at its default pole size c_max/40, timed side by side with the same solver on the
//! frictionless path (normal only), on the external decks' gmsh mesh (`[domain] mesher = "gmsh"`:
//! gmsh's CPU included) and with MDR, CPU medians over repeated runs; and Q against the
//! finite-body reference `mdr-domain` and plain MDR at every path position, on both meshes.
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
    let mut on_gmsh = scene.clone();
    on_gmsh.domain.mesher = spherecontact::domain::Mesher::Gmsh;
    let solvers: Vec<Box<dyn Solver>> = vec![Box::new(FemAxisym::default())];
    let mdr: Vec<Box<dyn Solver>> = vec![Box::new(spherecontact::analytic::mdr::Mdr::default())];
    println!(
        "paper path: {} steps, {repeat} timed runs each",
        scene.steps().len()
    );
    for (name, s, solvers) in [
        ("fem-axisym, normal + tangential", &scene, &solvers),
        ("fem-axisym, μ = 0 (normal only)", &frictionless, &solvers),
        ("fem-axisym, gmsh mesh (with gmsh)", &on_gmsh, &solvers),
        ("mdr", &scene, &mdr),
    ] {
        for t in time_solvers(solvers, s, repeat) {
            let Ok(t) = t else {
                println!("{name:34} not run: {:?}", t.err());
                continue;
            };
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
    let fem_gmsh = run(&FemAxisym::default(), &on_gmsh).ok();
    let reference = run(&MdrDomain::default(), &scene).expect("mdr-domain");
    let plain = run(&spherecontact::analytic::mdr::Mdr::default(), &scene).expect("mdr");
    let peak = reference.peak(spherecontact::history::Quantity::TangentialForce);
    let worst = |h: &spherecontact::history::History, r: &spherecontact::history::History| {
        h.steps
            .iter()
            .zip(&r.steps)
            .map(|(a, b)| {
                (a.tangential_force.unwrap_or(0.0) - b.tangential_force.unwrap_or(0.0)).abs() / peak
            })
            .fold(0.0, f64::max)
    };
    println!(
        "worst over every step, of the peak |Q| {peak:.4} N: fem-axisym − mdr-domain {:.3e}, raw − mdr {:.3e}; \
         on the gmsh mesh − mdr-domain {}",
        worst(&fem, &reference),
        worst(&fem, &plain),
        fem_gmsh
            .as_ref()
            .map_or_else(|| "—".to_owned(), |g| format!("{:.3e}", worst(g, &reference)))
    );
    println!(
        "position  δn [µm]  δt [µm]  Q fem-axisym  Q fem (gmsh)  Q mdr-domain  Q mdr [N]  err/peak(mdr-domain)  \
         err/peak(mdr)  gmsh err/peak(mdr-domain)"
    );
    let gmsh_rows: Vec<Option<f64>> = match &fem_gmsh {
        Some(g) => g.at_positions().map(|r| r.tangential_force).collect(),
        None => vec![None; fem.at_positions().count()],
    };
    for (((f, r), m), g) in fem
        .at_positions()
        .zip(reference.at_positions())
        .zip(plain.at_positions())
        .zip(gmsh_rows)
    {
        let (q, qr, qm) = (
            f.tangential_force.unwrap_or(0.0),
            r.tangential_force.unwrap_or(0.0),
            m.tangential_force.unwrap_or(0.0),
        );
        println!(
            "P{:<8} {:7.2} {:8.2} {:12.4} {:>13} {:13.4} {:10.4} {:+20.3e} {:+14.3e} {:>26}",
            f.position.unwrap_or(0),
            f.delta_n * 1e6,
            f.delta_t * 1e6,
            q,
            g.map_or_else(|| "—".to_owned(), |g| format!("{g:.4}")),
            qr,
            qm,
            (q - qr) / peak,
            (q - qm) / peak,
            g.map_or_else(|| "—".to_owned(), |g| format!("{:+.3e}", (g - qr) / peak)),
        );
    }
}
