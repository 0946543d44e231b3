//! The impact cost model against measured wall time (issue 42): every run (case, solver, over
//! every variant) of the impact cases given, one at a time, with its estimate
//! (`impact::cost::seconds`), its wall and CPU time (the process's and its children's: LAMMPS,
//! YADE) and wall / estimate, CPU / estimate; then the ratios' range per kind of solver. The
//! toolchain is probed first (once a process, not a run's cost).
//!
//! Run: `cargo run --release --example impact_estimate -- [--steps N] [--springs N]
//! [--solver NAME]… [CASE.toml]…` (default: every case of `cases/impact/`, their own steps and
//! springs; `--steps` and `--springs` override every case's, for the fit of the constants).
//! Figures quoted in docs/impact.md ("Speed") and in the constants' doc comments. A
//! measurement, not a test: no time limit is asserted anywhere.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

use spherecontact::bench::process_cpu_seconds;
use spherecontact::impact::case::ImpactCase;
use spherecontact::impact::{cost, run};
use spherecontact::reap::child_cpu_seconds;
use spherecontact::toolchain::{Tool, Toolchain};

/// The command line: overrides, the solvers kept (all when empty) and the case files.
struct Args {
    steps: Option<usize>,
    springs: Option<usize>,
    solvers: Vec<String>,
    files: Vec<PathBuf>,
}

fn args() -> Args {
    let mut args = Args {
        steps: None,
        springs: None,
        solvers: Vec::new(),
        files: Vec::new(),
    };
    let mut given = std::env::args().skip(1);
    while let Some(arg) = given.next() {
        let mut value = || given.next().unwrap_or_else(|| panic!("{arg}: a value"));
        match arg.as_str() {
            "--steps" => args.steps = Some(value().parse().expect("--steps: a whole number")),
            "--springs" => args.springs = Some(value().parse().expect("--springs: a whole number")),
            "--solver" => args.solvers.push(value()),
            _ => args.files.push(PathBuf::from(arg)),
        }
    }
    if args.files.is_empty() {
        args.files = spherecontact::case::case_files(&[PathBuf::from("cases/impact")]).expect("cases/impact");
    }
    args
}

/// The CPU time of this process and of the programs it has run [s].
fn total_cpu_seconds() -> f64 {
    process_cpu_seconds() + child_cpu_seconds()
}

/// The kind of solver a ratio is grouped under.
fn kind(solver: &str) -> &'static str {
    match solver {
        s if s.starts_with("lammps") => "lammps",
        s if s.starts_with("yade") => "yade",
        s if s.starts_with("mdr") => "mdr",
        _ => "law",
    }
}

fn load(args: &Args, file: &PathBuf) -> ImpactCase {
    let mut case = spherecontact::case::load_impact(file).unwrap_or_else(|e| panic!("{e}"));
    case.steps = args.steps.unwrap_or(case.steps);
    case.springs = args.springs.unwrap_or(case.springs);
    case
}

fn main() {
    let args = args();
    // The toolchain's probe (every tool, once a process: about 5 s) is no run's cost.
    let _ = Toolchain::default().require(Tool::Lammps);
    let mut ratios: BTreeMap<&str, Vec<(f64, f64)>> = BTreeMap::new();
    println!("case, solver, steps, springs, points, estimate_s, wall_s, cpu_s, wall/estimate, cpu/estimate");
    for file in &args.files {
        let case = load(&args, file);
        for solver in case.required_solvers() {
            if !args.solvers.is_empty() && !args.solvers.contains(&solver) {
                continue;
            }
            let estimate = cost::seconds(&case, &solver);
            let (start, cpu) = (Instant::now(), total_cpu_seconds());
            let runs = run::run_case(&case, std::slice::from_ref(&solver));
            let (wall, cpu) = (start.elapsed().as_secs_f64(), total_cpu_seconds() - cpu);
            if let Some(why) = runs.iter().find_map(|r| r.unavailable.as_ref()) {
                println!("{}, {solver}: not available: {why}", case.name);
                continue;
            }
            let ratio = (wall / estimate, cpu / estimate);
            ratios.entry(kind(&solver)).or_default().push(ratio);
            println!(
                "{}, {solver}, {}, {}, {}, {estimate:.3e}, {wall:.3e}, {cpu:.3e}, {:.2}, {:.2}",
                case.name,
                case.steps,
                case.springs,
                cost::points(&case),
                ratio.0,
                ratio.1
            );
        }
    }
    let range = |xs: &mut dyn Iterator<Item = f64>| {
        xs.fold((f64::INFINITY, 0.0_f64), |(a, b), x| (a.min(x), b.max(x)))
    };
    for (kind, ratios) in &ratios {
        let wall = range(&mut ratios.iter().map(|r| r.0));
        let cpu = range(&mut ratios.iter().map(|r| r.1));
        println!(
            "{kind}: {} runs, wall/estimate {:.2} … {:.2}, cpu/estimate {:.2} … {:.2}",
            ratios.len(),
            wall.0,
            wall.1,
            cpu.0,
            cpu.1
        );
    }
}
