//! The formulation table of the Kratos deck `kratos-3d` (issue 40), as
//! examples/ccx_formulations.rs is CalculiX's: the case's spheres and `[domain]` (default
//! `cases/kratos-3d.toml`: the paper's spheres, the hemisphere gripped rigidly) along a short
//! frictional path — pressed to δn = 10 µm in N increments, then shifted to δt = 1 µm in one —
//! solved with each Kratos contact formulation and factor at a coarse mesh (c_max/2 by default),
//! printed as a markdown table. Per row:
//!
//! - P and Q at every position and their errors against mdr-domain (the corrected reference:
//!   MDR in series with the hemisphere's compliance); Q where mdr-domain has one (after the shift);
//!   `n.c.` where Kratos did not converge (or, under friction, after a step it did not): a step
//!   that did not converge has no value, never the force Kratos left there;
//! - the convergence record: the computed steps not converged, and the Newton iterations of each
//!   step (`convergence_by_step`), `*` marking a step not converged;
//! - the median wall time of Kratos' steps after the unloaded first (its own clock,
//!   `kratos_step_s`), and the whole run's wall time (gmsh, Kratos' start-up, the reading back).
//!
//! Run: `cargo run --release --example kratos_formulations -- [OPTIONS]` (needs gmsh and Kratos:
//! scripts/setup.sh; 5–100 s a row at c_max/2 on the shared machine, an unconverged step costing
//! 30 iterations):
//!
//! - `--case FILE` (default `cases/kratos-3d.toml`); `--case-path` keeps the case's own path
//!   (e.g. the Figure 7 path of a case that has it) instead of the short one;
//! - `--pole N`: the pole element c_max/N (default 2); `--increments N`: the approach's (default 2);
//! - `--element tet4[,…]`: the elements (`[kratos] element`; default tet4);
//! - `--contact LIST` (default every formulation), `--alm LIST` (the ALM factors, default
//!   0.1,1,10), `--penalty LIST` (default 1e2,1e3).

use std::path::Path;
use std::time::Instant;

use spherecontact::bench::{median, significant};
use spherecontact::case::Case;
use spherecontact::history::History;
use spherecontact::kratos_settings::{Element, Formulation, Settings};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::solver::{self, Solver};

/// The options of a sweep.
struct Options {
    case: String,
    case_path: bool,
    pole: f64,
    increments: usize,
    elements: Vec<Element>,
    formulations: Vec<Formulation>,
    alm: Vec<f64>,
    penalty: Vec<f64>,
}

/// Prints `message` and exits with code 2 (bad input).
fn refuse(message: &str) -> ! {
    eprintln!("kratos_formulations: {message}");
    std::process::exit(2)
}

/// The comma-separated list `text`, each item read by `parse`.
fn list<T, E: std::fmt::Display>(text: &str, parse: impl Fn(&str) -> Result<T, E>) -> Vec<T> {
    text.split(',')
        .map(|item| parse(item.trim()).unwrap_or_else(|e| refuse(&e.to_string())))
        .collect()
}

/// A number ≥ 1 given to `flag`.
fn at_least_one<T: std::str::FromStr + PartialOrd + From<u8>>(flag: &str, text: &str) -> T {
    text.parse()
        .ok()
        .filter(|n| *n >= T::from(1))
        .unwrap_or_else(|| refuse(&format!("{flag} takes a number ≥ 1, not `{text}`")))
}

impl Options {
    fn parse() -> Self {
        let mut options = Options {
            case: "cases/kratos-3d.toml".into(),
            case_path: false,
            pole: 2.0,
            increments: 2,
            elements: vec![Element::Tet4],
            formulations: Formulation::ALL.to_vec(),
            alm: vec![0.1, 1.0, 10.0],
            penalty: vec![1e2, 1e3],
        };
        let mut args = std::env::args().skip(1);
        while let Some(flag) = args.next() {
            if flag == "--case-path" {
                options.case_path = true;
                continue;
            }
            let value = args
                .next()
                .unwrap_or_else(|| refuse(&format!("{flag} needs a value (see the file's header)")));
            match flag.as_str() {
                "--case" => options.case = value,
                "--pole" => options.pole = at_least_one(&flag, &value),
                "--increments" => options.increments = at_least_one(&flag, &value),
                "--element" => options.elements = list(&value, Settings::element),
                "--contact" => options.formulations = list(&value, Settings::formulation),
                "--alm" => options.alm = list(&value, |v| Settings::alm_factor(number(v))),
                "--penalty" => options.penalty = list(&value, |v| Settings::penalty(number(v))),
                _ => refuse(&format!("unknown option {flag} (see the file's header)")),
            }
        }
        options
    }

    /// Every row's settings: each element, formulation and its factors.
    fn rows(&self, base: Settings) -> Vec<Settings> {
        let mut rows = Vec::new();
        for &element in &self.elements {
            for &formulation in &self.formulations {
                let factors = match formulation {
                    Formulation::Penalty => &self.penalty,
                    _ => &self.alm,
                };
                for &factor in factors {
                    let mut settings = Settings {
                        formulation,
                        element,
                        ..base
                    };
                    match formulation {
                        Formulation::Penalty => settings.penalty = factor,
                        _ => settings.alm_factor = factor,
                    }
                    rows.push(settings);
                }
            }
        }
        rows
    }
}

/// `text` as a number (NaN when it is none: the range check then refuses it).
fn number(text: &str) -> f64 {
    text.parse().unwrap_or(f64::NAN)
}

/// The short frictional path: δn = 10 µm in `increments`, then δt = 1 µm in one.
fn short_path(increments: usize) -> LoadingPath {
    let at = |n: f64, t: f64| Position {
        delta_n: n * 1e-6,
        delta_t: t * 1e-6,
    };
    LoadingPath::try_new(
        vec![at(0.0, 0.0), at(10.0, 0.0), at(10.0, 1.0)],
        vec![increments, 1],
    )
    .expect("a valid path")
}

/// A quantity of a history at a position: P or Q.
type Reader = fn(&History, usize) -> Option<f64>;

const P: Reader = |h, k| h.at_position(k).and_then(|r| r.normal_force);
const Q: Reader = |h, k| h.at_position(k).and_then(|r| r.tangential_force);

/// The compared columns: (name, reader, position), P at every position after the first, Q where
/// mdr-domain has one.
fn columns(mdr: &History, positions: usize) -> Vec<(String, Reader, usize)> {
    let mut columns = Vec::new();
    for k in 1..positions {
        columns.push((format!("P@{k} [N]"), P, k));
        if Q(mdr, k).is_some_and(|q| q != 0.0) {
            columns.push((format!("Q@{k} [N]"), Q, k));
        }
    }
    columns
}

/// A value and its error against the reference; where the row has none, `n.c.` if `lost` (its
/// step not converged, or after one under friction), else `—` (no Q under frictionless contact).
fn cell(value: Option<f64>, reference: Option<f64>, lost: bool) -> String {
    match (value, reference) {
        (Some(v), Some(r)) if r != 0.0 => format!("{v:.2} ({:+.1} %)", (v / r - 1.0) * 1e2),
        (Some(v), _) => format!("{v:.2}"),
        (None, _) if lost => "n.c.".into(),
        (None, _) => "—".into(),
    }
}

/// Whether Kratos' values at position `k` are lost: its step did not converge, or under
/// friction a step before it did not (the history keeps none after the first).
fn lost(history: &History, k: usize, frictional: bool) -> bool {
    let Some(step) = history.at_position(k).map(|r| r.step) else {
        return true;
    };
    let failed: Vec<u64> = history.metadata.extra["steps_not_converged"]
        .as_array()
        .map(|a| a.iter().filter_map(serde_json::Value::as_u64).collect())
        .unwrap_or_default();
    failed
        .iter()
        .any(|&s| s as usize == step || (frictional && (s as usize) < step))
}

/// A failed run's reason on one line: the error's first line (its "last output" cut) and the
/// first error Kratos wrote to its stderr (a thread's exception, else Python's) in the run directory the failure kept, if it did.
fn reason(error: &str) -> String {
    let first = error.lines().next().unwrap_or_default();
    let first = first.split("; last output").next().unwrap_or(first);
    let kept = error
        .rsplit("kept in ")
        .next()
        .and_then(|s| s.strip_suffix(')'))
        .map(|dir| Path::new(dir).join("deck.stderr"));
    let kratos = kept
        .and_then(|file| std::fs::read_to_string(file).ok())
        .and_then(|log| {
            let lines = || log.lines();
            lines()
                .find(|l| l.contains("caught exception"))
                .or_else(|| lines().find(|l| l.starts_with("RuntimeError")))
                .map(|l| l.trim().to_owned())
        });
    match kratos {
        Some(kratos) => format!("{first}: {kratos}"),
        None => first.to_owned(),
    }
}

/// The convergence record of a kratos-3d history: (steps not converged / computed, the
/// iterations of each step with `*` on those not converged).
fn record(history: &History) -> (String, String) {
    let steps = history.metadata.extra["convergence_by_step"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    let failed = steps.iter().filter(|s| s["converged"] != true).count();
    let iterations: Vec<String> = steps
        .iter()
        .map(|s| {
            let mark = if s["converged"] == true { "" } else { "*" };
            format!("{}{mark}", s["iterations"])
        })
        .collect();
    (format!("{failed}/{}", steps.len()), iterations.join(" "))
}

/// The median of Kratos' own step times after the first [ms].
fn step_median_ms(history: &History) -> f64 {
    let mut times: Vec<f64> = history.metadata.extra["kratos_step_s"]
        .as_array()
        .map(|a| a.iter().skip(1).filter_map(serde_json::Value::as_f64).collect())
        .unwrap_or_default();
    times.sort_by(f64::total_cmp);
    if times.is_empty() {
        return f64::NAN;
    }
    median(&times) * 1e3
}

/// Solves one row and prints it.
fn row(solver: &dyn Solver, settings: &Settings, scene: &spherecontact::scene::Scene, mdr: &History) {
    let factor = settings.stiffness_factor();
    let label = format!(
        "| {} | {factor:e} | {} |",
        settings.formulation.name(),
        settings.element.name()
    );
    let start = Instant::now();
    match solver::run(solver, scene) {
        Ok(history) => {
            let wall = start.elapsed().as_secs_f64();
            let frictional = settings.formulation.frictional(!scene.path.is_normal_only());
            let cells: Vec<String> = columns(mdr, scene.path.positions().len())
                .iter()
                .map(|(_, read, k)| {
                    let lost = lost(&history, *k, frictional);
                    cell(read(&history, *k), read(mdr, *k), lost)
                })
                .collect();
            let (failed, iterations) = record(&history);
            println!(
                "{label} {} | {failed} | {iterations} | {} | {} |",
                cells.join(" | "),
                significant(step_median_ms(&history)),
                significant(wall)
            );
        }
        Err(e) => {
            eprintln!("{label} {e}");
            println!("{label} {} |", reason(&e.to_string()));
        }
    }
}

fn main() {
    let options = Options::parse();
    let mut case = Case::load(Path::new(&options.case)).unwrap_or_else(|e| refuse(&e.to_string()));
    if !options.case_path {
        case.scene.path = short_path(options.increments);
    }
    case.resolution
        .insert("kratos-3d".into(), format!("c/{}", options.pole));
    let scene = &case.scene;
    let mdr = solver::run(case.solver("mdr-domain").expect("built in").as_ref(), scene)
        .unwrap_or_else(|e| refuse(&format!("mdr-domain: {e}")));
    let kratos = case.solver("kratos-3d").expect("built in");
    let positions = scene.path.positions().len();
    let columns = columns(&mdr, positions);
    println!(
        "{}: {} steps, kratos-3d at c_max/{}; P and Q (error against mdr-domain), n.c. where Kratos \
         did not converge (or after it, under friction), — no value (Q under frictionless contact); iterations per step (* not converged); \
         Kratos' median step time after the first; the run's wall time\n",
        case.name(),
        scene.steps().len(),
        options.pole
    );
    let names: Vec<&str> = columns.iter().map(|(name, ..)| name.as_str()).collect();
    println!(
        "| contact | factor | element | {} | not converged | iterations per step | ms/increment | wall s |",
        names.join(" | ")
    );
    println!("|---|---|---|{}---|---|---|---|", "---|".repeat(names.len()));
    let references: Vec<String> = columns
        .iter()
        .map(|(_, read, k)| read(&mdr, *k).map_or("—".into(), |v| format!("{v:.2}")))
        .collect();
    println!("| mdr-domain | | | {} | | | | |", references.join(" | "));
    for settings in options.rows(case.kratos) {
        let solver = kratos.with_kratos(&settings).expect("a Kratos solver");
        row(solver.as_ref(), &settings, scene, &mdr);
    }
}
