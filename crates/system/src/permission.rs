//! Whether the programs a case names as solvers (`[[command_solvers]]`) may run: only when the
//! user says so, on the command line ([`ALLOW_FLAG`]) or, for CI, in the environment
//! ([`ALLOW_ENV`]`=1`). Without it such a solver is not run and says why and how to allow it;
//! the checks that need it are N/A, which `verify --require-external` counts as failures.
//!
//! An allowed program runs in a minimal environment ([`spherecontact_system::process::MINIMAL_ENV`]) plus the variables named
//! with [`PASS_ENV_FLAG`]: the secrets of the harness's environment do not reach it.

use crate::process::Environment;

/// The command-line flag that allows a case's command solvers to run.
pub const ALLOW_FLAG: &str = "--allow-commands";

/// The environment variable that allows them (value `1`), for CI.
pub const ALLOW_ENV: &str = "SPHERECONTACT_ALLOW_COMMANDS";

/// The command-line option that passes one more variable to the programs (repeatable).
pub const PASS_ENV_FLAG: &str = "--pass-env";

/// Who allowed the command solvers.
#[derive(Clone, Copy, Debug, PartialEq)]
enum AllowedBy {
    Flag,
    Environment,
}

/// Whether a case's command solvers may run, and with which environment.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CommandPermission {
    allowed_by: Option<AllowedBy>,
    pass_env: Vec<String>,
}

/// An opt-in given wrongly.
#[derive(Debug, thiserror::Error)]
pub enum PermissionError {
    /// The environment variable holds something else than 1 or 0.
    #[error("{ALLOW_ENV}={0:?} (allowed: 1 to run the command solvers cases name, 0 or unset not to)")]
    Environment(String),
    /// A name given to pass on is not a variable's name.
    #[error("{PASS_ENV_FLAG} {0:?}: not a variable's name (allowed: letters, digits and _, not starting with a digit)")]
    Name(String),
}

impl CommandPermission {
    /// No command solver may run (the default).
    pub fn refused() -> Self {
        Self::default()
    }

    /// The permission of the command line's flag `flag` or, without it, of [`ALLOW_ENV`] in the
    /// harness's environment; `pass_env`: the names of [`PASS_ENV_FLAG`].
    pub fn from_options(flag: bool, pass_env: &[String]) -> Result<Self, PermissionError> {
        let from_environment = match std::env::var(ALLOW_ENV) {
            Err(std::env::VarError::NotPresent) => false,
            Ok(value) if value.is_empty() || value == "0" => false,
            Ok(value) if value == "1" => true,
            Ok(value) => return Err(PermissionError::Environment(value)),
            Err(std::env::VarError::NotUnicode(value)) => {
                return Err(PermissionError::Environment(value.to_string_lossy().into_owned()))
            }
        };
        if let Some(bad) = pass_env.iter().find(|n| !is_variable_name(n)) {
            return Err(PermissionError::Name(bad.clone()));
        }
        let allowed_by = if flag {
            Some(AllowedBy::Flag)
        } else {
            from_environment.then_some(AllowedBy::Environment)
        };
        Ok(CommandPermission {
            allowed_by,
            pass_env: pass_env.to_vec(),
        })
    }

    /// The permission of the flag alone (the environment not read): for tests and library use.
    pub fn allowed() -> Self {
        CommandPermission {
            allowed_by: Some(AllowedBy::Flag),
            pass_env: Vec::new(),
        }
    }

    /// Whether command solvers may run.
    pub fn is_allowed(&self) -> bool {
        self.allowed_by.is_some()
    }

    /// The environment an allowed program runs in.
    pub fn environment(&self) -> Environment {
        Environment::Minimal(self.pass_env.clone())
    }

    /// The state in words, for `verify`, `list` and `doctor`.
    pub fn state(&self) -> String {
        let passed = match self.pass_env.as_slice() {
            [] => String::new(),
            names => format!(" and {}", names.join(", ")),
        };
        match self.allowed_by {
            Some(AllowedBy::Flag) => format!("allowed by {ALLOW_FLAG} (minimal environment{passed})"),
            Some(AllowedBy::Environment) => format!("allowed by {ALLOW_ENV}=1 (minimal environment{passed})"),
            None => format!("not allowed ({})", how_to_allow()),
        }
    }
}

/// How to allow command solvers, in words.
pub fn how_to_allow() -> String {
    format!("read the commands, then pass {ALLOW_FLAG} or set {ALLOW_ENV}=1")
}

/// True for a name an environment variable may have: letters, digits and `_`, not starting with
/// a digit.
fn is_variable_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with(|c: char| c.is_ascii_digit())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refused_unless_allowed() {
        assert!(!CommandPermission::refused().is_allowed());
        assert!(CommandPermission::refused().state().contains(ALLOW_FLAG));
        let flag = CommandPermission::from_options(true, &["LM_LICENSE_FILE".into()]).unwrap();
        assert!(flag.is_allowed());
        assert_eq!(
            flag.environment(),
            Environment::Minimal(vec!["LM_LICENSE_FILE".into()])
        );
        assert!(flag.state().contains("allowed by --allow-commands"));
    }

    #[test]
    fn pass_env_takes_only_variable_names() {
        for bad in ["", "1X", "A=B", "A B", "-x"] {
            let e = CommandPermission::from_options(true, &[bad.into()]).unwrap_err();
            assert!(e.to_string().contains("--pass-env"), "{e}");
        }
    }
}
