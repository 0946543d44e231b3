//! Wall time of the incremental DEM laws (and of the MDR reference) along the paper's path at
//! 100 substeps per segment (1100 increments): the median of 21 solves each, printed, never
//! asserted.
//!
//! Run with `cargo run --release --example dem_timing`.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use spherecontact::case::Case;
use spherecontact::registry;

/// Solves per solver; the median of an odd count is one measured solve.
const RUNS: usize = 21;

/// The solvers timed: the DEM laws, then the exact reference for scale.
const SOLVERS: [&str; 5] = [
    "hertz-mindlin-spring",
    "thornton",
    "md-incremental",
    "walton-braun",
    "mdr",
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/paper-fig7.toml");
    let scene = Case::load(&file)?.scene;
    let increments = scene.steps().len() - 1;
    println!("paper-fig7: {increments} increments; median of {RUNS} solves (release build expected)");
    for name in SOLVERS {
        let solver = registry::by_name(name).ok_or_else(|| format!("{name} is not registered"))?;
        let mut times: Vec<f64> = (0..RUNS)
            .map(|_| {
                let start = Instant::now();
                let history = solver.solve(black_box(&scene));
                black_box(history).map(|_| start.elapsed().as_secs_f64())
            })
            .collect::<Result<_, _>>()?;
        times.sort_by(f64::total_cmp);
        let median = times[RUNS / 2];
        println!(
            "{name:<22} median {:>10.1} µs   ({:.1} ns per increment; min {:.1} µs, max {:.1} µs)",
            median * 1e6,
            median * 1e9 / increments as f64,
            times[0] * 1e6,
            times[RUNS - 1] * 1e6
        );
    }
    Ok(())
}
