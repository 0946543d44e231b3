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
//! c: near the edge of a smooth contact p ∝ √(c − r) (Johnson 1985, §4.2), so p² is linear in r
//! there; c is the zero of the least-squares line through (r, p²) at the last [`EDGE_NODES`]
//! loaded nodes, kept between the last loaded and the first open node. A band of nodes rather
//! than the last two averages out the node-to-node scatter of nodal contact forces at the edge
//! (measured on the paper's spheres: ≤ 0.13 % from the local Hertz relation at h0 ≤ c/37).

use super::contact::cholesky_solve;

/// Loaded nodes at the edge that the contact radius is fitted to.
pub const EDGE_NODES: usize = 8;

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
        return Profile { pressure, peak: Some(0.0), radius: Some(0.0) };
    };
    let radius = contact_radius(radii, &pressure, last);
    let peak = radius.and_then(|c| peak_pressure(radii, &pressure, forces, c));
    if let (Some(p0), Some(first)) = (peak, weights.iter().position(|&w| w <= 0.0)) {
        pressure[first] = p0;
    }
    Profile { pressure, peak, radius }
}

/// c from the zero of the least-squares line p² = a + b r through the last loaded nodes.
fn contact_radius(radii: &[f64], pressure: &[f64], last: usize) -> Option<f64> {
    let first = (last + 1).saturating_sub(EDGE_NODES).max(1);
    if last < first + 1 {
        return None;
    }
    let band: Vec<[f64; 2]> = (first..=last).map(|i| [1.0, radii[i]]).collect();
    let values: Vec<f64> = (first..=last).map(|i| pressure[i].powi(2)).collect();
    let [a, b] = least_squares::<2>(&band, &values)?;
    let open = radii.get(last + 1).copied().unwrap_or(f64::INFINITY);
    let c = if b < 0.0 { -a / b } else { open };
    Some(c.clamp(radii[last], open))
}

/// Least-squares coefficients of `N` basis functions sampled in `rows` against `values`.
fn least_squares<const N: usize>(rows: &[[f64; N]], values: &[f64]) -> Option<[f64; N]> {
    let mut normal = vec![0.0; N * N];
    let mut rhs = vec![0.0; N];
    for (row, v) in rows.iter().zip(values) {
        for i in 0..N {
            rhs[i] += row[i] * v;
            for j in 0..N {
                normal[i * N + j] += row[i] * row[j];
            }
        }
    }
    cholesky_solve(&mut normal, N, &mut rhs).ok()?;
    Some(std::array::from_fn(|i| rhs[i]))
}

/// p0 = a₀ of the least-squares fit a₀ + a₁ x + a₂ x², x = (r/c)², over loaded nodes with
/// 0 < r ≤ c/2 (fewer terms when fewer nodes).
fn peak_pressure(radii: &[f64], pressure: &[f64], forces: &[f64], c: f64) -> Option<f64> {
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
        let p = |r: f64| if r < c { p0 * (1.0 - (r / c).powi(2)).sqrt() } else { 0.0 };
        // Lumped weights 2π r Δr (2π r Δr / 2 at the ends), zero on the axis.
        let weights: Vec<f64> = radii.iter().map(|r| 2.0 * std::f64::consts::PI * r * 0.01).collect();
        let forces: Vec<f64> = radii.iter().zip(&weights).map(|(r, w)| p(*r) * w).collect();
        let profile = recover(&radii, &weights, &forces);
        // Edge: p² = p0² (c − r)(c + r)/c² is linear in r only to first order: a line over the
        // last 8 nodes (width w = 0.07) misses c by about w²/(8c) ≈ 1e-3 (measured 6e-4).
        assert!((profile.radius.unwrap() - c).abs() < 1e-3, "{:?}", profile.radius);
        // Fit of √(1 − x) by a quadratic in x on x ≤ 1/4: error ≈ the cubic term, 1e-4 of p0.
        assert!((profile.peak.unwrap() - p0).abs() < 2e-4 * p0, "{:?}", profile.peak);
        assert_eq!(profile.pressure[0], profile.peak.unwrap());
    }

    #[test]
    fn only_the_axis_node_loaded_gives_no_radius_and_no_peak() {
        let profile = recover(&[0.0, 1.0, 2.0], &[0.0, 1.0, 1.0], &[1.0, 0.0, 0.0]);
        assert_eq!((profile.radius, profile.peak), (None, None));
    }
}
