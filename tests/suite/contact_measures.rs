//! The contact measures agree with themselves: along the paper's path the stick radius never
//! exceeds the contact radius on any solver that reports both (bem, fem-axisym, fem-3d: one
//! measure, c √(stick area / contact area), `fit::stick`; mdr: the bed's stick edge within Hertz's
//! contact), equals it at full stick and lies below it in partial slip, and the BEM reports the
//! slip it computes in its surface fields.
//!
//! Run: `cargo test --test suite contact_measures::`.

use std::path::Path;

use spherecontact::analytic::mdr::Mdr;
use spherecontact::bem::Bem;
use spherecontact::case::Case;
use spherecontact::fem::{FemAxisym, FemSolid3d};
use spherecontact::path::LoadingPath;
use spherecontact::solver::{self, Solver};
use spherecontact::toolchain::{Tool, Toolchain};

/// The paper's case with `substeps` a segment (fewer than the case's, for a fast test).
fn paper(substeps: usize) -> spherecontact::scene::Scene {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/paper-fig7.toml");
    let mut scene = Case::load(&file).unwrap().scene;
    let segments = scene.path.positions().len() - 1;
    scene.path = LoadingPath::try_new(scene.path.positions().to_vec(), vec![substeps; segments]).unwrap();
    scene
}

/// Checks a history's stick radii against its contact radii: never above (no slack: the stated
/// discretisation of the shared measure is zero, since it scales the contact radius by the stick
/// zone's share of the contact area, and mdr bounds its stick edge by its contact radius), equal
/// at some step (the first segment is normal only: full stick), strictly between 0 and c at some
/// step (the shift from P1 to P2 is partial slip).
fn check_stick_within_contact(name: &str, history: &spherecontact::history::History) {
    let (mut full_stick, mut partial_slip) = (0, 0);
    for row in &history.steps {
        let (Some(c), Some(cs)) = (row.contact_radius, row.stick_radius) else {
            continue;
        };
        assert!(cs <= c, "{name} step {}: stick {cs} > contact {c}", row.step);
        full_stick += usize::from(cs == c && c > 0.0);
        partial_slip += usize::from(cs > 0.0 && cs < c);
    }
    assert!(full_stick > 0, "{name}: no step at full stick");
    assert!(partial_slip > 0, "{name}: no step in partial slip");
}

#[test]
fn the_stick_radius_never_exceeds_the_contact_radius() {
    let scene = paper(4);
    let solvers: [Box<dyn Solver>; 2] = [Box::new(Bem::with_grid(32)), Box::new(Mdr::default())];
    for solver in solvers {
        let history = solver::run(solver.as_ref(), &scene).unwrap();
        check_stick_within_contact(solver.name(), &history);
    }
}

#[test]
fn the_finite_element_stick_radius_never_exceeds_the_contact_radius() {
    // Coarse meshes (a few seconds each): the bound holds at any resolution.
    let scene = paper(2);
    let c = scene.max_contact_radius();
    let history = solver::run(&FemAxisym::with_pole_size(c / 10.0), &scene).unwrap();
    check_stick_within_contact("fem-axisym", &history);
    if Toolchain::default().require(Tool::Gmsh).is_err() {
        eprintln!("gmsh is not installed, fem-3d is not available: fem-3d not checked");
        return;
    }
    let history = solver::run(&FemSolid3d::with_pole_size(c / 4.0), &scene).unwrap();
    check_stick_within_contact("fem-3d", &history);
}

#[test]
fn the_bem_keeps_the_slip_it_computes() {
    let scene = paper(4);
    let history = solver::run(&Bem::with_grid(32), &scene).unwrap();
    let slipped = history.fields.iter().any(|field| {
        let slip = field.slip.as_ref().expect("bem fields carry the slip");
        assert_eq!(slip.len(), field.points.len());
        slip.iter().any(|s| s[0] != 0.0)
    });
    assert!(slipped, "the paper's path slips somewhere at its positions");
}
