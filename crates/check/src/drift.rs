//! A check's value against its non-regression baseline, and how a row shows it.

use serde::Serialize;

use spherecontact_model::number::format_value;

/// A check's value against the value stored in its baseline.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Drift {
    /// Compared at the baseline's step.
    Measured {
        /// The value stored.
        baseline: f64,
        /// |value − baseline| / max(|baseline|, |value|, |reference|) at the baseline's step (the
        /// reference's magnitude: a profile's value is a small RMS difference): 0 when equal.
        change: f64,
        /// The largest change accepted for this check's solvers.
        tolerance: f64,
    },
    /// Not comparable: the baseline records another resolution of this solver than the one it
    /// ran at now (the case's resolution changed, or the baseline was edited). A failure until
    /// `baseline update` records the run's.
    OtherResolution {
        /// The solver.
        solver: String,
    },
}

impl Drift {
    /// The drift as a check's row shows it (path and impact checks alike).
    pub fn cell(&self) -> String {
        match self {
            Drift::Measured {
                baseline,
                change,
                tolerance,
            } => format!(
                " | drift {} (baseline {}, tol {})",
                format_value(Some(*change)),
                format_value(Some(*baseline)),
                format_value(Some(*tolerance))
            ),
            Drift::OtherResolution { solver } => format!(
                " | drift: the baseline records another resolution of {solver} than this run's (run \
                 `spherecontact baseline update` if the case's resolution changed)"
            ),
        }
    }
}
