//! Stored results: a History CSV computed elsewhere (a commercial FE code, a lab rig, an earlier
//! run) named by a case as a solver's results for its path, validated against the path
//! ([`crate::exchange::results_csv`]: row count, positions, δn and δt in SI) and then checked and
//! reported like any solver.

use std::path::PathBuf;

use serde_json::json;

use crate::exchange::results_csv;
use spherecontact_model::history::{History, Metadata};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};

/// Results stored in a file, as a solver.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredResults {
    /// The solver's name in the case (a plain name: it names output files).
    pub name: String,
    /// The History CSV.
    pub file: PathBuf,
    /// The description shown in reports.
    pub description: String,
    /// The kind of model that computed them, as the case says.
    pub kind: Kind,
}

impl Solver for StoredResults {
    fn name(&self) -> &str {
        &self.name
    }

    fn kind(&self) -> Kind {
        self.kind
    }

    fn description(&self) -> &str {
        &self.description
    }

    /// The stored rows, if they follow `scene`'s path (a refined path of `bench` does not), with
    /// why a quantity is not in them (`Metadata::unread`).
    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let results = results_csv::read(&self.file, &scene.steps())
            .map_err(|e| SolveError::NotApplicable(format!("stored results do not follow this path: {e}")))?;
        let mut metadata = Metadata {
            version: "stored".into(),
            model: format!("stored results: {}", self.description),
            resolution: "as stored".into(),
            unread: results.unread(),
            ..Metadata::default()
        };
        metadata
            .extra
            .insert("file".into(), json!(self.file.display().to_string()));
        Ok(History {
            metadata,
            steps: results.steps,
            fields: Vec::new(),
        })
    }
}
