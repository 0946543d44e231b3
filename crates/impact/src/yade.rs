//! The YADE script of an impact sweep (template `templates/yade_impact.py`, run by `yade -n -x`):
//! the script is fixed and reads the sweep points from the points file
//! ([`super::placement::points_file`]); the law is the kinematic adapter's
//! ([`spherecontact_external::dem::yade::YadeLaw::Mindlin`]), the damping YADE's own (`en`, [`super::code_rule`]).

/// The script's file name in the run folder.
pub const SCRIPT: &str = "yade_impact.py";

/// The script.
pub const SCRIPT_TEXT: &str = include_str!("templates/yade_impact.py");
