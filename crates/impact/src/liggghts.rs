//! The LIGGGHTS input of an impact sweep: one block per sweep point (template
//! `templates/liggghts_impact.in`, each starting with `clear` and opening its own log, the point's
//! file), all in one file run by one process; numbers only, formatted here. The tangential model
//! is the kinematic adapter's (`tangential history`, [`spherecontact_external::dem::liggghts`]),
//! the damping LIGGGHTS' own (Tsuji's from `coefficientRestitution`, the total normal force
//! clamped at zero by `limitForce on`, friction bounded by it; [`super::code_rule`]).
//!
//! Two spheres are placed as for LAMMPS and YADE ([`Placement`]); a rigid flat is LIGGGHTS' own
//! wall (`fix wall/gran … primitive type 2 zplane 0`), its modulus [`WALL_STIFFNESS_FACTOR`]
//! times body 1's, with body 1 of its own material (E1 = E'/2, ν1 = ν': the one material of a
//! sphere on a rigid flat, [`spherecontact_external::dem::lammps::equivalent_material`]). Its
//! effect: E* and G* are 1/(1 + 1/factor) of the rigid flat's, measured in
//! `tests/suite/impact_codes.rs`. The log's thermo rows are read as every code's rows
//! ([`super::code_readback`]), against a mirror sphere of radius R1 at (x1, −R1) for the wall.

use std::path::Path;

use super::code_readback::{file_name, ReadbackError, Rows};
use super::placement::Placement;
use spherecontact_external::dem::liggghts::{num, NAME};

/// The input's file name in the run folder.
pub const INPUT: &str = "in.impact";

/// The block template of one sweep point.
pub const TEMPLATE: &str = include_str!("templates/liggghts_impact.in");

/// A rigid flat's wall modulus as a multiple of body 1's: E* and G* are 1/(1 + 10⁻⁶) of a rigid
/// flat's, 1e-6 below the reference (the effect measured in `tests/suite/impact_codes.rs`).
pub const WALL_STIFFNESS_FACTOR: f64 = 1e6;

/// The input for `placements`, each rigid flat's wall `factor` times body 1's modulus.
pub fn input(placements: &[Placement], factor: f64) -> String {
    placements.iter().map(|p| block(p, factor)).collect()
}

/// The placement the rows of `placement` are read against: a wall's mirror sphere of radius R1
/// below the plane z = 0, at (x1, −R1) (as the rows print it).
pub fn readback(placement: &Placement) -> Placement {
    let mut seen = *placement;
    if placement.fixed {
        let r1 = placement.radius[0];
        seen.radius = [r1, r1];
        seen.centre[1] = [0.0, -r1];
    }
    seen
}

/// The rows of a point's log `file`: its thermo rows (13 numbers, the step first), the log's
/// other lines (LIGGGHTS' set-up and timing) left out.
pub fn rows(file: &Path) -> Result<Rows, ReadbackError> {
    let text = std::fs::read_to_string(file).map_err(|e| ReadbackError::Unreadable(e.to_string()))?;
    let thermo: String = text
        .lines()
        .filter(|line| {
            let words: Vec<&str> = line.split_whitespace().collect();
            words.len() == 13
                && words[0].parse::<u64>().is_ok()
                && words.iter().all(|w| w.parse::<f64>().is_ok())
        })
        .flat_map(|line| [line, "\n"])
        .collect();
    Rows::parse(&thermo)
}

/// The block of one sweep point.
fn block(p: &Placement, factor: f64) -> String {
    let [r1, r2] = p.radius;
    let (young, young2, body2, wall, row2, half_box) = if p.fixed {
        let own = p.pair_young / 2.0;
        let wall =
            "fix             wall all wall/gran model hertz tangential history primitive type 2 zplane 0 \
                    tangential_damping off limitForce on";
        let row = format!(
            "variable        x2 equal x[1]\nvariable        z2 equal {}\nvariable        vx2 equal 0\n\
             variable        vz2 equal 0\nvariable        wy2 equal 0",
            num(-r1)
        );
        let travel = p.half_box - 2.0 * (r1 + r2);
        (
            own,
            factor * own,
            String::new(),
            wall.to_owned(),
            row,
            4.0 * r1 + travel,
        )
    } else {
        let body2 = format!(
            "create_atoms    1 single {} 0 {} units box\nset             atom 2 diameter {} density {}\n\
             set             atom 2 vx {} vz {} omegay {}",
            num(p.centre[1][0]),
            num(p.centre[1][1]),
            num(2.0 * r2),
            num(p.density[1]),
            num(p.velocity[1][0]),
            num(p.velocity[1][1]),
            num(p.spin_y[1])
        );
        let row =
            "variable        x2 equal x[2]\nvariable        z2 equal z[2]\nvariable        vx2 equal vx[2]\n\
                   variable        vz2 equal vz[2]\nvariable        wy2 equal c_spin[2]";
        (p.young, p.young, body2, String::new(), row.to_owned(), p.half_box)
    };
    let keys = [
        ("@SOLVER@", NAME.to_owned()),
        ("@INDEX@", p.index.to_string()),
        ("@FILE@", file_name(p.index)),
        ("@WALLFACTOR@", num(factor)),
        ("@BOX@", num(half_box)),
        ("@X1@", num(p.centre[0][0])),
        ("@Z1@", num(p.centre[0][1])),
        ("@D1@", num(2.0 * r1)),
        ("@RHO1@", num(p.density[0])),
        ("@VX1@", num(p.velocity[0][0])),
        ("@VZ1@", num(p.velocity[0][1])),
        ("@WY1@", num(p.spin_y[0])),
        ("@BODY2@", body2),
        ("@E@", num(young)),
        ("@E2@", num(young2)),
        ("@NU@", num(p.poisson)),
        ("@EN@", num(p.restitution)),
        ("@MU@", num(p.friction)),
        ("@WALL@", wall),
        ("@SKIN@", num(0.1 * r1)),
        ("@DT@", num(p.step)),
        ("@BODY2ROW@", row2),
        ("@STEPS@", p.max_steps.to_string()),
    ];
    keys.iter()
        .fold(TEMPLATE.to_owned(), |text, (key, value)| text.replace(key, value))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn placement(case: &str) -> Placement {
        let file = spherecontact_model::fixtures::repository().join(case);
        let case = spherecontact_case::load_impact(&file).unwrap();
        Placement::of(&case, &case.points()[0], 0)
    }

    #[test]
    fn every_key_is_filled_and_a_flat_is_a_wall_of_its_type() {
        let flat = placement("cases/impact/chung-ooi-4.toml");
        let text = input(&[flat], WALL_STIFFNESS_FACTOR);
        assert!(!text.contains('@'), "{text}");
        assert!(text.contains("primitive type 2 zplane 0"));
        assert!(
            !text.contains("create_atoms    1 single 0 0 -"),
            "no second sphere"
        );
        // Body 1 of its own E (E' = 2 E1 for a sphere on a rigid flat), the wall 1e6 times it.
        assert!(
            text.contains(&format!("peratomtype {} {}", num(3.8e11), num(3.8e17))),
            "{text}"
        );
        let spheres = placement("cases/impact/chung-ooi-1.toml");
        let text = input(&[spheres], WALL_STIFFNESS_FACTOR);
        assert!(
            !text.contains('@') && !text.contains("fix             wall all"),
            "{text}"
        );
    }

    #[test]
    fn a_walls_rows_are_read_against_its_mirror_sphere() {
        let flat = placement("cases/impact/chung-ooi-4.toml");
        let seen = readback(&flat);
        assert_eq!(seen.radius, [flat.radius[0]; 2]);
        assert_eq!(seen.centre[1], [0.0, -flat.radius[0]]);
    }

    #[test]
    fn only_the_logs_thermo_rows_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("point-0.txt");
        let row = |k: usize| format!("{k:>8} 0 1 0 0 0 -1 0 0 0 0 0 0\n");
        std::fs::write(
            &file,
            format!(
                "LIGGGHTS (Version …)\n    Step v_x1 …\n{}{}Loop time of 0.1\n",
                row(0),
                row(1)
            ),
        )
        .unwrap();
        assert!(rows(&file).is_ok());
        std::fs::write(&file, format!("{}{}", row(0), row(2))).unwrap();
        assert!(matches!(rows(&file), Err(ReadbackError::Malformed { .. })));
    }
}
