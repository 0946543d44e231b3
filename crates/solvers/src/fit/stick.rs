//! The stick zone of a frictional contact state: one measure for every layout of surface values
//! (a radial profile of rings, a grid of panels, the nodes of triangles).
//!
//! # The stick radius
//!
//! The contact zone A and the stick zone S ⊂ A of two spheres are discs of radii c and b
//! (Cattaneo–Mindlin, and after any reversal Mindlin–Deresiewicz), so |S| / |A| = b² / c² and
//!
//! ```text
//! b = c √(|S| / |A|).
//! ```
//!
//! Every layout samples the surface at points j with area weights w_j (a ring: 2π ∫ N_j r ds, or
//! ω_j with the 2π dropped, which cancels; a panel: h²; a node of triangles: ∫ φ_j dA) and flags
//! each point in contact (λ_j > 0) and sticking. The areas are the weighted counts
//! |A| ≈ Σ_{j in contact} w_j and |S| ≈ Σ_{j sticking} w_j, and c is the layout's own fitted
//! contact radius (sub-sample accurate). So:
//! - b = c exactly at full stick (the two counts are equal) and b = 0 in gross sliding;
//! - **b ≤ c always** (every sticking point is in contact): the stick radius never exceeds the
//!   contact radius, at any resolution;
//! - its error is that of counting the stick zone in whole points: the stick edge falls anywhere
//!   between the last sticking and the first slipping point, so b is resolved to the spacing of
//!   the points there (a ring, a panel, a node spacing), plus c's relative error times b;
//! - it assumes no shape of the traction: it holds after reversals and in Masing loops, where the
//!   deficit μp − |q| inside the stick zone is not one square root;
//! - where the zone is ragged or has a hole it reads the sticking area, not its outer edge: a band
//!   of alternating flags counts at the sticking points' share of its weight (quadratic
//!   elements' corners carry a third of a band's ring weight, the midsides two thirds: where the
//!   corners stick, b falls two thirds of the way into the band), and a slipping centre takes
//!   its area off the disc. The outermost sticking point would read both as sticking out to the
//!   band's or the annulus's outer edge.
//!
//! The alternative, the √-edge fit of the deficit μp − |q| = μ p0/c · √(b² − r²) (Cattaneo) like
//! the pressure's at c, resolves b below the spacing in monotonic loading from rest, but after a
//! reversal the deficit has a kink at the previous stick edge inside the zone, and a fit through
//! it is biased by an amount no tolerance can state in advance.
//!
//! # Semi-axes
//!
//! Where the zone departs from a disc (3D solvers; x is the loading direction and every scene is
//! symmetric in y = 0), the semi-axes are those of the ellipse with the stick points' weighted
//! central second moments: an ellipse of semi-axes a_x, a_y has ⟨(x − x̄)²⟩ = a_x²/4 and
//! ⟨y²⟩ = a_y²/4 over its area, so a_x = 2 √⟨(x − x̄)²⟩ and a_y = 2 √⟨y²⟩ (y about the
//! symmetry plane, so a half surface mirrored in y = 0 gives the whole zone's).

/// The stick zone of one contact state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StickZone {
    /// The stick radius b = c √(|S| / |A|) [m] (see the module doc).
    pub radius: f64,
    /// Semi-axes along x and y [m], from the stick points' second moments.
    pub semi_axes: [f64; 2],
}

/// The stick radius b = c √(|S| / |A|) [m] of points with area weights `weights`, in contact where
/// `pressure` > 0 and sticking where also `stick`; 0 when nothing is in contact.
pub fn stick_radius(contact_radius: f64, weights: &[f64], pressure: &[f64], stick: &[bool]) -> f64 {
    let (mut contact, mut sticking) = (0.0, 0.0);
    for ((&w, &p), &s) in weights.iter().zip(pressure).zip(stick) {
        if p > 0.0 {
            contact += w;
            if s {
                sticking += w;
            }
        }
    }
    if contact > 0.0 {
        contact_radius * (sticking / contact).sqrt()
    } else {
        0.0
    }
}

/// The stick zone of points `points` (x, y on the contact plane) with area weights `weights`, in
/// contact where `pressure` > 0 and sticking where also `stick`, whose contact radius is
/// `contact_radius`; `None` when no point sticks.
pub fn stick_zone(
    contact_radius: f64,
    points: &[[f64; 2]],
    weights: &[f64],
    pressure: &[f64],
    stick: &[bool],
) -> Option<StickZone> {
    semi_axes(points, weights, pressure, stick).map(|semi_axes| StickZone {
        radius: stick_radius(contact_radius, weights, pressure, stick),
        semi_axes,
    })
}

/// The stick zone's semi-axes along x and y [m] (see the module doc: the ellipse with the sticking
/// points' weighted central second moments); `None` when no point sticks.
pub fn semi_axes(points: &[[f64; 2]], weights: &[f64], pressure: &[f64], stick: &[bool]) -> Option<[f64; 2]> {
    let sticking: Vec<usize> = (0..points.len())
        .filter(|&j| stick[j] && pressure[j] > 0.0)
        .collect();
    let area: f64 = sticking.iter().map(|&j| weights[j]).sum();
    if area <= 0.0 {
        return None;
    }
    let mean = |f: &dyn Fn(usize) -> f64| sticking.iter().map(|&j| weights[j] * f(j)).sum::<f64>() / area;
    let x_bar = mean(&|j| points[j][0]);
    let xx = mean(&|j| (points[j][0] - x_bar).powi(2));
    let yy = mean(&|j| points[j][1].powi(2));
    Some([2.0 * xx.sqrt(), 2.0 * yy.sqrt()])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square lattice of spacing d over |x|, |y| ≤ 0.5 with unit pressure inside the disc
    /// r < c and stick inside `inside`.
    fn lattice(
        d: f64,
        c: f64,
        inside: impl Fn([f64; 2]) -> bool,
    ) -> (Vec<[f64; 2]>, Vec<f64>, Vec<f64>, Vec<bool>) {
        let n = (0.5 / d).round() as i32;
        let points: Vec<[f64; 2]> = (-n..=n)
            .flat_map(|i| (-n..=n).map(move |k| [f64::from(i) * d, f64::from(k) * d]))
            .collect();
        let pressure = points
            .iter()
            .map(|p| if p[0].hypot(p[1]) < c { 1.0 } else { 0.0 })
            .collect();
        let stick = points.iter().map(|&p| inside(p)).collect();
        (points.clone(), vec![d * d; points.len()], pressure, stick)
    }

    #[test]
    fn full_stick_gives_the_contact_radius_and_gross_sliding_zero() {
        let (points, weights, pressure, _) = lattice(0.01, 0.4, |_| true);
        let all = vec![true; points.len()];
        // The fitted c, whatever the staircase of the counted contact.
        assert_eq!(stick_radius(0.4013, &weights, &pressure, &all), 0.4013);
        let none = vec![false; points.len()];
        assert_eq!(stick_radius(0.4, &weights, &pressure, &none), 0.0);
        assert_eq!(stick_zone(0.4, &points, &weights, &pressure, &none), None);
        assert_eq!(stick_radius(0.4, &weights, &vec![0.0; points.len()], &all), 0.0);
    }

    #[test]
    fn a_central_disc_is_resolved_to_the_spacing_and_never_exceeds_c() {
        let (c, d) = (0.4, 0.01);
        for b in [0.05, 0.17, 0.3, 0.39] {
            let (points, weights, pressure, stick) = lattice(d, c, |p| p[0].hypot(p[1]) < b);
            let zone = stick_zone(c, &points, &weights, &pressure, &stick).unwrap();
            // Counting whole points: the stick and the contact edges each within about a spacing.
            assert!((zone.radius - b).abs() < d, "b = {b}: {zone:?}");
            assert!(zone.radius <= c);
            for a in zone.semi_axes {
                assert!((a - b).abs() < d, "b = {b}: {zone:?}");
            }
        }
    }

    #[test]
    fn an_elliptic_stick_zone_gives_its_semi_axes() {
        // A fine lattice over y ≥ 0 (the row y = 0 at half weight, as a half surface shares it
        // with its mirror image), stick inside the ellipse a = 0.3, b = 0.2 shifted by 0.05 in x.
        let (a, b, d) = (0.3_f64, 0.2_f64, 2e-3);
        let (mut points, mut weights) = (Vec::new(), Vec::new());
        for i in -250..=250 {
            for k in 0..=200 {
                points.push([f64::from(i) * d, f64::from(k) * d]);
                weights.push(if k == 0 { 0.5 * d * d } else { d * d });
            }
        }
        let stick: Vec<bool> = points
            .iter()
            .map(|p| ((p[0] - 0.05) / a).powi(2) + (p[1] / b).powi(2) < 1.0)
            .collect();
        let pressure: Vec<f64> = points.iter().map(|p| f64::from(p[0].hypot(p[1]) < 0.4)).collect();
        let zone = stick_zone(0.4, &points, &weights, &pressure, &stick).unwrap();
        // The lattice's staircase edge: errors of order d/a ≈ 0.7 %.
        assert!((zone.semi_axes[0] / a - 1.0).abs() < 7e-3, "{zone:?}");
        assert!((zone.semi_axes[1] / b - 1.0).abs() < 1e-2, "{zone:?}");
        // The radius: the area of the ellipse, π a b, in the disc of radius 0.4.
        assert!((zone.radius / (a * b).sqrt() - 1.0).abs() < 1e-2, "{zone:?}");
    }

    #[test]
    fn rings_of_a_radial_profile_place_the_edge_between_nodes() {
        // Rings of width d around nodes r_j = j d (weights 2π r_j d, the axis node d²π/4): stick
        // on r < 0.3 + d/2, contact on r < 0.5 + d/2; c fitted at 0.5 + d/2.
        let d = 0.01;
        let radii: Vec<f64> = (0..80).map(|j| f64::from(j) * d).collect();
        let weights: Vec<f64> = radii
            .iter()
            .map(|&r| {
                if r == 0.0 {
                    std::f64::consts::PI * d * d / 4.0
                } else {
                    std::f64::consts::TAU * r * d
                }
            })
            .collect();
        let pressure: Vec<f64> = radii.iter().map(|&r| f64::from(r < 0.5 + 0.5 * d)).collect();
        let stick: Vec<bool> = radii.iter().map(|&r| r < 0.3 + 0.5 * d).collect();
        let b = stick_radius(0.5 + 0.5 * d, &weights, &pressure, &stick);
        // The rings tile the discs exactly: b is the stick rings' outer radius, 0.3 + d/2.
        assert!((b - (0.3 + 0.5 * d)).abs() < 1e-12, "{b}");
    }

    /// The stick radius of a radial profile on quadratic elements of length 2h = 0.02, nodes r_j =
    /// j h (even j corners, odd j midsides), in contact out to c = 0.5 and sticking where
    /// `sticks(j, r_j)`. The ring weights 2π ∫ N_j r dr are 2π r_j 2h/3 at a corner, 2π r_j 4h/3
    /// at a midside, 0 on the axis (Simpson's rule, exact for the linear integrand: they sum to
    /// π r² at a corner), as fem-axisym's.
    fn on_quadratic_rings(sticks: impl Fn(usize, f64) -> bool) -> f64 {
        let (h, c) = (0.01, 0.5);
        let radii: Vec<f64> = (0..80).map(|j| f64::from(j) * h).collect();
        let weights: Vec<f64> = radii
            .iter()
            .enumerate()
            .map(|(j, &r)| std::f64::consts::TAU * r * h * if j % 2 == 0 { 2.0 / 3.0 } else { 4.0 / 3.0 })
            .collect();
        let pressure: Vec<f64> = radii.iter().map(|&r| f64::from(r <= c + 1e-9)).collect();
        let stick: Vec<bool> = radii.iter().enumerate().map(|(j, &r)| sticks(j, r)).collect();
        stick_radius(c, &weights, &pressure, &stick)
    }

    #[test]
    fn a_ragged_stick_edge_counts_at_its_weights_share() {
        // fem-axisym's stick edge on the paper path (step 376, c_max/40): a band of alternating
        // flags, the corners sticking and the midsides slipping. Here stick on r < 0.3, the band
        // 0.3 ≤ r < 0.4 (corners stick), slip out to c = 0.5.
        let b = on_quadratic_rings(|j, r| r < 0.3 - 1e-9 || (r < 0.4 - 1e-9 && j % 2 == 0));
        // The band counts at the corners' third of its area: b is the radius of the disc of that
        // area, √(0.3² + (0.4² − 0.3²)/3) = 0.3367, to the spacing h = 0.01 (measured 0.3305) ...
        let equal_area = (0.09_f64 + (0.16 - 0.09) / 3.0).sqrt();
        assert!((b - equal_area).abs() < 0.01, "{b}");
        // ... where the outermost sticking node, 0.38, reads the band as sticking.
        assert!(b < 0.34, "{b}");
    }

    #[test]
    fn a_slipping_centre_reads_as_the_disc_of_the_sticking_area() {
        // A slip patch r < 0.1 inside a sticking annulus 0.1 ≤ r < 0.3 (c = 0.5): the measure is
        // the disc of the annulus's area, √(0.3² − 0.1²) = 0.2828, to the spacing h = 0.01
        // (measured 0.2786); the outermost sticking node would read 0.29.
        let b = on_quadratic_rings(|_, r| (0.1 - 1e-9..0.3 - 1e-9).contains(&r));
        assert!((b - (0.09_f64 - 0.01).sqrt()).abs() < 0.01, "{b}");
    }
}
