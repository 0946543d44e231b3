//! A check's judged values against its non-regression baseline, and how a row shows it.
//!
//! A baseline records every value a check judged (every step or sweep point it covers), so the
//! comparison names the first step that moved beyond the tolerance and the largest change, each
//! with its value and the baseline's, and how many of the compared values moved at all.

use serde::Serialize;

use spherecontact_model::number::{format_value, Short};

/// One value a check judged: the step (a path's) or sweep point (an impact's) and the subject's
/// value and the reference's there.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct JudgedValue {
    /// The step of the path, or the index of the sweep point.
    pub step: usize,
    /// The judged solver's value there.
    pub value: f64,
    /// The reference's value there.
    pub reference: f64,
}

/// A value that moved from its baseline.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Change {
    /// Its step (or sweep point).
    pub step: usize,
    /// The value now.
    pub value: f64,
    /// The value stored.
    pub baseline: f64,
    /// |value − baseline| / max(|baseline|, |value|, |reference|): the reference's magnitude
    /// scales it because a profile's value is a small RMS difference.
    pub change: f64,
}

/// A check's values against the values stored in its baseline.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Drift {
    /// Compared value by value, at the same steps.
    Measured {
        /// What a step is called in this kind of case ("step", "sweep point").
        unit: &'static str,
        /// How many values were compared.
        compared: usize,
        /// How many of them differ from the baseline at all (any bit).
        moved: usize,
        /// The first value whose change exceeds the tolerance, if any: where the check moved.
        first: Option<Change>,
        /// The largest change, if any value moved.
        largest: Option<Change>,
        /// The largest change accepted for this check's solvers.
        tolerance: f64,
    },
    /// The check judged a value at a step the baseline has none for, or the reverse (the case's
    /// path or sweep changed, or which steps have a reference): a failure until `baseline update`.
    OtherSteps {
        /// What a step is called.
        unit: &'static str,
        /// The first step judged on one side only.
        step: usize,
        /// True when it is judged now and absent from the baseline.
        now: bool,
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
    /// Whether the drift fails the check: a change beyond the tolerance, other steps or another
    /// resolution.
    pub fn fails(&self) -> bool {
        match self {
            Drift::Measured { first, .. } => first.is_some(),
            Drift::OtherSteps { .. } | Drift::OtherResolution { .. } => true,
        }
    }

    /// The drift as a check's row shows it (path and impact checks alike).
    pub fn cell(&self) -> String {
        match self {
            Drift::Measured {
                unit,
                compared,
                moved,
                first,
                largest,
                tolerance,
            } => {
                let tol = format_value(Some(*tolerance));
                let Some(largest) = largest else {
                    return format!(" | drift 0 at all {compared} values (tol {tol})");
                };
                let shown = |c: &Change| {
                    format!(
                        "{unit} {}: {} vs baseline {} (change {})",
                        c.step,
                        Short(c.value),
                        Short(c.baseline),
                        format_value(Some(c.change))
                    )
                };
                let first = first.as_ref().map_or_else(
                    || "none beyond tol".to_owned(),
                    |c| format!("first beyond tol at {}", shown(c)),
                );
                format!(
                    " | drift: {first}; largest at {}; {moved} of {compared} values moved (tol {tol})",
                    shown(largest)
                )
            }
            Drift::OtherSteps { unit, step, now } => format!(
                " | drift: {unit} {step} is judged {} (the case's {unit}s changed: run `spherecontact \
                 baseline update` if that is meant)",
                if *now {
                    "now but has no value in the baseline"
                } else {
                    "in the baseline but not now"
                }
            ),
            Drift::OtherResolution { solver } => format!(
                " | drift: the baseline records another resolution of {solver} than this run's (run \
                 `spherecontact baseline update` if the case's resolution changed)"
            ),
        }
    }
}

/// Compares `now`, a check's judged values, with `stored`, its baseline's (step, value) pairs,
/// both in step order, at `tolerance`.
pub fn compare(unit: &'static str, now: &[JudgedValue], stored: &[(usize, f64)], tolerance: f64) -> Drift {
    let steps_now = now.iter().map(|j| j.step);
    if let Some((step, now)) = first_difference(steps_now, stored.iter().map(|s| s.0)) {
        return Drift::OtherSteps { unit, step, now };
    }
    let changes = now.iter().zip(stored).map(|(j, &(_, baseline))| Change {
        step: j.step,
        value: j.value,
        baseline,
        change: change(j.value, baseline, j.reference),
    });
    let (mut moved, mut first, mut largest) = (0, None, None::<Change>);
    for c in changes.filter(|c| c.change > 0.0) {
        moved += 1;
        if first.is_none() && c.change > tolerance {
            first = Some(c);
        }
        if largest.is_none_or(|l| c.change > l.change) {
            largest = Some(c);
        }
    }
    Drift::Measured {
        unit,
        compared: now.len(),
        moved,
        first,
        largest,
        tolerance,
    }
}

/// |v − b| / max(|b|, |v|, |r|), 0 when v and b are the same number.
fn change(value: f64, baseline: f64, reference: f64) -> f64 {
    let difference = (value - baseline).abs();
    if difference == 0.0 {
        0.0
    } else {
        difference / baseline.abs().max(value.abs()).max(reference.abs())
    }
}

/// The first step in one of two increasing sequences and not the other, and whether it is in
/// the first.
fn first_difference(
    mut a: impl Iterator<Item = usize>,
    mut b: impl Iterator<Item = usize>,
) -> Option<(usize, bool)> {
    loop {
        match (a.next(), b.next()) {
            (None, None) => return None,
            (Some(x), Some(y)) if x == y => continue,
            (Some(x), Some(y)) => return Some(if x < y { (x, true) } else { (y, false) }),
            (Some(x), None) => return Some((x, true)),
            (None, Some(y)) => return Some((y, false)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn judged(values: &[(usize, f64)]) -> Vec<JudgedValue> {
        values
            .iter()
            .map(|&(step, value)| JudgedValue {
                step,
                value,
                reference: 1.0,
            })
            .collect()
    }

    #[test]
    fn names_the_first_step_beyond_the_tolerance_and_the_largest_change() {
        // Requirement (issue 39): every value compared; the first that moved beyond the
        // tolerance and the largest named with their steps. Reference: hand-computed changes.
        let stored = [(0, 1.0), (1, 2.0), (2, 4.0), (3, 8.0)];
        let now = judged(&[(0, 1.0), (1, 2.0 * (1.0 + 1e-14)), (2, 4.4), (3, 16.0)]);
        let drift = compare("step", &now, &stored, 1e-12);
        let Drift::Measured {
            compared,
            moved,
            first,
            largest,
            ..
        } = &drift
        else {
            panic!("{drift:?}")
        };
        assert_eq!((*compared, *moved), (4, 3));
        let (first, largest) = (first.unwrap(), largest.unwrap());
        assert_eq!((first.step, first.value, first.baseline), (2, 4.4, 4.0));
        assert!((first.change - 0.4 / 4.4).abs() < 1e-15, "{first:?}");
        assert_eq!((largest.step, largest.change), (3, 0.5));
        assert!(drift.fails());
        let cell = drift.cell();
        assert!(
            cell.contains("first beyond tol at step 2: 4.4 vs baseline 4"),
            "{cell}"
        );
        assert!(cell.contains("largest at step 3: 16 vs baseline 8"), "{cell}");
        assert!(cell.contains("3 of 4 values moved"), "{cell}");
    }

    #[test]
    fn round_off_below_the_tolerance_is_shown_but_does_not_fail() {
        let stored = [(5, 3.0)];
        let drift = compare(
            "sweep point",
            &judged(&[(5, 3.0 * (1.0 + 4e-16))]),
            &stored,
            1e-12,
        );
        assert!(!drift.fails(), "{drift:?}");
        assert!(
            drift.cell().contains("none beyond tol; largest at sweep point 5"),
            "{}",
            drift.cell()
        );
        let same = compare("step", &judged(&[(5, 3.0)]), &stored, 1e-12);
        assert_eq!(same.cell(), " | drift 0 at all 1 values (tol 1.0000e-12)");
    }

    #[test]
    fn a_step_on_one_side_only_fails_naming_it() {
        let drift = compare(
            "step",
            &judged(&[(0, 1.0), (2, 1.0)]),
            &[(0, 1.0), (1, 1.0)],
            1e-12,
        );
        assert_eq!(
            drift,
            Drift::OtherSteps {
                unit: "step",
                step: 1,
                now: false
            }
        );
        assert!(drift.fails());
        let drift = compare("step", &judged(&[(0, 1.0), (1, 1.0)]), &[(0, 1.0)], 1e-12);
        assert!(
            matches!(
                drift,
                Drift::OtherSteps {
                    step: 1,
                    now: true,
                    ..
                }
            ),
            "{drift:?}"
        );
    }
}
