//! Validation of the `[kratos]` table: the `kratos-3d` deck's contact formulation, element, ALM
//! factor and penalty (see [`spherecontact_model::kratos_settings`]), each against its allowed set.

use super::raw::RawKratos;
use crate::{CaseError, Validator};
use spherecontact_model::kratos_settings::{SettingError, Settings};

impl Validator<'_> {
    /// The `[kratos]` table over the defaults.
    pub(super) fn kratos(&self, raw: &RawKratos) -> Result<Settings, CaseError> {
        let mut settings = Settings::default();
        let located =
            |at, field: &str, e: SettingError| self.error(at, format!("kratos.{field}"), e.to_string());
        if let Some(name) = &raw.contact {
            settings.formulation =
                Settings::formulation(name.get_ref()).map_err(|e| located(name, "contact", e))?;
        }
        if let Some(name) = &raw.element {
            settings.element = Settings::element(name.get_ref()).map_err(|e| located(name, "element", e))?;
        }
        if let Some(value) = &raw.alm_factor {
            settings.alm_factor = Settings::alm_factor(*value.get_ref())
                .map_err(|e| self.error(value, "kratos.alm_factor", e.to_string()))?;
        }
        if let Some(value) = &raw.penalty {
            settings.penalty = Settings::penalty(*value.get_ref())
                .map_err(|e| self.error(value, "kratos.penalty", e.to_string()))?;
        }
        Ok(settings)
    }
}

#[cfg(test)]
mod tests {
    use crate::Case;
    use spherecontact_model::kratos_settings::{Element, Formulation};
    use std::path::Path;

    fn case(table: &str) -> Result<Case, crate::CaseError> {
        let text = format!(
            "friction = 0.2\nsolvers = [\"hertz\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
             [path]\nunit = \"um\"\ndelta_n = [0, 10]\ndelta_t = [0, 0]\nsubsteps = 1\n{table}"
        );
        Case::parse(Path::new("c.toml"), &text)
    }

    /// Requirement: every field of `[kratos]` sets the deck, and a bad value names the file, the
    /// field and the allowed set (no tolerance: exact values and messages).
    #[test]
    fn the_table_sets_the_kratos_deck_and_bad_values_list_the_allowed_set() {
        let c =
            case("[kratos]\ncontact = \"penalty\"\nelement = \"hex8\"\nalm_factor = 10.0\npenalty = 100.0\n")
                .unwrap();
        assert_eq!(c.kratos.formulation, Formulation::Penalty);
        assert_eq!(c.kratos.element, Element::Hex8);
        assert_eq!((c.kratos.alm_factor, c.kratos.penalty), (10.0, 100.0));
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
        ];
        for (line, field, allowed) in bad {
            let e = case(&format!("[kratos]\n{line}\n")).unwrap_err().to_string();
            assert!(
                e.contains("c.toml") && e.contains(field) && e.contains(allowed),
                "{e}"
            );
        }
        let e = case("[kratos]\nsolver = \"x\"\n").unwrap_err().to_string();
        assert!(e.contains("solver"), "{e}");
    }
}
