//! The `[resolution]` table of a case and `--resolution SOLVER=VALUE`: a resolution per solver,
//! each value judged by the solver it names ([`spherecontact_model::solver::Solver::at_resolution`]).
//!
//! ```toml
//! [resolution]
//! bem = 128                    # panels a side: even, 4 ≤ n ≤ 512
//! mdr = 16000                  # springs: 1 ≤ n ≤ 1 000 000
//! fem-axisym = "c/80"          # pole element: c/N with 2 ≤ N ≤ 320, or a length ("10um")
//! fem-3d = "c/12"              # pole element: c/N with 2 ≤ N ≤ 14, or a length
//! ```

use std::collections::BTreeMap;

use toml::Spanned;

use crate::registry;
use crate::{Case, CaseError, Validator};
use spherecontact_model::resolution::ResolutionError;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::Solver;

/// The registry's solvers that have a resolution to choose, for `scene`, with their names.
fn resolvable(scene: &Scene) -> String {
    // A solver without a resolution refuses every value as NotResolvable; one with a
    // resolution refuses the empty value as Invalid.
    let names: Vec<String> = registry::registry()
        .iter()
        .filter(|s| {
            !matches!(
                s.at_resolution(scene, ""),
                Err(ResolutionError::NotResolvable { .. })
            )
        })
        .map(|s| s.name().to_owned())
        .collect();
    format!("a solver with a resolution: {}", names.join(", "))
}

/// Text of a TOML value given as a resolution: a whole number, a number or a string.
fn value_text(value: &toml::Value) -> Option<String> {
    match value {
        toml::Value::Integer(n) => Some(n.to_string()),
        toml::Value::Float(x) => Some(x.to_string()),
        toml::Value::String(s) => Some(s.clone()),
        _ => None,
    }
}

impl Case {
    /// Sets `name`'s resolution to `value` (the command line's, over the case file's), after the
    /// solver judged it for this case's scene.
    pub fn set_resolution(&mut self, name: &str, value: &str) -> Result<(), ResolutionError> {
        self.at_resolution(name, value)?;
        self.resolution.insert(name.to_owned(), value.to_owned());
        Ok(())
    }

    /// The solver `name` at `value`, or why not.
    fn at_resolution(&self, name: &str, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let solver = self.unresolved_solver(name).ok_or_else(|| {
            let known = registry::names();
            ResolutionError::UnknownSolver {
                solver: name.to_owned(),
                did_you_mean: registry::did_you_mean(name, &known),
                known: known.join(", "),
            }
        })?;
        solver.at_resolution(&self.scene, value).map_err(|e| match e {
            ResolutionError::NotResolvable { solver, .. } => ResolutionError::NotResolvable {
                solver,
                with: resolvable(&self.scene),
            },
            other => other,
        })
    }

    /// The solver `name` at the resolution chosen for it, if any.
    pub(super) fn resolved(&self, solver: Box<dyn Solver>) -> Box<dyn Solver> {
        match self.resolution.get(solver.name()) {
            // Validated when set: a refusal here is a solver whose limits changed since.
            Some(value) => match solver.at_resolution(&self.scene, value) {
                Ok(inner) => Box::new(spherecontact_model::solver::Resolved {
                    inner,
                    value: value.clone(),
                }),
                Err(_) => solver,
            },
            None => solver,
        }
    }
}

impl Validator<'_> {
    /// The `[resolution]` table, each value judged by its solver for `case`'s scene.
    pub(super) fn resolution(
        &self,
        table: &BTreeMap<Spanned<String>, Spanned<toml::Value>>,
        case: &mut Case,
    ) -> Result<(), CaseError> {
        for (name, value) in table {
            let field = format!("resolution.{}", name.get_ref());
            let text = value_text(value.get_ref()).ok_or_else(|| {
                self.error(
                    value,
                    &field,
                    "not a resolution (allowed: a number such as 128, or a string such as \"c/80\" or \"10um\")",
                )
            })?;
            case.set_resolution(name.get_ref(), &text).map_err(|e| match e {
                ResolutionError::UnknownSolver { .. } | ResolutionError::NotResolvable { .. } => {
                    self.error(name, &field, e.to_string())
                }
                ResolutionError::Invalid { .. } => self.error(value, &field, e.to_string()),
            })?;
        }
        Ok(())
    }
}
