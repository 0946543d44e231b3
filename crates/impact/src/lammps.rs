//! The LAMMPS input of an impact sweep: one block per sweep point (template
//! `templates/lammps_impact.in`, each starting with `clear`), all in one file run by one process.
//! The placement and the material are [`super::placement::Placement`]'s; the tangential model is
//! the kinematic adapter's ([`spherecontact_external::dem::lammps::TangentialModel`]); the damping is LAMMPS's own
//! (`damping tsuji` with the prescribed restitution, `limit_damping`; [`super::code_rule`]).

use super::code_readback::file_name;
use super::placement::Placement;
use spherecontact_external::dem::lammps::TangentialModel;

/// The input's file name in the run folder.
pub const INPUT: &str = "in.impact";

/// The block template of one sweep point.
pub const TEMPLATE: &str = include_str!("templates/lammps_impact.in");

/// The input for `placements` with `model`.
pub fn input(model: TangentialModel, placements: &[Placement]) -> String {
    placements.iter().map(|p| block(model, p)).collect()
}

/// The block of one sweep point.
fn block(model: TangentialModel, p: &Placement) -> String {
    let num = |v: f64| format!("{v:e}");
    let [r1, r2] = p.radius;
    let (damping, damp) = if p.restitution < 1.0 {
        ("tsuji", num(p.restitution))
    } else {
        ("viscoelastic", num(0.0))
    };
    let (moving, freeze) = if p.fixed {
        (
            "1",
            "group           wall id 2\nfix             freeze wall freeze",
        )
    } else {
        ("1 2", "")
    };
    let keys = [
        ("@SOLVER@", model.solver_name().to_owned()),
        ("@INDEX@", p.index.to_string()),
        ("@MODEL@", model.keyword().to_owned()),
        ("@BOX@", num(p.half_box)),
        ("@X1@", num(p.centre[0][0])),
        ("@Z1@", num(p.centre[0][1])),
        ("@X2@", num(p.centre[1][0])),
        ("@Z2@", num(p.centre[1][1])),
        ("@D1@", num(2.0 * r1)),
        ("@D2@", num(2.0 * r2)),
        ("@RHO1@", num(p.density[0])),
        ("@RHO2@", num(p.density[1])),
        ("@VX1@", num(p.velocity[0][0])),
        ("@VZ1@", num(p.velocity[0][1])),
        ("@WY1@", num(p.spin_y[0])),
        ("@VX2@", num(p.velocity[1][0])),
        ("@VZ2@", num(p.velocity[1][1])),
        ("@WY2@", num(p.spin_y[1])),
        ("@E@", num(p.young)),
        ("@DAMP@", damp),
        ("@NU@", num(p.poisson)),
        ("@MU@", num(p.friction)),
        ("@DAMPING@", damping.to_owned()),
        ("@SKIN@", num(0.1 * r1)),
        ("@DT@", num(p.step)),
        ("@MOVING@", moving.to_owned()),
        ("@FREEZE@", freeze.to_owned()),
        ("@RSUM@", num(r1 + r2)),
        ("@FILE@", file_name(p.index)),
        ("@STEPS@", p.max_steps.to_string()),
    ];
    keys.iter()
        .fold(TEMPLATE.to_owned(), |text, (key, value)| text.replace(key, value))
}
