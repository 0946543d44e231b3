//! The contact measures agree with themselves: along the paper's path the stick radius never
//! exceeds the contact radius (bem: both from the same edge-fitted contact radius; mdr: the bed's
//! stick edge within Hertz's contact), equals it at full stick, and the BEM reports the slip it
//! computes in its surface fields.
//!
//! Run: `cargo test --test contact_measures`.

use std::path::Path;

use spherecontact::analytic::mdr::Mdr;
use spherecontact::bem::Bem;
use spherecontact::case::Case;
use spherecontact::path::LoadingPath;
use spherecontact::solver::{self, Solver};

/// The paper's case with `substeps` a segment (fewer than the case's, for a fast test).
fn paper(substeps: usize) -> spherecontact::scene::Scene {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/paper-fig7.toml");
    let mut scene = Case::load(&file).unwrap().scene;
    let segments = scene.path.positions().len() - 1;
    scene.path = LoadingPath::try_new(scene.path.positions().to_vec(), vec![substeps; segments]).unwrap();
    scene
}

#[test]
fn the_stick_radius_never_exceeds_the_contact_radius() {
    let scene = paper(4);
    let solvers: [Box<dyn Solver>; 2] = [Box::new(Bem::with_grid(32)), Box::new(Mdr::default())];
    for solver in solvers {
        let history = solver::run(solver.as_ref(), &scene).unwrap();
        let mut full_stick = 0;
        for row in &history.steps {
            let (Some(c), Some(cs)) = (row.contact_radius, row.stick_radius) else {
                continue;
            };
            // No slack: both measures come from one edge (bem) or the stick edge is bounded by
            // the contact radius the model reports (mdr).
            assert!(
                cs <= c,
                "{} step {}: stick {cs} > contact {c}",
                solver.name(),
                row.step
            );
            full_stick += usize::from(cs == c && c > 0.0);
        }
        // The path's first loading is normal only: every point in contact sticks there.
        assert!(full_stick > 0, "{}: no step at full stick", solver.name());
    }
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
