//! LIGGGHTS-PUBLIC along the path: `liggghts-hertz-history` (`pair_style gran model hertz
//! tangential history`), Hertz normal force and the history tangential model from each body's
//! own E and ν.
//!
//! The input is generated from the case (template `templates/liggghts_path.in`, then one `set` of
//! sphere 2's height and sphere 1's spin and one `run 1` per path increment; numbers only, each
//! formatted here from the validated scene: no case string reaches it). LIGGGHTS prints δn, P, Q
//! and its contact area at every step with 17 significant digits (thermo into `forces.txt`);
//! they are read back into one row per path step ([`super::path_rows`]). The law, in LIGGGHTS
//! 3.8.0's sources (`src/normal_model_hertz.h`, `src/tangential_model_history.h`):
//!
//! - k_t = 8 G* a, a = √(R* δ) (`St = 8.*Geff*sqrtval`, normal_model_hertz.h:232);
//! - the history is the accumulated tangential displacement s (`shear += vtr dt`, :149) and
//!   Q = k_t(a) s (`Ft_ela = -(kt * shear)`, :166): the stored displacement times the current
//!   stiffness, as LAMMPS's `mindlin`;
//! - at the Coulomb limit μ|F_n| (:175) Q is scaled onto it and s reset to Q/k_t (:197).
//!
//! Its `contactArea` (compute pair/gran/local) is the geometric lens π(R_1² − (r² − R_2² +
//! R_1²)²/4r²) ≈ π R δ for identical spheres (compute_pair_gran_local.cpp:558), twice Hertz's
//! π a²: the history's contact radius is √(area/π), LIGGGHTS's own measure, shown as it is.

use std::time::Duration;

use serde_json::json;

use super::path_rows;
use crate::program;
use spherecontact_model::history::{History, Metadata, StepResult};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_system::process::{Environment, Job};
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The input template (the steps are appended by [`Liggghts::input`]).
pub const TEMPLATE: &str = include_str!("templates/liggghts_path.in");

/// The solver's name.
pub const NAME: &str = "liggghts-hertz-history";

/// The input's file name in the run folder.
const INPUT: &str = "in.path";

/// Where LIGGGHTS writes its log, with the thermo rows.
const OUTPUT: &str = "forces.txt";

/// LIGGGHTS's start-up, and the time allowed per path increment (each a `run 1`: about 0.5 ms).
const START_UP: Duration = Duration::from_secs(60);
const PER_STEP: Duration = Duration::from_millis(20);

/// LIGGGHTS with Hertz and tangential history, as a solver.
#[derive(Clone, Debug)]
pub struct Liggghts {
    /// The executables.
    pub toolchain: Toolchain,
    /// The timestep [s]: a bookkeeping unit of a quasi-static run (one per increment); changing
    /// it changes nothing but the spin rates (shown by a test).
    pub timestep: f64,
}

impl Default for Liggghts {
    /// LIGGGHTS from the default toolchain, timestep 1 s.
    fn default() -> Self {
        Self {
            toolchain: Toolchain::default(),
            timestep: 1.0,
        }
    }
}

/// A number as the input carries it: Rust's shortest round-trip form (`1e-6`, `7e10`).
pub fn num(value: f64) -> String {
    format!("{value:e}")
}

impl Solver for Liggghts {
    fn name(&self) -> &str {
        NAME
    }

    fn kind(&self) -> Kind {
        Kind::DemCode
    }

    fn description(&self) -> &str {
        "LIGGGHTS pair gran, hertz + tangential history: stored displacement × current k_t = 8G*a, Coulomb cap"
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        super::two_finite_spheres(scene, "LIGGGHTS pair gran")?;
        let version = self
            .toolchain
            .require(Tool::Liggghts)
            .map_err(SolveError::Unavailable)?;
        program::in_run_folder(self.name(), |dir| {
            std::fs::write(dir.join(INPUT), self.input(scene))
                .map_err(|e| SolveError::Failed(format!("writing the LIGGGHTS input: {e}")))?;
            let job = Job {
                program: self.toolchain.liggghts.clone(),
                args: ["-in", INPUT, "-log", "none", "-nocite"]
                    .map(String::from)
                    .to_vec(),
                env: Vec::new(),
                timeout: program::time_limit(START_UP, PER_STEP, scene.steps().len()),
            };
            let meaning = |_| "LIGGGHTS error (see ERROR in its output)";
            let run = program::run_to_success(
                &job,
                dir,
                "liggghts",
                "LIGGGHTS",
                meaning,
                &Environment::Inherited,
            )?;
            let (rows, worst) = path_rows::read(&dir.join(OUTPUT), scene, 5, is_thermo_row)?;
            let steps = path_rows::steps(scene, &rows, |row, step| {
                step.contact_radius = Some((row.rest[0].max(0.0) / std::f64::consts::PI).sqrt());
            });
            Ok(self.history(&version, steps, worst, run.wall_s))
        })
    }
}

/// True for a thermo row of the log: five numbers, the step first (the log's other lines have
/// words: "1 settings made for z").
fn is_thermo_row(line: &str) -> bool {
    let words: Vec<&str> = line.split_whitespace().collect();
    words.len() == 5 && words[0].parse::<u64>().is_ok() && words.iter().all(|w| w.parse::<f64>().is_ok())
}

impl Liggghts {
    /// The LIGGGHTS input for `scene`.
    pub fn input(&self, scene: &Scene) -> String {
        let (b1, b2) = (scene.pair.body1, scene.pair.body2);
        let rsum = b1.radius + b2.radius;
        let steps = scene.steps();
        let dt = self.timestep;
        let mut lines = String::new();
        for (k, pair) in steps.windows(2).enumerate() {
            let (before, after) = (&pair[0], &pair[1]);
            // The lever arm LIGGGHTS applies to sphere 1's spin at this step's overlap.
            let arm = b1.radius - 0.5 * after.delta_n;
            let omega = (after.delta_t - before.delta_t) / (arm * dt);
            let setup = if k == 0 { "yes" } else { "no" };
            lines.push_str(&format!(
                "set atom 2 z {}\nset atom 1 omegay {}\nrun 1 pre {setup} post no\n",
                num(rsum - after.delta_n),
                num(omega)
            ));
        }
        let keys = [
            ("@SOLVER@", NAME.to_owned()),
            ("@BOX@", num(2.0 * rsum)),
            ("@Z0@", num(rsum - steps[0].delta_n)),
            ("@D1@", num(2.0 * b1.radius)),
            ("@D2@", num(2.0 * b2.radius)),
            ("@E1@", num(b1.material.young)),
            ("@E2@", num(b2.material.young)),
            ("@NU1@", num(b1.material.poisson)),
            ("@NU2@", num(b2.material.poisson)),
            ("@MU@", num(scene.friction)),
            ("@SKIN@", num(0.1 * b1.radius.min(b2.radius))),
            ("@DT@", num(dt)),
            ("@RSUM@", num(rsum)),
            ("@STEPS@", lines),
        ];
        keys.iter()
            .fold(TEMPLATE.to_owned(), |text, (key, value)| text.replace(key, value))
    }

    fn history(&self, version: &str, steps: Vec<StepResult>, worst_delta_n: f64, wall_s: f64) -> History {
        let mut metadata = Metadata {
            version: format!("LIGGGHTS {version}"),
            model: format!(
                "{}; two spheres driven kinematically (overlap by position, slip by spin), no integration, no damping",
                self.description()
            ),
            resolution: format!("one timestep per path increment ({} increments)", steps.len().saturating_sub(1)),
            ..Metadata::default()
        };
        metadata.warnings.push(
            "contact radius is √(contactArea/π) of LIGGGHTS's geometric lens area (≈ π R δ), not Hertz's a; \
             peak pressure is not output (empty)"
                .into(),
        );
        let extra = &mut metadata.extra;
        extra.insert(
            "pair_style".into(),
            json!("gran model hertz tangential history tangential_damping off"),
        );
        extra.insert("largest_delta_n_deviation_m".into(), json!(worst_delta_n));
        extra.insert("timestep_s".into(), json!(self.timestep));
        extra.insert("liggghts_wall_s".into(), json!(wall_s));
        History {
            metadata,
            steps,
            fields: Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_of_the_template_is_filled_with_numbers_only() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 10.0, 17.0]);
        scene.name = "x\nshell rm -rf /".into();
        let input = Liggghts::default().input(&scene);
        assert!(!input.contains('@'), "{input}");
        assert!(!input.contains("shell"), "a case string reached the input");
        assert_eq!(input.matches("\nrun 1 ").count(), scene.steps().len() - 1);
        assert!(input.contains("tangential history tangential_damping off"));
    }

    #[test]
    fn the_spin_carries_liggghts_lever_arm() {
        let scene = spherecontact_model::fixtures::paper_scene(&[0.0, 10.0], &[0.0, 1.0], 1);
        let input = Liggghts::default().input(&scene);
        let arm = scene.pair.body1.radius - 0.5 * 10e-6;
        assert!(
            input.contains(&format!("set atom 1 omegay {}\n", num(1e-6 / arm))),
            "{input}"
        );
    }

    #[test]
    fn only_thermo_rows_are_data() {
        assert!(is_thermo_row("      12 1e-06 11.4 -0 1.5e-06 "));
        assert!(!is_thermo_row("  1 settings made for omegay"));
        assert!(!is_thermo_row("  1 settings made for z"));
        assert!(!is_thermo_row(
            "    Step             dn              p              q          area "
        ));
    }
}
