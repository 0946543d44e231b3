//! A DEM code driven by a script of its own that reads the scene file and writes the History CSV
//! (YADE's and Kratos' path solvers): one run through the command-solver exchange
//! ([`crate::command::run_exchange`]) and the History it gives, with what every such run records.

use std::path::Path;

use serde_json::json;

use crate::command;
use crate::exchange::scene_file;
use spherecontact_model::history::{History, Metadata};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::SolveError;
use spherecontact_system::process::{Environment, Job};

/// Runs `job` (the `code`'s script, written into `dir`) on `scene` and reads its History back:
/// the script's version and warnings, `model` in words, one step of the code per path increment,
/// the `law`'s class, the code's wall time (`<code>_wall_s`) and the scene file's name.
pub fn run(
    scene: &Scene,
    dir: &Path,
    job: &Job,
    code: &str,
    model: String,
    law: &str,
) -> Result<History, SolveError> {
    let (results, told, wall_s) = command::run_exchange(scene, dir, job, code, &Environment::Inherited)?;
    let unread = results.unread();
    let steps = results.steps;
    let mut metadata = Metadata {
        version: told.version.unwrap_or_default(),
        model,
        resolution: format!(
            "one {code} step per path increment ({} increments)",
            steps.len().saturating_sub(1)
        ),
        warnings: told.warnings,
        unread,
        ..Metadata::default()
    };
    metadata.extra.insert("law".into(), json!(law));
    metadata
        .extra
        .insert(format!("{}_wall_s", code.to_lowercase()), json!(wall_s));
    metadata
        .extra
        .insert("scene_file".into(), json!(scene_file::FILE_NAME));
    Ok(History {
        metadata,
        steps,
        fields: Vec::new(),
    })
}
