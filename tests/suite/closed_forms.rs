//! Requirement: the closed forms reproduce independent numbers for the paper's spheres
//! (R = 0.1 m, E = 70 GPa, ν = 0.3) at δn = 17 µm: P = 803.76 N, c = 0.92195 mm,
//! p0 = 451.49 MPa, K_T0 = 4cG/(2 − ν) = 5.8404e7 N/m (hand-computed, 5 significant figures:
//! tolerance 1e-5 relative, the rounding of the reference).

use crate::common;

use approx::assert_relative_eq;
use common::{case, paper_scene_with_path, solve};

#[test]
fn hertz_at_17_micrometres() {
    let hertz = case("cases/paper-fig7.toml").scene.hertz();
    assert_relative_eq!(hertz.force(17e-6), 803.76, max_relative = 1e-5);
    assert_relative_eq!(hertz.contact_radius(17e-6), 0.92195e-3, max_relative = 1e-5);
    assert_relative_eq!(hertz.peak_pressure(17e-6), 451.49e6, max_relative = 1e-5);
}

#[test]
fn mindlin_initial_stiffness_at_17_micrometres() {
    let scene = case("cases/paper-fig7.toml").scene;
    let c = scene.hertz().contact_radius(17e-6);
    let k_t0 = 8.0 * scene.pair.mindlin_shear_modulus() * c;
    assert_relative_eq!(k_t0, 5.8404e7, max_relative = 1e-5);
}

#[test]
fn cattaneo_mindlin_starts_at_mindlin_stiffness_and_slides_at_mu_p() {
    // A 1 nm tangential step from rest: the secant stiffness Q/δ equals K_T0 to first order in
    // δ/δs (δs = 4.13 µm, so within 3/4 · δ/δs ≈ 2e-4); the end of the path is gross sliding.
    let scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 0.001), (17.0, 6.0)], 1);
    let history = solve("cattaneo-mindlin", &scene);
    let q = history.at_position(2).unwrap().tangential_force.unwrap();
    assert_relative_eq!(q / 1e-9, 5.8404e7, max_relative = 3e-4);
    let sliding = history.at_position(3).unwrap();
    assert_relative_eq!(
        sliding.tangential_force.unwrap(),
        0.2 * 803.7552,
        max_relative = 1e-6
    );
    assert_eq!(sliding.stick_radius, Some(0.0));
}
