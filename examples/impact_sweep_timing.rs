//! The speed figure of issue 31: a 17-angle sweep (Chung & Ooi test 4, 5° … 85°) with the exact
//! reference (`mdr`: MDR's 4000 springs in the rigid-body integrator, 2000 steps per Hertz
//! contact duration), timed per variant, wall and CPU, median of `REPEAT` runs after one warm-up.
//!
//! Run: `cargo run --release --example impact_sweep_timing [REPEAT]` (default 5). Figures quoted
//! in docs/impact.md ("Speed"). A measurement, not a test: no time limit is asserted anywhere.

use std::time::Instant;

use spherecontact::bench::process_cpu_seconds;
use spherecontact::impact::case::Variant;
use spherecontact::impact::run::{run_solver, REFERENCE};

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

fn main() {
    let repeat: usize = std::env::args()
        .nth(1)
        .map_or(5, |n| n.parse().expect("REPEAT: a whole number"))
        .max(1);
    let file = std::path::Path::new("cases/impact/chung-ooi-4.toml");
    let case = spherecontact::case::load_impact(file).unwrap_or_else(|e| panic!("{e}"));
    let points = case.points().len();
    println!(
        "{}: {points} sweep points, {} steps per Hertz duration, {} springs; median of {repeat}",
        case.name, case.steps, case.springs
    );
    for variant in [Variant::Elastic, Variant::Prescribed] {
        run_solver(&case, REFERENCE, variant);
        let (mut wall, mut cpu) = (Vec::new(), Vec::new());
        for _ in 0..repeat {
            let (start, cpu_start) = (Instant::now(), process_cpu_seconds());
            let run = run_solver(&case, REFERENCE, variant);
            cpu.push(process_cpu_seconds() - cpu_start);
            wall.push(start.elapsed().as_secs_f64());
            assert!(run.points.iter().all(|(_, r)| r.is_ok()), "a sweep point failed");
        }
        println!(
            "mdr {:<10} {points}-angle sweep: {:.3} s wall, {:.3} s CPU (median; wall min {:.3} s, max {:.3} s)",
            variant.name(),
            median(wall.clone()),
            median(cpu),
            wall.iter().copied().fold(f64::INFINITY, f64::min),
            wall.iter().copied().fold(0.0, f64::max),
        );
    }
}
