//! What people and machines read: the check table on the terminal, per-solver CSV and JSON
//! files, and JUnit XML for CI.

pub mod bench;
pub mod claims;
pub mod compare;
pub mod dem_scoreboard;
pub mod discretisation;
pub mod document;
pub mod figures;
pub mod glance;
pub mod history_files;
pub mod junit;
pub mod paper;
pub mod paper_numbers;
pub mod plot;
pub mod summary;
pub mod table;

/// Formats a value for people: four significant digits in scientific notation, "—" when absent,
/// and never "NaN" (a non-finite value prints as what it is).
pub fn format_value(value: Option<f64>) -> String {
    match value {
        None => "—".to_owned(),
        Some(v) if v.is_nan() => "non-finite".to_owned(),
        Some(v) if v.is_infinite() => if v > 0.0 { "inf" } else { "-inf" }.to_owned(),
        Some(v) => format!("{v:.4e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn never_prints_nan() {
        assert_eq!(format_value(Some(f64::NAN)), "non-finite");
        assert_eq!(format_value(Some(f64::INFINITY)), "inf");
        assert_eq!(format_value(None), "—");
        assert_eq!(format_value(Some(803.76)), "8.0376e2");
    }
}
