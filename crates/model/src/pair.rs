//! Two elastic bodies in contact and the effective properties every contact model is written in.
//!
//! Body 1 and body 2 are spheres of radius `R1`, `R2` (a flat has `R = ∞`), isotropic and linear
//! elastic with Young's modulus `E` and Poisson ratio `ν`.

use serde::Serialize;

/// An isotropic linear elastic material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Material {
    /// Young's modulus E [Pa].
    pub young: f64,
    /// Poisson ratio ν [-].
    pub poisson: f64,
}

impl Material {
    /// Shear modulus G = E / (2(1 + ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }
}

/// A sphere (or, with an infinite radius, a flat) of one material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Body {
    /// Radius R [m]; `f64::INFINITY` for a flat.
    pub radius: f64,
    /// The body's material.
    pub material: Material,
}

impl Body {
    /// Curvature 1/R [1/m]; zero for a flat.
    pub fn curvature(&self) -> f64 {
        1.0 / self.radius
    }
}

/// Two bodies in contact, with the effective properties of Hertz and Mindlin.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ContactPair {
    /// The first body.
    pub body1: Body,
    /// The second body.
    pub body2: Body,
}

impl ContactPair {
    /// Effective modulus E* = [(1 − ν1²)/E1 + (1 − ν2²)/E2]⁻¹ (Johnson 1985, eq. 4.22).
    ///
    /// The paper prints this (its Eqn. 3) without the −1 exponent; see `reproduce-paper`.
    pub fn effective_modulus(&self) -> f64 {
        let compliance = |m: &Material| (1.0 - m.poisson * m.poisson) / m.young;
        1.0 / (compliance(&self.body1.material) + compliance(&self.body2.material))
    }

    /// Effective radius R* = [1/R1 + 1/R2]⁻¹ (a flat contributes 1/R = 0).
    pub fn effective_radius(&self) -> f64 {
        1.0 / (self.body1.curvature() + self.body2.curvature())
    }

    /// Mindlin's effective shear modulus G* = [(2 − ν1)/G1 + (2 − ν2)/G2]⁻¹.
    ///
    /// With it the initial tangential stiffness of a Hertz contact of radius c is
    /// K_T0 = 8 G* c (Mindlin 1949; the paper's Eqn. 8), which for identical spheres is
    /// 4 c G / (2 − ν).
    pub fn mindlin_shear_modulus(&self) -> f64 {
        let compliance = |m: &Material| (2.0 - m.poisson) / m.shear_modulus();
        1.0 / (compliance(&self.body1.material) + compliance(&self.body2.material))
    }

    /// Dundurs' second parameter β = ½ [(1 − 2ν1)/G1 − (1 − 2ν2)/G2] / [(1 − ν1)/G1 + (1 − ν2)/G2].
    ///
    /// β = 0 means the pair is elastically similar: normal pressure then causes no relative
    /// tangential displacement and shear traction no relative normal displacement, which is the
    /// decoupling that Cattaneo, Mindlin and Deresiewicz (and every DEM law) assume.
    pub fn dundurs_beta(&self) -> f64 {
        let (m1, m2) = (&self.body1.material, &self.body2.material);
        let (g1, g2) = (m1.shear_modulus(), m2.shear_modulus());
        let numerator = (1.0 - 2.0 * m1.poisson) / g1 - (1.0 - 2.0 * m2.poisson) / g2;
        let denominator = (1.0 - m1.poisson) / g1 + (1.0 - m2.poisson) / g2;
        0.5 * numerator / denominator
    }

    /// True when both bodies have the same radius and material (the symmetric two-sphere case).
    pub fn is_symmetric(&self) -> bool {
        self.body1 == self.body2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::paper_pair;
    use approx::assert_relative_eq;

    #[test]
    fn effective_properties_of_the_paper_spheres() {
        let pair = paper_pair();
        // E* = E / (2(1 − ν²)), R* = R/2, G* = G / (2(2 − ν)) for identical spheres.
        assert_relative_eq!(
            pair.effective_modulus(),
            70e9 / (2.0 * 0.91),
            max_relative = 1e-14
        );
        assert_relative_eq!(pair.effective_radius(), 0.05, max_relative = 1e-14);
        let g = 70e9 / 2.6;
        assert_relative_eq!(pair.mindlin_shear_modulus(), g / 3.4, max_relative = 1e-14);
        assert_eq!(pair.dundurs_beta(), 0.0);
        assert!(pair.is_symmetric());
    }

    #[test]
    fn a_flat_contributes_no_curvature() {
        let mut pair = paper_pair();
        pair.body2.radius = f64::INFINITY;
        assert_relative_eq!(pair.effective_radius(), 0.1, max_relative = 1e-14);
    }

    #[test]
    fn dissimilar_materials_have_nonzero_beta() {
        let mut pair = paper_pair();
        pair.body2.material = Material {
            young: 210e9,
            poisson: 0.29,
        };
        let beta = pair.dundurs_beta();
        assert!(beta.abs() > 0.01 && beta.abs() < 0.5, "beta = {beta}");
    }
}
