//! fem-3d's regularised stick: Coulomb friction whose sticking points slip elastically, as the
//! penalty codes' friction does (CalculiX's `*FRICTION` stick slope λ, Abaqus's elastic slip),
//! so that fem-3d can be the same model as such a code on the same mesh and the comparison
//! isolates the contact discretisation.
//!
//! The law: while |q| < μp a point's relative tangential displacement of the two surfaces is
//! s = q/λ (the elastic slip; λ [Pa/m]), beyond it the point slides. In the engine's terms the
//! tangential compliance maps the traction multipliers to one body's tangential displacement
//! (the pair's relative slip is twice it, `fem::solid3d::contact` (spherecontact-solvers)), so the elastic slip adds
//! 1/(2λ) to its diagonal: u = (C + I/(2λ)) q. The engine's stick and slip then follow the
//! regularised law unchanged (a point sticks while |q| < μp, and the slip it accumulates is the
//! slip beyond the elastic one). The regularisation is lumped at the corner multipliers, as a
//! node-to-face penalty is.
//!
//! Exact Coulomb friction (no regularisation) is fem-3d's default; a case sets the slope in
//! `[fem-3d] stick_slope` as a factor of E/h (h the pole element size), the unit of CalculiX's
//! `[calculix] penalty`: `ccx-3d`'s λ = K/100 = (penalty/100) E/h on the same mesh.

/// The stick slope as a factor f of E/h: λ = f E/h.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StickSlope {
    factor: f64,
}

/// The factors accepted: from a slope that lets a point slip elastically a thousand times its
/// element's strain (1e-3) to one a million times stiffer than the element (1e6, beyond which
/// the elastic slip is below the engine's tolerance), covering CalculiX's K/100 for every
/// `[calculix] penalty` (1 to 1e6, so 0.01 to 1e4).
pub const RANGE: [f64; 2] = [1e-3, 1e6];

/// A factor outside [`RANGE`].
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("{0} is out of range (allowed: {lo:e} ≤ stick_slope ≤ {hi:e}, λ = stick_slope · E/h)", lo = RANGE[0], hi = RANGE[1])]
pub struct StickSlopeError(pub f64);

impl StickSlope {
    /// The slope f E/h; `factor` within [`RANGE`].
    pub fn try_new(factor: f64) -> Result<Self, StickSlopeError> {
        if (RANGE[0]..=RANGE[1]).contains(&factor) {
            Ok(Self { factor })
        } else {
            Err(StickSlopeError(factor))
        }
    }

    /// The factor f of E/h.
    pub fn factor(self) -> f64 {
        self.factor
    }

    /// λ = f E/h [Pa/m] for Young's modulus `young` [Pa] and pole element size `h` [m].
    pub fn per_metre(self, young: f64, h: f64) -> f64 {
        self.factor * young / h
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors_outside_the_range_are_refused_with_it() {
        assert_eq!(StickSlope::try_new(10.0).unwrap().per_metre(70e9, 1e-4), 7e15);
        for bad in [0.0, -1.0, 1e-4, 2e6, f64::NAN, f64::INFINITY] {
            let e = StickSlope::try_new(bad).unwrap_err().to_string();
            assert!(e.contains("1e-3 ≤ stick_slope ≤ 1e6"), "{e}");
        }
    }
}
