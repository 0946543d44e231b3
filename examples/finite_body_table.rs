//! Every finite-body solver (FEM and decks) at δn = 17 µm on the paper's spheres, for the
//! hemisphere (cases/paper-fig7.toml) and the 20 mm caps (cases/paper-fig7-cap.toml): P, p0, c
//! and the RMS of the pressure profile p(r), each raw against Hertz's half-space and against the
//! corrected reference `mdr-domain` (MDR in series with the case's domain, docs/finite-body.md),
//! and the profile against fem-axisym's.
//!
//! The path is the case's own scene pressed to 17 µm (17 increments, no shift); the RMS is of
//! (p − p_ref)/p0_ref over 0.1 c < r < 0.9 c along x (away from the centre's few samples and the
//! √ edge), with p_ref = p0 √(1 − r²/c²) at the reference's c and p0 (Hertz's at the local
//! approach for `mdr-domain`).
//!
//! Run: `cargo run --release --example finite_body_table [SOLVER...]` (default: every finite-body
//! solver of the registry; the decks and fem-3d need the external toolchain and take minutes).

use std::path::Path;

use spherecontact::case::Case;
use spherecontact::domain::models_a_finite_body;
use spherecontact::fem::MdrDomain;
use spherecontact::history::{History, StepResult};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::registry;
use spherecontact::report::figures::surface::{FieldView, HalfAxis};
use spherecontact::scene::Scene;
use spherecontact::solver::run;

/// The approach of the table [m].
const APPROACH: f64 = 17e-6;

fn main() {
    let chosen: Vec<String> = std::env::args().skip(1).collect();
    let names: Vec<String> = if chosen.is_empty() {
        registry::names()
            .into_iter()
            .filter(|n| models_a_finite_body(n))
            .collect()
    } else {
        chosen
    };
    for file in ["cases/paper-fig7.toml", "cases/paper-fig7-cap.toml"] {
        let scene = pressed(file);
        println!("\n{} ({}), δn = 17 µm", scene.name, scene.domain.describe());
        table(&scene, &names);
    }
}

/// The case's scene pressed to [`APPROACH`] in 17 increments, fields at the end.
fn pressed(file: &str) -> Scene {
    let mut scene = Case::load(Path::new(file)).expect("a shipped case").scene;
    let at = |n: f64| Position {
        delta_n: n,
        delta_t: 0.0,
    };
    scene.path = LoadingPath::try_new(vec![at(0.0), at(APPROACH)], vec![17]).expect("a valid path");
    scene
}

/// The row at the end of the path.
fn last(history: &History) -> &StepResult {
    history.at_position(1).expect("the path's last position")
}

fn table(scene: &Scene, names: &[String]) {
    let hertz = scene.hertz();
    let raw = Reference {
        force: hertz.force(APPROACH),
        peak: hertz.peak_pressure(APPROACH),
        radius: hertz.contact_radius(APPROACH),
    };
    let corrected_history = run(&MdrDomain::default(), scene).expect("mdr-domain");
    let corrected = Reference::of(last(&corrected_history));
    println!(
        "  references: Hertz P {:.3} N, p0 {:.2} MPa, c {:.4} mm; mdr-domain P {:.3} N, p0 {:.2} MPa, c {:.4} mm",
        raw.force,
        raw.peak * 1e-6,
        raw.radius * 1e3,
        corrected.force,
        corrected.peak * 1e-6,
        corrected.radius * 1e3
    );
    println!(
        "  {:16} {:>10} {:>10} {:>10} | {:>10} {:>10} | {:>10} {:>10} | {:>10} {:>10} {:>10}",
        "solver",
        "P [N]",
        "P−Hertz",
        "P−corr",
        "p0−Hertz",
        "p0−corr",
        "c−Hertz",
        "c−corr",
        "RMS Hertz",
        "RMS corr",
        "RMS fem-ax"
    );
    let histories: Vec<(String, Result<History, String>)> = names
        .iter()
        .map(|name| {
            let history = registry::by_name(name)
                .ok_or_else(|| format!("no solver {name} in this build"))
                .and_then(|s| run(s.as_ref(), scene).map_err(|e| e.to_string()));
            (name.clone(), history)
        })
        .collect();
    let axisym = histories
        .iter()
        .find(|(n, _)| n == "fem-axisym")
        .and_then(|(_, h)| h.as_ref().ok())
        .and_then(|h| FieldView::at_position(h, 1))
        .map(|view| profile(&view));
    for (name, history) in &histories {
        let history = match history {
            Ok(h) => h,
            Err(e) => {
                println!("  {name:16} not run: {e}");
                continue;
            }
        };
        let row = last(history);
        let relative = |value: Option<f64>, reference: f64| {
            value.map_or_else(|| "—".to_owned(), |v| format!("{:+.3e}", v / reference - 1.0))
        };
        let rms = |reference: &Reference| {
            FieldView::at_position(history, 1)
                .and_then(|view| reference.rms(&profile(&view)))
                .map_or_else(|| "—".to_owned(), |e| format!("{e:.3e}"))
        };
        let against_axisym = FieldView::at_position(history, 1)
            .zip(axisym.as_ref())
            .and_then(|(view, axisym)| rms_between(&profile(&view), axisym, &corrected))
            .map_or_else(|| "—".to_owned(), |e| format!("{e:.3e}"));
        println!(
            "  {name:16} {:>10.3} {:>10} {:>10} | {:>10} {:>10} | {:>10} {:>10} | {:>10} {:>10} {:>10}",
            row.normal_force.unwrap_or(0.0),
            relative(row.normal_force, raw.force),
            relative(row.normal_force, corrected.force),
            relative(row.peak_pressure, raw.peak),
            relative(row.peak_pressure, corrected.peak),
            relative(row.contact_radius, raw.radius),
            relative(row.contact_radius, corrected.radius),
            rms(&raw),
            rms(&corrected),
            against_axisym
        );
    }
}

/// P, p0 and c of a reference, and its profile p0 √(1 − r²/c²).
struct Reference {
    force: f64,
    peak: f64,
    radius: f64,
}

impl Reference {
    fn of(row: &StepResult) -> Self {
        Self {
            force: row.normal_force.expect("P"),
            peak: row.peak_pressure.expect("p0"),
            radius: row.contact_radius.expect("c"),
        }
    }

    fn pressure(&self, r: f64) -> f64 {
        self.peak * (1.0 - (r / self.radius).powi(2)).max(0.0).sqrt()
    }

    /// RMS of (p − p_ref)/p0 over 0.1 c < r < 0.9 c.
    fn rms(&self, profile: &[(f64, f64)]) -> Option<f64> {
        rms(profile
            .iter()
            .filter(|(r, _)| *r > 0.1 * self.radius && *r < 0.9 * self.radius)
            .map(|&(r, p)| (p - self.pressure(r)) / self.peak))
    }
}

/// (r, p) along x.
fn profile(view: &FieldView) -> Vec<(f64, f64)> {
    view.along(HalfAxis::X)
        .iter()
        .filter_map(|probe| Some((probe.r, view.at(probe, |i| Some(view.pressure(i)))?)))
        .collect()
}

/// RMS of (p − p_other)/p0 over 0.1 c < r < 0.9 c of `reference`, `other` interpolated linearly.
fn rms_between(profile: &[(f64, f64)], other: &[(f64, f64)], reference: &Reference) -> Option<f64> {
    let interpolate = |r: f64| {
        let k = other.partition_point(|&(x, _)| x < r);
        let ((r0, p0), (r1, p1)) = (*other.get(k.checked_sub(1)?)?, *other.get(k)?);
        Some(p0 + (p1 - p0) * (r - r0) / (r1 - r0))
    };
    rms(profile
        .iter()
        .filter(|(r, _)| *r > 0.1 * reference.radius && *r < 0.9 * reference.radius)
        .filter_map(|&(r, p)| Some((p - interpolate(r)?) / reference.peak)))
}

fn rms(errors: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, count) = errors.fold((0.0, 0usize), |(s, n), e| (s + e * e, n + 1));
    (count > 0).then(|| (sum / count as f64).sqrt())
}
