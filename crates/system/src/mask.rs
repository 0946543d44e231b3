//! Secrets masked in a program's output before the harness shows or stores any of it
//! (docs/security.md, "Programs a case may run"): the values of the variables passed on with
//! `--pass-env`, and of every variable of the harness's environment named like a secret
//! ([`is_secret_name`]), are replaced by `[masked: NAME]` in the excerpt of a program's output
//! that failure messages, `run.json`, JUnit, `summary.txt` and the reports carry
//! ([`super::process::Run`]).
//!
//! Secret-named variables are masked whether or not they reach the program: a program runs as
//! the user and can read the harness's own `/proc/<pid>/environ`. Values shorter than
//! [`MIN_MASKED_CHARS`] are left as they are. A value is masked as it is written and line by line
//! (a multi-line key printed in part); a program that transforms a value (base64, reversed, one
//! character a line) defeats the mask: it guards against a secret printed by accident, the
//! minimal environment against the program ([`super::process::MINIMAL_ENV`]).

use std::borrow::Cow;
use std::ffi::OsString;

/// The words that make a variable's name a secret's, matched anywhere in the name, ignoring
/// case: the names CI services, cloud and package tools give their credentials (`GITHUB_TOKEN`,
/// `CI_JOB_TOKEN`, `AWS_SECRET_ACCESS_KEY`, `AWS_SESSION_TOKEN`, `PGPASSWORD`, `DB_PASS`,
/// `MYSQL_PWD`, `GOOGLE_APPLICATION_CREDENTIALS`, `SSH_PRIVATE_KEY`, `OPENAI_APIKEY`,
/// `SIGNING_KEY`, `NPM_AUTH`, `SESSION_COOKIE`, `SLACK_WEBHOOK_URL`). A name matched by
/// mistake (`GIT_AUTHOR_NAME`, `XAUTHORITY`, `DBUS_SESSION_BUS_ADDRESS`) only hides a value a
/// solver's output rarely holds; a name missed publishes a secret. `_PASS`, `_PWD` and `_KEY`
/// carry their underscore so that `PWD` (the current folder, in every path), `OLDPWD`,
/// `KEYBOARD_LAYOUT` or `MONKEY` are not matched.
pub const SECRET_NAME_WORDS: [&str; 15] = [
    "TOKEN",
    "SECRET",
    "PASSWORD",
    "PASSWD",
    "PASSPHRASE",
    "_PASS",
    "_PWD",
    "CREDENTIAL",
    "PRIVATE",
    "APIKEY",
    "_KEY",
    "SESSION",
    "AUTH",
    "COOKIE",
    "WEBHOOK",
];

/// The shortest value masked, in characters (8): a shorter value (`1`, `true`, `x11`, a port, a
/// user name) stands for ordinary words and numbers of any output, and masking it would garble
/// every excerpt (a value `1` would take every digit 1); tokens, keys and passwords under most
/// policies are longer. GitLab's masked CI variables must have 8 characters or more, for the same
/// reason.
pub const MIN_MASKED_CHARS: usize = 8;

/// True for a variable's name that holds one of [`SECRET_NAME_WORDS`], ignoring case.
pub fn is_secret_name(name: &str) -> bool {
    let name = name.to_ascii_uppercase();
    SECRET_NAME_WORDS.iter().any(|word| name.contains(word))
}

/// The values to mask, each with the name of its variable.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mask {
    /// (value or line of a value, the variable's name), longest value first.
    secrets: Vec<(String, String)>,
}

impl Mask {
    /// The mask of the harness's environment: the values of the variables named in `passed` and
    /// of every variable named like a secret.
    pub fn of_environment(passed: &[String]) -> Self {
        Self::of(std::env::vars_os(), passed)
    }

    /// The mask of the environment `variables` (name, value): the values of the variables named
    /// in `passed` and of every variable named like a secret, each whole and line by line, each
    /// of [`MIN_MASKED_CHARS`] characters or more after trimming.
    pub fn of(variables: impl IntoIterator<Item = (OsString, OsString)>, passed: &[String]) -> Self {
        let mut secrets: Vec<(String, String)> = Vec::new();
        for (name, value) in variables {
            let name = name.to_string_lossy();
            if !(passed.iter().any(|p| *p == name) || is_secret_name(&name)) {
                continue;
            }
            let value = value.to_string_lossy();
            let pieces = std::iter::once(value.as_ref()).chain(value.lines());
            for piece in pieces.map(str::trim) {
                if piece.chars().count() >= MIN_MASKED_CHARS {
                    secrets.push((piece.to_owned(), name.clone().into_owned()));
                }
            }
        }
        // Longest first (a value holding another is masked whole), then by name: one mask for
        // one environment, whatever order it lists its variables in.
        secrets.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then_with(|| a.cmp(b)));
        secrets.dedup_by(|a, b| a.0 == b.0);
        Mask { secrets }
    }

    /// `text` with every value of the mask replaced by `[masked: NAME]`.
    pub fn apply<'a>(&self, text: &'a str) -> Cow<'a, str> {
        let mut text = Cow::Borrowed(text);
        for (value, name) in &self.secrets {
            if text.contains(value.as_str()) {
                text = Cow::Owned(text.replace(value.as_str(), &format!("[masked: {name}]")));
            }
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(variables: &[(&str, &str)], passed: &[&str]) -> Mask {
        let variables = variables
            .iter()
            .map(|(n, v)| (OsString::from(n), OsString::from(v)));
        let passed: Vec<String> = passed.iter().map(|p| p.to_string()).collect();
        Mask::of(variables, &passed)
    }

    /// Names holding a secret's word are secrets, in any case; the current folder, a keyboard
    /// layout and the ordinary variables are not.
    #[test]
    fn a_name_holding_a_secret_word_is_a_secret_s_name() {
        for name in [
            "GITHUB_TOKEN",
            "aws_secret_access_key",
            "AWS_SESSION_TOKEN",
            "PGPASSWORD",
            "DB_PASS",
            "MYSQL_PWD",
            "GOOGLE_APPLICATION_CREDENTIALS",
            "SSH_PRIVATE_KEY",
            "OPENAI_APIKEY",
            "SIGNING_KEY",
            "NPM_AUTH",
            "SESSION_COOKIE",
            "SLACK_WEBHOOK_URL",
            "PASSPHRASE",
        ] {
            assert!(is_secret_name(name), "{name}");
        }
        for name in [
            "PATH",
            "HOME",
            "PWD",
            "OLDPWD",
            "KEYBOARD_LAYOUT",
            "MONKEY",
            "LANG",
            "LM_LICENSE_FILE",
        ] {
            assert!(!is_secret_name(name), "{name}");
        }
    }

    /// The values of passed and secret-named variables are replaced by their mask, whole and line
    /// by line; other variables and values under the least length are left as they are.
    #[test]
    fn passed_and_secret_named_values_are_masked_others_are_not() {
        let mask = mask(
            &[
                ("LM_LICENSE_FILE", "27000@licence-host"),
                ("CI_JOB_TOKEN", "glcbt-64-abcdefgh"),
                (
                    "SSH_PRIVATE_KEY",
                    "-----BEGIN KEY-----\nMIIEowIBAAKCAQEA\n-----END KEY-----\n",
                ),
                ("DESKTOP_SESSION", "ubuntu"),
                ("HOSTNAME", "build-host-17"),
            ],
            &["LM_LICENSE_FILE"],
        );
        let printed = "licence 27000@licence-host; token=glcbt-64-abcdefgh\nMIIEowIBAAKCAQEA\n\
                       on build-host-17, session ubuntu";
        assert_eq!(
            mask.apply(printed),
            "licence [masked: LM_LICENSE_FILE]; token=[masked: CI_JOB_TOKEN]\n\
             [masked: SSH_PRIVATE_KEY]\non build-host-17, session ubuntu"
        );
    }

    /// A value holding another value is masked whole, and text without a secret is borrowed
    /// unchanged.
    #[test]
    fn the_longest_value_is_masked_first_and_clean_text_is_unchanged() {
        let mask = mask(&[("A_TOKEN", "abcdefgh"), ("B_TOKEN", "xx-abcdefgh-yy")], &[]);
        assert_eq!(
            mask.apply("xx-abcdefgh-yy abcdefgh"),
            "[masked: B_TOKEN] [masked: A_TOKEN]"
        );
        assert!(matches!(mask.apply("nothing here"), Cow::Borrowed(_)));
    }
}
