//! Hertz's closed forms of the elastic normal impact of two spheres (Johnson 1985, §11.4):
//! with the approach speed v, the effective mass m*, radius R* and modulus E*,
//!
//! ```text
//! δ_max = (15 m* v² / (16 E* √R*))^{2/5}
//! P_max = 4/3 E* √R* δ_max^{3/2}
//! t_c   = 2 I δ_max / v,  I = ∫₀¹ (1 − x^{5/2})^{−1/2} dx = (2/5) B(2/5, 1/2) = 1.4716375…
//!       = 2.8682657 (m*² / (R* E*² v))^{1/5}        (Chung & Ooi's 2.868)
//! ```
//! and the restitution of the elastic impact is 1.

use crate::impact::problem::Point;
use spherecontact_model::hertz::Hertz;

/// 2 (2/5) B(2/5, 1/2) = 2.943275184…: t_c = this × δ_max / v.
/// (B(2/5, 1/2) = Γ(2/5) Γ(1/2) / Γ(9/10), evaluated to 16 digits.)
pub const DURATION_FACTOR: f64 = 2.943_275_184_324_705;

/// The closed-form outcome of an elastic normal impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HertzImpact {
    /// Contact duration t_c [s].
    pub duration: f64,
    /// Largest overlap δ_max [m].
    pub max_overlap: f64,
    /// Largest force P_max [N].
    pub max_force: f64,
}

impl HertzImpact {
    /// The closed forms for the normal part of `point` (its approach speed, masses and pair).
    pub fn of(point: &Point, hertz: &Hertz) -> Self {
        let v = point.approach_speed();
        let m = point.effective_mass();
        let (e, r) = (hertz.effective_modulus, hertz.effective_radius);
        let max_overlap = (15.0 * m * v * v / (16.0 * e * r.sqrt())).powf(0.4);
        Self {
            duration: DURATION_FACTOR * max_overlap / v,
            max_overlap,
            max_force: hertz.force(max_overlap),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_duration_factor_is_the_integral_and_chung_and_oois_constant() {
        // ∫₀¹ (1 − x^{5/2})^{−1/2} dx with x = 1 − s² (dx = −2s ds), which removes the end
        // singularity: ∫₀¹ 2s / √(1 − (1 − s²)^{5/2}) ds, a smooth integrand (2/√(5/2) at s = 0),
        // by the midpoint rule on 100 000 cells (error ~ 1e-10).
        let n = 100_000;
        let width = 1.0 / n as f64;
        let integral: f64 = (0..n)
            .map(|i| {
                let s = (i as f64 + 0.5) * width;
                width * 2.0 * s / (1.0 - (1.0 - s * s).powf(2.5)).sqrt()
            })
            .sum();
        assert!(
            (2.0 * integral - DURATION_FACTOR).abs() < 1e-8,
            "{}",
            2.0 * integral
        );
        // Chung & Ooi's 2.868 = (15/16)^{2/5} × the factor (to their 4 digits).
        assert!(((15.0_f64 / 16.0).powf(0.4) * DURATION_FACTOR - 2.868).abs() < 5e-4);
    }
}
