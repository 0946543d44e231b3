//! The YADE script of an impact sweep (template `templates/yade_impact.py`, run by `yade -n -x`):
//! the script is fixed and reads the sweep points from `points.json`, written here from each
//! point's [`Placement`]; the law is the kinematic adapter's
//! ([`spherecontact_external::dem::yade::YadeLaw::Mindlin`]), the damping YADE's own (`en`, [`super::code_rule`]).

use serde_json::json;

use super::placement::Placement;

/// The script's file name in the run folder.
pub const SCRIPT: &str = "yade_impact.py";

/// The script.
pub const SCRIPT_TEXT: &str = include_str!("templates/yade_impact.py");

/// The points file's name in the run folder.
pub const POINTS: &str = "points.json";

/// The points file for `placements`.
pub fn points(placements: &[Placement]) -> String {
    let points: Vec<serde_json::Value> = placements
        .iter()
        .map(|p| {
            json!({
                "index": p.index,
                "radius": p.radius,
                "density": p.density,
                "centre": p.centre,
                "velocity": p.velocity,
                "spin_y": p.spin_y,
                "fixed": p.fixed,
                "young": p.young,
                "poisson": p.poisson,
                "friction": p.friction,
                "restitution": p.restitution,
                "step": p.step,
                "max_steps": p.max_steps,
            })
        })
        .collect();
    serde_json::Value::Array(points).to_string()
}
