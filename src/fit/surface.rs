//! The contact radius c and the peak pressure p0 of a 3D contact state, from the
//! nodal values of the candidate surface (scattered nodes, not rings): the measures of `fem-3d`
//! and of the `fenicsx-3d` deck, which share the surface's contact rule and weights.
//!
//! c: from the second moment of the pressure, ⟨r²⟩ = ∫ p r² dA / ∫ p dA, which for Hertz's
//! profile p0 √(1 − r²/c²) is (2/5) c², so c = √(5 ⟨r²⟩ / 2). An integral, it does not depend on
//! where the discrete contact edge falls between nodes: at pole size c/8 the outermost loaded node
//! lies 2 % inside c and nodal p² fits at the edge scatter by 0.1–6 % with the band chosen
//! (measured against fem-axisym on the paper's spheres), while the moment agrees to 0.12 %. It
//! assumes Hertz's shape of the profile; the finite body departs from it by much less (its c and
//! p0 follow its P as P^(1/3), fem-axisym), and the check against fem-axisym's edge fit, which
//! assumes no shape, bounds what is left. The integrals are exact for the contact rule's
//! interpolation, linear on its triangles (a nodal quadrature Σ w_j p_j r_j² instead put c
//! 0.57 % low at 10 µm with the corner multipliers, c_max/10 apart).
//!
//! p0: the smooth even fit a₀ + a₁ (r/c)² + a₂ (r/c)⁴ to the nodal pressures on 0 < r ≤ c/2, as in
//! the axisymmetric model (`fem::axisym::pressure`): a fit, not the pole node's value.

use crate::fit::profile::peak_pressure;
use crate::quadrature;

/// c and p0 of one contact state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Measures {
    /// Contact radius [m].
    pub radius: Option<f64>,
    /// Peak pressure [Pa]; `None` when fewer than two loaded nodes lie within c/2 off the pole.
    pub peak: Option<f64>,
}

/// c and p0 from the pressures `pressure` at the surface points `points` (x, y, z), linear on
/// `triangles` (the contact rule's interpolation); the axis is x = y = 0.
pub fn measure(points: &[[f64; 3]], triangles: &[[usize; 3]], pressure: &[f64]) -> Measures {
    let radii: Vec<f64> = points.iter().map(|p| p[0].hypot(p[1])).collect();
    let [force, moment] = moments(points, triangles, pressure);
    if force <= 0.0 {
        return Measures {
            radius: Some(0.0),
            peak: Some(0.0),
        };
    }
    let c = (2.5 * moment / force).sqrt();
    Measures {
        radius: Some(c),
        peak: peak_pressure(&radii, pressure, pressure, c),
    }
}

/// ∫ p dA and ∫ p r² dA of the pressure linear on each triangle, on the triangles projected on
/// the contact plane (the surface's slope within the contact is below c/R, a relative area
/// change of (c/R)²/2 < 1e-4 that cancels in ⟨r²⟩), by the degree-4 rule (exact: degree 3).
fn moments(points: &[[f64; 3]], triangles: &[[usize; 3]], pressure: &[f64]) -> [f64; 2] {
    let rule = quadrature::triangle_degree4();
    let mut sums = [0.0; 2];
    for t in triangles {
        let p = t.map(|j| pressure[j].max(0.0));
        if p.iter().all(|&v| v == 0.0) {
            continue;
        }
        let [a, b, c] = t.map(|j| points[j]);
        let jacobian = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
        for q in &rule {
            let hat = [1.0 - q.at[0] - q.at[1], q.at[0], q.at[1]];
            let x = [0, 1].map(|d| hat[0] * a[d] + hat[1] * b[d] + hat[2] * c[d]);
            let value = q.weight * jacobian * (hat[0] * p[0] + hat[1] * p[1] + hat[2] * p[2]);
            sums[0] += value;
            sums[1] += value * (x[0] * x[0] + x[1] * x[1]);
        }
    }
    sums
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_hertz_pressure_sampled_at_scattered_points() {
        // A triangulated square lattice over y ≥ 0 (spacing d, each square cut along a
        // diagonal), Hertz pressure with c = 0.503, p0 = 2.
        let (c, p0, d, n) = (0.503_f64, 2.0, 0.01, 60_usize);
        let id = |i: usize, k: usize| i * (n + 1) + k;
        let mut points = Vec::new();
        for i in 0..=2 * n {
            for k in 0..=n {
                points.push([(i as f64 - n as f64) * d, k as f64 * d, 0.0]);
            }
        }
        let mut triangles = Vec::new();
        for i in 0..2 * n {
            for k in 0..n {
                triangles.push([id(i, k), id(i + 1, k), id(i + 1, k + 1)]);
                triangles.push([id(i, k), id(i + 1, k + 1), id(i, k + 1)]);
            }
        }
        let pressure: Vec<f64> = points
            .iter()
            .map(|p| p0 * (1.0 - (p[0].hypot(p[1]) / c).powi(2)).max(0.0).sqrt())
            .collect();
        let m = measure(&points, &triangles, &pressure);
        // Linear interpolation across the √ edge: error ~ (d/c)^1.5 ≈ 3e-3 at d = 0.01, c = 0.5.
        assert!((m.radius.unwrap() - c).abs() < 3e-3 * c, "{:?}", m.radius);
        // √(1 − x) by a quadratic in x on x ≤ 1/4: the cubic term, ≤ 2e-4 of p0.
        assert!((m.peak.unwrap() - p0).abs() < 2e-4 * p0, "{:?}", m.peak);
    }

    #[test]
    fn no_load_gives_zero_radius_and_peak() {
        let m = measure(
            &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            &[[0, 1, 2]],
            &[0.0; 3],
        );
        assert_eq!((m.radius, m.peak), (Some(0.0), Some(0.0)));
    }
}
