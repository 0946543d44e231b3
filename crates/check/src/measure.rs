//! How far a value is from its reference: the error measures, and MOOSE's `abs_zero`, the
//! magnitude below which a number is zero.

use serde::Serialize;

/// The default [`super::CheckSpec::abs_zero`]: 1e-10 in SI units, MOOSE's default. It is far below any
/// value a check looks at (a force of 1e-10 N, a radius of 1e-10 m, a pressure of 1e-10 Pa,
/// a ratio of 1e-10) and far above the round-off of a zero that a solver computes as a difference
/// (the mortar's −8.8e-22 N at the unloaded step).
pub const ABS_ZERO: f64 = 1e-10;

/// `x`, or 0 when |x| < `abs_zero`.
pub(super) fn zeroed(x: f64, abs_zero: f64) -> f64 {
    if x.abs() < abs_zero {
        0.0
    } else {
        x
    }
}

/// |v − r| / |scale| with MOOSE's `abs_zero`: magnitudes below it are zero, and the denominator
/// is at least it, so the error is finite whatever the reference (never +∞ or NaN); a nonzero
/// value against a zero reference gives |v| / abs_zero, large.
pub fn relative_error(value: f64, reference: f64, scale: f64, abs_zero: f64) -> f64 {
    let difference = (zeroed(value, abs_zero) - zeroed(reference, abs_zero)).abs();
    difference / zeroed(scale, abs_zero).abs().max(abs_zero)
}

/// How the difference between value and reference is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ErrorMeasure {
    /// |v − r| / |r| at each step.
    Relative,
    /// |v − r| / max |r| over the looked-at steps: for quantities that pass through zero.
    RelativeToPeak,
    /// |v − r| in the quantity's unit.
    Absolute,
}

impl ErrorMeasure {
    /// The name used in case files.
    pub fn name(self) -> &'static str {
        match self {
            ErrorMeasure::Relative => "relative",
            ErrorMeasure::RelativeToPeak => "relative-to-peak",
            ErrorMeasure::Absolute => "absolute",
        }
    }

    /// The measure named `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        [
            ErrorMeasure::Relative,
            ErrorMeasure::RelativeToPeak,
            ErrorMeasure::Absolute,
        ]
        .into_iter()
        .find(|m| m.name() == name)
    }
}
