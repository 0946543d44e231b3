//! Surface-field profiles compared: the RMS difference of a solver's p(r) or q_x(r) from a
//! reference solver's over the annulus 0.1 c < r < 0.9 c at one path position, relative to the
//! reference profile's peak (p0 for the pressure; for the traction its largest |q_x|, at most
//! μ p0). The check that catches a field that is wrong while its resultant (P, Q) is right.
//!
//! The annulus leaves out the pole (where a 3D or grid field has few samples and every profile
//! is flat) and the contact edge (where p ~ √(c − r) is resolved only to one element, so a
//! difference of a fraction of an element in c reads as a large local difference).

use spherecontact_model::history::{History, Quantity, SurfaceField};

/// Inner and outer radius of the compared annulus, in units of the reference's contact radius.
pub const ANNULUS: (f64, f64) = (0.1, 0.9);

/// Fewest samples of the judged field inside the annulus for an RMS to mean anything.
pub const MIN_SAMPLES: usize = 5;

/// Which field is compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// The contact pressure p.
    Pressure,
    /// The tangential traction's component q_x along the shift.
    Traction,
}

impl Field {
    /// The field a profile quantity compares; `None` for a step value.
    pub fn of(quantity: Quantity) -> Option<Self> {
        match quantity {
            Quantity::PressureProfile => Some(Field::Pressure),
            Quantity::TractionProfile => Some(Field::Traction),
            _ => None,
        }
    }
}

/// The comparison of one profile with its reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// RMS of the difference over the annulus [Pa].
    pub rms: f64,
    /// The reference profile's peak (largest |value|) [Pa].
    pub peak: f64,
}

/// The RMS difference of `field` in `subject` from `reference` at path position `position`.
pub fn compare(
    subject: &History,
    reference: &History,
    position: usize,
    field: Field,
) -> Result<Comparison, String> {
    let (mine, theirs) = (
        field_at(subject, position, "the solver")?,
        field_at(reference, position, "the reference")?,
    );
    let c = reference
        .at_position(position)
        .and_then(|row| row.contact_radius)
        .filter(|c| *c > 0.0)
        .ok_or_else(|| format!("the reference has no contact radius at position {position}"))?;
    let reference_profile = radial(theirs, field)?;
    let peak = reference_profile.iter().fold(0.0_f64, |m, (_, v)| m.max(v.abs()));
    if peak == 0.0 {
        return Err(format!("the reference's profile is zero at position {position}"));
    }
    let (lo, hi) = (ANNULUS.0 * c, ANNULUS.1 * c);
    let squares: Vec<f64> = radial(mine, field)?
        .into_iter()
        .filter(|(r, _)| *r > lo && *r < hi)
        .map(|(r, v)| (v - interpolate(&reference_profile, r)).powi(2))
        .collect();
    if squares.len() < MIN_SAMPLES {
        return Err(format!(
            "{} samples of the field in {lo:.3e} m < r < {hi:.3e} m (at least {MIN_SAMPLES})",
            squares.len()
        ));
    }
    let rms = (squares.iter().sum::<f64>() / squares.len() as f64).sqrt();
    Ok(Comparison { rms, peak })
}

/// The surface field of `history` at `position`.
fn field_at<'a>(history: &'a History, position: usize, who: &str) -> Result<&'a SurfaceField, String> {
    history
        .field_at(position)
        .ok_or_else(|| format!("{who} has no surface field at position {position}"))
}

/// (r, value) of every sample of `field`, sorted by r.
fn radial(surface: &SurfaceField, field: Field) -> Result<Vec<(f64, f64)>, String> {
    let values: Vec<f64> = match field {
        Field::Pressure => surface.pressure.clone(),
        Field::Traction => surface
            .traction
            .as_ref()
            .ok_or("no tangential traction in the field (frictionless solver)")?
            .iter()
            .map(|q| q[0])
            .collect(),
    };
    let mut samples: Vec<(f64, f64)> = surface
        .points
        .iter()
        .map(|x| x[0].hypot(x[1]))
        .zip(values)
        .collect();
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(samples)
}

/// The profile linearly interpolated at r (held constant beyond its ends).
fn interpolate(profile: &[(f64, f64)], r: f64) -> f64 {
    let k = profile.partition_point(|(x, _)| *x < r);
    match (k.checked_sub(1).map(|i| profile[i]), profile.get(k)) {
        (Some((r0, v0)), Some(&(r1, v1))) if r1 > r0 => v0 + (v1 - v0) * (r - r0) / (r1 - r0),
        (_, Some(&(_, v))) | (Some((_, v)), None) => v,
        (None, None) => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_model::history::{Layout, StepResult, TangentialComponents};

    fn history(points: &[f64], pressure: impl Fn(f64) -> f64, c: f64) -> History {
        History {
            steps: vec![StepResult {
                position: Some(1),
                step: 0,
                contact_radius: Some(c),
                ..StepResult::default()
            }],
            fields: vec![SurfaceField {
                position: 1,
                points: points.iter().map(|&r| [r, 0.0]).collect(),
                pressure: points.iter().map(|&r| pressure(r)).collect(),
                traction: Some(points.iter().map(|&r| [0.2 * pressure(r), 0.0]).collect()),
                stick: None,
                slip: None,
                components: TangentialComponents::AlongX,
                layout: Layout::Profile,
            }],
            ..History::default()
        }
    }

    #[test]
    fn a_profile_offset_by_one_percent_of_p0_reads_one_percent() {
        let hertz = |r: f64| 1e9 * (1.0 - r * r).max(0.0).sqrt();
        let fine: Vec<f64> = (0..=2000).map(|i| f64::from(i) * 6e-4).collect();
        let coarse: Vec<f64> = (0..=40).map(|i| f64::from(i) * 0.03).collect();
        let reference = history(&fine, hertz, 1.0);
        let same = history(&coarse, hertz, 1.0);
        let e = compare(&same, &reference, 1, Field::Pressure).unwrap();
        assert!(e.rms / e.peak < 1e-5, "{e:?}");
        let shifted = history(&coarse, |r| hertz(r) + 1e7, 1.0);
        let e = compare(&shifted, &reference, 1, Field::Pressure).unwrap();
        assert!((e.rms / e.peak - 1e-2).abs() < 1e-6, "{e:?}");
        let e = compare(&shifted, &reference, 1, Field::Traction).unwrap();
        assert!((e.rms / e.peak - 1e-2).abs() < 1e-6, "{e:?}");
    }

    #[test]
    fn missing_fields_and_too_few_samples_are_errors() {
        let flat = |_: f64| 1.0;
        let reference = history(&[0.0, 0.5, 1.0], flat, 1.0);
        assert!(compare(&reference, &reference, 2, Field::Pressure).is_err());
        let e = compare(&reference, &reference, 1, Field::Pressure).unwrap_err();
        assert!(e.contains("samples"), "{e}");
        let mut frictionless = history(&[0.0, 0.5, 1.0], flat, 1.0);
        frictionless.fields[0].traction = None;
        assert!(compare(&frictionless, &reference, 1, Field::Traction).is_err());
    }
}
