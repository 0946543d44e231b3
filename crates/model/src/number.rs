//! Numbers for people: in messages short and exact, never a 300-digit decimal; in tables four
//! significant digits, never "NaN".
//!
//! Rust's `{}` prints an `f64` as a plain decimal, so `5e-324` becomes a 324-digit string. [`Short`]
//! prints the shortest text that reads back as the same number: plainly for magnitudes from 1e-3
//! to 1e6, in scientific notation outside (`5e-324`, `1.7e308`, `7e10`).

use std::fmt;

/// An `f64` shown for a reader: `Short(0.25)` is `0.25`, `Short(5e-324)` is `5e-324`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Short(pub f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v == 0.0 || !v.is_finite() || (1e-3..1e6).contains(&v.abs()) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

/// A number as a CSV cell: its shortest round-trip form ([`Short`]: it reads back bit for bit),
/// empty when absent or not finite (a file never holds NaN or ∞). Every results file is written
/// with it, so that what is compared with a stored file or a baseline is the value itself, not
/// its printed digits.
pub fn cell(value: Option<f64>) -> String {
    value
        .filter(|v| v.is_finite())
        .map_or_else(String::new, |v| Short(v).to_string())
}

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
    use super::{cell, format_value, Short};

    #[test]
    fn a_cell_reads_back_bit_for_bit_and_is_empty_when_not_finite() {
        for v in [
            0.1 + 0.2,
            -1.8009997416520088e2,
            5e-324,
            1.7976931348623157e308,
            -0.0,
        ] {
            assert_eq!(
                cell(Some(v)).parse::<f64>().unwrap().to_bits(),
                v.to_bits(),
                "{v}"
            );
        }
        assert_eq!(cell(Some(f64::NAN)), "");
        assert_eq!(cell(Some(f64::NEG_INFINITY)), "");
        assert_eq!(cell(None), "");
    }

    #[test]
    fn never_prints_nan() {
        assert_eq!(format_value(Some(f64::NAN)), "non-finite");
        assert_eq!(format_value(Some(f64::INFINITY)), "inf");
        assert_eq!(format_value(None), "—");
        assert_eq!(format_value(Some(803.76)), "8.0376e2");
    }

    #[test]
    fn extremes_print_in_scientific_notation_and_read_back_exactly() {
        for (v, text) in [
            (5e-324, "5e-324"),
            (-5e-324, "-5e-324"),
            (1.7e308, "1.7e308"),
            (70e9, "7e10"),
            (0.25, "0.25"),
            (-1000.0, "-1000"),
            (0.0, "0"),
            (f64::INFINITY, "inf"),
        ] {
            let shown = Short(v).to_string();
            assert_eq!(shown, text);
            if v.is_finite() {
                assert_eq!(shown.parse::<f64>().unwrap(), v);
            }
        }
    }
}
