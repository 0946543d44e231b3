//! From contact ring forces to the pressure profile p(r), the peak pressure p0 and the contact
//! radius c.
//!
//! Nodal pressure: p_i = λ_i / w_i with w_i = 2π ∫ N_i r ds the ring force a unit pressure puts
//! on node i (positive except on the axis, where r = 0 makes it vanish: the axis node's force
//! says nothing about the pressure there, the known unreliability of nodal pressure at the axis
//! of axisymmetric models).
//!
//! p0 is therefore a fit, not a nodal value: p(r) is smooth and even in r inside the contact, so
//! p = a₀ + a₁ (r/c)² + a₂ (r/c)⁴ is fitted by least squares to the nodal pressures with
//! 0 < r ≤ c/2 and p0 = a₀. The fit assumes smoothness, not Hertz's shape.
//!
//! c: near the edge of a smooth contact p ∝ √(c − r) (Johnson 1985, §4.2), so p² is a smooth
//! function of r with a simple zero at c. A quadratic p² = a + b t + d t², t = r − r_last, is
//! fitted by least squares to the last [`EDGE_NODES`] loaded nodes and c is its zero, kept
//! between the last loaded and the first open node (a line when fewer than six nodes are
//! loaded). A band of nodes averages out the node-to-node scatter of nodal contact forces at the
//! edge; the quadratic term removes the bias a line has from the curvature of p² (measured on
//! the paper's spheres at h0 = 25 µm: 0.02–0.12 % against 0.04–0.28 % for a line over 8 nodes).

use faer::linalg::solvers::Solve;
use faer::{Col, Mat, Side};

/// Loaded nodes at the edge that the contact radius is fitted to.
pub const EDGE_NODES: usize = 16;

/// The recovered pressure at one approach.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Profile {
    /// Nodal pressure p_i [Pa] (the axis node carries the fitted p0).
    pub pressure: Vec<f64>,
    /// Peak pressure p0 [Pa]; `None` when fewer than two loaded nodes lie within c/2.
    pub peak: Option<f64>,
    /// Contact radius c [m]; `None` when only the axis node is loaded.
    pub radius: Option<f64>,
}

/// Recovers the profile from the forces λ at nodes of radii `radii` with ring weights `weights`.
pub fn recover(radii: &[f64], weights: &[f64], forces: &[f64]) -> Profile {
    let mut pressure: Vec<f64> = forces
        .iter()
        .zip(weights)
        .map(|(&f, &w)| if w > 0.0 { f / w } else { 0.0 })
        .collect();
    let Some(last) = forces.iter().rposition(|&f| f > 0.0) else {
        return Profile {
            pressure,
            peak: Some(0.0),
            radius: Some(0.0),
        };
    };
    let radius = contact_radius(radii, &pressure, last);
    let peak = radius.and_then(|c| peak_pressure(radii, &pressure, forces, c));
    if let (Some(p0), Some(first)) = (peak, weights.iter().position(|&w| w <= 0.0)) {
        pressure[first] = p0;
    }
    Profile {
        pressure,
        peak,
        radius,
    }
}

/// c from the zero of the least-squares quadratic (or line) in r through the last loaded nodes.
fn contact_radius(radii: &[f64], pressure: &[f64], last: usize) -> Option<f64> {
    let first = (last + 1).saturating_sub(EDGE_NODES).max(1);
    if last < first + 1 {
        return None;
    }
    let r_last = radii[last];
    let t: Vec<f64> = (first..=last).map(|i| radii[i] - r_last).collect();
    let values: Vec<f64> = (first..=last).map(|i| pressure[i].powi(2)).collect();
    let zero = if t.len() >= 6 {
        let rows: Vec<[f64; 3]> = t.iter().map(|&t| [1.0, t, t * t]).collect();
        least_squares(&rows, &values).and_then(|[a, b, d]| nearest_root(a, b, d))
    } else {
        let rows: Vec<[f64; 2]> = t.iter().map(|&t| [1.0, t]).collect();
        least_squares(&rows, &values).and_then(|[a, b]| (b < 0.0).then(|| -a / b))
    };
    let open = radii.get(last + 1).copied().unwrap_or(f64::INFINITY);
    Some(zero.map_or(open, |t| r_last + t).clamp(r_last, open))
}

/// The root of a + b t + d t² nearest t = 0 (the last loaded node), if real.
fn nearest_root(a: f64, b: f64, d: f64) -> Option<f64> {
    if d == 0.0 {
        return (b != 0.0).then(|| -a / b);
    }
    let disc = b * b - 4.0 * a * d;
    if disc < 0.0 {
        return None;
    }
    // Numerically stable pair of roots (Press et al. 2007, §5.6).
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let roots = [q / d, if q != 0.0 { a / q } else { 0.0 }];
    roots.into_iter().min_by(|x, y| x.abs().total_cmp(&y.abs()))
}

/// Least-squares coefficients of `N` basis functions sampled in `rows` against `values`.
pub(crate) fn least_squares<const N: usize>(rows: &[[f64; N]], values: &[f64]) -> Option<[f64; N]> {
    // The normal equations AᵀA x = Aᵀv: N ≤ 3 well-scaled columns, by faer's dense Cholesky.
    let normal = Mat::from_fn(N, N, |i, j| rows.iter().map(|r| r[i] * r[j]).sum::<f64>());
    let mut rhs = Col::from_fn(N, |i| rows.iter().zip(values).map(|(r, v)| r[i] * v).sum::<f64>());
    normal.llt(Side::Lower).ok()?.solve_in_place(rhs.as_mat_mut());
    Some(std::array::from_fn(|i| rhs[i]))
}

/// p0 = a₀ of the least-squares fit a₀ + a₁ x + a₂ x², x = (r/c)², over loaded nodes with
/// 0 < r ≤ c/2 (fewer terms when fewer nodes).
pub fn peak_pressure(radii: &[f64], pressure: &[f64], forces: &[f64], c: f64) -> Option<f64> {
    let samples: Vec<(f64, f64)> = radii
        .iter()
        .zip(pressure)
        .zip(forces)
        .filter(|((&r, _), &f)| r > 0.0 && r <= 0.5 * c && f > 0.0)
        .map(|((&r, &p), _)| ((r / c).powi(2), p))
        .collect();
    let values: Vec<f64> = samples.iter().map(|s| s.1).collect();
    match samples.len() {
        0 | 1 => None,
        2..=4 => {
            let rows: Vec<[f64; 2]> = samples.iter().map(|&(x, _)| [1.0, x]).collect();
            least_squares(&rows, &values).map(|a| a[0])
        }
        _ => {
            let rows: Vec<[f64; 3]> = samples.iter().map(|&(x, _)| [1.0, x, x * x]).collect();
            least_squares(&rows, &values).map(|a| a[0])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_hertz_profile_from_consistent_ring_forces() {
        // Nodes every 0.01 on a flat surface, Hertz pressure with c = 0.503, p0 = 2.
        let radii: Vec<f64> = (0..80).map(|i| 0.01 * f64::from(i)).collect();
        let (c, p0) = (0.503, 2.0);
        let p = |r: f64| {
            if r < c {
                p0 * (1.0 - (r / c).powi(2)).sqrt()
            } else {
                0.0
            }
        };
        // Lumped weights 2π r Δr (2π r Δr / 2 at the ends), zero on the axis.
        let weights: Vec<f64> = radii
            .iter()
            .map(|r| 2.0 * std::f64::consts::PI * r * 0.01)
            .collect();
        let forces: Vec<f64> = radii.iter().zip(&weights).map(|(r, w)| p(*r) * w).collect();
        let profile = recover(&radii, &weights, &forces);
        // Edge: p² = p0² (c − r)(c + r)/c² is a quadratic in r: the fit is exact up to round-off
        // (and the cubic-free form), so c is recovered to 1e-9.
        assert!((profile.radius.unwrap() - c).abs() < 1e-9, "{:?}", profile.radius);
        // Fit of √(1 − x) by a quadratic in x on x ≤ 1/4: error ≈ the cubic term, 1e-4 of p0.
        assert!(
            (profile.peak.unwrap() - p0).abs() < 2e-4 * p0,
            "{:?}",
            profile.peak
        );
        assert_eq!(profile.pressure[0], profile.peak.unwrap());
    }

    #[test]
    fn only_the_axis_node_loaded_gives_no_radius_and_no_peak() {
        let profile = recover(&[0.0, 1.0, 2.0], &[0.0, 1.0, 1.0], &[1.0, 0.0, 0.0]);
        assert_eq!((profile.radius, profile.peak), (None, None));
    }
}
