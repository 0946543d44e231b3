//! The impact scene file a case's own impact program reads (`{scene}`, `scene.json` in its run
//! folder): every sweep point of one variant, fully resolved, with the constants the harness
//! derives from them, so that the program needs no case-file parser.
//!
//! ```json
//! { "format": "spherecontact-impact-scene", "version": 1, "case": "chung-ooi-4",
//!   "variant": "prescribed", "friction": 0.092, "steps_per_contact": 2000,
//!   "sweep": "incident_angle", "results_file": "history.csv",
//!   "columns": ["sweep", "value", "contact_duration", …],
//!   "points": [ { "value": 0.0873, "restitution": 0.98,
//!     "body1": { "rigid_flat": false, "radius": 0.0025, "young": 3.8e11, "poisson": 0.23,
//!                "density": 4000, "velocity": [0.34, -3.885], "spin": 0 },
//!     "body2": { "rigid_flat": true, "velocity": [0, 0], "spin": 0 },
//!     "effective": { "modulus": …, "radius": …, "mindlin_shear_modulus": …, "mass": … },
//!     "hertz": { "contact_duration": …, "max_overlap": …, "max_normal_force": … },
//!     "damping": { "coefficient": …, "friction_bound": "elastic" } } ] }
//! ```
//!
//! SI throughout; the sweep value in SI (radians for an angle); velocities `[x, z]` (z the
//! contact normal, from body 2 into body 1), spins signed so that ω > 0 moves that body's contact
//! point towards +x (docs/impact.md). A rigid flat has no radius, modulus or density. `hertz` is
//! the elastic normal impact's closed form; `damping` is the harness's rule for the prescribed
//! restitution (Tsuji's form: total normal force P + c δn^{1/4} dδn/dt, clamped at zero, friction
//! bounded by the elastic force P), `null` when e = 1: a program that damps the same way is
//! compared with `mdr` on equal terms. The program writes the sweep table (`columns`, one row per
//! point in order; spherecontact_reference::impact::table) to `results_file` (`{history}`).

use serde::Serialize;

use super::case::{ImpactBody, ImpactCase, Point, Variant};
use super::closed_form::HertzImpact;
use spherecontact_model::hertz::Hertz;
use spherecontact_reference::impact::law::Damping;
use spherecontact_reference::impact::table;

/// The file's name in the run folder.
pub const FILE_NAME: &str = "scene.json";

/// The scene file of `case` in `variant`, as JSON text.
pub fn to_json(case: &ImpactCase, variant: Variant) -> String {
    let file = SceneFile {
        format: "spherecontact-impact-scene",
        version: 1,
        case: &case.name,
        variant: match variant {
            Variant::Prescribed => "prescribed",
            Variant::Elastic => "elastic",
        },
        friction: case.friction,
        steps_per_contact: case.steps,
        sweep: case.sweep_name(),
        results_file: spherecontact_external::exchange::scene_file::HISTORY_FILE,
        columns: table::header().split(',').map(str::to_owned).collect(),
        points: case
            .points_of(variant)
            .iter()
            .map(|p| PointFile::of(case, p))
            .collect(),
    };
    serde_json::to_string_pretty(&file).expect("a scene of finite numbers serialises")
}

#[derive(Serialize)]
struct SceneFile<'a> {
    format: &'static str,
    version: u32,
    case: &'a str,
    variant: &'static str,
    friction: f64,
    steps_per_contact: usize,
    sweep: &'static str,
    results_file: &'static str,
    columns: Vec<String>,
    points: Vec<PointFile>,
}

#[derive(Serialize)]
struct PointFile {
    value: Option<f64>,
    restitution: f64,
    body1: BodyFile,
    body2: BodyFile,
    effective: EffectiveFile,
    hertz: HertzFile,
    damping: Option<DampingFile>,
}

#[derive(Serialize)]
struct BodyFile {
    rigid_flat: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    young: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    poisson: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    density: Option<f64>,
    velocity: [f64; 2],
    spin: f64,
}

#[derive(Serialize)]
struct EffectiveFile {
    modulus: f64,
    radius: f64,
    mindlin_shear_modulus: f64,
    mass: f64,
}

#[derive(Serialize)]
struct HertzFile {
    contact_duration: f64,
    max_overlap: f64,
    max_normal_force: f64,
}

#[derive(Serialize)]
struct DampingFile {
    coefficient: f64,
    friction_bound: &'static str,
}

impl PointFile {
    fn of(case: &ImpactCase, point: &Point) -> Self {
        let pair = case.pair();
        let hertz = Hertz::of(&pair);
        let elastic = HertzImpact::of(point, &hertz);
        let mass = point.effective_mass();
        Self {
            value: point.value,
            restitution: point.restitution,
            body1: BodyFile::of(&point.body1),
            body2: BodyFile::of(&point.body2),
            effective: EffectiveFile {
                modulus: hertz.effective_modulus,
                radius: hertz.effective_radius,
                mindlin_shear_modulus: pair.mindlin_shear_modulus(),
                mass,
            },
            hertz: HertzFile {
                contact_duration: elastic.duration,
                max_overlap: elastic.max_overlap,
                max_normal_force: elastic.max_force,
            },
            damping: (point.restitution < 1.0).then(|| DampingFile {
                coefficient: Damping::new(point.restitution, mass, &hertz).coefficient(),
                friction_bound: "elastic",
            }),
        }
    }
}

impl BodyFile {
    fn of(body: &ImpactBody) -> Self {
        let rigid = body.is_rigid();
        let solid = |v: f64| (!rigid).then_some(v);
        Self {
            rigid_flat: rigid,
            radius: solid(body.body.radius),
            young: solid(body.body.material.young),
            poisson: solid(body.body.material.poisson),
            density: body.density,
            velocity: body.velocity,
            spin: body.spin,
        }
    }
}
