//! The error of a case file that cannot be read or does not validate.

use std::fmt;
use std::path::{Path, PathBuf};

use spherecontact_model::number::Short;
use spherecontact_system::input::line_and_column;
use spherecontact_system::text::one_line;

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
            field: shortened(one_line(&field.into()).into_owned(), MAX_FIELD_CHARS),
            message: shortened(one_line(&message.into()).into_owned(), MAX_MESSAGE_CHARS),
        }
    }
}

/// The longest field name shown [characters]: the validator's are under 40; a longer one comes
/// from the input (a table name of 200 000 keys).
const MAX_FIELD_CHARS: usize = 120;

/// The longest message shown [characters]: ours are under 400; a message that echoes a huge input
/// keeps its head and its tail (the allowed range).
const MAX_MESSAGE_CHARS: usize = 1000;

/// `text` cut to at most `max` characters around an ellipsis, head and tail kept.
fn shortened(text: String, max: usize) -> String {
    let count = text.chars().count();
    if count <= max {
        return text;
    }
    let half = (max - 3) / 2;
    let head: String = text.chars().take(half).collect();
    let tail: String = text.chars().skip(count - half).collect();
    format!("{head} … {tail}")
}

/// The dotted field of TOML `text` at byte `offset` (`body1.young`, `checks[2].tolerance`), for
/// errors of the parser, which locate a fault but do not name it.
///
/// Reads the table headers before the offset (`[path]`, `[[checks]]` counted) and the `key =`
/// of the offset's own line; a header line names its table. `None` on a comment or blank line
/// outside any table.
pub fn field_at(text: &str, offset: usize) -> Option<String> {
    let offset = offset.min(text.len());
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
    let mut table = String::new();
    let mut counts = std::collections::BTreeMap::<&str, usize>::new();
    for line in text[..line_end].split('\n').map(str::trim_start) {
        if let Some(name) = line.strip_prefix("[[").and_then(|l| l.split_once("]]")) {
            let count = counts.entry(name.0.trim()).or_insert(0);
            table = format!("{}[{count}]", name.0.trim());
            *count += 1;
        } else if let Some(name) = line.strip_prefix('[').and_then(|l| l.split_once(']')) {
            table = name.0.trim().to_owned();
        }
    }
    let line = text[line_start..line_end].trim_start();
    let bare = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.');
    let key = line
        .split_once('=')
        .map(|(k, _)| k.trim())
        .filter(|k| !k.is_empty() && k.chars().all(bare) && !line.starts_with('['));
    match key {
        Some(key) if table.is_empty() => Some(key.to_owned()),
        Some(key) => Some(format!("{table}.{key}")),
        None if table.is_empty() => None,
        None => Some(table),
    }
}

/// A TOML value as a message shows it: floats short ([`Short`]), never a 300-digit decimal.
pub struct ShortValue<'a>(pub &'a toml::Value);

impl fmt::Display for ShortValue<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            toml::Value::Float(x) => write!(f, "{}", Short(*x)),
            toml::Value::Array(items) => {
                let items: Vec<_> = items.iter().map(|v| ShortValue(v).to_string()).collect();
                write!(f, "[{}]", items.join(", "))
            }
            toml::Value::Table(table) => {
                let entries: Vec<_> = table
                    .iter()
                    .map(|(k, v)| format!("{k} = {}", ShortValue(v)))
                    .collect();
                write!(f, "{{ {} }}", entries.join(", "))
            }
            other => write!(f, "{other}"),
        }
    }
}

/// The message of a TOML parser error, on one line; never empty (the parser gives an empty one
/// for some faults, such as a key with no value at the end of the text).
pub fn parser_message(e: &toml::de::Error) -> String {
    let message = shorten_numbers(&e.message().trim().replace('\n', "; "));
    if message.is_empty() {
        "invalid TOML here (allowed: a key = value, a [table] or a comment)".to_owned()
    } else {
        message
    }
}

/// `text` with every long decimal number (serde prints `1.7e308` in full, 309 digits) written
/// short.
fn shorten_numbers(text: &str) -> String {
    let numeric = |c: char| c.is_ascii_digit() || c == '.';
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(numeric) {
        let end = rest[start..]
            .find(|c| !numeric(c))
            .map_or(rest.len(), |n| start + n);
        let run = &rest[start..end];
        out.push_str(&rest[..start]);
        match run.parse::<f64>() {
            Ok(v) if run.len() > 24 => out.push_str(&Short(v).to_string()),
            _ => out.push_str(run),
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", one_line(&self.file.display().to_string()))?;
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
    fn fields_are_found_from_tables_and_keys() {
        let text = "name = \"a\"\n[body1]\nyoung = \"x\"\n[[checks]]\nsolver = 1\n[[checks]]\nat = 2\n";
        let at = |needle: &str| field_at(text, text.find(needle).unwrap());
        assert_eq!(at("\"a\"").as_deref(), Some("name"));
        assert_eq!(at("\"x\"").as_deref(), Some("body1.young"));
        assert_eq!(at("1\n").as_deref(), Some("checks[0].solver"));
        assert_eq!(at("2\n").as_deref(), Some("checks[1].at"));
        assert_eq!(at("[body1]").as_deref(), Some("body1"));
        assert_eq!(field_at("# comment\n", 0), None);
    }

    #[test]
    fn parser_messages_show_short_numbers() {
        let e = toml::from_str::<std::collections::BTreeMap<String, String>>("a = 1.7e308").unwrap_err();
        assert_eq!(
            parser_message(&e),
            "invalid type: floating point `1.7e308`, expected a string"
        );
        assert_eq!(shorten_numbers("line 3.5, 12 and 0.1"), "line 3.5, 12 and 0.1");
    }

    #[test]
    fn huge_fields_and_messages_keep_their_head_and_tail() {
        let e = CaseError::new(
            Path::new("a"),
            None,
            "x".repeat(5000),
            format!("{}(allowed: 1)", "y".repeat(9000)),
        );
        assert_eq!(e.field.chars().count(), MAX_FIELD_CHARS - 1);
        assert!(e.message.len() <= MAX_MESSAGE_CHARS + 2 && e.message.ends_with("(allowed: 1)"));
    }

    #[test]
    fn values_show_short_floats() {
        let value: toml::Value = toml::from_str::<toml::Table>("v = { a = [1.7e308, 2], b = \"s\" }")
            .unwrap()
            .remove("v")
            .unwrap();
        assert_eq!(ShortValue(&value).to_string(), "{ a = [1.7e308, 2], b = \"s\" }");
    }

    #[test]
    fn lines_and_columns_are_one_based() {
        assert_eq!(line_and_column("ab\ncd", 0), (1, 1));
        assert_eq!(line_and_column("ab\ncd", 4), (2, 2));
    }
}
