//! The Kratos script of an impact sweep (template `templates/kratos_impact.py`, run by the Python
//! of the project's Kratos environment): fixed but for the law's class, it reads the sweep points
//! from the points file ([`super::placement::points_file`]); the law is the kinematic adapter's
//! ([`spherecontact_external::dem::kratos::KratosLaw`]), the damping Kratos' own
//! (`COEFFICIENT_OF_RESTITUTION`, [`super::code_rule`]).

use spherecontact_external::dem::kratos::KratosLaw;

/// The script's file name in the run folder.
pub const SCRIPT: &str = "kratos_impact.py";

/// The script template.
const TEMPLATE: &str = include_str!("templates/kratos_impact.py");

/// The script for `law` (the solver's name and the law's class: the harness's own constants).
pub fn script(law: KratosLaw) -> String {
    TEMPLATE
        .replace("@SOLVER@", law.solver_name())
        .replace("@LAW@", law.class())
}
