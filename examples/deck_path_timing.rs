//! Speed of the external decks along a whole loading path, side by side with the in-crate
//! `fem-axisym` in one run: the paper's path (cases/paper-fig7.toml, 1101 steps) at the default
//! pole size c_max/40 through FreeFEM, dolfinx and fem-axisym, interleaved, one warm-up run each
//! then REPEATS timed runs (default 3); medians of wall and CPU time (CPU includes the external
//! programs'), the decks' own split (set-up: assembly, factorisation, condensation; path), and the
//! errors (worst over every step: for P relative to the reference's P at that step, so the first
//! small steps weigh most; for Q relative to the reference's peak |Q|):
//! against mdr-domain, the finite-body reference (MDR in series with the case's domain's
//! compliances, docs/finite-body.md: the discretisation error, so the CPU ratio is at equal error
//! when these columns match), the raw offset of P from Hertz beside it, and each deck against
//! fem-axisym; then P and Q at every path position beside mdr and mdr-domain. The machine may be
//! shared: compare the solvers within one run.
//!
//! Run: `cargo run --release --example deck_path_timing [CASE] [REPEATS] [SOLVERS]` (needs
//! scripts/setup.sh). SOLVERS is a comma-separated list of the solvers to time (default
//! `freefem-axisym,fenicsx-axisym,fem-axisym`), each at the case's `[resolution]`; e.g.
//! `… cases/paper-fig7.toml 1 fem-3d,fem-axisym` prints the closing note's table of P and Q at
//! every path position for fem-3d, fem-axisym, MDR and mdr-domain.

use std::path::Path;

use spherecontact::bench::{self, worst_error};
use spherecontact::case::Case;
use spherecontact::history::{History, Quantity};
use spherecontact::registry;
use spherecontact::solver::{self, Solver};

/// A column of seconds, or "—" where a solver does not report that part.
fn seconds(history: &History, key: &str) -> String {
    history
        .metadata
        .extra
        .get(key)
        .and_then(serde_json::Value::as_f64)
        .map_or_else(|| "—".to_owned(), |s| format!("{s:.1}"))
}

/// A percentage, or "—".
fn percent(value: Option<f64>) -> String {
    value.map_or_else(|| "—".to_owned(), |v| format!("{:.3}", v * 100.0))
}

/// A force to the table's 1 mN: a Q a few µN below zero (the decks' round-off at Q = 0) prints
/// as 0.000, not −0.000.
fn newtons(q: f64) -> String {
    let shown = format!("{q:.3}");
    if shown == "-0.000" {
        "0.000".to_owned()
    } else {
        shown
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let case = args.next().unwrap_or_else(|| "cases/paper-fig7.toml".into());
    let repeats: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(3);
    let names = args
        .next()
        .unwrap_or_else(|| "freefem-axisym,fenicsx-axisym,fem-axisym".into());
    let loaded = Case::load(Path::new(&case)).expect("a valid case, run from the crate root");
    let solvers: Vec<Box<dyn Solver>> = names
        .split(',')
        .filter_map(|name| {
            let solver = loaded.solver(name.trim());
            if solver.is_none() {
                println!("{name}: no such solver in this build");
            }
            solver
        })
        .collect();
    let scene = loaded.scene;
    let reference = |name: &str| registry::by_name(name).and_then(|s| solver::run(s.as_ref(), &scene).ok());
    let (hertz, domain, mdr) = (reference("hertz"), reference("mdr-domain"), reference("mdr"));
    println!(
        "{case}: {} steps, c_max = {:.4} mm; medians of {repeats} runs after a warm-up, interleaved; errors in %",
        scene.steps().len(),
        scene.max_contact_radius() * 1e3
    );
    println!(
        "{:<15} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>10} {:>10}",
        "solver", "wall s", "CPU s", "setup s", "path s", "P-Hertz", "P-dom", "Q-dom", "Q-fem"
    );
    let timings = bench::time_solvers(&solvers, &scene, repeats);
    let fem = timings
        .iter()
        .flatten()
        .find(|t| t.solver == "fem-axisym")
        .map(|t| t.history.clone());
    let fem_cpu = timings
        .iter()
        .flatten()
        .find(|t| t.solver == "fem-axisym")
        .map(|t| bench::median(&t.cpu_seconds));
    for timing in &timings {
        let timing = match timing {
            Ok(t) => t,
            Err((name, e)) => {
                println!("{name:<15} {e}");
                continue;
            }
        };
        let h = &timing.history;
        let against = |r: &Option<History>, q: Quantity, to_peak: bool| {
            r.as_ref().and_then(|r| worst_error(h, r, q, to_peak))
        };
        let cpu = bench::median(&timing.cpu_seconds);
        println!(
            "{:<15} {:>8.1} {:>8.1} {:>8} {:>8} {:>9} {:>9} {:>10} {:>10}{}",
            timing.solver,
            bench::median(&timing.seconds),
            cpu,
            seconds(h, "deck_setup_s"),
            seconds(h, "deck_path_s"),
            percent(against(&hertz, Quantity::NormalForce, false)),
            percent(against(&domain, Quantity::NormalForce, false)),
            percent(against(&domain, Quantity::TangentialForce, true)),
            percent(against(&fem, Quantity::TangentialForce, true)),
            fem_cpu.map_or_else(String::new, |f| format!("   CPU ×{:.0} fem-axisym", cpu / f)),
        );
    }
    // P and Q at every path position, each solver beside the references.
    let rows: Vec<(String, History)> = timings
        .iter()
        .flatten()
        .map(|t| (t.solver.clone(), t.history.clone()))
        .chain(
            [("mdr", &mdr), ("mdr-domain", &domain)]
                .into_iter()
                .filter_map(|(n, h)| Some((n.to_owned(), h.clone()?))),
        )
        .collect();
    for (title, quantity) in [("P", Quantity::NormalForce), ("Q", Quantity::TangentialForce)] {
        println!("\n{title} [N] at the path positions");
        print!("{:<15}", "position");
        rows.iter().for_each(|(name, _)| print!(" {name:>15}"));
        println!();
        for position in 0..scene.path.positions().len() {
            print!("{position:<15}");
            for (_, h) in &rows {
                let value = h.at_position(position).and_then(|r| quantity.of(r));
                print!(" {:>15}", value.map_or_else(|| "—".to_owned(), newtons));
            }
            println!();
        }
    }
}
