//! The contact engine on dense Boussinesq–Cerruti matrices built from the BEM's influence
//! coefficients: Cattaneo's partial slip converging to the closed form.

use faer::Mat;
use spherecontact::bem::grid::Grid;
use spherecontact::bem::influence::{Kernels, PairCompliance};
use spherecontact::contact::{Contact, DenseCompliance, FrictionSet, Method, Settings};
use spherecontact::hertz::Hertz;
use spherecontact::pair::{Body, ContactPair, Material};

/// The paper's spheres with ν = 0: the Cerruti cross term vanishes and Cattaneo–Mindlin is the
/// exact partial-slip solution of the half-space problem.
fn pair() -> ContactPair {
    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.0,
        },
    };
    ContactPair {
        body1: body,
        body2: body,
    }
}

/// The dense matrix of a kernel in the circulant layout of [`Kernels`] on `grid`.
fn dense(grid: &Grid, kernels: &[&[f64]], components: usize) -> Mat<f64> {
    let (n, len) = (grid.n, grid.len());
    let m2 = 2 * n;
    let at = |kernel: &[f64], i: usize, j: usize| {
        let dx = (i % n) as isize - (j % n) as isize;
        let dy = (i / n) as isize - (j / n) as isize;
        let wrap = |d: isize| d.rem_euclid(m2 as isize) as usize;
        kernel[wrap(dy) * m2 + wrap(dx)]
    };
    Mat::from_fn(components * len, components * len, |r, c| {
        let (cr, i, cc, j) = (r / len, r % len, c / len, c % len);
        at(kernels[cr * components + cc], i, j)
    })
}

/// Q of one partial-slip increment (δn = 17 µm, δt = 0 → 2 µm) on an n × n grid, and μP_Hertz.
fn cattaneo_q(n: usize, method: Method) -> (f64, f64) {
    let pair = pair();
    let hertz = Hertz::of(&pair);
    let (delta, shift, mu) = (17e-6, 2e-6, 0.2);
    let c = hertz.contact_radius(delta);
    let grid = Grid::covering(n, 1.1 * c);
    let compliance = PairCompliance::of(&pair);
    let zz = Kernels::normal(&grid, &compliance);
    let t = Kernels::tangential(&grid, &compliance);
    let weights = vec![grid.panel_area(); grid.len()];
    let normal = DenseCompliance::try_new(dense(&grid, &[&zz], 1), weights.clone(), 1).unwrap();
    let tangential =
        DenseCompliance::try_new(dense(&grid, &[&t.xx, &t.xy, &t.xy, &t.yy], 2), weights, 2).unwrap();
    let r_star = pair.effective_radius();
    let separation = grid
        .centres()
        .iter()
        .map(|[x, y]| (x * x + y * y) / (2.0 * r_star))
        .collect();
    let settings = Settings {
        method,
        normal_tolerance: 1e-10,
        tangential_tolerance: 1e-9,
        seed_stiffness: Some(pair.effective_modulus() / c),
        ..Settings::default()
    };
    let mut contact = Contact::new(normal, separation, settings)
        .unwrap()
        .with_friction(tangential, FrictionSet::Disc, mu)
        .unwrap();
    contact.advance(delta, &[0.0, 0.0]).unwrap();
    contact.advance(delta, &[shift, 0.0]).unwrap();
    (contact.tangential_force(0), mu * hertz.force(delta))
}

/// Cattaneo–Mindlin: δt = 3μP/(16 G* c) [1 − (1 − Q/μP)^{2/3}], inverted for Q.
fn cattaneo_mindlin() -> f64 {
    let pair = pair();
    let hertz = Hertz::of(&pair);
    let (p, c) = (hertz.force(17e-6), hertz.contact_radius(17e-6));
    let mu_p = 0.2 * p;
    let ratio = 16.0 * pair.mindlin_shear_modulus() * c * 2e-6 / (3.0 * mu_p);
    mu_p * (1.0 - (1.0 - ratio).powf(1.5))
}

#[test]
fn cattaneo_partial_slip_on_dense_matrices_converges_to_the_closed_form() {
    let reference = cattaneo_mindlin();
    let mut errors = Vec::new();
    for n in [12, 16, 24] {
        let (q, mu_p) = cattaneo_q(n, Method::Auto);
        let error = (q - reference) / mu_p;
        eprintln!("{n}²: Q = {q:.5} N, C–M {reference:.5} N, error {error:+.3e} of μP");
        errors.push(error.abs());
    }
    // The error falls with the panel size (constant-traction collocation, about second order
    // where the traction is smooth) and is below 0.3 % of μP at 24² (h = c/10).
    assert!(errors[2] < errors[0] && errors[2] < 3e-3, "{errors:?}");
}

#[test]
fn direct_and_iterative_agree_on_a_dense_cattaneo_problem() {
    let (direct, _) = cattaneo_q(12, Method::Direct);
    let (iterative, mu_p) = cattaneo_q(12, Method::Iterative);
    // Both converge to 1e-9 of the traction scale.
    assert!(
        (direct - iterative).abs() < 1e-6 * mu_p,
        "{direct} vs {iterative}"
    );
}

#[test]
fn the_fft_operator_and_the_dense_matrix_give_the_same_contact() {
    use spherecontact::bem::operator::FftCompliance;
    use spherecontact::contact::Compliance;
    // The paper's spheres (ν = 0.3: the Cerruti cross term is in) on 16² panels.
    let mut pair = pair();
    pair.body1.material.poisson = 0.3;
    pair.body2.material.poisson = 0.3;
    let hertz = Hertz::of(&pair);
    let c = hertz.contact_radius(17e-6);
    let grid = Grid::covering(16, 1.1 * c);
    let compliance = PairCompliance::of(&pair);
    let (zz, t) = (
        Kernels::normal(&grid, &compliance),
        Kernels::tangential(&grid, &compliance),
    );
    let weights = vec![grid.panel_area(); grid.len()];
    let dense_normal = DenseCompliance::try_new(dense(&grid, &[&zz], 1), weights.clone(), 1).unwrap();
    let dense_tangential =
        DenseCompliance::try_new(dense(&grid, &[&t.xx, &t.xy, &t.xy, &t.yy], 2), weights, 2).unwrap();
    // The products agree, and so do the columns added to a product.
    let mut fft = FftCompliance::<f64>::tangential(&grid, &compliance);
    let mut matrix = dense_tangential.clone();
    let load: Vec<f64> = (0..2 * grid.len()).map(|k| ((k * 7) % 13) as f64 - 6.0).collect();
    let (mut a, mut b) = (vec![0.0; load.len()], vec![0.0; load.len()]);
    fft.apply(&load, &mut a);
    matrix.apply(&load, &mut b);
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12 * scale));
    // In single precision (the BEM's tangential products): f32 round-off, 6e-8 a rounding, grown
    // by the transforms' log₂(32) = 5 stages and the kernel's sum over 256 panels.
    let mut single = FftCompliance::<f32>::tangential(&grid, &compliance);
    let mut rounded = vec![0.0; load.len()];
    single.apply(&load, &mut rounded);
    let worst = rounded
        .iter()
        .zip(&b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        / scale;
    assert!(worst < 1e-6, "f32 product off by {worst:e} of the largest value");
    fft.add_columns(&[(3, 2.0), (grid.len() + 40, -1.0)], &mut a);
    matrix.add_columns(&[(3, 2.0), (grid.len() + 40, -1.0)], &mut b);
    assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12 * scale));
    // The same contact along a short path: loading, partial slip, reversal.
    let r_star = pair.effective_radius();
    let separation: Vec<f64> = grid
        .centres()
        .iter()
        .map(|[x, y]| (x * x + y * y) / (2.0 * r_star))
        .collect();
    let settings = Settings {
        normal_tolerance: 1e-12,
        tangential_tolerance: 1e-11,
        seed_stiffness: Some(pair.effective_modulus() / c),
        ..Settings::default()
    };
    let mut with_fft = Contact::new(
        FftCompliance::<f64>::normal(&grid, &compliance),
        separation.clone(),
        settings,
    )
    .unwrap()
    .with_friction(
        FftCompliance::<f64>::tangential(&grid, &compliance),
        FrictionSet::Disc,
        0.2,
    )
    .unwrap();
    let mut with_matrix = Contact::new(
        dense_normal,
        separation,
        Settings {
            method: Method::Direct,
            ..settings
        },
    )
    .unwrap()
    .with_friction(dense_tangential, FrictionSet::Disc, 0.2)
    .unwrap();
    let mu_p = 0.2 * hertz.force(17e-6);
    for (delta, shift) in [(17e-6, 0.0), (17e-6, 1e-6), (17e-6, 1e-6), (16e-6, -1.5e-6)] {
        with_fft.advance(delta, &[shift, 0.0]).unwrap();
        with_matrix.advance(delta, &[shift, 0.0]).unwrap();
        let (p, q) = (with_fft.normal_force(), with_fft.tangential_force(0));
        let (p_ref, q_ref) = (with_matrix.normal_force(), with_matrix.tangential_force(0));
        // Tolerance: both solves converge to 1e-11–1e-12 of their scales.
        assert!((p - p_ref).abs() < 1e-9 * p_ref, "P {p} vs {p_ref}");
        assert!((q - q_ref).abs() < 1e-8 * mu_p, "Q {q} vs {q_ref}");
        assert_eq!(with_fft.stick(), with_matrix.stick());
    }
}
