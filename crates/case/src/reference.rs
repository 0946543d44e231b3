//! Stored reference values (`reference/*.toml`): a value with its quantity, SI unit and source.
//!
//! ```toml
//! [paper_spheres_17um_force]
//! quantity = "normal_force"
//! value = 803.76
//! unit = "N"
//! source = "where the number comes from"
//! ```

use std::path::{Path, PathBuf};

use super::error::CaseError;
use super::raw::RawReferenceValue;
use spherecontact_model::history::Quantity;

/// One stored value.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredValue {
    /// The quantity it is a value of.
    pub quantity: Quantity,
    /// The value in SI units.
    pub value: f64,
    /// Where it comes from.
    pub source: String,
}

/// Why a stored value could not be had: the file could not be read, or its entry is invalid.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file cannot be read (missing, not a regular file, too large, not UTF-8).
    #[error("cannot read reference file {}: {source}", file.display())]
    Unreadable {
        /// The file.
        file: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file has no such key.
    #[error("no key `{key}` in reference file {}", file.display())]
    NoKey {
        /// The file.
        file: PathBuf,
        /// The key asked for.
        key: String,
    },
    /// The file or its entry is invalid.
    #[error("reference file {0}")]
    Invalid(CaseError),
}

/// Reads entry `key` of the reference file `path` (a regular file of bounded size), checking
/// that its value is finite and its quantity and unit are known and agree.
pub fn load(path: &Path, key: &str) -> Result<StoredValue, LoadError> {
    let text = spherecontact_system::input::read_text(path).map_err(|source| LoadError::Unreadable {
        file: path.to_path_buf(),
        source,
    })?;
    let invalid = |message: String| LoadError::Invalid(CaseError::new(path, None, key, message));
    let mut table: toml::Table = toml::from_str(&text).map_err(|e| {
        LoadError::Invalid(CaseError::new(
            path,
            e.span().map(|s| (text.as_str(), s)),
            "",
            super::error::parser_message(&e),
        ))
    })?;
    let entry = table.remove(key).ok_or_else(|| LoadError::NoKey {
        file: path.to_path_buf(),
        key: key.to_owned(),
    })?;
    let entry: RawReferenceValue = entry
        .try_into()
        .map_err(|e: toml::de::Error| invalid(super::error::parser_message(&e)))?;
    let quantity = Quantity::from_name(&entry.quantity)
        .ok_or_else(|| invalid(format!("unknown quantity `{}`", entry.quantity)))?;
    if !entry.value.is_finite() {
        return Err(invalid("value is not finite (allowed: a finite number)".into()));
    }
    if entry.unit != quantity.unit() {
        return Err(invalid(format!(
            "unit `{}` (allowed: {}, SI)",
            entry.unit,
            quantity.unit()
        )));
    }
    Ok(StoredValue {
        quantity,
        value: entry.value,
        source: entry.source,
    })
}
