//! `fem-axisym` against Hertz corrected for its finite bodies (`mdr-domain`) and Hertz's local
//! relations: the paper's spheres (symmetric reduction) and a steel ball on an aluminium flat
//! (two bodies). Run: `cargo test --test suite fem_hertz::` (about 20 s in the dev
//! profile); the finer ladder with the domain/mesh split of the P error:
//! `cargo test --release --test suite fem_hertz:: -- --ignored --nocapture`.

use crate::common;

use common::{identical_spheres, normal_scene};
use spherecontact::fem::axisym::model::{Model, Settings};
use spherecontact::fem::{FemAxisym, MdrDomain};
use spherecontact::hertz::Hertz;
use spherecontact::history::History;
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::scene::Scene;
use spherecontact::solver::run;

fn scene(pair: ContactPair, delta_um: &[f64]) -> Scene {
    normal_scene(pair, delta_um)
}

fn paper() -> ContactPair {
    identical_spheres(0.1, 70e9, 0.3)
}

fn ball_on_flat() -> ContactPair {
    ContactPair {
        body1: Body {
            radius: 0.01,
            material: Material {
                young: 210e9,
                poisson: 0.29,
            },
        },
        body2: Body {
            radius: f64::INFINITY,
            material: Material {
                young: 70e9,
                poisson: 0.3,
            },
        },
    }
}

/// Per path position (after the start): P/P_ref − 1 against `reference` (mdr-domain: Hertz
/// corrected for the modelled finite bodies, docs/finite-body.md), and the local Hertz relations
/// p0 / (3P/(2πc²)) − 1 and c / (3PR*/4E*)^{1/3} − 1.
fn errors(history: &History, reference: &History, hertz: &Hertz) -> Vec<[f64; 3]> {
    history
        .at_positions()
        .zip(reference.at_positions())
        .skip(1)
        .map(|(row, reference)| {
            let (p, c, p0) = (
                row.normal_force.unwrap(),
                row.contact_radius.unwrap(),
                row.peak_pressure.unwrap(),
            );
            let c_local = (3.0 * p * hertz.effective_radius / (4.0 * hertz.effective_modulus)).cbrt();
            [
                p / reference.normal_force.unwrap() - 1.0,
                p0 / (3.0 * p / (2.0 * std::f64::consts::PI * c * c)) - 1.0,
                c / c_local - 1.0,
            ]
        })
        .collect()
}

/// Runs the ladder of pole sizes; returns errors[h][position][quantity].
fn ladder(pair: ContactPair, deltas: &[f64], divisions: &[f64]) -> Vec<Vec<[f64; 3]>> {
    let s = scene(pair, deltas);
    let c = s.max_contact_radius();
    let reference = run(&MdrDomain::default(), &s).unwrap();
    divisions
        .iter()
        .map(|&n| {
            let history = run(&FemAxisym::with_pole_size(c / n), &s).unwrap();
            errors(&history, &reference, &s.hertz())
        })
        .collect()
}

/// Largest |error| of quantity q over the positions.
fn worst(e: &[[f64; 3]], q: usize) -> f64 {
    e.iter().map(|v| v[q].abs()).fold(0.0, f64::max)
}

/// Root mean square of quantity q over the positions: the edge's place between two nodes
/// changes with δn, so one position's error scatters; the mean over many does not.
fn rms(e: &[[f64; 3]], q: usize) -> f64 {
    (e.iter().map(|v| v[q] * v[q]).sum::<f64>() / e.len() as f64).sqrt()
}

/// Least-squares slope of log(error) against log(h) over a ladder halving h per rung.
fn rate(errors: &[f64]) -> f64 {
    let n = errors.len() as f64;
    let x: Vec<f64> = (0..errors.len()).map(|k| -(k as f64) * 2f64.ln()).collect();
    let y: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

fn assert_hertz(e: &[Vec<[f64; 3]>], name: &str) {
    let finest = e.last().unwrap();
    // P: within 5e-4 of the finite-body reference (the rigidly gripped hemisphere is +0.58 %
    // from Hertz at 20 µm; mdr-domain explains it): what is left at pole size c_max/40 is the
    // mesh error, ≤ 2.5e-4 measured (its coarse far field 1.3e-4, the contact zone ≤ 1.2e-4).
    assert!(worst(finest, 0) < 5e-4, "{name}: P {finest:?}");
    // Mesh part of the P error: the RMS over positions of the change per refinement. It must
    // fall (rate ≥ 1) and be below 0.1 % at the last rung.
    let changes: Vec<f64> = e
        .windows(2)
        .map(|w| {
            (w[0]
                .iter()
                .zip(&w[1])
                .map(|(a, b)| (a[0] - b[0]).powi(2))
                .sum::<f64>()
                / w[0].len() as f64)
                .sqrt()
        })
        .collect();
    let r = rate(&changes);
    println!(
        "{name}: P errors on the finest mesh {:?}; RMS change per refinement {:?}, rate {r:.2}",
        finest
            .iter()
            .map(|v| format!("{:+.3}%", 100.0 * v[0]))
            .collect::<Vec<_>>(),
        changes
            .iter()
            .map(|v| format!("{:.4}%", 100.0 * v))
            .collect::<Vec<_>>()
    );
    assert!(
        r > 1.0 && *changes.last().unwrap() < 1e-3,
        "{name}: P mesh part {changes:?}"
    );
    for (q, what) in [(1, "p0"), (2, "c")] {
        // Local relations within 0.5 % on the finest mesh at every position.
        assert!(worst(finest, q) < 5e-3, "{name}: {what} {finest:?}");
        // Convergence: the RMS error over the positions falls at least as h^1 (the edge is
        // located by a fit across nodes; h^1 is what a nodal contact edge guarantees).
        let errors: Vec<f64> = e.iter().map(|v| rms(v, q)).collect();
        let r = rate(&errors);
        println!(
            "{name}: {what} RMS errors {:?}, rate {r:.2}",
            errors
                .iter()
                .map(|v| format!("{:.4}%", 100.0 * v))
                .collect::<Vec<_>>()
        );
        assert!(r > 1.0, "{name}: {what} rate {r}");
    }
}

#[test]
fn paper_spheres_converge_to_hertz() {
    let deltas: Vec<f64> = std::iter::once(0.0)
        .chain((0..11).map(|k| 5.0 + 1.5 * f64::from(k)))
        .collect();
    let e = ladder(paper(), &deltas, &[5.0, 10.0, 20.0, 40.0]);
    assert_hertz(&e, "paper spheres");
}

/// The finer ladder, with the split of the P error against mdr-domain into what refining the
/// pole leaves (Richardson extrapolation of P in h at each position, with the measured rate)
/// and the pole's mesh part.
/// Run: `cargo test --release --test suite fem_hertz:: -- --ignored --nocapture` (about 10 s).
#[test]
#[ignore]
fn paper_spheres_finer_ladder_and_domain_part_of_p() {
    let deltas: Vec<f64> = std::iter::once(0.0)
        .chain((0..11).map(|k| 5.0 + 1.5 * f64::from(k)))
        .collect();
    let e = ladder(paper(), &deltas, &[10.0, 20.0, 40.0, 80.0]);
    assert_hertz(&e, "paper spheres (finer)");
    let changes: Vec<f64> = e
        .windows(2)
        .map(|w| {
            (w[0]
                .iter()
                .zip(&w[1])
                .map(|(a, b)| (a[0] - b[0]).powi(2))
                .sum::<f64>()
                / w[0].len() as f64)
                .sqrt()
        })
        .collect();
    let k = rate(&changes[1..]);
    let factor = 2f64.powf(k) - 1.0;
    for (position, (fine, coarse)) in e[3].iter().zip(&e[2]).enumerate() {
        let extrapolated = fine[0] + (fine[0] - coarse[0]) / factor;
        println!(
            "δn = {:4.1} µm: P error {:+.4} % at c/80 = far field {:+.4} % + pole mesh {:+.4} %",
            deltas[position + 1],
            100.0 * fine[0],
            100.0 * extrapolated,
            100.0 * (fine[0] - extrapolated)
        );
        // Reason: refining the pole only leaves fem-axisym's coarse far field (growth 0.25), 2.4 %
        // off in the hemisphere's λ_n: ≈ 1.3e-4 of P (tests/domain_compliance.rs); the domain's
        // own offset (2.6e-3 … 5.8e-3) must be gone.
        assert!(
            extrapolated.abs() < 3e-4,
            "left after the pole's refinement {extrapolated}"
        );
    }
}

#[test]
fn steel_ball_on_aluminium_flat_converges_to_hertz() {
    let deltas: Vec<f64> = std::iter::once(0.0)
        .chain((0..11).map(|k| 2.0 + 0.6 * f64::from(k)))
        .collect();
    let e = ladder(ball_on_flat(), &deltas, &[5.0, 10.0, 20.0, 40.0]);
    assert_hertz(&e, "ball on flat");
}

#[test]
fn contact_holds_at_every_candidate_node() {
    // Non-penetration and non-negative forces at the converged active set, at each δn.
    for pair in [paper(), ball_on_flat()] {
        let s = scene(pair, &[0.0, 20.0]);
        let settings: Settings = FemAxisym::with_pole_size(s.max_contact_radius() / 20.0)
            .settings(&s)
            .unwrap();
        let model = Model::generate(&s, &settings).unwrap();
        let mut contact = model.contact(0.0).unwrap();
        for delta in [1e-6, 5e-6, 10e-6, 20e-6, 3e-6, 0.0] {
            contact.advance(model.reduction.approach(delta), &[]).unwrap();
            let scale = model.reduction.approach(delta).abs().max(1e-9);
            for (i, (&f, &g)) in contact.pressure().iter().zip(&contact.gaps()).enumerate() {
                assert!(f >= 0.0, "negative force at node {i}");
                // Exact on the active set (round-off of the dense solve), open elsewhere.
                assert!(g >= -1e-11 * scale, "penetration {g} at node {i}");
                assert!(
                    f == 0.0 || g.abs() <= 1e-11 * scale,
                    "complementarity at node {i}"
                );
            }
        }
    }
}
