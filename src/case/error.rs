//! The error of a case file that cannot be read or does not validate.

use std::fmt;
use std::path::{Path, PathBuf};

/// A case file that cannot be used: it names the file, the field, the line and column where
/// the parser knows them, and what is allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseError {
    /// The file at fault (a case file, or a reference file it points to).
    pub file: PathBuf,
    /// Line and column (1-based), where known.
    pub location: Option<(usize, usize)>,
    /// The field, as a path (`body1.poisson`, `checks[2].tolerance`); empty for syntax errors.
    pub field: String,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl CaseError {
    /// An error at `field` of `file`, located by the byte `span` of `source` when given.
    pub fn new(
        file: &Path,
        source: Option<(&str, std::ops::Range<usize>)>,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Self {
            file: file.to_path_buf(),
            location: source.map(|(text, span)| line_and_column(text, span.start)),
            field: field.into(),
            message: message.into(),
        }
    }
}

/// The 1-based line and column of byte `offset` in `text`.
pub fn line_and_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some((line, column)) = self.location {
            write!(f, ":{line}:{column}")?;
        }
        if !self.field.is_empty() {
            write!(f, ": field `{}`", self.field)?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for CaseError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_columns_are_one_based() {
        assert_eq!(line_and_column("ab\ncd", 0), (1, 1));
        assert_eq!(line_and_column("ab\ncd", 4), (2, 2));
    }
}
