//! Validation of the `[kratos]` table: the `kratos-3d` deck's contact formulation, element, ALM
//! factor and penalty (see [`spherecontact_model::kratos_settings`]), each against its allowed set.

use super::raw::RawKratos;
use crate::{CaseError, Validator};
use spherecontact_model::kratos_settings::Settings;

impl Validator<'_> {
    /// The `[kratos]` table over the defaults.
    pub(super) fn kratos(&self, raw: &RawKratos) -> Result<Settings, CaseError> {
        let default = Settings::default();
        Ok(Settings {
            formulation: self.setting(
                raw.contact.as_ref(),
                "kratos.contact",
                default.formulation,
                |name| Settings::formulation(name),
            )?,
            element: self.setting(raw.element.as_ref(), "kratos.element", default.element, |name| {
                Settings::element(name)
            })?,
            alm_factor: self.setting(
                raw.alm_factor.as_ref(),
                "kratos.alm_factor",
                default.alm_factor,
                |value| Settings::alm_factor(*value),
            )?,
            penalty: self.setting(raw.penalty.as_ref(), "kratos.penalty", default.penalty, |value| {
                Settings::penalty(*value)
            })?,
            operator_threshold: self.setting(
                raw.operator_threshold.as_ref(),
                "kratos.operator_threshold",
                default.operator_threshold,
                |value| Settings::operator_threshold(*value),
            )?,
            mixed_ulm_solver: raw
                .mixed_ulm_solver
                .as_ref()
                .map_or(default.mixed_ulm_solver, |value| *value.get_ref()),
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::test_case::paper_case as case;
    use spherecontact_model::kratos_settings::{Element, Formulation};

    /// Requirement: every field of `[kratos]` sets the deck, and a bad value names the file, the
    /// field and the allowed set (no tolerance: exact values and messages).
    #[test]
    fn the_table_sets_the_kratos_deck_and_bad_values_list_the_allowed_set() {
        let c =
            case("[kratos]\ncontact = \"penalty\"\nelement = \"hex8\"\nalm_factor = 10.0\npenalty = 100.0\noperator_threshold = 1e-3\nmixed_ulm_solver = true\n")
                .unwrap();
        assert_eq!(c.kratos.formulation, Formulation::Penalty);
        assert_eq!(c.kratos.element, Element::Hex8);
        assert_eq!((c.kratos.alm_factor, c.kratos.penalty), (10.0, 100.0));
        assert_eq!(c.kratos.operator_threshold, 1e-3);
        assert!(c.kratos.mixed_ulm_solver);
        assert_eq!(case("").unwrap().kratos, Default::default());
        let bad = [
            (
                "contact = \"mortar\"",
                "kratos.contact",
                "allowed: alm-frictional, alm-frictionless, penalty",
            ),
            ("element = \"hex20\"", "kratos.element", "allowed: tet4, hex8"),
            (
                "alm_factor = 1e9",
                "kratos.alm_factor",
                "0.01 ≤ alm_factor ≤ 10000",
            ),
            ("penalty = 0.1", "kratos.penalty", "1 ≤ penalty ≤ 1000000"),
            (
                "operator_threshold = -1.0",
                "kratos.operator_threshold",
                "0 ≤ operator_threshold ≤ 1000",
            ),
        ];
        for (line, field, allowed) in bad {
            let e = case(&format!("[kratos]\n{line}\n")).unwrap_err().to_string();
            assert!(
                e.contains("c.toml") && e.contains(field) && e.contains(allowed),
                "{e}"
            );
        }
        let e = case("[kratos]\nmixed_ulm_solver = 1\n").unwrap_err().to_string();
        assert!(
            e.contains("c.toml") && e.contains("mixed_ulm_solver") && e.contains("bool"),
            "{e}"
        );
        let e = case("[kratos]\nsolver = \"x\"\n").unwrap_err().to_string();
        assert!(e.contains("solver"), "{e}");
    }
}
