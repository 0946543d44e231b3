//! The judgement's tail that every check row shows, a path case's and an impact case's alike.

use std::fmt::Write;

use spherecontact_model::number::format_value;

use crate::Drift;

/// Appends ` | tol T` (or ` | informational`), the drift from the baseline when there is one,
/// and ` | message` when there is one.
pub fn push_judgement(
    row: &mut String,
    tolerance: Option<f64>,
    drift: Option<&Drift>,
    message: Option<&str>,
) {
    match tolerance {
        Some(t) => {
            let _ = write!(row, " | tol {}", format_value(Some(t)));
        }
        None => row.push_str(" | informational"),
    }
    if let Some(drift) = drift {
        row.push_str(&drift.cell());
    }
    if let Some(message) = message {
        let _ = write!(row, " | {message}");
    }
}
