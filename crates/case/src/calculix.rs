//! Validation of the `[calculix]` table: the CalculiX solvers' contact formulation, penalty
//! factor and element (see [`spherecontact_model::calculix_settings`]), each against its allowed set.

use super::raw::RawCalculix;
use crate::{CaseError, Validator};
use spherecontact_model::calculix_settings::Settings;

impl Validator<'_> {
    /// The `[calculix]` table over the defaults.
    pub(super) fn calculix(&self, raw: &RawCalculix) -> Result<Settings, CaseError> {
        let default = Settings::default();
        Ok(Settings {
            formulation: self.setting(
                raw.contact.as_ref(),
                "calculix.contact",
                default.formulation,
                |name| Settings::formulation(name),
            )?,
            penalty: self.setting(
                raw.penalty.as_ref(),
                "calculix.penalty",
                default.penalty,
                |value| Settings::penalty(*value),
            )?,
            element: self.setting(
                raw.element.as_ref(),
                "calculix.element",
                default.element,
                |name| Settings::element(name),
            )?,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::test_case::paper_case as case;
    use spherecontact_model::calculix_settings::{Element, Formulation};

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
