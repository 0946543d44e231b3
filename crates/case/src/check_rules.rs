//! Validation of a case's checks: solver, quantity, where along the path, reference (another
//! solver, or a value stored in a reference file), error measure, tolerance and its reason.

use toml::Spanned;

use super::error::ShortValue;
use super::raw::RawCheck;
use super::reference::{self, LoadError};
use crate::{CaseError, Validator};
use spherecontact_check::{CheckSpec, ErrorMeasure, Reference, Where};
use spherecontact_model::history::Quantity;

impl Validator<'_> {
    pub(super) fn check(
        &self,
        raw: &RawCheck,
        field: &str,
        positions: usize,
    ) -> Result<CheckSpec, CaseError> {
        let solver = self.solver_name(&raw.solver, &format!("{field}.solver"))?;
        let quantity = Quantity::checkable(raw.quantity.get_ref()).ok_or_else(|| {
            let names: Vec<_> = Quantity::ALL
                .iter()
                .chain(&Quantity::PROFILES)
                .chain(&Quantity::MAP_MEASURES)
                .map(|q| q.name())
                .collect();
            self.unknown_quantity(&raw.quantity, field, &names)
        })?;
        let at = self.at(&raw.at, &format!("{field}.at"), positions)?;
        let reference = self.reference(&raw.reference, &format!("{field}.reference"), quantity)?;
        let measure = match &raw.error {
            None => ErrorMeasure::Relative,
            Some(name) => ErrorMeasure::from_name(name.get_ref()).ok_or_else(|| {
                self.error(
                    name,
                    format!("{field}.error"),
                    format!(
                        "unknown error measure `{}` (allowed: relative, relative-to-peak, absolute)",
                        name.get_ref()
                    ),
                )
            })?,
        };
        if spherecontact_solvers::profile::Field::of(quantity).is_some() {
            self.profile_rules(raw, field, quantity, at, &reference, measure)?;
        }
        if quantity.is_map_measure() && at == Where::EveryStep {
            return Err(self.error(
                &raw.at,
                format!("{field}.at"),
                format!(
                    "a {quantity} is measured on the surface fields, which solvers write at path \
                     positions only (allowed: \"every-position\", {{ position = K }} or \
                     {{ positions = [FIRST, LAST] }})"
                ),
            ));
        }
        let tolerance = match (&raw.tolerance, raw.informational) {
            (Some(t), _) => Some(self.number(
                t,
                &format!("{field}.tolerance"),
                |t| t.is_finite() && t > 0.0,
                "finite tolerance > 0",
            )?),
            (None, true) => None,
            (None, false) => {
                return Err(self.error(
                    &raw.solver,
                    format!("{field}.tolerance"),
                    "missing (required unless informational = true)",
                ))
            }
        };
        let tolerance = if raw.informational { None } else { tolerance };
        let reason = raw.reason.clone().unwrap_or_default();
        if tolerance.is_some() && reason.trim().is_empty() {
            return Err(self.error(
                &raw.solver,
                format!("{field}.reason"),
                "missing: every tolerance needs its reason (discretisation, domain, model …)",
            ));
        }
        let known_failure = self.known_failure(raw, field, tolerance)?;
        let abs_zero = match &raw.abs_zero {
            None => spherecontact_check::ABS_ZERO,
            Some(z) => self.number(
                z,
                &format!("{field}.abs_zero"),
                |z| z.is_finite() && z > 0.0,
                "finite abs_zero > 0 (SI, the quantity's unit)",
            )?,
        };
        Ok(CheckSpec {
            solver,
            quantity,
            at,
            reference,
            measure,
            tolerance,
            reason,
            known_failure,
            abs_zero,
        })
    }

    /// A known-failure mark: the evidence in words, on a check that is judged (a tolerance).
    fn known_failure(
        &self,
        raw: &RawCheck,
        field: &str,
        tolerance: Option<f64>,
    ) -> Result<Option<String>, CaseError> {
        let Some(evidence) = &raw.known_failure else {
            return Ok(None);
        };
        let field = format!("{field}.known_failure");
        if tolerance.is_none() {
            return Err(self.error(
                evidence,
                field,
                "an informational check is never judged, so it cannot fail (allowed: a known-failure mark on a check with a tolerance)",
            ));
        }
        if evidence.get_ref().trim().is_empty() {
            return Err(self.error(
                evidence,
                field,
                "empty (allowed: the evidence that the failure is the code's defect: what was run, what it showed, where it is written up)",
            ));
        }
        Ok(Some(evidence.get_ref().clone()))
    }

    /// A profile is compared at one position with another solver's, relative to its peak.
    fn profile_rules(
        &self,
        raw: &RawCheck,
        field: &str,
        quantity: Quantity,
        at: Where,
        reference: &Reference,
        measure: ErrorMeasure,
    ) -> Result<(), CaseError> {
        if !matches!(at, Where::Position(_)) {
            return Err(self.error(
                &raw.at,
                format!("{field}.at"),
                format!("a {quantity} is compared at one position (allowed: {{ position = K }})"),
            ));
        }
        if !matches!(reference, Reference::Solver(_)) {
            return Err(self.error(
                &raw.reference,
                format!("{field}.reference"),
                format!("a {quantity} is compared with another solver's (allowed: {{ solver = \"NAME\" }})"),
            ));
        }
        if measure != ErrorMeasure::RelativeToPeak {
            return Err(self.error(
                raw.error.as_ref().unwrap_or(&raw.quantity),
                format!("{field}.error"),
                format!(
                    "a {quantity} is measured as its RMS relative to the reference's peak (allowed: \
                     relative-to-peak)"
                ),
            ));
        }
        Ok(())
    }

    fn at(&self, raw: &Spanned<toml::Value>, field: &str, positions: usize) -> Result<Where, CaseError> {
        let allowed = "\"every-step\", \"every-position\", { position = K } or { positions = [FIRST, LAST] }";
        let bad = |what: String| {
            self.error(
                raw,
                field,
                format!(
                    "{what} (allowed: {allowed}, with positions 0 to {})",
                    positions - 1
                ),
            )
        };
        let index = |v: &toml::Value| match v {
            toml::Value::Integer(k) if *k >= 0 && (*k as usize) < positions => Ok(*k as usize),
            other => Err(bad(format!("position {} is not on the path", ShortValue(other)))),
        };
        match raw.get_ref() {
            toml::Value::String(s) if s == "every-step" => Ok(Where::EveryStep),
            toml::Value::String(s) if s == "every-position" => Ok(Where::EveryPosition),
            toml::Value::Table(t) if t.len() == 1 => match (t.get("position"), t.get("positions")) {
                (Some(k), None) => Ok(Where::Position(index(k)?)),
                (None, Some(toml::Value::Array(range))) if range.len() == 2 => {
                    let (a, b) = (index(&range[0])?, index(&range[1])?);
                    if a > b {
                        return Err(bad(format!("range {a}–{b} runs backwards")));
                    }
                    Ok(Where::Positions(a, b))
                }
                _ => Err(bad(format!("`{}` is not understood", ShortValue(raw.get_ref())))),
            },
            other => Err(bad(format!("`{}` is not understood", ShortValue(other)))),
        }
    }

    fn reference(
        &self,
        raw: &Spanned<toml::Value>,
        field: &str,
        quantity: Quantity,
    ) -> Result<Reference, CaseError> {
        let allowed = "{ solver = \"NAME\" } or { file = \"PATH\", key = \"KEY\" }";
        let table = match raw.get_ref() {
            toml::Value::Table(t) => t,
            other => {
                return Err(self.error(
                    raw,
                    field,
                    format!("`{}` is not understood (allowed: {allowed})", ShortValue(other)),
                ))
            }
        };
        let get = |key: &str| table.get(key).and_then(toml::Value::as_str);
        match (get("solver"), get("file"), get("key"), table.len()) {
            (Some(name), None, None, 1) => {
                let name = Spanned::new(raw.span(), name.to_owned());
                Ok(Reference::Solver(
                    self.solver_name(&name, &format!("{field}.solver"))?,
                ))
            }
            (None, Some(file), Some(key), 2) => self.stored_value(raw, field, file, key, quantity),
            _ => Err(self.error(
                raw,
                field,
                format!(
                    "`{}` is not understood (allowed: {allowed})",
                    ShortValue(raw.get_ref())
                ),
            )),
        }
    }

    /// A value from a reference file, which is resolved against the case file's folder and
    /// must lie in the case's tree ([`super::reads`]).
    fn stored_value(
        &self,
        raw: &Spanned<toml::Value>,
        field: &str,
        file: &str,
        key: &str,
        quantity: Quantity,
    ) -> Result<Reference, CaseError> {
        let path = self
            .tree
            .resolve(file)
            .map_err(|e| self.error(raw, format!("{field}.file"), format!("reference file {e}")))?;
        let stored = reference::load(&path, key).map_err(|e| match e {
            LoadError::NoKey { .. } => self.error(raw, format!("{field}.key"), e.to_string()),
            LoadError::Unreadable { .. } => self.error(raw, format!("{field}.file"), e.to_string()),
            // The fault is in the reference file; the message also names the check using it.
            LoadError::Invalid(e) => self.error(raw, field, format!("key `{key}` of reference file {e}")),
        })?;
        if stored.quantity != quantity {
            return Err(self.error(
                raw,
                field,
                format!(
                    "key `{key}` of reference file {} holds {} but the check judges {quantity} \
                     (allowed: a value of {quantity})",
                    path.display(),
                    stored.quantity
                ),
            ));
        }
        Ok(Reference::Value {
            value: stored.value,
            key: format!("{file}#{key}"),
            source: stored.source,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::Case;
    use spherecontact_model::history::Quantity;
    use std::path::Path;

    /// A case with two solvers and one check given by its fields.
    fn check(fields: &str) -> Result<Case, crate::CaseError> {
        let text = format!(
            "friction = 0.2\nsolvers = [\"hertz\", \"mdr\"]\n[body1]\nradius = 0.1\nyoung = 70e9\n\
             poisson = 0.3\n[path]\nunit = \"um\"\ndelta_n = [0, 17]\ndelta_t = [0, 1]\nsubsteps = 2\n\
             [[checks]]\nsolver = \"mdr\"\nreference = {{ solver = \"hertz\" }}\ntolerance = 1e-3\n\
             reason = \"r\"\n{fields}"
        );
        Case::parse(Path::new("p.toml"), &text)
    }

    #[test]
    fn a_profile_is_checked_at_one_position_relative_to_the_peak() {
        let ok = "quantity = \"traction_profile\"\nat = { position = 1 }\nerror = \"relative-to-peak\"";
        assert_eq!(check(ok).unwrap().checks[0].quantity, Quantity::TractionProfile);
        let everywhere = "quantity = \"pressure_profile\"\nat = \"every-step\"\nerror = \"relative-to-peak\"";
        let e = check(everywhere).unwrap_err();
        assert!(
            e.field.ends_with(".at") && e.to_string().contains("one position"),
            "{e}"
        );
        let relative = "quantity = \"pressure_profile\"\nat = { position = 1 }";
        let e = check(relative).unwrap_err();
        assert!(
            e.field.ends_with(".error") && e.to_string().contains("relative-to-peak"),
            "{e}"
        );
        let unknown = check("quantity = \"shape\"\nat = { position = 1 }").unwrap_err();
        assert!(unknown.to_string().contains("pressure_profile"), "{unknown}");
    }

    #[test]
    fn a_map_measure_is_checked_at_positions_not_at_every_step() {
        for name in ["transverse_ratio", "stick_semi_axis_x", "stick_semi_axis_y"] {
            let ok = format!("quantity = \"{name}\"\nat = {{ positions = [1, 1] }}");
            assert_eq!(check(&ok).unwrap().checks[0].quantity.name(), name);
            let every = format!("quantity = \"{name}\"\nat = \"every-position\"");
            assert!(check(&every).is_ok(), "{name} at every position");
            let e = check(&format!("quantity = \"{name}\"\nat = \"every-step\"")).unwrap_err();
            let message = e.to_string();
            assert_eq!(e.field, "checks[0].at", "{message}");
            assert!(
                message.contains("p.toml")
                    && message.contains("path positions only")
                    && message.contains("every-position")
                    && message.contains("{ position = K }"),
                "{message}"
            );
        }
        let unknown = check("quantity = \"shape\"\nat = { position = 1 }").unwrap_err();
        assert!(unknown.to_string().contains("stick_semi_axis_y"), "{unknown}");
    }
    #[test]
    fn a_known_failure_mark_needs_evidence_and_a_tolerance() {
        let base = "quantity = \"normal_force\"\nat = \"every-position\"\n";
        let marked = check(&format!("{base}known_failure = \"ccx shows it: docs\"")).unwrap();
        assert_eq!(
            marked.checks[0].known_failure.as_deref(),
            Some("ccx shows it: docs")
        );
        assert_eq!(check(base).unwrap().checks[0].known_failure, None);
        let e = check(&format!("{base}known_failure = \"  \"")).unwrap_err();
        assert_eq!(e.field, "checks[0].known_failure", "{e}");
        assert!(e.to_string().contains("the evidence"), "{e}");
        let e = check(&format!("{base}informational = true\nknown_failure = \"x\"")).unwrap_err();
        assert!(
            e.to_string().contains("an informational check is never judged"),
            "{e}"
        );
    }

    #[test]
    fn abs_zero_defaults_to_mooses_and_must_be_positive() {
        let base = "quantity = \"normal_force\"\nat = \"every-position\"\n";
        assert_eq!(
            check(base).unwrap().checks[0].abs_zero,
            spherecontact_check::ABS_ZERO
        );
        let set = check(&format!("{base}abs_zero = 1e-6")).unwrap();
        assert_eq!(set.checks[0].abs_zero, 1e-6);
        for bad in ["0.0", "-1e-6", "inf", "nan"] {
            let e = check(&format!("{base}abs_zero = {bad}")).unwrap_err();
            assert_eq!(e.field, "checks[0].abs_zero", "{e}");
            assert!(e.to_string().contains("finite abs_zero > 0"), "{e}");
        }
    }
}
