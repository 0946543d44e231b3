//! The placeholders of a command solver's command, and the rule that keeps a folder's name from
//! running as code.
//!
//! | placeholder | value | also in the environment as |
//! |---|---|---|
//! | `{case_dir}` | the case file's folder (absolute) | `SPHERECONTACT_CASE_DIR` |
//! | `{scene}` | the scene file in the run's fresh folder (absolute) | `SPHERECONTACT_SCENE` |
//! | `{history}` | the History CSV the program writes there (absolute) | `SPHERECONTACT_HISTORY` |
//!
//! **The rule.** A placeholder is filled only when its value is made of [safe
//! characters](is_safe): letters and digits (any script), `/ . _ - + , : @ %`. None of these
//! means anything to a shell, to Python, Perl or an MPI launcher, so a filled command means what
//! its author wrote whatever the folder is called, inside `sh -c "…"` or `python3 -c "…"` too.
//! A value with any other character (a space, a quote, `$`, `;`, `|`, `&`, a backtick, a
//! newline, brackets, `*`, …) is refused: the solver is not run, and the error names the folder,
//! the character and the way out (move the case, or use the environment variable, quoted, where
//! a shell reads it: `"$SPHERECONTACT_CASE_DIR"`). The variables are always set, whatever the
//! values hold. Filling is one pass: a value is never searched for placeholders again.

use std::path::Path;

use crate::exchange::scene_file;

/// The placeholders and the environment variables that carry the same values.
pub const PLACEHOLDERS: [(&str, &str); 3] = [
    ("{case_dir}", "SPHERECONTACT_CASE_DIR"),
    ("{scene}", "SPHERECONTACT_SCENE"),
    ("{history}", "SPHERECONTACT_HISTORY"),
];

/// The characters other than letters and digits a placeholder's value may hold.
pub const SAFE_PUNCTUATION: &str = "/._-+,:@%";

/// A placeholder whose value may not be filled in.
#[derive(Debug, thiserror::Error)]
pub enum PlaceholderError {
    /// The value holds a character outside the safe set.
    #[error(
        "{placeholder} is {value:?}, which holds {character:?}: a placeholder's value may hold only letters, \
         digits and {SAFE_PUNCTUATION} (a folder's name must never run as code); move the case to a folder \
         with a plain name, or use the environment variable {variable} (quoted, e.g. \"${variable}\") where a \
         shell reads it"
    )]
    Unsafe {
        /// The placeholder.
        placeholder: &'static str,
        /// Its value.
        value: String,
        /// The first character outside the safe set.
        character: char,
        /// The environment variable with the same value.
        variable: &'static str,
    },
}

/// True for a character a placeholder's value may hold.
pub fn is_safe(c: char) -> bool {
    c.is_alphanumeric() || SAFE_PUNCTUATION.contains(c)
}

/// The values of one run: the case's folder, and the run's folder once there is one.
#[derive(Clone, Copy, Debug)]
pub struct Values<'a> {
    /// The case file's folder (absolute).
    pub case_dir: &'a Path,
    /// The run's folder (absolute); `None` when showing a command before it runs: `{scene}` and
    /// `{history}` are then left as they are.
    pub run_dir: Option<&'a Path>,
}

impl Values<'_> {
    /// The value of each placeholder (in [`PLACEHOLDERS`]' order), `None` when not known yet.
    fn all(&self) -> [Option<String>; 3] {
        let in_run = |file: &str| self.run_dir.map(|d| d.join(file).to_string_lossy().into_owned());
        [
            Some(self.case_dir.to_string_lossy().into_owned()),
            in_run(scene_file::FILE_NAME),
            in_run(scene_file::HISTORY_FILE),
        ]
    }

    /// The environment variables of [`PLACEHOLDERS`] with their values (those known).
    pub fn environment(&self) -> Vec<(String, String)> {
        PLACEHOLDERS
            .iter()
            .zip(self.all())
            .filter_map(|((_, variable), value)| Some(((*variable).to_owned(), value?)))
            .collect()
    }

    /// `text` with its placeholders filled, in one pass; an unknown value leaves its placeholder.
    pub fn fill(&self, text: &str) -> Result<String, PlaceholderError> {
        let values = self.all();
        let mut out = String::with_capacity(text.len());
        let mut rest = text;
        while let Some(open) = rest.find('{') {
            out.push_str(&rest[..open]);
            rest = &rest[open..];
            let found = PLACEHOLDERS
                .iter()
                .zip(&values)
                .find(|((placeholder, _), _)| rest.starts_with(placeholder));
            match found {
                Some(((placeholder, variable), value)) => {
                    match value {
                        Some(value) => out.push_str(checked(placeholder, variable, value)?),
                        None => out.push_str(placeholder),
                    }
                    rest = &rest[placeholder.len()..];
                }
                None => {
                    out.push('{');
                    rest = &rest[1..];
                }
            }
        }
        out.push_str(rest);
        Ok(out)
    }
}

/// `value`, when all its characters are safe.
fn checked<'v>(
    placeholder: &'static str,
    variable: &'static str,
    value: &'v str,
) -> Result<&'v str, PlaceholderError> {
    match value.chars().find(|&c| !is_safe(c)) {
        None => Ok(value),
        Some(character) => Err(PlaceholderError::Unsafe {
            placeholder,
            value: value.to_owned(),
            character,
            variable,
        }),
    }
}

/// One argument as a reader should see it: as it is when made of safe characters (and `{`,
/// `}`, `=`), else in single quotes with control characters escaped.
pub fn shown(argument: &str) -> String {
    if !argument.is_empty()
        && argument
            .chars()
            .all(|c| is_safe(c) || matches!(c, '{' | '}' | '='))
    {
        return argument.to_owned();
    }
    let mut out = String::from("'");
    for c in argument.chars() {
        match c {
            '\'' => out.push_str("'\\''"),
            c if c.is_control() => out.extend(c.escape_default()),
            c => out.push(c),
        }
    }
    out.push('\'');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values<'a>(case_dir: &'a str, run_dir: Option<&'a str>) -> Values<'a> {
        Values {
            case_dir: Path::new(case_dir),
            run_dir: run_dir.map(Path::new),
        }
    }

    #[test]
    fn fills_every_placeholder_once() {
        let v = values("/cases/a-1", Some("/tmp/run.x"));
        assert_eq!(
            v.fill("python3 {case_dir}/s.py {scene} > {history} {other}")
                .unwrap(),
            "python3 /cases/a-1/s.py /tmp/run.x/scene.json > /tmp/run.x/history.csv {other}"
        );
        // Before the run, {scene} and {history} stay as they are.
        assert_eq!(
            values("/c", None).fill("{case_dir} {scene}").unwrap(),
            "/c {scene}"
        );
    }

    #[test]
    fn refuses_a_value_with_shell_syntax_naming_folder_and_character() {
        for (folder, bad) in [
            ("/c/x;touch pwned", ';'),
            ("/c/$(id)", '$'),
            ("/c/a b", ' '),
            ("/c/`id`", '`'),
            ("/c/'q'", '\''),
            ("/c/x\ny", '\n'),
            ("/c/{scene}", '{'),
        ] {
            let e = values(folder, None).fill("sh -c 'cd {case_dir}'").unwrap_err();
            let message = e.to_string();
            let PlaceholderError::Unsafe { character, value, .. } = &e;
            assert_eq!((*character, value.as_str()), (bad, folder), "{message}");
            assert!(message.contains("SPHERECONTACT_CASE_DIR"), "{message}");
        }
        // Unused placeholders are not checked.
        assert_eq!(values("/c/a b", None).fill("true").unwrap(), "true");
        // Letters of any script are safe.
        assert!(values("/home/josé/Müller_2.0", None).fill("{case_dir}").is_ok());
    }

    #[test]
    fn shows_arguments_quoted_when_they_need_it() {
        assert_eq!(shown("{scene}"), "{scene}");
        assert_eq!(shown("a b"), "'a b'");
        assert_eq!(shown("it's"), "'it'\\''s'");
        assert_eq!(shown("x\u{1b}[2J"), "'x\\u{1b}[2J'");
    }
}
