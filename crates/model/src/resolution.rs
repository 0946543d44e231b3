//! A resolution chosen by the user: the values of a case's `[resolution]` table and of
//! `--resolution SOLVER=VALUE`, read by the solver they name.
//!
//! Each solver parses its own values ([`crate::solver::Solver::at_resolution`]); the forms they
//! share live here: a count in a range (`bem = 128` panels a side, `mdr = 16000` springs) and a
//! pole element size (`fem-axisym = "c/80"`, a fraction of the path's largest Hertz contact
//! radius, or a length `"10um"`, `"0.01mm"`, `"1e-5"` in metres). Every form has limits, so that
//! no valid value exhausts the machine ([`crate::limits`]).

use crate::number::Short;
use crate::scene::Scene;

/// Why a resolution value was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ResolutionError {
    /// The solver has nothing to resolve (a closed form, a law on the path's own increments).
    #[error("`{solver}` has no resolution to choose (allowed: {with})")]
    NotResolvable {
        /// The solver named.
        solver: String,
        /// The solvers that have one, in words.
        with: String,
    },
    /// No solver of that name.
    #[error("unknown solver `{solver}`{did_you_mean} (allowed: {known})")]
    UnknownSolver {
        /// The name given.
        solver: String,
        /// "; did you mean `NAME`?" where a known name is near enough to be what was meant, else
        /// empty.
        did_you_mean: String,
        /// The solvers of this build, in words.
        known: String,
    },
    /// The value is not one the solver can take.
    #[error("`{value}` is not a resolution of {solver}: {why} (allowed: {allowed})")]
    Invalid {
        /// The solver named.
        solver: String,
        /// The value as given.
        value: String,
        /// What is wrong with it.
        why: String,
        /// The allowed values, in words.
        allowed: String,
    },
}

impl ResolutionError {
    /// `value` refused by `solver`, whose allowed values are `allowed`.
    pub fn invalid(solver: &str, value: &str, why: impl Into<String>, allowed: impl Into<String>) -> Self {
        Self::Invalid {
            solver: solver.to_owned(),
            value: value.to_owned(),
            why: why.into(),
            allowed: allowed.into(),
        }
    }
}

/// A whole number `min ≤ n ≤ max` (and even when `even`), e.g. panels a side or springs.
pub fn count(
    solver: &str,
    value: &str,
    min: usize,
    max: usize,
    even: bool,
) -> Result<usize, ResolutionError> {
    let parity = if even { "an even number" } else { "a whole number" };
    let allowed = format!("{parity} {min} ≤ n ≤ {max}");
    let why = match value.trim().parse::<i128>() {
        Ok(n) if (min as i128..=max as i128).contains(&n) && (!even || n % 2 == 0) => {
            return usize::try_from(n)
                .map_err(|_| ResolutionError::invalid(solver, value, "out of range", allowed));
        }
        Ok(_) => "out of range",
        Err(_) => "not a whole number",
    };
    Err(ResolutionError::invalid(solver, value, why, allowed))
}

/// The limits of a pole element size, in pole elements per largest contact radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoleLimits {
    /// The finest: c_max / `finest` [m] is the smallest size allowed.
    pub finest: f64,
    /// The coarsest: c_max / `coarsest` [m] is the largest size allowed.
    pub coarsest: f64,
}

/// The length the pole sizes of `scene` are measured against [m]: the path's largest Hertz
/// contact radius c_max, or a hundredth of body 1's radius when the path never closes the gap
/// (the same count of elements over a hundredth of the radius).
pub fn contact_span(scene: &Scene) -> f64 {
    let c_max = scene.max_contact_radius();
    if c_max > 0.0 {
        c_max
    } else {
        scene.pair.body1.radius / 100.0
    }
}

/// A pole element size [m] from `c/N` (N pole elements per largest contact radius) or a length
/// (`10um`, `0.01mm`, `1e-5` in metres), within `limits` for `scene`.
pub fn pole_size(
    solver: &str,
    scene: &Scene,
    value: &str,
    limits: PoleLimits,
) -> Result<f64, ResolutionError> {
    let span = contact_span(scene);
    let (smallest, largest) = (span / limits.finest, span / limits.coarsest);
    let allowed = format!(
        "c/N with {} ≤ N ≤ {}, or a length {} m ≤ h ≤ {} m such as 10um or 0.01mm",
        limits.coarsest,
        limits.finest,
        Short(smallest),
        Short(largest)
    );
    let text = value.trim();
    let size = match text.strip_prefix("c/") {
        Some(divisions) => match divisions.trim().parse::<f64>() {
            Ok(n) if n.is_finite() && n > 0.0 => Ok(span / n),
            _ => Err(format!("`{divisions}` is not a positive number of pole elements")),
        },
        None => parse_length(text),
    };
    let invalid = |why: String| ResolutionError::invalid(solver, value, why, allowed.clone());
    let h = size.map_err(invalid)?;
    // A relative margin of 1e-9 accepts c/320 itself against its own rounding.
    if h < smallest * (1.0 - 1e-9) {
        Err(invalid(format!("{} m is finer than allowed", Short(h))))
    } else if h > largest * (1.0 + 1e-9) {
        Err(invalid(format!("{} m is coarser than allowed", Short(h))))
    } else {
        Ok(h)
    }
}

/// Reads a length such as `20um`, `0.02mm` or `2e-5` (metres) into metres.
pub fn parse_length(text: &str) -> Result<f64, String> {
    let text = text.trim();
    let units = [("um", 1e-6), ("µm", 1e-6), ("μm", 1e-6), ("mm", 1e-3), ("m", 1.0)];
    let (number, scale) = units
        .iter()
        .find_map(|(unit, scale)| text.strip_suffix(unit).map(|n| (n, *scale)))
        .unwrap_or((text, 1.0));
    let value: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("`{text}` is not a length (e.g. 20um, 0.02mm, 2e-5)"))?;
    if value.is_finite() && value > 0.0 {
        Ok(value * scale)
    } else {
        Err(format!("`{text}`: a length must be finite and positive"))
    }
}

/// A `SOLVER=VALUE` pair of `--resolution`, split (the value is the solver's to judge).
pub fn split_option(text: &str) -> Result<(String, String), String> {
    match text.split_once('=') {
        Some((name, value)) if !name.trim().is_empty() && !value.trim().is_empty() => {
            Ok((name.trim().to_owned(), value.trim().to_owned()))
        }
        _ => Err(format!(
            "`{text}` is not SOLVER=VALUE (e.g. bem=128, fem-axisym=c/80, mdr=16000)"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_refuse_what_is_out_of_range() {
        assert_eq!(count("bem", "128", 4, 512, true), Ok(128));
        for bad in [
            "",
            "0",
            "2",
            "513",
            "514",
            "127",
            "-4",
            "1e2",
            "12.0",
            "nan",
            "99999999999999999999999",
        ] {
            assert!(count("bem", bad, 4, 512, true).is_err(), "{bad:?}");
        }
        let message = count("mdr", "0", 1, 9, false).unwrap_err().to_string();
        assert!(message.contains("1 ≤ n ≤ 9"), "{message}");
    }

    #[test]
    fn options_split_at_the_first_equals_sign() {
        assert_eq!(split_option("bem=128"), Ok(("bem".into(), "128".into())));
        assert_eq!(
            split_option(" fem-axisym = c/80 "),
            Ok(("fem-axisym".into(), "c/80".into()))
        );
        for bad in ["bem", "=128", "bem=", " = "] {
            assert!(split_option(bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn lengths_carry_their_units() {
        // Each is 2e-5 m to one rounding of the unit's scale.
        for text in ["20um", "20µm", "0.02mm", "2e-5", "2e-5m"] {
            assert!((parse_length(text).unwrap() - 2e-5).abs() < 1e-20, "{text}");
        }
        for bad in ["", "um", "-1um", "0", "inf", "nan", "1 parsec"] {
            assert!(parse_length(bad).is_err(), "{bad:?}");
        }
    }
}
