//! The scene file: what a program outside the harness is told to solve (`scene.json`).
//!
//! Format `spherecontact-scene`, version [`VERSION`], SI units (m, N, Pa), written in full
//! precision (every number round-trips to the same `f64`):
//!
//! ```json
//! {
//!   "format": "spherecontact-scene", "version": 1,
//!   "units": { "length": "m", "force": "N", "stress": "Pa" },
//!   "name": "paper-fig7",
//!   "friction": 0.2,
//!   "body1": { "radius": 0.1, "young": 70000000000.0, "poisson": 0.3 },
//!   "body2": { "radius": null, "young": 210000000000.0, "poisson": 0.3 },
//!   "effective": { "modulus": 3.8e10, "radius": 0.05, "mindlin_shear_modulus": 1.4e10 },
//!   "positions": [ { "delta_n": 0.0, "delta_t": 0.0 }, … ],
//!   "substeps": [ 100, … ],
//!   "steps": [ { "step": 0, "position": 0, "delta_n": 0.0, "delta_t": 0.0 }, … ],
//!   "history_file": "history.csv",
//!   "columns": [ "step", "position", "delta_n", … ]
//! }
//! ```
//!
//! - `radius: null` is a flat (infinite radius; JSON has no infinity).
//! - `effective` repeats the derived constants the crate uses, so that a program can check its
//!   own: E* = [(1−ν1²)/E1 + (1−ν2²)/E2]⁻¹, R* = [1/R1 + 1/R2]⁻¹, G* = [(2−ν1)/G1 + (2−ν2)/G2]⁻¹.
//! - δn is the total approach of the bodies' far points, δt their relative tangential
//!   displacement along x; `steps` lists every increment the harness's own solvers see (step 0
//!   is position 0; `position` is null between positions), so a program needs no interpolation.
//! - The program writes `history_file` (relative to its working directory) with `columns`:
//!   one row per step, see [`super::results_csv`].
//!
//! A later, incompatible format gets a new `version`; additions that old readers may ignore
//! keep it.

use serde::Serialize;

use spherecontact_model::pair::Body;
use spherecontact_model::path::Position;
use spherecontact_model::scene::Scene;

/// The format name, first key of the file.
pub const FORMAT: &str = "spherecontact-scene";

/// The format version.
pub const VERSION: u32 = 1;

/// The scene file's name in a run folder.
pub const FILE_NAME: &str = "scene.json";

/// The History CSV's name in a run folder.
pub const HISTORY_FILE: &str = "history.csv";

/// The scene file as written.
#[derive(Debug, Serialize)]
pub struct SceneFile<'a> {
    format: &'static str,
    version: u32,
    units: Units,
    name: &'a str,
    friction: f64,
    body1: BodyEntry,
    body2: BodyEntry,
    effective: Effective,
    positions: &'a [Position],
    substeps: &'a [usize],
    steps: Vec<StepEntry>,
    history_file: &'static str,
    columns: Vec<&'static str>,
}

#[derive(Debug, Serialize)]
struct Units {
    length: &'static str,
    force: &'static str,
    stress: &'static str,
}

#[derive(Debug, Serialize)]
struct BodyEntry {
    /// `None` (null) for a flat.
    radius: Option<f64>,
    young: f64,
    poisson: f64,
}

#[derive(Debug, Serialize)]
struct Effective {
    modulus: f64,
    radius: f64,
    mindlin_shear_modulus: f64,
}

#[derive(Debug, Serialize)]
struct StepEntry {
    step: usize,
    position: Option<usize>,
    delta_n: f64,
    delta_t: f64,
}

impl BodyEntry {
    fn of(body: &Body) -> Self {
        Self {
            radius: body.radius.is_finite().then_some(body.radius),
            young: body.material.young,
            poisson: body.material.poisson,
        }
    }
}

impl<'a> SceneFile<'a> {
    /// The scene file of `scene`.
    pub fn of(scene: &'a Scene) -> Self {
        let pair = &scene.pair;
        Self {
            format: FORMAT,
            version: VERSION,
            units: Units {
                length: "m",
                force: "N",
                stress: "Pa",
            },
            name: &scene.name,
            friction: scene.friction,
            body1: BodyEntry::of(&pair.body1),
            body2: BodyEntry::of(&pair.body2),
            effective: Effective {
                modulus: pair.effective_modulus(),
                radius: pair.effective_radius(),
                mindlin_shear_modulus: pair.mindlin_shear_modulus(),
            },
            positions: scene.path.positions(),
            substeps: scene.path.substeps(),
            steps: scene
                .steps()
                .into_iter()
                .map(|s| StepEntry {
                    step: s.index,
                    position: s.position,
                    delta_n: s.delta_n,
                    delta_t: s.delta_t,
                })
                .collect(),
            history_file: HISTORY_FILE,
            columns: super::results_csv::columns(),
        }
    }

    /// The JSON text (pretty-printed: a person reads it when a program fails).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a scene file has only finite numbers and strings")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip_and_a_flat_has_a_null_radius() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0, 17.0]);
        scene.pair.body2.radius = f64::INFINITY;
        let text = SceneFile::of(&scene).to_json();
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(value["format"], FORMAT);
        assert_eq!(value["version"], VERSION);
        assert!(value["body2"]["radius"].is_null());
        let steps = value["steps"].as_array().unwrap();
        assert_eq!(steps.len(), scene.steps().len());
        for (entry, step) in steps.iter().zip(scene.steps()) {
            assert_eq!(entry["delta_n"].as_f64().unwrap(), step.delta_n);
            assert_eq!(entry["position"].as_u64().map(|p| p as usize), step.position);
        }
        assert_eq!(
            value["effective"]["mindlin_shear_modulus"].as_f64().unwrap(),
            scene.pair.mindlin_shear_modulus()
        );
    }
}
