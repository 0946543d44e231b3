//! Helpers of the tests of fem-axisym's tangential path: the Cattaneo path, Q's worst error and
//! its convergence under refinement of the pole size.

use spherecontact::history::{History, Quantity};
use spherecontact::scene::Scene;

/// The Cattaneo path of cases/cattaneo.toml (17 µm, then δt 0 → 6 → −6 → 6 µm: partial slip,
/// gross sliding, two reversals) at `substeps` a segment.
pub fn cattaneo(substeps: usize) -> Scene {
    super::paper_scene_with_path(
        &[(0.0, 0.0), (17.0, 0.0), (17.0, 6.0), (17.0, -6.0), (17.0, 6.0)],
        substeps,
    )
}

/// Worst |Q − Q_ref| over the steps, relative to the reference's peak |Q|.
pub fn worst_q(h: &History, reference: &History) -> f64 {
    let peak = reference.peak(Quantity::TangentialForce);
    h.steps
        .iter()
        .zip(&reference.steps)
        .map(|(a, b)| (a.tangential_force.unwrap() - b.tangential_force.unwrap()).abs() / peak)
        .fold(0.0, f64::max)
}

/// Asserts that Q's change per halving of the pole size falls at order ≥ 1 on a ladder of three
/// rungs (each h half the last): the discretisation error's estimate (the nodal stick edge and
/// pressure are first order at least). Prints the changes and the order under `label`.
pub fn assert_first_order(label: &str, ladder: &[History]) {
    let (d1, d2) = (worst_q(&ladder[0], &ladder[1]), worst_q(&ladder[1], &ladder[2]));
    println!(
        "{label}: Q change per halving {d1:.3e}, {d2:.3e} of peak, order {:.2}",
        (d1 / d2).log2()
    );
    assert!(d2 <= d1 / 2.0, "{label}: Q changes {d1:e} then {d2:e}");
}
