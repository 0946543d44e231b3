//! Validation of a case's checks: solver, quantity, where along the path, reference (another
//! solver, or a value stored in a reference file), error measure, tolerance and its reason.

use std::path::Path;
use toml::Spanned;

use super::error::ShortValue;
use super::raw::RawCheck;
use super::reference::{self, LoadError};
use super::{CaseError, Validator};
use crate::check::{CheckSpec, ErrorMeasure, Reference, Where};
use crate::history::Quantity;

impl Validator<'_> {
    pub(super) fn check(
        &self,
        raw: &RawCheck,
        field: &str,
        positions: usize,
    ) -> Result<CheckSpec, CaseError> {
        let solver = self.solver_name(&raw.solver, &format!("{field}.solver"))?;
        let quantity = Quantity::from_name(raw.quantity.get_ref()).ok_or_else(|| {
            let names: Vec<_> = Quantity::ALL.iter().map(|q| q.name()).collect();
            self.error(
                &raw.quantity,
                format!("{field}.quantity"),
                format!(
                    "unknown quantity `{}` (allowed: {})",
                    raw.quantity.get_ref(),
                    names.join(", ")
                ),
            )
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
        Ok(CheckSpec {
            solver,
            quantity,
            at,
            reference,
            measure,
            tolerance,
            reason,
        })
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

    /// A value from a reference file, which is resolved against the case file's folder.
    fn stored_value(
        &self,
        raw: &Spanned<toml::Value>,
        field: &str,
        file: &str,
        key: &str,
        quantity: Quantity,
    ) -> Result<Reference, CaseError> {
        let path = self.file.parent().unwrap_or(Path::new(".")).join(file);
        let stored = reference::load(&path, key).map_err(|e| match e {
            LoadError::Unreadable(e) => self.error(
                raw,
                format!("{field}.file"),
                format!("cannot read reference file {}: {e}", path.display()),
            ),
            LoadError::NoKey => self.error(
                raw,
                format!("{field}.key"),
                format!("no key `{key}` in {}", path.display()),
            ),
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
