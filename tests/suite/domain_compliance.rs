//! The modelled domain's compliances relative to the half-space (`fem::axisym::compliance`) and
//! the finite-body reference built on them (`mdr-domain`): converged under uniform mesh
//! refinement, far-field (nearly independent of the contact radius over the paper's path), and
//! explaining `fem-axisym`'s offset from Hertz to within its mesh error.
//!
//! Run: `cargo test --test suite domain_compliance::` (about 20 s in the dev profile); the uniform ladder
//! one level finer (heavy: 1.3 M DOFs): `cargo test --release --test domain_compliance --
//! --ignored --nocapture`.

use crate::common;

use common::{identical_spheres, normal_scene};
use spherecontact::domain::{Domain, DomainKind, Grip};
use spherecontact::fem::axisym::compliance::{BodyCompliance, FiniteBody};
use spherecontact::fem::axisym::model::{grading, Settings, GROWTH};
use spherecontact::fem::axisym::reference::FAR_FIELD_REFINEMENT;
use spherecontact::fem::element::tri6::Integration;
use spherecontact::fem::factor::Ordering;
use spherecontact::fem::mesh::meridian;
use spherecontact::fem::{FemAxisym, MdrDomain};
use spherecontact::memory::{self, Budget};
use spherecontact::pair::{Body, Material};
use spherecontact::scene::Scene;
use spherecontact::solver::run;

/// The paper's sphere.
const BODY: Body = Body {
    radius: 0.1,
    material: Material {
        young: 70e9,
        poisson: 0.3,
    },
};

/// The Hertz contact radius of the paper's spheres (R* = 0.05 m) at approach `delta_um` [µm].
fn contact_radius(delta_um: f64) -> f64 {
    (0.05 * delta_um * 1e-6).sqrt()
}

fn cap() -> Domain {
    Domain {
        kind: DomainKind::Cap { height: 0.02 },
        grip: Grip::Rigid,
        ..Domain::default()
    }
}

/// The body factored on the mesh of pole size c_max/`divisions` (c_max at 20 µm) whose growth
/// is the default divided by `refinement`: `refinement` = k halves every element k-fold.
fn body(domain: Domain, divisions: f64, refinement: f64) -> FiniteBody {
    let c_max = contact_radius(20.0);
    let settings = Settings {
        pole_size: c_max / divisions,
        candidate_radius: 1.25 * c_max,
        ordering: Ordering::Amd,
        integration: Integration::Full,
        domain,
        growth: GROWTH / refinement,
        shear: false,
        contact_radius: c_max,
    };
    let mesh = meridian::graded(&grading(&BODY, &settings, c_max)).unwrap();
    FiniteBody::new(
        mesh,
        BODY.material,
        domain.grip,
        Integration::Full,
        domain.grip == Grip::Rigid,
        &Budget::new("mdr-domain", c_max, settings.pole_size, memory::MERIDIAN),
    )
    .unwrap()
}

/// (λ_n, λ_t) of `b` at the contact radius of `delta_um`.
fn lambdas(b: &FiniteBody, delta_um: f64) -> [f64; 2] {
    let l: BodyCompliance = b.compliance(contact_radius(delta_um)).unwrap();
    [l.normal, l.tangential.unwrap_or(0.0)]
}

/// The uniform ladder h, h/2, h/4 (pole size and growth halved together) from c_max/10: λ at
/// 17 µm for the hemisphere and the cap, rigidly gripped.
fn ladder(domain: Domain, levels: usize) -> Vec<[f64; 2]> {
    (0..levels)
        .map(|k| {
            let f = f64::from(1u32 << k);
            lambdas(&body(domain, 10.0 * f, f), 17.0)
        })
        .collect()
}

#[test]
fn the_compliances_converge_under_uniform_refinement() {
    for (name, domain) in [("hemisphere", Domain::default()), ("cap 20 mm", cap())] {
        let l = ladder(domain, 3);
        for (i, component) in ["normal", "tangential"].iter().enumerate() {
            let (d1, d2) = ((l[1][i] - l[0][i]).abs(), (l[2][i] - l[1][i]).abs());
            println!(
                "{name} λ_{component}: {:+.5e} {:+.5e} {:+.5e} m/N, differences {d1:.2e} {d2:.2e}, order {:.2}",
                l[0][i],
                l[1][i],
                l[2][i],
                (d1 / d2).log2()
            );
            // Reason: the rim where the rigidly gripped face meets the free surface is a corner
            // singularity that pollutes the whole body, so the rate on these coarse levels is
            // about 1 (measured 1.06 for the hemisphere's λ_n; 3 on the next level, the ignored
            // test below); order ≥ 0.8 asserts convergence, not the asymptotic rate.
            assert!(
                d2 <= d1 / 2f64.powf(0.8),
                "{name} λ_{component}: {d1:e} then {d2:e}"
            );
            // And level 2 (what `mdr-domain` uses) moves by < 0.5 % of λ_n from level 1: the
            // offset it explains (≤ 4.5 % of P) is then right to ≤ 2e-4 of P; the cap's λ_t is
            // near zero, so its scale is λ_n too.
            let scale = l[2][i].abs().max(l[2][0].abs());
            assert!(d2 < 5e-3 * scale, "{name} λ_{component}: {d2:e} vs {scale:e}");
        }
    }
}

#[test]
fn the_compliances_are_far_field_nearly_independent_of_the_contact_radius() {
    // The local (half-space) compliances of the contact, per body: dδ/dP = 1/(2 E' c) and the
    // Cattaneo shift per unit Q, (2 − ν)/(8 G c), change by a factor 2 from δn = 5 to 20 µm;
    // the domain's λ must change by a small fraction of them.
    let m = BODY.material;
    let plane = m.young / (1.0 - m.poisson.powi(2));
    let shear = m.young / (2.0 * (1.0 + m.poisson));
    for (name, domain) in [("hemisphere", Domain::default()), ("cap 20 mm", cap())] {
        let b = body(domain, 40.0, 1.0);
        let path: Vec<[f64; 2]> = [5.0, 10.0, 17.0, 20.0].iter().map(|&d| lambdas(&b, d)).collect();
        let c = contact_radius(20.0);
        let local = [1.0 / (2.0 * plane * c), (2.0 - m.poisson) / (8.0 * shear * c)];
        for i in 0..2 {
            let (lo, hi) = path
                .iter()
                .map(|l| l[i])
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    (a.min(v), b.max(v))
                });
            println!(
                "{name} component {i}: λ from {lo:+.4e} to {hi:+.4e} m/N over c = 0.5 … 1 mm; local {:.4e}",
                local[i]
            );
            // Reason: the residual c dependence is the sphere's own curvature near the contact
            // (∝ ln c, about 9 % of the hemisphere's λ over the path); it must stay below 0.5 %
            // of the local compliance (measured ≤ 0.36 %, the hemisphere's λ_t), else λ is not
            // a far-field spring. `mdr-domain` tabulates λ(c) all the same.
            assert!(hi - lo < 5e-3 * local[i], "{name} component {i}: {lo:e} … {hi:e}");
        }
    }
}

/// The paper's spheres at 5, 10, 17 and 20 µm in `domain`, frictionless.
fn normal(domain: Domain) -> Scene {
    let mut scene = normal_scene(identical_spheres(0.1, 70e9, 0.3), &[5.0, 10.0, 17.0, 20.0]);
    scene.friction = 0.0;
    scene.domain = domain;
    scene
}

#[test]
fn the_corrected_reference_explains_fem_axisym_offset_from_hertz() {
    let axial = Domain {
        grip: Grip::Axial,
        ..Domain::default()
    };
    for (name, domain) in [
        ("hemisphere rigid", Domain::default()),
        ("hemisphere axial", axial),
        ("cap 20 mm", cap()),
    ] {
        let scene = normal(domain);
        let reference = run(&MdrDomain::default(), &scene).unwrap();
        let hertz = scene.hertz();
        // fem-axisym at its default mesh, and with its far field refined as the reference's.
        let fine = FemAxisym {
            growth: Some(GROWTH / FAR_FIELD_REFINEMENT),
            ..FemAxisym::default()
        };
        let fems = [
            run(&FemAxisym::default(), &scene).unwrap(),
            run(&fine, &scene).unwrap(),
        ];
        let rows = fems[0]
            .at_positions()
            .zip(fems[1].at_positions())
            .zip(reference.at_positions());
        for ((f, g), r) in rows.filter(|r| r.1.delta_n > 0.0) {
            let p = f.normal_force.unwrap();
            let raw = p / hertz.force(f.delta_n) - 1.0;
            let corrected = p / r.normal_force.unwrap() - 1.0;
            let refined = g.normal_force.unwrap() / r.normal_force.unwrap() - 1.0;
            println!(
                "{name} δn {:4.1} µm: P − Hertz {raw:+.4e}, P − mdr-domain {corrected:+.4e} (far field refined: {refined:+.4e})",
                f.delta_n * 1e6
            );
            // Reason: the domain offset (2.6e-3 … 4.5e-2 here) must be explained to fem-axisym's
            // mesh error at its default mesh (pole c_max/40, growth 0.25): its coarse far field
            // alone is 0.9 to 2.4 % off in λ_n (uniform ladder, examples/domain_compliance.rs),
            // 1.3e-4 to 4e-4 of P (the cap's 4.5 % offset × its 0.9 % far-field λ error); the
            // contact zone's h adds about 1e-4. Measured ≤ 5.3e-4 (the cap at 20 µm).
            assert!(
                corrected.abs() < 6e-4,
                "{name} at {:e}: {corrected:e} (raw {raw:e})",
                f.delta_n
            );
            assert!(
                raw.abs() > 5.0 * corrected.abs(),
                "{name}: the offset must be visible"
            );
            // With the far field refined as the reference's, what is left is the contact zone's
            // h = c_max/40, which moves P by up to 1.2e-4 with where the contact edge falls
            // between nodes (measured 4e-6 … 1.27e-4 here).
            assert!(
                refined.abs() < 1.5e-4,
                "{name} at {:e}: refined {refined:e}",
                f.delta_n
            );
        }
    }
}

#[test]
fn bench_scores_fem_axisym_against_the_corrected_reference_with_the_raw_offset_beside() {
    use spherecontact::bench::{References, Timing, CORRECTED_REFERENCE};
    for (name, domain) in [("hemisphere", Domain::default()), ("cap 20 mm", cap())] {
        let scene = normal(domain);
        let references = References::of(&scene, true).unwrap();
        let score = |history| {
            references.score(Timing {
                solver: "fem-axisym".into(),
                seconds: Vec::new(),
                cpu_seconds: Vec::new(),
                history,
            })
        };
        let rung = score(run(&FemAxisym::default(), &scene).unwrap());
        let (raw, _) = rung.raw.expect("a finite body keeps its raw offset");
        let (corrected, raw) = (rung.normal_error.unwrap(), raw.unwrap());
        println!(
            "{name}: bench P error {corrected:.3e} against {}, raw {raw:.3e} against Hertz",
            rung.reference
        );
        assert_eq!(rung.reference, CORRECTED_REFERENCE);
        // Reason: as in the test above, the corrected error is fem-axisym's mesh error at its
        // default mesh (≤ 6e-4 at these four approaches), the raw one the domain's offset.
        assert!(
            corrected < 6e-4 && raw > 5.0 * corrected,
            "{name}: {corrected:e}, raw {raw:e}"
        );
        // A half-space solver is scored against Hertz as before, with nothing beside.
        let hertz = references.score(Timing {
            solver: "mdr".into(),
            seconds: Vec::new(),
            cpu_seconds: Vec::new(),
            history: run(&spherecontact::analytic::mdr::Mdr::default(), &scene).unwrap(),
        });
        assert!(hertz.raw.is_none() && hertz.reference != CORRECTED_REFERENCE);
    }
}

#[test]
#[ignore = "heavy: the uniform ladder to h/8 (1.3 M DOFs in the mode n = 1); run in --release"]
fn the_compliances_converge_on_a_finer_ladder() {
    for (name, domain) in [("hemisphere", Domain::default()), ("cap 20 mm", cap())] {
        let l = ladder(domain, 4);
        for (i, component) in ["normal", "tangential"].iter().enumerate() {
            let d: Vec<f64> = l.windows(2).map(|w| (w[1][i] - w[0][i]).abs()).collect();
            println!(
                "{name} λ_{component}: {:?}, differences {d:?}",
                l.iter().map(|x| x[i]).collect::<Vec<_>>()
            );
            assert!(d[2] <= d[1], "{name} λ_{component}");
        }
    }
}
