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
//! there; c is where the line through (r, p²) at the last two loaded nodes reaches zero, capped
//! at the first open node.

use super::contact::cholesky_solve;

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

/// c from the zero of p² extrapolated from the last two loaded nodes.
fn contact_radius(radii: &[f64], pressure: &[f64], last: usize) -> Option<f64> {
    if last == 0 || radii[last - 1] <= 0.0 {
        return None;
    }
    let open = radii.get(last + 1).copied().unwrap_or(f64::INFINITY);
    let (r1, r2) = (radii[last - 1], radii[last]);
    let (q1, q2) = (pressure[last - 1].powi(2), pressure[last].powi(2));
    let c = if q1 > q2 { r2 + q2 * (r2 - r1) / (q1 - q2) } else { open };
    Some(c.clamp(r2, open))
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
    let terms = match samples.len() {
        0 | 1 => return None,
        2..=4 => 2,
        _ => 3,
    };
    let mut normal = vec![0.0; terms * terms];
    let mut rhs = vec![0.0; terms];
    for &(x, p) in &samples {
        let basis: Vec<f64> = (0..terms).map(|k| x.powi(k as i32)).collect();
        for i in 0..terms {
            rhs[i] += basis[i] * p;
            for j in 0..terms {
                normal[i * terms + j] += basis[i] * basis[j];
            }
        }
    }
    cholesky_solve(&mut normal, terms, &mut rhs).ok()?;
    Some(rhs[0])
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
        // Edge: p² is exactly linear in r² (not r): extrapolation in r errs by ~Δr²/c, ≈ 2e-4.
        assert!((profile.radius.unwrap() - c).abs() < 5e-4, "{:?}", profile.radius);
        // Fit of √(1 − x) by a quadratic in x on x ≤ 1/4: error ≈ the cubic term, 1e-4 of p0.
        assert!((profile.peak.unwrap() - p0).abs() < 2e-4 * p0, "{:?}", profile.peak);
        assert_eq!(profile.pressure[0], profile.peak.unwrap());
    }

    #[test]
    fn only_the_axis_node_loaded_gives_no_radius_and_no_peak() {
        let profile = recover(&[0.0, 1.0], &[0.0, 1.0], &[1.0, 0.0]);
        assert_eq!((profile.radius, profile.peak), (None, None));
    }
}
