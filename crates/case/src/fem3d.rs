//! Validation of the `[fem-3d]` table: fem-3d's regularised stick, `stick_slope` (a factor of
//! E/h, [`spherecontact_model::stick_slope`]), within its range.

use super::raw::RawFem3d;
use crate::{CaseError, Validator};
use spherecontact_model::stick_slope::StickSlope;

impl Validator<'_> {
    /// The `[fem-3d]` table: its stick slope, if set.
    pub(super) fn fem3d(&self, raw: &RawFem3d) -> Result<Option<StickSlope>, CaseError> {
        raw.stick_slope
            .as_ref()
            .map(|value| {
                StickSlope::try_new(*value.get_ref())
                    .map_err(|e| self.error(value, "fem-3d.stick_slope", e.to_string()))
            })
            .transpose()
    }
}

#[cfg(test)]
mod tests {
    use crate::Case;
    use std::path::Path;

    fn case(table: &str) -> Result<Case, crate::CaseError> {
        let text = format!(
            "friction = 0.2\nsolvers = [\"hertz\", \"fem-3d\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
             [path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 1]\nsubsteps = 1\n{table}"
        );
        Case::parse(Path::new("c.toml"), &text)
    }

    #[test]
    fn the_table_regularises_fem_3ds_stick_and_bad_values_name_the_field_and_range() {
        assert_eq!(case("").unwrap().stick_slope, None);
        let c = case("[fem-3d]\nstick_slope = 10.0\n").unwrap();
        assert_eq!(c.stick_slope.map(|s| s.factor()), Some(10.0));
        for bad in ["0.0", "-1.0", "1e7", "nan"] {
            let e = case(&format!("[fem-3d]\nstick_slope = {bad}\n"))
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("c.toml")
                    && e.contains("fem-3d.stick_slope")
                    && e.contains("1e-3 ≤ stick_slope ≤ 1e6"),
                "{e}"
            );
        }
        let e = case("[fem-3d]\npenalty = 1.0\n").unwrap_err().to_string();
        assert!(e.contains("penalty"), "{e}");
    }
}
