//! `fem-axisym`'s tangential path (Fourier mode n = 1 on the shared contact engine) against the
//! finite-body reference `mdr-domain` (MDR in series with the hemisphere's computed compliances):
//! Q and the stick radius on the Cattaneo path with Masing loops and along the paper's path, the
//! error falling under refinement; μ = 0, dissimilar bodies and separation; the slip field and the
//! n = 1 displacement. Run: `cargo test --test suite fem_friction:: -- --nocapture` (about 30 s in the dev
//! profile); the whole paper path (1101 steps) on the ladder c/10 … c/80, heavy in the dev
//! profile: `cargo test --release --test suite fem_friction:: -- --ignored --nocapture` (about 10 s).

use crate::common;

use common::friction::{self, worst_q};
use common::paper_scene_with_path;
use spherecontact::fem::axisym::model::Model;
use spherecontact::fem::axisym::output_n1;
use spherecontact::fem::{FemAxisym, MdrDomain};
use spherecontact::history::{History, TangentialComponents};
use spherecontact::report::history_files::fields_to_csv;
use spherecontact::scene::Scene;
use spherecontact::solver::run;

fn cattaneo() -> Scene {
    friction::cattaneo(30)
}

/// Worst |stick radius − reference| over the steps in partial slip (0 < |Q| < 0.99 μP, both
/// stick radii positive), absolute [m].
fn worst_stick(h: &History, reference: &History, friction: f64) -> f64 {
    h.steps
        .iter()
        .zip(&reference.steps)
        .filter(|(_, b)| {
            let (q, p) = (
                b.tangential_force.unwrap_or(0.0).abs(),
                b.normal_force.unwrap_or(0.0),
            );
            q > 0.0 && q < 0.99 * friction * p
        })
        .map(|(a, b)| (a.stick_radius.unwrap() - b.stick_radius.unwrap()).abs())
        .fold(0.0, f64::max)
}

/// fem-axisym on the ladder c_max/10, c_max/20, c_max/40 along `scene`'s path, each rung's stick
/// radius held within `elements` contact-line elements of the reference's, its Q error and raw
/// offset printed under `label`.
fn ladder(label: &str, scene: &Scene, reference: &History, plain: &History, elements: f64) -> Vec<History> {
    let c = scene.max_contact_radius();
    [10.0, 20.0, 40.0]
        .iter()
        .map(|&n| {
            let h = run(&FemAxisym::with_pole_size(c / n), scene).unwrap();
            let stick = worst_stick(&h, reference, scene.friction);
            println!(
                "{label}, pole c/{n}: Q − mdr-domain {:.3e} of peak (raw, against plain MDR: {:.3e}); \
                 stick radius within {:.2} elements",
                worst_q(&h, reference),
                worst_q(&h, plain),
                stick / (c / n)
            );
            // Reason: see the callers (the stick radius is fit::stick's c √(stick area/contact
            // area) of the nodes' ring weights, the reference's edge the exact one).
            assert!(
                stick <= elements * c / n,
                "{label}, pole c/{n}: stick radius off by {stick:e} m"
            );
            h
        })
        .collect()
}

#[test]
fn q_on_the_cattaneo_path_converges_and_meets_the_finite_body_reference() {
    let scene = cattaneo();
    let reference = run(&MdrDomain::default(), &scene).unwrap();
    let plain = run(&spherecontact::analytic::mdr::Mdr::default(), &scene).unwrap();
    // The stick edge lies between the last sticking and the first slipping node: one element.
    let ladder = ladder("Cattaneo path", &scene, &reference, &plain, 1.0);
    // Measured order 1.14 (1.09e-3, then 4.9e-4 of the peak).
    friction::assert_first_order("Cattaneo path", &ladder);
    // Against the reference: the bound is 5e-3 of the peak at c_max/40. What is left
    // (1.1e-3, constant under refinement of the pole and of the far field) is the reference's
    // own first-order error: it puts the domain's correction field Δu(r) in series as one
    // spring, but Δu varies over the contact (λ_t 2.5 % larger at the pole than its load-weighted
    // mean), which moves the stick edge: Q · 2Δλ_t / δs ≈ 6e-4 … 1e-3 of μP.
    let e = worst_q(&ladder[2], &reference);
    assert!(e < 3e-3, "Q error at c/40: {e:e}");
    // The raw offset from the half-space (plain MDR) is the domain's, far above the error.
    let raw = worst_q(&ladder[2], &plain);
    assert!(raw > 10.0 * e, "raw {raw:e} against corrected {e:e}");
}

#[test]
fn q_along_the_paper_path_converges_and_meets_the_finite_body_reference() {
    // The paper's path at 10 increments a segment (111 steps: rising and falling load, partial
    // slip, gross sliding, reversal, separation), every step judged, on the ladder c/10, c/20,
    // c/40 (the whole 1101-step path to c/80 is the ignored test below).
    let scene = common::paper_scene_with_substeps(10);
    let reference = run(&MdrDomain::default(), &scene).unwrap();
    let plain = run(&spherecontact::analytic::mdr::Mdr::default(), &scene).unwrap();
    // The stick edge is a band up to four elements wide in which the corners stick and the
    // midsides slip, counted at the corners' third of its ring weight (cases/paper-fig7.toml,
    // fit::stick): two elements; measured 0.85, 0.74, 1.08 elements at c/10, c/20, c/40.
    let ladder = ladder("paper path", &scene, &reference, &plain, 2.0);
    // Measured order 2.10 (2.5e-3, then 5.8e-4 of the peak), as on the whole path.
    friction::assert_first_order("paper path", &ladder);
    // Reason: the bound, 0.5 % of the peak |Q| at pole size c_max/40, at every step.
    let e = worst_q(&ladder[2], &reference);
    assert!(e < 5e-3, "{e:e}");
    assert!(
        ladder[2].metadata.extra["fourier_modes"] == serde_json::json!([0, 1]),
        "{:?}",
        ladder[2].metadata.extra
    );
}

#[test]
fn without_friction_q_is_zero_exactly() {
    let mut scene = cattaneo();
    scene.friction = 0.0;
    let h = run(
        &FemAxisym::with_pole_size(scene.max_contact_radius() / 10.0),
        &scene,
    )
    .unwrap();
    assert!(h.steps.iter().all(|r| r.tangential_force == Some(0.0)));
    assert_eq!(h.metadata.extra["fourier_modes"], serde_json::json!([0]));
}

#[test]
fn dissimilar_bodies_leave_the_tangential_columns_empty_with_the_reason() {
    // Aluminium 100 mm on steel 50 mm (Dundurs β ≠ 0): the normal and tangential problems
    // couple, which the uncoupled n = 1 model does not capture; the normal problem (both
    // bodies meshed) is still solved.
    let mut scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 2.0)], 4);
    scene.pair.body2 = spherecontact::pair::Body {
        radius: 0.05,
        material: spherecontact::pair::Material {
            young: 210e9,
            poisson: 0.29,
        },
    };
    let h = run(
        &FemAxisym::with_pole_size(scene.max_contact_radius() / 10.0),
        &scene,
    )
    .unwrap();
    assert!(h.steps[1..].iter().all(|r| r.normal_force.unwrap() > 0.0));
    assert!(h
        .steps
        .iter()
        .all(|r| r.tangential_force.is_none() && r.stick_radius.is_none()));
    assert!(h.fields.iter().all(|f| f.traction.is_none() && f.slip.is_none()));
    assert_eq!(h.metadata.extra["fourier_modes"], serde_json::json!([0]));
    assert!(
        h.metadata
            .warnings
            .iter()
            .any(|w| w.contains("dissimilar") && w.contains("Dundurs")),
        "{:?}",
        h.metadata.warnings
    );
}

#[test]
fn separation_clears_the_memory() {
    // Sheared to partial slip, separated with the shift held, re-pressed: nothing shifts after
    // re-contact, so a memory cleared at separation leaves Q = 0 exactly.
    let scene = paper_scene_with_path(
        &[(0.0, 0.0), (17.0, 0.0), (17.0, 2.0), (0.0, 2.0), (17.0, 2.0)],
        10,
    );
    let h = run(
        &FemAxisym::with_pole_size(scene.max_contact_radius() / 10.0),
        &scene,
    )
    .unwrap();
    let at = |p: usize| h.at_position(p).unwrap().tangential_force.unwrap();
    assert!(at(2) > 0.0, "partial slip carries Q");
    assert_eq!(at(3), 0.0, "separated");
    assert_eq!(at(4), 0.0, "re-contact without shift");
}

#[test]
#[ignore = "heavy in the dev profile (the 1101-step paper path four times, to c_max/80): run with --release"]
fn q_along_the_whole_paper_path_converges_under_refinement() {
    // The shipped path (cases/paper-fig7.toml, 100 substeps a segment): every step judged.
    let scene = common::case("cases/paper-fig7.toml").scene;
    let reference = run(&MdrDomain::default(), &scene).unwrap();
    let plain = run(&spherecontact::analytic::mdr::Mdr::default(), &scene).unwrap();
    let c = scene.max_contact_radius();
    let ladder: Vec<History> = [10.0, 20.0, 40.0, 80.0]
        .iter()
        .map(|&n| {
            let h = run(&FemAxisym::with_pole_size(c / n), &scene).unwrap();
            println!(
                "pole c/{n}: {} steps, Q − mdr-domain {:.3e} of peak (raw, against plain MDR: {:.3e})",
                h.steps.len(),
                worst_q(&h, &reference),
                worst_q(&h, &plain)
            );
            h
        })
        .collect();
    let changes: Vec<f64> = ladder.windows(2).map(|w| worst_q(&w[0], &w[1])).collect();
    println!("Q change per halving: {changes:?} of peak");
    // Reason: Q's own change per halving of h falls at order ≥ 1 (measured 2.7e-3, 7.9e-4,
    // 1.8e-4: order 1.8 then 2.2): that is the discretisation error's rate; the distance to
    // mdr-domain (3.5e-3, 1.7e-3, 1.17e-3, 1.12e-3) levels off at the reference's own
    // first-order treatment of the domain (≈ 1.1e-3, see the Cattaneo test).
    for w in changes.windows(2) {
        assert!(w[1] <= w[0] / 2.0, "changes {changes:?}");
    }
    // Reason: the bound, 5e-3 of the peak at c_max/40 and beyond.
    for h in &ladder[2..] {
        assert!(worst_q(h, &reference) < 5e-3);
    }
}

/// The paper's spheres pressed to 17 µm and sheared along x to `shifts_um`, fields at every
/// position.
fn sheared(shifts_um: &[f64]) -> Scene {
    let mut positions = vec![(0.0, 0.0), (17.0, 0.0)];
    positions.extend(shifts_um.iter().map(|&t| (17.0, t)));
    paper_scene_with_path(&positions, 20)
}

#[test]
fn the_slip_field_grows_by_the_shift_in_gross_sliding_and_vanishes_where_it_sticks() {
    // δt = 1 µm: partial slip; 5 and 6 µm: gross sliding (from δs = 4.13 µm on).
    let scene = sheared(&[1.0, 5.0, 6.0]);
    let c = scene.max_contact_radius();
    let h = run(&FemAxisym::with_pole_size(c / 20.0), &scene).unwrap();
    let field = |p: usize| h.field_at(p).unwrap();
    let (partial, five, six) = (field(2), field(3), field(4));
    let stick = partial.stick.as_ref().unwrap();
    let slip = partial.slip.as_ref().unwrap();
    let traction = partial.traction.as_ref().unwrap();
    let mut slipping = 0;
    for i in 0..slip.len() {
        if partial.pressure[i] <= 0.0 {
            continue;
        }
        if stick[i] {
            // The direct active-set solve holds the stick condition to round-off.
            assert!(
                slip[i][0].abs() < 1e-15,
                "stick node {i} slipped {:e}",
                slip[i][0]
            );
        } else {
            slipping += 1;
            // Slip along the traction: positive shift, positive q and slip.
            assert!(slip[i][0] > 0.0 && traction[i][0] > 0.0, "node {i}");
        }
        assert_eq!(partial.points[i][1], 0.0, "node {i} samples the x axis");
    }
    assert!(slipping > 0, "partial slip has a slip annulus");
    // In gross sliding the tractions stay at μp while P is held, so every node in contact slides
    // by the whole shift increment, 1 µm relative (round-off of the accumulated sums).
    for i in 0..six.pressure.len() {
        if six.pressure[i] > 0.0 {
            let ds = six.slip.as_ref().unwrap()[i][0] - five.slip.as_ref().unwrap()[i][0];
            assert!((ds - 1e-6).abs() < 1e-12, "node {i}: slip increment {ds:e}");
        }
    }
}

#[test]
fn the_fields_csv_leaves_the_transverse_columns_empty() {
    // The n = 1 model takes the traction along x: q_y and the transverse slip are not solved,
    // so the fields CSV leaves their cells empty (not produced), while q_x and slip_x are filled.
    let scene = sheared(&[1.0]);
    let h = run(
        &FemAxisym::with_pole_size(scene.max_contact_radius() / 10.0),
        &scene,
    )
    .unwrap();
    assert!(h
        .fields
        .iter()
        .all(|f| f.components == TangentialComponents::AlongX));
    let text = fields_to_csv(&h).unwrap();
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header = reader.headers().unwrap().clone();
    let column = |name: &str| header.iter().position(|c| c == name).unwrap();
    let (qx, qy, sx, sy) = (
        column("traction_x"),
        column("traction_y"),
        column("slip_x"),
        column("slip_y"),
    );
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    let sheared_rows: Vec<&csv::StringRecord> = rows.iter().filter(|r| &r[0] == "2").collect();
    assert!(!sheared_rows.is_empty(), "fields at the sheared position");
    for row in &rows {
        assert_eq!((&row[qy], &row[sy]), ("", ""), "row {row:?}");
    }
    for row in sheared_rows {
        assert!(
            row[qx].parse::<f64>().is_ok() && row[sx].parse::<f64>().is_ok(),
            "row {row:?}"
        );
    }
}

#[test]
fn the_n1_displacement_holds_the_sticking_surface_and_the_vtu_files_are_written() {
    // The displacement amplitudes reconstructed from the contact's ring forces: A at a node in
    // contact since the shift began is the surface's slip against the symmetry plane, so it is
    // zero where the node has stuck and equals the engine's accumulated slip where it slipped.
    let scene = sheared(&[1.0]);
    let solver = FemAxisym::with_pole_size(scene.max_contact_radius() / 10.0);
    let settings = solver.settings(&scene).unwrap();
    assert!(
        settings.shear,
        "a sheared scene's settings ask for the mode n = 1"
    );
    let model = Model::generate(&scene, &settings).unwrap();
    let mut contact = model.contact(scene.friction).unwrap();
    let approach = 0.5 * 17e-6;
    contact.advance(approach, &[0.0]).unwrap();
    let increments = 10;
    for _ in 0..increments {
        contact.advance(approach, &[0.5e-6 / increments as f64]).unwrap();
    }
    let body = &model.bodies[0];
    let shear = &model.shear.as_ref().unwrap().bodies[0];
    let u = output_n1::displacement(body, shear, contact.traction(), 0.5e-6);
    let slip = contact.slip();
    let mut worst: f64 = 0.0;
    for (i, &n) in body.candidates.iter().enumerate() {
        if contact.pressure()[i] > 0.0 {
            worst = worst.max((u[n][0] - slip[i]).abs());
        }
    }
    println!("|A − slip| at the contact nodes: {worst:.3e} m of a 0.5 µm shift");
    // Reason: the same linear system solved two ways (condensed, and in full) agrees to the
    // round-off of the factorisation, ε·κ(K) of the displacement (measured 8.5e-22 m, 2e-15 of
    // the shift); 1e-12 of the shift leaves room for the condition number and nothing else.
    assert!(worst < 1e-12 * 0.5e-6, "{worst:e}");
    // The files: the meridian amplitudes and the 3D surface, beside the normal fields.
    let dir = tempfile::tempdir().unwrap();
    let writer = FemAxisym {
        vtu_dir: Some(dir.path().to_path_buf()),
        ..solver
    };
    run(&writer, &scene).unwrap();
    for suffix in ["", "-n1", "-surface"] {
        let path = dir
            .path()
            .join(format!("{}-fem-axisym-2{suffix}.vtu", scene.name));
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(text.contains("<VTKFile"), "{}", path.display());
    }
    let surface = std::fs::read_to_string(
        dir.path()
            .join(format!("{}-fem-axisym-2-surface.vtu", scene.name)),
    )
    .unwrap();
    for array in ["displacement", "pressure", "traction", "stick", "slip_x"] {
        assert!(surface.contains(&format!("Name=\"{array}\"")), "{array}");
    }
}
