//! Solvers an impact case defines itself: the user's own law or code, as a program that writes
//! the sweep table of the variant it is given, or as sweep tables stored in files. The same rules
//! as a path case's (`super::case_solvers`: a plain new name, a kind, opt-in programs, files
//! inside the case's tree, bounded reads), and a stored table is read against the sweep here,
//! when the case is read.
//!
//! ```toml
//! [[command_solvers]]
//! name = "my-law"
//! kind = "dem-law"                      # analytic, dem-law, dem-code, fe, be
//! command = ["python3", "{case_dir}/my_law.py", "{scene}", "{history}"]
//! timeout = 60                          # s, optional (default 600), per variant
//!
//! [[stored_results]]
//! name = "lab-rig"
//! kind = "dem-code"
//! file = "data/lab-rig.csv"             # the prescribed variant's sweep table (docs/impact.md)
//! elastic_file = "data/lab-rig-e1.csv"  # optional: the elastic variant's (cases with e < 1)
//! ```

use toml::Spanned;

use super::impact_raw::{RawImpact, RawImpactStored};
use crate::{CaseError, Validator};
use spherecontact_reference::impact::own_solver::{OwnSolver, Source};
use spherecontact_reference::impact::problem::{ImpactCase, Variant};
use spherecontact_reference::impact::table;
use spherecontact_system::input::Links;

impl Validator<'_> {
    /// The impact case's own solvers, their names checked against each other and every solver
    /// of this build, stored tables read against the sweep.
    pub(super) fn impact_own_solvers(
        &self,
        raw: &RawImpact,
        case: &ImpactCase,
    ) -> Result<Vec<OwnSolver>, CaseError> {
        let mut solvers: Vec<OwnSolver> = Vec::new();
        for (i, raw) in raw.command_solvers.iter().enumerate() {
            let field = format!("command_solvers[{i}]");
            self.own_name(&raw.name, &field, &solvers)?;
            let command = self.command_solver(raw, &field)?;
            solvers.push(OwnSolver {
                name: command.name,
                kind: command.kind,
                description: command.description,
                source: Source::Command {
                    command: command.command,
                    timeout: command.timeout,
                    case_dir: command.case_dir,
                    permission: command.permission,
                },
            });
        }
        for (i, raw) in raw.stored_results.iter().enumerate() {
            let field = format!("stored_results[{i}]");
            self.own_name(&raw.name, &field, &solvers)?;
            solvers.push(self.impact_stored(raw, &field, case)?);
        }
        Ok(solvers)
    }

    fn own_name(&self, name: &Spanned<String>, field: &str, earlier: &[OwnSolver]) -> Result<(), CaseError> {
        let earlier: Vec<&str> = earlier.iter().map(|s| s.name.as_str()).collect();
        self.new_solver_name(name, field, &earlier)
    }

    fn impact_stored(
        &self,
        raw: &RawImpactStored,
        field: &str,
        case: &ImpactCase,
    ) -> Result<OwnSolver, CaseError> {
        let prescribed = self.sweep_table(&raw.file, &format!("{field}.file"), case, Variant::Prescribed)?;
        let elastic = match &raw.elastic_file {
            Some(_) if case.restitution >= 1.0 => {
                let at = raw.elastic_file.as_ref().expect("matched Some");
                return Err(self.error(
                    at,
                    format!("{field}.elastic_file"),
                    "the case is elastic already (allowed: only with restitution < 1)",
                ));
            }
            Some(file) => {
                Some(self.sweep_table(file, &format!("{field}.elastic_file"), case, Variant::Elastic)?)
            }
            None => None,
        };
        Ok(OwnSolver {
            name: raw.name.get_ref().clone(),
            kind: self.solver_kind(&raw.kind, field)?,
            description: raw
                .description
                .clone()
                .unwrap_or_else(|| format!("stored results {}", raw.file.get_ref())),
            source: Source::Stored { prescribed, elastic },
        })
    }

    /// The file `name` inside the case's tree, read as `variant`'s sweep table of `case`.
    fn sweep_table(
        &self,
        name: &Spanned<String>,
        field: &str,
        case: &ImpactCase,
        variant: Variant,
    ) -> Result<std::path::PathBuf, CaseError> {
        let file = self
            .tree
            .resolve(name.get_ref())
            .map_err(|e| self.error(name, field, format!("stored results {e}")))?;
        table::read_file(&file, case.sweep_name(), &case.points_of(variant), Links::Follow)
            .map_err(|e| self.error(name, field, e))?;
        Ok(file)
    }
}
