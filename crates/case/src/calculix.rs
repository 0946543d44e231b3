//! Validation of the `[calculix]` table: the CalculiX solvers' contact formulation, penalty
//! factor and element (see [`spherecontact_model::calculix_settings`]), each against its allowed set.

use super::raw::RawCalculix;
use crate::{CaseError, Validator};
use spherecontact_model::calculix_settings::{SettingError, Settings};

impl Validator<'_> {
    /// The `[calculix]` table over the defaults.
    pub(super) fn calculix(&self, raw: &RawCalculix) -> Result<Settings, CaseError> {
        let mut settings = Settings::default();
        let located =
            |at, field: &str, e: SettingError| self.error(at, format!("calculix.{field}"), e.to_string());
        if let Some(name) = &raw.contact {
            settings.formulation =
                Settings::formulation(name.get_ref()).map_err(|e| located(name, "contact", e))?;
        }
        if let Some(value) = &raw.penalty {
            settings.penalty = Settings::penalty(*value.get_ref())
                .map_err(|e| self.error(value, "calculix.penalty", e.to_string()))?;
        }
        if let Some(name) = &raw.element {
            settings.element = Settings::element(name.get_ref()).map_err(|e| located(name, "element", e))?;
        }
        Ok(settings)
    }
}

#[cfg(test)]
mod tests {
    use crate::Case;
    use spherecontact_model::calculix_settings::{Element, Formulation};
    use std::path::Path;

    fn case(table: &str) -> Result<Case, crate::CaseError> {
        let text = format!(
            "friction = 0.2\nsolvers = [\"hertz\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
             [path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n{table}"
        );
        Case::parse(Path::new("c.toml"), &text)
    }

    #[test]
    fn the_table_sets_the_calculix_solvers_and_bad_values_list_the_allowed_set() {
        let c =
            case("[calculix]\ncontact = \"node-to-face\"\npenalty = 100.0\nelement = \"hex20r\"\n").unwrap();
        assert_eq!(c.calculix.formulation, Formulation::NodeToFace);
        assert_eq!(c.calculix.penalty, 100.0);
        assert_eq!(c.calculix.element, Element::Hex20r);
        assert_eq!(case("").unwrap().calculix, Default::default());
        let e = case("[calculix]\ncontact = \"lagrange\"\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("calculix.contact")
                && e.contains("allowed: face-to-face, node-to-face, mortar, linmortar, pglinmortar"),
            "{e}"
        );
        let e = case("[calculix]\npenalty = 1e9\n").unwrap_err().to_string();
        assert!(
            e.contains("calculix.penalty") && e.contains("1 ≤ penalty ≤ 1000000"),
            "{e}"
        );
        let e = case("[calculix]\nelement = \"c3d10\"\n").unwrap_err().to_string();
        assert!(
            e.contains("calculix.element") && e.contains("allowed: tet10, hex20, hex20r"),
            "{e}"
        );
        let e = case("[calculix]\nsolver = \"x\"\n").unwrap_err().to_string();
        assert!(e.contains("solver"), "{e}");
    }
}
