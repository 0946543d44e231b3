//! The exact reference's convergence in the time step and the spring count, per shipped impact
//! case: for each quantity, the largest change over the sweep when the steps per contact double
//! (and when the springs double), in the elastic variant and the prescribed one.
//!
//! Run: `cargo run --release --example impact_convergence [STEPS] [SPRINGS]` (defaults: the
//! cases' own, 2000 and 4000). Figures quoted in docs/impact.md.

use spherecontact::impact::case::{ImpactCase, Quantity, Variant};
use spherecontact::impact::run::{run_solver, REFERENCE};

fn largest_changes(coarse: &ImpactCase, fine: &ImpactCase, variant: Variant) -> Vec<(Quantity, f64, f64)> {
    let (a, b) = (
        run_solver(coarse, REFERENCE, variant),
        run_solver(fine, REFERENCE, variant),
    );
    Quantity::ALL
        .iter()
        .map(|&q| {
            let mut worst = (0.0_f64, f64::NAN);
            for ((at, x), (_, y)) in a.points.iter().zip(&b.points) {
                let (Ok(x), Ok(y)) = (x, y) else { continue };
                if let (Some(x), Some(y)) = (x.get(q), y.get(q)) {
                    // Relative for dimensional quantities, absolute for ratios and angles.
                    let change = match q {
                        Quantity::ContactDuration
                        | Quantity::MaxNormalForce
                        | Quantity::MaxOverlap
                        | Quantity::ReboundAngularVelocity => (x - y).abs() / y.abs().max(f64::MIN_POSITIVE),
                        _ => (x - y).abs(),
                    };
                    if change > worst.0 {
                        worst = (change, at.unwrap_or(f64::NAN));
                    }
                }
            }
            (q, worst.0, worst.1)
        })
        .collect()
}

fn main() {
    let args: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    for n in 1..=8 {
        let file = std::path::PathBuf::from(format!("cases/impact/chung-ooi-{n}.toml"));
        let mut case = spherecontact::case::load_impact(&file).unwrap_or_else(|e| panic!("{e}"));
        if let Some(&steps) = args.first() {
            case.steps = steps;
        }
        if let Some(&springs) = args.get(1) {
            case.springs = springs;
        }
        let mut halved = case.clone();
        halved.steps *= 2;
        let mut finer = case.clone();
        finer.springs *= 2;
        for variant in case.variants() {
            println!(
                "{} ({}), {} steps, {} springs:",
                case.name,
                variant.name(),
                case.steps,
                case.springs
            );
            let steps = largest_changes(&case, &halved, variant);
            let springs = largest_changes(&case, &finer, variant);
            for ((q, ds, at_s), (_, dx, at_x)) in steps.iter().zip(&springs) {
                println!(
                    "  {:<26} step halved {:>10.3e} (at {:>9.4}), springs doubled {:>10.3e} (at {:>9.4})",
                    q.name(),
                    ds,
                    at_s,
                    dx,
                    at_x
                );
            }
        }
    }
}
