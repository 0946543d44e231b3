//! The formulation sweep of the CalculiX decks (Code_Aster's "modelings" of one physical test):
//! a case solved with each contact formulation CalculiX 2.20 has ([`Formulation::ALL`]) at the
//! case's penalty factor (or each of PENALTIES), beside the in-crate FEM on the same mesh, with
//! the errors against mdr-domain (the corrected reference: Hertz in series with the hemisphere's
//! compliance) at the case's focus position and the largest over the positions, and the wall
//! and CPU time (this process's and ccx's, gmsh's). A formulation CalculiX refuses prints its
//! reason (N/A).
//!
//! - **Axisymmetric** (a case without `ccx-3d`; default `cases-heavy/ccx-formulations.toml`, the
//!   paper path to position 5 at c_max/20): `ccx-axisym` beside fem-axisym; P, c and p0.
//! - **3D** (a case listing `ccx-3d`, e.g. `cases-heavy/ccx-3d-maps.toml`): `ccx-3d` beside
//!   fem-3d at the pole size c_max/N (N the third argument; default the case's); P and Q against
//!   mdr-domain, and at the focus position the q_y ratio and the stick semi-axes against fem-3d
//!   on the same mesh (mdr-domain is axisymmetric: it has no map). Where the contact's forces
//!   reach the outermost candidate ring (ccx-3d's metadata warning: the contact may reach beyond
//!   the candidate faces, which the maps do not see) the map columns mark their values with *.
//!
//! Run: `cargo run --release --example ccx_formulations [CASE] [PENALTIES] [N] [FORMULATIONS]`
//! (FORMULATIONS a comma-separated list of `[calculix] contact` names; default all), e.g.
//! `cargo run --release --example ccx_formulations cases-heavy/ccx-formulations.toml 1e2,1e3,1e4`
//! or `cargo run --release --example ccx_formulations cases-heavy/ccx-3d-maps.toml 1e3 2
//! face-to-face,mortar,linmortar,pglinmortar`
//! (needs gmsh and ccx: scripts/setup.sh; minutes a formulation).

use std::path::Path;
use std::time::Instant;

use spherecontact::bench::process_cpu_seconds;
use spherecontact::calculix_settings::{Formulation, Settings};
use spherecontact::case::Case;
use spherecontact::history::{History, Quantity};
use spherecontact::map_measure;
use spherecontact::reap::child_cpu_seconds;
use spherecontact::solver::{self, Solver};

/// A quantity of a history at a path position.
type Reader = fn(&History, usize) -> Option<f64>;

/// A compared quantity: its name, its reader, and whether it is judged against the in-crate FEM
/// on the same mesh at the focus position only (a map measure) rather than against mdr-domain at
/// every position.
struct Column(&'static str, Reader, bool);

const AXISYMMETRIC: [Column; 3] = [
    Column("P", |h, k| h.at_position(k).and_then(|r| r.normal_force), false),
    Column("c", |h, k| h.at_position(k).and_then(|r| r.contact_radius), false),
    Column("p0", |h, k| h.at_position(k).and_then(|r| r.peak_pressure), false),
];

const SOLID: [Column; 5] = [
    Column("P", |h, k| h.at_position(k).and_then(|r| r.normal_force), false),
    Column(
        "Q",
        |h, k| h.at_position(k).and_then(|r| r.tangential_force),
        false,
    ),
    Column("qy", |h, k| map(h, k, Quantity::TransverseRatio), true),
    Column("ax", |h, k| map(h, k, Quantity::StickSemiAxisX), true),
    Column("ay", |h, k| map(h, k, Quantity::StickSemiAxisY), true),
];

/// A map measure of the field at position `k`.
fn map(history: &History, k: usize, quantity: Quantity) -> Option<f64> {
    map_measure::measure(quantity, history.field_at(k)?)
}

/// What a row is compared with: the case, mdr-domain's history and the in-crate FEM's.
struct References<'a> {
    case: &'a Case,
    mdr: &'a History,
    fem: Option<&'a History>,
    columns: &'a [Column],
}

/// Whether the contact's forces reach the outermost candidate ring (ccx-3d's warning): the maps
/// may miss contact beyond the candidate faces.
fn edge_loaded(history: &History) -> bool {
    history
        .metadata
        .warnings
        .iter()
        .any(|w| w.contains("outermost candidate ring"))
}

/// The cells of `history`: per column, the relative error at the focus and the largest over
/// positions 1… (for a map column, at the focus only).
fn cells(history: &History, references: &References) -> Vec<String> {
    let focus = references.case.focus;
    let positions = references.case.scene.path.positions().len();
    references
        .columns
        .iter()
        .map(|Column(_, read, on_map)| {
            let reference = if *on_map {
                references.fem
            } else {
                Some(references.mdr)
            };
            // None where the reference has no value or a zero one (Q before the shift); NaN
            // where the reference has one and the row none.
            let error = |k| match (read(history, k), reference.and_then(|r| read(r, k))) {
                (_, None) | (_, Some(0.0)) => None,
                (Some(x), Some(r)) => Some(x / r - 1.0),
                (None, Some(_)) => Some(f64::NAN),
            };
            let at_focus = error(focus).unwrap_or(f64::NAN);
            if *on_map {
                return if edge_loaded(history) {
                    format!("{:>10}", format!("{}*", cell(at_focus).trim_start()))
                } else {
                    cell(at_focus)
                };
            }
            let worst = (1..positions).filter_map(error).fold(0.0_f64, |w, e| {
                if e.abs() > w.abs() || e.is_nan() {
                    e
                } else {
                    w
                }
            });
            format!("{} {}", cell(at_focus), cell(worst))
        })
        .collect()
}

/// A relative error in its column, "—" where there is none (no value, or no reference).
fn cell(error: f64) -> String {
    if error.is_finite() {
        format!("{error:>+10.2e}")
    } else {
        format!("{:>10}", "—")
    }
}

/// Solves and prints one row; the history, if any.
fn row(label: &str, solver: &dyn Solver, references: &References) -> Option<History> {
    let (cpu, child, start) = (process_cpu_seconds(), child_cpu_seconds(), Instant::now());
    match solver::run(solver, &references.case.scene) {
        Ok(history) => {
            let wall = start.elapsed().as_secs_f64();
            let cpu = process_cpu_seconds() - cpu + child_cpu_seconds() - child;
            println!(
                "{label:<30} {} {wall:>8.1} {cpu:>8.1}",
                cells(&history, references).join(" ")
            );
            Some(history)
        }
        Err(e) => {
            println!("{label:<30} N/A: {e}");
            None
        }
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
    let solid = case.solvers.iter().any(|s| s == "ccx-3d");
    let (ccx, fem, columns): (&str, &str, &[Column]) = if solid {
        ("ccx-3d", "fem-3d", &SOLID)
    } else {
        ("ccx-axisym", "fem-axisym", &AXISYMMETRIC)
    };
    let mut case = case;
    if let Some(n) = args.get(2) {
        // The pole size of both meshes, over the case's `[resolution]`.
        for name in [ccx, fem] {
            case.resolution.insert(name.to_owned(), format!("c/{n}"));
        }
    }
    let mdr = solver::run(case.solver("mdr-domain").expect("built in").as_ref(), &case.scene)
        .expect("mdr-domain solves the case");
    println!(
        "case {}: errors against mdr-domain at position {} and the largest over positions 1…{}{}",
        case.name(),
        case.focus,
        case.scene.path.positions().len() - 1,
        if solid {
            "; the maps' (q_y ratio, stick semi-axes) against fem-3d on the same mesh at the focus"
        } else {
            ""
        }
    );
    let header: Vec<String> = columns
        .iter()
        .map(|Column(name, _, on_map)| {
            if *on_map {
                format!("{:>10}", format!("{name} @{}", case.focus))
            } else {
                format!(
                    "{:>10} {:>10}",
                    format!("{name} @{}", case.focus),
                    format!("{name} max")
                )
            }
        })
        .collect();
    println!(
        "{:<30} {} {:>8} {:>8}",
        "solver / formulation",
        header.join(" "),
        "wall [s]",
        "CPU [s]"
    );
    let mut references = References {
        case: &case,
        mdr: &mdr,
        fem: None,
        columns,
    };
    let fem_solver = case.solver(fem).expect("built in");
    let fem_history = row(&format!("{fem} (same mesh)"), fem_solver.as_ref(), &references);
    references.fem = fem_history.as_ref();
    let ccx_solver = case.solver(ccx).expect("built in");
    let formulations: Vec<Formulation> = args.get(3).map_or(Formulation::ALL.to_vec(), |list| {
        list.split(',')
            .map(|name| Settings::formulation(name).unwrap_or_else(|e| panic!("{e}")))
            .collect()
    });
    for penalty in penalties {
        for &formulation in &formulations {
            let settings = Settings {
                formulation,
                penalty: Settings::penalty(penalty).unwrap_or_else(|e| panic!("{e}")),
                ..case.calculix
            };
            let solver = ccx_solver.with_calculix(&settings).expect("a CalculiX solver");
            row(
                &format!("{ccx} {} K={penalty:e}", formulation.name()),
                solver.as_ref(),
                &references,
            );
        }
    }
}
