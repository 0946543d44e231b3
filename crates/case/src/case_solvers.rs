//! Solvers a case defines itself: a program run as a solver (`[[command_solvers]]`) and results
//! computed elsewhere (`[[stored_results]]`).
//!
//! ```toml
//! [[command_solvers]]
//! name = "hertz-python"                 # a plain name (letters, digits, . _ -), not a built-in's
//! kind = "analytic"                     # required: analytic, dem-law, dem-code, fe or be
//! command = ["python3", "{case_dir}/../examples/hertz_command_solver.py", "{scene}"]
//! timeout = 60                          # s, optional (default 600), 0 < t ≤ 86400
//! description = "…"                     # optional
//!
//! [[stored_results]]
//! name = "lab-rig"
//! kind = "fe"                           # required, as above
//! file = "data/lab-rig.csv"             # a History CSV, relative to the case file, inside
//!                                       # its tree (`super::reads`), at most 256 MiB
//! description = "…"                     # optional
//! ```
//! Both formats (the scene file a command reads, the History CSV it writes and a stored file
//! holds) are in `spherecontact_external::exchange` and docs/own-solver.md. A stored file is
//! validated against the path here, when the case is read.

use std::path::Path;
use std::time::Duration;

use toml::Spanned;

use super::raw::{RawCommandSolver, RawStoredResults};
use crate::registry;
use crate::{Case, CaseError, Validator};
use spherecontact_external::command::CommandSolver;
use spherecontact_external::exchange::results_csv;
use spherecontact_external::permission::CommandPermission;
use spherecontact_external::stored::StoredResults;
use spherecontact_model::path::LoadingPath;
use spherecontact_model::solver::{Kind, Solver};

/// A command's time limit when the case gives none [s].
pub const DEFAULT_TIMEOUT_S: f64 = 600.0;

/// The longest time limit a case may give a command [s]: one day.
pub const MAX_TIMEOUT_S: f64 = 86_400.0;

/// The longest solver name (it names output files).
const MAX_NAME: usize = 64;

/// A solver defined by the case.
#[derive(Clone, Debug, PartialEq)]
pub enum CaseSolver {
    /// A program run as a solver.
    Command(CommandSolver),
    /// Results stored in a file.
    Stored(StoredResults),
}

impl CaseSolver {
    /// The solver.
    pub fn solver(&self) -> Box<dyn Solver> {
        match self {
            CaseSolver::Command(s) => Box::new(s.clone()),
            CaseSolver::Stored(s) => Box::new(s.clone()),
        }
    }

    /// Its name.
    pub fn name(&self) -> &str {
        match self {
            CaseSolver::Command(s) => &s.name,
            CaseSolver::Stored(s) => &s.name,
        }
    }

    /// The kind of model it is, as the case says.
    pub fn kind(&self) -> Kind {
        match self {
            CaseSolver::Command(s) => s.kind,
            CaseSolver::Stored(s) => s.kind,
        }
    }

    /// How it gives its results, in words: "a program" or "stored results".
    pub fn origin(&self) -> &'static str {
        match self {
            CaseSolver::Command(_) => "a program",
            CaseSolver::Stored(_) => "stored results",
        }
    }
}

impl Case {
    /// The kind of model the solver `name` is: a case's own solver's as the case says, a built-in
    /// solver's its own; `None` for a name this build and the case do not know.
    pub fn solver_kind(&self, name: &str) -> Option<Kind> {
        match self.own_solver(name) {
            Some(own) => Some(own.kind()),
            None => registry::by_name(name).map(|s| s.kind()),
        }
    }

    /// The kind of the solver `name` in words, for tables: "DEM law", "finite elements", or for
    /// the case's own solvers "DEM law, yours (a program)"; "unknown" for a name nobody knows.
    pub fn kind_in_words(&self, name: &str) -> String {
        match (self.solver_kind(name), self.own_solver(name)) {
            (Some(kind), Some(own)) => format!("{kind}, yours ({})", own.origin()),
            (Some(kind), None) => kind.to_string(),
            (None, _) => "unknown".to_owned(),
        }
    }

    /// The case's own solver called `name`, if it defines one.
    pub fn own_solver(&self, name: &str) -> Option<&CaseSolver> {
        self.own_solvers.iter().find(|s| s.name() == name)
    }

    /// Lets the case's command solvers run under `permission` (they are refused until then).
    pub fn permit_commands(&mut self, permission: &CommandPermission) {
        for solver in &mut self.own_solvers {
            if let CaseSolver::Command(command) = solver {
                command.permission = permission.clone();
            }
        }
    }

    /// The case's command solvers that a run of the case needs (its list and its checks'), each
    /// with the command it would run ([`CommandSolver::shown`]).
    pub fn commands(&self) -> Vec<&CommandSolver> {
        let needed = self.required_solvers();
        self.own_solvers
            .iter()
            .filter_map(|s| match s {
                CaseSolver::Command(c) if needed.contains(&c.name) => Some(c),
                _ => None,
            })
            .collect()
    }

    /// Lines that say which commands a run of the case would run and whether they may: for
    /// `verify`, `list` and `doctor`; none for a case without command solvers.
    pub fn command_lines(&self) -> Vec<String> {
        spherecontact_external::command::lines(self.name(), &self.commands())
    }
}

impl Validator<'_> {
    /// The case's own solvers, their names checked against each other and the registry.
    pub(super) fn case_solvers(
        &self,
        commands: &[RawCommandSolver],
        stored: &[RawStoredResults],
        path: &LoadingPath,
    ) -> Result<Vec<CaseSolver>, CaseError> {
        let mut solvers: Vec<CaseSolver> = Vec::new();
        for (i, raw) in commands.iter().enumerate() {
            let field = format!("command_solvers[{i}]");
            self.new_name(&raw.name, &field, &solvers)?;
            solvers.push(CaseSolver::Command(self.command_solver(raw, &field)?));
        }
        for (i, raw) in stored.iter().enumerate() {
            let field = format!("stored_results[{i}]");
            self.new_name(&raw.name, &field, &solvers)?;
            solvers.push(CaseSolver::Stored(self.stored_results(raw, &field, path)?));
        }
        Ok(solvers)
    }

    /// Checks that `name` is a plain name that no built-in or earlier case solver has.
    fn new_name(&self, name: &Spanned<String>, field: &str, earlier: &[CaseSolver]) -> Result<(), CaseError> {
        let earlier: Vec<&str> = earlier.iter().map(CaseSolver::name).collect();
        self.new_solver_name(name, field, &earlier)
    }

    /// Checks that `name` is a plain name that no built-in solver and none of `earlier` has.
    pub(super) fn new_solver_name(
        &self,
        name: &Spanned<String>,
        field: &str,
        earlier: &[&str],
    ) -> Result<(), CaseError> {
        let text = name.get_ref();
        let plain = !text.is_empty()
            && text.len() <= MAX_NAME
            && text
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'))
            && text.starts_with(|c: char| c.is_ascii_alphanumeric());
        let field = format!("{field}.name");
        if !plain {
            return Err(self.error(
                name,
                field,
                format!("`{text}` is not a plain name (allowed: 1 to {MAX_NAME} ASCII letters, digits, . _ -, starting with a letter or digit)"),
            ));
        }
        if registry::by_name(text).is_some()
            || earlier.contains(&text.as_str())
            || super::impact_solvers::solver_names().contains(&text.as_str())
        {
            return Err(self.error(
                name,
                field,
                format!("`{text}` is already a solver's name (allowed: a new name)"),
            ));
        }
        Ok(())
    }

    pub(super) fn command_solver(
        &self,
        raw: &RawCommandSolver,
        field: &str,
    ) -> Result<CommandSolver, CaseError> {
        let command = raw.command.get_ref();
        if command.first().is_none_or(|p| p.trim().is_empty()) {
            return Err(self.error(
                &raw.command,
                format!("{field}.command"),
                "no program (allowed: [\"PROGRAM\", \"ARGUMENT\", …])",
            ));
        }
        let timeout = match &raw.timeout {
            Some(t) => self.number(
                t,
                &format!("{field}.timeout"),
                |t| t > 0.0 && t <= MAX_TIMEOUT_S,
                "0 < timeout ≤ 86400 s",
            )?,
            None => DEFAULT_TIMEOUT_S,
        };
        Ok(CommandSolver {
            name: raw.name.get_ref().clone(),
            command: command.clone(),
            timeout: Duration::from_secs_f64(timeout),
            case_dir: self.case_dir().to_path_buf(),
            description: raw
                .description
                .clone()
                .unwrap_or_else(|| format!("command: {}", command.join(" "))),
            kind: self.solver_kind(&raw.kind, field)?,
            permission: CommandPermission::refused(),
        })
    }

    /// The kind of model a case's own solver is (`kind = "dem-law"`, …).
    pub(super) fn solver_kind(&self, raw: &Spanned<String>, field: &str) -> Result<Kind, CaseError> {
        Kind::from_name(raw.get_ref()).ok_or_else(|| {
            self.error(
                raw,
                format!("{field}.kind"),
                format!(
                    "`{}` is not a kind of model (allowed: {}: an analytic model, a DEM law, a DEM code, finite or boundary elements)",
                    raw.get_ref(),
                    Kind::allowed()
                ),
            )
        })
    }

    fn stored_results(
        &self,
        raw: &RawStoredResults,
        field: &str,
        path: &LoadingPath,
    ) -> Result<StoredResults, CaseError> {
        let file_field = format!("{field}.file");
        let file = self
            .tree
            .resolve(raw.file.get_ref())
            .map_err(|e| self.error(&raw.file, &file_field, format!("stored results {e}")))?;
        results_csv::read(&file, &path.steps())
            .map_err(|e| self.error(&raw.file, file_field, e.to_string()))?;
        Ok(StoredResults {
            name: raw.name.get_ref().clone(),
            file,
            description: raw
                .description
                .clone()
                .unwrap_or_else(|| format!("stored results {}", raw.file.get_ref())),
            kind: self.solver_kind(&raw.kind, field)?,
        })
    }

    /// The case file's folder, against which its relative paths resolve.
    fn case_dir(&self) -> &Path {
        match self.file.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        }
    }
}
