//! The formulation sweep of `ccx-axisym` (Code_Aster's "modelings" of one physical test): the
//! case `cases-heavy/ccx-formulations.toml` (the paper's spheres along its Figure 7 path to
//! position 5, the hemisphere held rigidly, gmsh's mesh at c_max/20) solved with each contact
//! formulation CalculiX 2.20 has ([`Formulation::ALL`]) at the case's penalty factor (or each of
//! PENALTIES), beside fem-axisym on the same mesh. Per formulation: the errors of P, c and p0
//! against mdr-domain (the corrected reference: Hertz in series with the hemisphere's compliance)
//! at the case's focus position and the largest over the positions, and the wall time. A
//! formulation CalculiX refuses on this model prints its reason (N/A).
//!
//! Run: `cargo run --release --example ccx_formulations [CASE] [PENALTIES]`, e.g.
//! `cargo run --release --example ccx_formulations cases-heavy/ccx-formulations.toml 1e2,1e3,1e4`
//! (needs gmsh and ccx: scripts/setup.sh; about two minutes a formulation).

use std::path::Path;
use std::time::Instant;

use spherecontact::calculix_settings::{Formulation, Settings};
use spherecontact::case::Case;
use spherecontact::history::History;
use spherecontact::solver::{self, Solver};

/// The quantities compared, by name and reader.
type Reader = fn(&History, usize) -> Option<f64>;
const QUANTITIES: [(&str, Reader); 3] = [
    ("P", |h, k| h.at_position(k).and_then(|r| r.normal_force)),
    ("c", |h, k| h.at_position(k).and_then(|r| r.contact_radius)),
    ("p0", |h, k| h.at_position(k).and_then(|r| r.peak_pressure)),
];

/// The relative errors (at `focus`, largest over positions 1…) of each quantity.
fn errors(history: &History, reference: &History, positions: usize, focus: usize) -> Vec<(f64, f64)> {
    QUANTITIES
        .iter()
        .map(|(_, read)| {
            let error = |k| match (read(history, k), read(reference, k)) {
                (Some(x), Some(r)) if r != 0.0 => x / r - 1.0,
                _ => f64::NAN,
            };
            let worst =
                (1..positions).map(error).fold(
                    0.0_f64,
                    |w, e| {
                        if e.abs() > w.abs() || e.is_nan() {
                            e
                        } else {
                            w
                        }
                    },
                );
            (error(focus), worst)
        })
        .collect()
}

fn row(label: &str, solver: &dyn Solver, case: &Case, reference: &History) {
    let positions = case.scene.path.positions().len();
    let start = Instant::now();
    match solver::run(solver, &case.scene) {
        Ok(history) => {
            let wall = start.elapsed().as_secs_f64();
            let cells: Vec<String> = errors(&history, reference, positions, case.focus)
                .iter()
                .map(|(at, worst)| format!("{at:>+10.2e} {worst:>+10.2e}"))
                .collect();
            println!("{label:<26} {} {wall:>8.1}", cells.join(" "));
        }
        Err(e) => println!("{label:<26} N/A: {e}"),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let file = args
        .first()
        .map_or("cases-heavy/ccx-formulations.toml", String::as_str);
    let case = Case::load(Path::new(file)).unwrap_or_else(|e| panic!("{e}"));
    let penalties: Vec<f64> = args.get(1).map_or(vec![case.calculix.penalty], |list| {
        list.split(',')
            .map(|p| p.parse().expect("a penalty factor"))
            .collect()
    });
    let reference = solver::run(case.solver("mdr-domain").expect("built in").as_ref(), &case.scene)
        .expect("mdr-domain solves the case");
    println!(
        "case {}: errors against mdr-domain at position {} and the largest over positions 1…{}",
        case.name(),
        case.focus,
        case.scene.path.positions().len() - 1
    );
    let header: Vec<String> = QUANTITIES
        .iter()
        .map(|(name, _)| {
            format!(
                "{:>10} {:>10}",
                format!("{name} @{}", case.focus),
                format!("{name} max")
            )
        })
        .collect();
    println!(
        "{:<26} {} {:>8}",
        "solver / formulation",
        header.join(" "),
        "wall [s]"
    );
    row(
        "fem-axisym (same mesh)",
        case.solver("fem-axisym").expect("built in").as_ref(),
        &case,
        &reference,
    );
    let ccx = case.solver("ccx-axisym").expect("built in");
    for penalty in penalties {
        for formulation in Formulation::ALL {
            let settings = Settings {
                formulation,
                penalty: Settings::penalty(penalty).unwrap_or_else(|e| panic!("{e}")),
                ..case.calculix
            };
            let solver = ccx.with_calculix(&settings).expect("a CalculiX solver");
            row(
                &format!("ccx {} K={penalty:e}", formulation.name()),
                solver.as_ref(),
                &case,
                &reference,
            );
        }
    }
}
