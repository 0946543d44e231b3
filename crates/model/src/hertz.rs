//! Hertz's frictionless normal contact of two elastic spheres (Hertz 1882; Johnson 1985, §4.2).
//!
//! With the effective modulus E* and radius R* of the pair and the total approach δ of the two
//! bodies' far points, the contact radius, force and pressure are
//!
//! ```text
//! c  = √(R* δ)                      (paper Eqn. 2: δ = c²/R*)
//! P  = 4/3 E* √R* δ^{3/2}           (equivalently c = (3PR*/4E*)^{1/3}, paper Eqn. 1)
//! p0 = 3P / (2π c²) = 2 E* c / (π R*)                   (paper Eqn. 6)
//! p(r) = p0 √(1 − r²/c²)  for r < c                     (paper Eqn. 5)
//! ```
//! A gap (δ ≤ 0) gives no contact.

use crate::pair::ContactPair;

/// The Hertz solution of one contact pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hertz {
    /// Effective modulus E* [Pa].
    pub effective_modulus: f64,
    /// Effective radius R* [m].
    pub effective_radius: f64,
}

impl Hertz {
    /// The Hertz solution of `pair`.
    pub fn of(pair: &ContactPair) -> Self {
        Self {
            effective_modulus: pair.effective_modulus(),
            effective_radius: pair.effective_radius(),
        }
    }

    /// Contact radius c = √(R* δ) [m] at approach `delta` [m].
    pub fn contact_radius(&self, delta: f64) -> f64 {
        if delta > 0.0 {
            (self.effective_radius * delta).sqrt()
        } else {
            0.0
        }
    }

    /// Normal force P = 4/3 E* √R* δ^{3/2} [N] at approach `delta` [m].
    pub fn force(&self, delta: f64) -> f64 {
        let c = self.contact_radius(delta);
        // 4/3 E* √R* δ^{3/2} = 4/3 E* c δ, since c = √(R* δ).
        4.0 / 3.0 * self.effective_modulus * c * delta.max(0.0)
    }

    /// Approach δ = (9P² / (16 R* E*²))^{1/3} [m] under normal force `force` [N].
    pub fn approach(&self, force: f64) -> f64 {
        let e = self.effective_modulus;
        (9.0 * force.max(0.0).powi(2) / (16.0 * self.effective_radius * e * e)).cbrt()
    }

    /// Peak pressure p0 = 2 E* c / (π R*) [Pa] at approach `delta` [m].
    pub fn peak_pressure(&self, delta: f64) -> f64 {
        2.0 * self.effective_modulus * self.contact_radius(delta)
            / (std::f64::consts::PI * self.effective_radius)
    }

    /// Pressure p(r) = p0 √(1 − r²/c²) [Pa] at radius `r` [m], approach `delta` [m].
    pub fn pressure(&self, delta: f64, r: f64) -> f64 {
        let c = self.contact_radius(delta);
        if r.abs() >= c {
            return 0.0;
        }
        self.peak_pressure(delta) * (1.0 - (r / c).powi(2)).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// The paper's spheres: E* = 70 GPa / (2 · 0.91), R* = 0.05 m.
    fn paper() -> Hertz {
        Hertz {
            effective_modulus: 70e9 / 1.82,
            effective_radius: 0.05,
        }
    }

    #[test]
    fn paper_spheres_at_17_micrometres_match_independent_numbers() {
        // Reference: the issue's hand-computed values, quoted to 5 significant figures
        // (P = 803.76 N, c = 0.92195 mm, p0 = 451.49 MPa); tolerance: that rounding, 1e-5.
        let h = paper();
        assert_relative_eq!(h.force(17e-6), 803.76, max_relative = 1e-5);
        assert_relative_eq!(h.contact_radius(17e-6), 0.92195e-3, max_relative = 1e-5);
        assert_relative_eq!(h.peak_pressure(17e-6), 451.49e6, max_relative = 1e-5);
    }

    #[test]
    fn approach_inverts_force_and_pressure_integrates_to_force() {
        let h = paper();
        let delta = 12.3e-6;
        assert_relative_eq!(h.approach(h.force(delta)), delta, max_relative = 1e-12);
        // ∫ p 2πr dr over the contact, by the midpoint rule on 20 000 rings (error ~ n^-1.5 at
        // the square-root edge, below 1e-5 here).
        let c = h.contact_radius(delta);
        let n = 20_000;
        let dr = c / n as f64;
        let integral: f64 = (0..n)
            .map(|i| {
                let r = (i as f64 + 0.5) * dr;
                h.pressure(delta, r) * 2.0 * std::f64::consts::PI * r * dr
            })
            .sum();
        assert_relative_eq!(integral, h.force(delta), max_relative = 1e-5);
    }

    #[test]
    fn a_gap_gives_no_contact() {
        let h = paper();
        for delta in [0.0, -1e-6] {
            assert_eq!(h.force(delta), 0.0);
            assert_eq!(h.contact_radius(delta), 0.0);
            assert_eq!(h.peak_pressure(delta), 0.0);
            assert_eq!(h.pressure(delta, 0.0), 0.0);
        }
    }
}
