//! `fem-3d` with a regularised stick (`[fem-3d] stick_slope`, crates/model/src/stick_slope.rs):
//! the elastic slip q/λ before sliding that penalty codes' friction has (CalculiX's stick
//! slope), so that fem-3d can be the same model as `ccx-3d` on the same mesh.

use crate::common::paper_scene_with_path;
use spherecontact::fem::FemSolid3d;
use spherecontact::solver::{self, Solver};
use spherecontact::stick_slope::StickSlope;
use spherecontact::toolchain::{Tool, Toolchain};

/// P and Q at the last position of fem-3d at c_max/2, its stick regularised by `factor` E/h
/// (`None`: exact Coulomb friction).
fn last_forces(factor: Option<f64>) -> [f64; 2] {
    let scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 3.0)], 1);
    let exact = FemSolid3d::with_pole_size(scene.max_contact_radius() / 2.0);
    let solver: Box<dyn Solver> = match factor {
        Some(f) => exact.with_stick_slope(StickSlope::try_new(f).unwrap()).unwrap(),
        None => Box::new(exact),
    };
    let history = solver::run(solver.as_ref(), &scene).unwrap_or_else(|e| panic!("fem-3d: {e}"));
    let last = history.steps.last().unwrap();
    [last.normal_force.unwrap(), last.tangential_force.unwrap()]
}

/// Requirement: the regularised stick converges to exact Coulomb friction at first order in
/// 1/λ, and leaves the normal problem alone. The elastic slip q/λ is a compliance in series with
/// the body's at every sticking point, so the regularised contact is softer in shear (Q below
/// the exact Q) by an offset proportional to 1/λ while it is small: a decade of λ divides it by
/// 10. Reference: the exact Q on the same mesh (the paper's spheres pressed to 17 µm and shifted
/// by 3 µm, partial slip); tolerance on the ratio of the offsets at λ = 10 and 100 E/h: 8.5 to
/// 11, the first order's 10 less the offset's own share at λ = 10 (1.5 % of Q: the series
/// compliance is 1/(1 + offset), and the slip annulus widens as the stick softens; measured
/// 9.32, and 9.77 from 100 to 1000). P is the same to the last bit: the slope enters the
/// tangential operator only.
#[test]
#[ignore = "heavy: three fem-3d runs at c_max/2 (gmsh, factor, path), 3.6 s; .ci/run runs it"]
fn the_regularised_stick_converges_to_coulomb_at_first_order_in_the_slope() {
    if Toolchain::default().require(Tool::Gmsh).is_err() {
        eprintln!("gmsh is not installed, fem-3d is not available: nothing to run");
        return;
    }
    let [p_exact, q_exact] = last_forces(None);
    let [p10, q10] = last_forces(Some(10.0));
    let [p100, q100] = last_forces(Some(100.0));
    assert_eq!((p10, p100), (p_exact, p_exact));
    assert!(
        q10 < q100 && q100 < q_exact,
        "softer the softer the slope: {q10}, {q100}, {q_exact}"
    );
    let ratio = (q_exact - q10) / (q_exact - q100);
    assert!(
        (8.5..=11.0).contains(&ratio),
        "offset ratio per decade {ratio} ({q10}, {q100}, {q_exact} N)"
    );
}
