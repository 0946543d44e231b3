//! Files from elsewhere: what the harness reads that it did not write in this run and that no
//! case file names — baselines (`reference/baselines/<case>.toml`, `--baselines DIR`), run files
//! (`run.json` of `verify --out`, read by `merge` and `--from`) and the results in a deck folder
//! (`deck read`). A pull request, a colleague or a cluster can plant any of them, so each is
//! read by one rule (docs/security.md, "Files from elsewhere"):
//!
//! - **a regular file in its own folder**: a symbolic link is followed only when it leads to a
//!   file inside the folder that holds the link (or below it); a link out of its folder (to
//!   `/proc/self/environ`, `~/.aws/credentials`), a FIFO, a device or a folder is refused
//!   before a byte is read, and a FIFO never blocks ([`super::open_regular`]);
//! - **of bounded size**, checked on the opened file before it is read and again while it is
//!   read ([`super::Bounded`]);
//! - **never echoed**: an error names the file, the line and column where known and the form
//!   expected, never a line of the file. A parser's message is kept only where it speaks of
//!   the expected form: what it quotes of the input (a value, an unknown key) is replaced by
//!   `…` ([`redacted`]).

use std::io::{self, Read};
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use crate::{input::open_regular, input::Bounded, input::Links};

/// A file from elsewhere that cannot be used: where, and what is wrong in words that quote
/// nothing of it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}: {problem}", file.display(), location.map(|(l, c)| format!(":{l}:{c}")).unwrap_or_default())]
pub struct ForeignError {
    /// The file.
    pub file: PathBuf,
    /// Line and column (1-based), where known.
    pub location: Option<(usize, usize)>,
    /// What is wrong and what is allowed.
    pub problem: String,
}

impl ForeignError {
    /// An error of `file` as a whole.
    pub fn new(file: &Path, problem: impl Into<String>) -> Self {
        Self {
            file: file.to_path_buf(),
            location: None,
            problem: crate::text::one_line(&problem.into()).into_owned(),
        }
    }

    /// An error at `line` and `column` of `file`.
    pub fn at(file: &Path, line: usize, column: usize, problem: impl Into<String>) -> Self {
        Self {
            location: Some((line, column)),
            ..Self::new(file, problem)
        }
    }
}

/// Opens the file from elsewhere at `path`: a regular file no longer than `limit` bytes, reached
/// directly or through a symbolic link that stays inside the link's own folder.
pub fn open(path: &Path, limit: u64) -> Result<Bounded, ForeignError> {
    refuse_link_out_of_folder(path)?;
    open_regular(path, limit, Links::Follow).map_err(|e| ForeignError::new(path, e.to_string()))
}

/// The bytes of the file from elsewhere at `path` ([`open`]).
pub fn read_bytes(path: &Path, limit: u64) -> Result<Vec<u8>, ForeignError> {
    let mut bytes = Vec::new();
    open(path, limit)?
        .read_to_end(&mut bytes)
        .map_err(|e| ForeignError::new(path, e.to_string()))?;
    Ok(bytes)
}

/// The text of the file from elsewhere at `path` ([`open`]), UTF-8.
pub fn read_text(path: &Path, limit: u64) -> Result<String, ForeignError> {
    String::from_utf8(read_bytes(path, limit)?).map_err(|e| {
        ForeignError::new(
            path,
            format!(
                "not UTF-8 text: invalid byte at offset {} (allowed: UTF-8 text)",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// A stream over the file from elsewhere at `path` ([`open`]), whose reads fail past `limit`.
pub fn reader(path: &Path, limit: u64) -> Result<impl Read, ForeignError> {
    open(path, limit)
}

/// `text`, the TOML file `path`, as a `T`; `form` says what the file should be (its error's
/// "allowed: …").
pub fn parse_toml<T: DeserializeOwned>(path: &Path, text: &str, form: &str) -> Result<T, ForeignError> {
    toml::from_str(text).map_err(|e| {
        let problem = format!("{} (allowed: {form})", redacted(e.message()));
        match e.span() {
            Some(span) => {
                let (line, column) = super::line_and_column(text, span.start);
                ForeignError::at(path, line, column, problem)
            }
            None => ForeignError::new(path, problem),
        }
    })
}

/// `text`, the JSON file `path`, as a `T`; `form` as for [`parse_toml`].
pub fn parse_json<T: DeserializeOwned>(path: &Path, text: &str, form: &str) -> Result<T, ForeignError> {
    serde_json::from_str(text).map_err(|e| {
        // serde_json's message ends with its own " at line L column C": kept as the location.
        let message = e.to_string();
        let message = message
            .rfind(" at line ")
            .map_or(message.as_str(), |end| &message[..end]);
        ForeignError::at(
            path,
            e.line(),
            e.column(),
            format!("{} (allowed: {form})", redacted(message)),
        )
    })
}

/// What the parsers quote of the input, removed from their `message`: every span in backticks
/// or double quotes before the first "expected" outside quotes (`unknown field `token``,
/// `invalid type: string "ghp_…"`) becomes `…`, except the name after "missing field" and
/// "duplicate field" (the schema's own names); from that "expected" on, the message speaks of
/// the schema and is kept (`expected one of `case`, `solvers``). The result is one line of at
/// most [`MAX_PROBLEM_CHARS`] characters.
pub fn redacted(message: &str) -> String {
    let message = message.trim().replace('\n', "; ");
    let keeps_name = ["missing field", "duplicate field"]
        .iter()
        .any(|p| message.starts_with(p));
    let text = if keeps_name {
        message
    } else {
        without_quoted_input(&message)
    };
    let text = crate::text::one_line(&text).into_owned();
    if text.chars().count() > MAX_PROBLEM_CHARS {
        let cut: String = text.chars().take(MAX_PROBLEM_CHARS - 1).collect();
        format!("{cut}…")
    } else if text.trim().is_empty() {
        "not in the form expected".to_owned()
    } else {
        text
    }
}

/// The longest parser message shown [characters]: the parsers' own messages about a schema are
/// under 300 (an `expected one of` list of a dozen names).
pub const MAX_PROBLEM_CHARS: usize = 400;

/// `text` with every span between a pair of backticks or of double quotes replaced by `…`
/// (quotes kept) up to the first "expected" outside quotes, the rest kept as it is; an unpaired
/// quote hides the rest of the text.
fn without_quoted_input(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut open: Option<char> = None;
    for (i, c) in text.char_indices() {
        match open {
            Some(q) if c == q => {
                out.push('…');
                out.push(c);
                open = None;
            }
            Some(_) => {}
            None if text[i..].starts_with("expected") => {
                out.push_str(&text[i..]);
                return out;
            }
            None if c == '`' || c == '"' => {
                out.push(c);
                open = Some(c);
            }
            None => out.push(c),
        }
    }
    if open.is_some() {
        out.push('…');
    }
    out
}

/// Refuses `path` when it is a symbolic link whose target (every further link followed) is not
/// inside the canonical folder that holds the link.
fn refuse_link_out_of_folder(path: &Path) -> Result<(), ForeignError> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => {}
        _ => return Ok(()),
    }
    let folder = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let out = || {
        ForeignError::new(
            path,
            "a symbolic link that leads out of its folder (allowed: a regular file, or a link to a file in \
             the same folder)",
        )
    };
    let (Ok(folder), Ok(target)) = (std::fs::canonicalize(folder), std::fs::canonicalize(path)) else {
        return Err(out());
    };
    if target.starts_with(&folder) {
        Ok(())
    } else {
        Err(out())
    }
}

/// An `io::Error` of a stream over a file from elsewhere, as a [`ForeignError`] of `path`.
pub fn stream_error(path: &Path, error: &io::Error) -> ForeignError {
    ForeignError::new(path, error.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Form {
        case: String,
        value: f64,
    }

    #[test]
    fn a_link_out_of_its_folder_is_refused_and_one_inside_is_followed() {
        let dir = tempfile::tempdir().unwrap();
        let (inner, outer) = (dir.path().join("in"), dir.path().join("secret"));
        std::fs::create_dir(&inner).unwrap();
        std::fs::write(&outer, "TOKEN=abc").unwrap();
        std::fs::write(inner.join("real.toml"), "case = \"x\"").unwrap();
        std::os::unix::fs::symlink(&outer, inner.join("out.toml")).unwrap();
        std::os::unix::fs::symlink("real.toml", inner.join("alias.toml")).unwrap();
        let e = read_text(&inner.join("out.toml"), 100).unwrap_err();
        assert!(e.problem.contains("leads out of its folder"), "{e}");
        assert!(!e.to_string().contains("abc"), "{e}");
        assert_eq!(read_text(&inner.join("alias.toml"), 100).unwrap(), "case = \"x\"");
        let environ = inner.join("environ.toml");
        std::os::unix::fs::symlink("/proc/self/environ", &environ).unwrap();
        assert!(read_text(&environ, 1 << 20).is_err());
    }

    #[test]
    fn a_fifo_a_device_and_a_large_file_are_refused_without_blocking() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo");
        rustix::fs::mkfifoat(rustix::fs::CWD, &fifo, rustix::fs::Mode::from_raw_mode(0o600)).unwrap();
        assert!(read_text(&fifo, 100).unwrap_err().problem.contains("a FIFO"));
        assert!(read_text(Path::new("/dev/zero"), 100)
            .unwrap_err()
            .problem
            .contains("a device"));
        let large = dir.path().join("large");
        std::fs::write(&large, [b'a'; 101]).unwrap();
        assert!(read_text(&large, 100)
            .unwrap_err()
            .problem
            .contains("at most 100 bytes"));
    }

    /// Requirement: no parser message echoes the input's values or unknown keys; the location and
    /// the schema's names are kept.
    #[test]
    fn parse_errors_quote_nothing_of_the_file() {
        let file = Path::new("b.toml");
        for (text, secret) in [
            ("case = \"x\"\nvalue = \"ghp_SECRET\"\n", "ghp_SECRET"),
            (
                "case = \"x\"\nvalue = 1\naws_secret_access_key = \"k\"\n",
                "aws_secret",
            ),
            ("AWS_SECRET=wJalrXUtnFEMI\n", "wJalr"),
            ("case = \"x\"\n[token_ABC]\n", "token_ABC"),
        ] {
            let e = parse_toml::<Form>(file, text, "a test form").unwrap_err();
            let shown = e.to_string();
            assert!(!shown.contains(secret), "{shown}");
            assert!(
                e.location.is_some() && shown.contains("allowed: a test form"),
                "{shown}"
            );
        }
        let e = parse_toml::<Form>(file, "case = \"x\"\n", "a test form").unwrap_err();
        assert!(e.to_string().contains("missing field `value`"), "{e}");
        let e = parse_json::<Form>(
            Path::new("r.json"),
            "{\"case\": \"x\", \"value\": \"SECRET\"}",
            "a form",
        )
        .unwrap_err();
        assert!(
            !e.to_string().contains("SECRET") && e.location == Some((1, 31)),
            "{e}"
        );
        let e =
            parse_json::<Form>(Path::new("r.json"), "{\"case\": \"x\", \"leak\": 1}", "a form").unwrap_err();
        assert!(
            !e.to_string().contains("leak") && e.to_string().contains("`case`"),
            "{e}"
        );
    }

    #[test]
    fn redaction_keeps_the_schema_and_bounds_the_length() {
        assert_eq!(
            redacted("unknown field `tok`, expected one of `case`, `value`"),
            "unknown field `…`, expected one of `case`, `value`"
        );
        assert_eq!(
            redacted("invalid type: string \"I expected `x`\", expected f64"),
            "invalid type: string \"…\", expected f64"
        );
        assert_eq!(
            redacted("invalid type: string \"abc, expected f64"),
            "invalid type: string \"…"
        );
        assert_eq!(redacted(""), "not in the form expected");
        assert!(redacted(&"x".repeat(5000)).chars().count() <= MAX_PROBLEM_CHARS);
    }
}
