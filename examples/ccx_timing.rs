//! ccx-axisym's path positions against fem-axisym's, side by side in one run on the same mesh:
//! `cases/ccx-axisym.toml` (the paper's spheres to δn = 17 and 25 µm, gmsh's mesh at c_max/20,
//! face-to-face contact), each solver REPEATS times (default 3), interleaved; medians of the wall
//! time, of the CPU time (this process's for fem-axisym, ccx's as a child for ccx-axisym), and of
//! the time a path position takes, with P at the last position beside mdr-domain's.
//!
//! Run: `cargo run --release --example ccx_timing [REPEATS]` (needs gmsh and ccx: scripts/setup.sh).

use std::path::Path;
use std::time::Instant;

use spherecontact::bench::{median, process_cpu_seconds};
use spherecontact::case::Case;
use spherecontact::external::process::child_cpu_seconds;
use spherecontact::solver;

fn main() {
    let repeats: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(3)
        .max(1);
    let case = Case::load(Path::new("cases/ccx-axisym.toml")).expect("run from the crate root");
    let positions = case.scene.path.positions().len();
    let reference = solver::run(case.solver("mdr-domain").expect("built in").as_ref(), &case.scene)
        .expect("mdr-domain solves the case");
    let last = positions - 1;
    let p_ref = reference
        .at_position(last)
        .and_then(|r| r.normal_force)
        .unwrap_or(f64::NAN);
    println!(
        "case {} ({} positions, {} steps), {repeats} runs each; P at position {last} against mdr-domain {p_ref:.3} N",
        case.name(),
        positions,
        case.scene.steps().len()
    );
    println!(
        "{:<12} {:>9} {:>9} {:>14} {:>12} {:>10}",
        "solver", "wall [s]", "CPU [s]", "per position", "P [N]", "error"
    );
    let names = ["fem-axisym", "ccx-axisym"];
    let mut samples = vec![(Vec::new(), Vec::new(), f64::NAN); names.len()];
    for _ in 0..repeats {
        for (name, sample) in names.iter().zip(&mut samples) {
            let solver = case.solver(name).expect("built in");
            let (cpu, child) = (process_cpu_seconds(), child_cpu_seconds());
            let start = Instant::now();
            match solver::run(solver.as_ref(), &case.scene) {
                Ok(history) => {
                    sample.0.push(start.elapsed().as_secs_f64());
                    sample
                        .1
                        .push(process_cpu_seconds() - cpu + child_cpu_seconds() - child);
                    sample.2 = history
                        .at_position(last)
                        .and_then(|r| r.normal_force)
                        .unwrap_or(f64::NAN);
                }
                Err(e) => {
                    println!("{name}: {e}");
                    return;
                }
            }
        }
    }
    for (name, (mut wall, mut cpu, p)) in names.iter().zip(samples) {
        wall.sort_by(f64::total_cmp);
        cpu.sort_by(f64::total_cmp);
        let (w, c) = (median(&wall), median(&cpu));
        println!(
            "{name:<12} {w:>9.2} {c:>9.2} {:>14.2} {p:>12.3} {:>+10.2e}",
            w / positions as f64,
            p / p_ref - 1.0
        );
    }
}
