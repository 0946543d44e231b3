//! LAMMPS `pair_style granular` along the path: one solver per tangential model
//! (`lammps-mindlin`, `lammps-mindlin-rescale`, `lammps-mindlin-force`,
//! `lammps-mindlin-rescale-force`), Hertz normal force from the case's E and ν.
//!
//! The input is generated from the case (template `templates/lammps_granular.in`): two spheres
//! driven kinematically, one timestep per path increment, no time integration and no damping
//! (the template says how, line by line). LAMMPS prints δn, P and Q at every step with 17
//! significant digits; they are read back into one row per path step. LAMMPS's tangential laws,
//! with k_t = 8 G* a and a = √(R* δ) (pair_granular.cpp of 29 Sep 2021, the Debian build):
//!
//! - `mindlin`: the history is the accumulated tangential displacement s; Q = k_t(a) s, with s
//!   reset to μP/k_t at the Coulomb limit (stored displacement times the current stiffness);
//! - `mindlin_rescale`: the same, with s scaled by a/a_old whenever the contact shrinks;
//! - `mindlin/force`: the history is the force, Q ← Q + k_t(a) Δs, capped at μP (incremental);
//! - `mindlin_rescale/force`: the same, with Q scaled by a/a_old whenever the contact shrinks.

use std::path::Path;
use std::time::Duration;

use serde_json::json;

use super::path_rows;
use crate::program;
use spherecontact_model::history::{History, Metadata, StepResult};
use spherecontact_model::pair::ContactPair;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_system::process::{Environment, Job};
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The input template.
pub const TEMPLATE: &str = include_str!("templates/lammps_granular.in");

/// Where LAMMPS prints its step rows.
const OUTPUT: &str = "forces.txt";

/// LAMMPS's start-up, and the time allowed per path increment (it takes about 0.1 ms).
const START_UP: Duration = Duration::from_secs(60);
const PER_STEP: Duration = Duration::from_millis(10);

/// One of LAMMPS's tangential models with history.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TangentialModel {
    /// `mindlin`: displacement history, current stiffness.
    Mindlin,
    /// `mindlin_rescale`: displacement history scaled with the contact radius on unloading.
    MindlinRescale,
    /// `mindlin/force`: incremental force history.
    MindlinForce,
    /// `mindlin_rescale/force`: force history scaled with the contact radius on unloading.
    MindlinRescaleForce,
}

impl TangentialModel {
    /// Every model, in listing order.
    pub const ALL: [TangentialModel; 4] = [
        TangentialModel::Mindlin,
        TangentialModel::MindlinRescale,
        TangentialModel::MindlinForce,
        TangentialModel::MindlinRescaleForce,
    ];

    /// The keyword in `pair_coeff … tangential KEYWORD`.
    pub fn keyword(self) -> &'static str {
        match self {
            TangentialModel::Mindlin => "mindlin",
            TangentialModel::MindlinRescale => "mindlin_rescale",
            TangentialModel::MindlinForce => "mindlin/force",
            TangentialModel::MindlinRescaleForce => "mindlin_rescale/force",
        }
    }

    /// The solver's name.
    pub fn solver_name(self) -> &'static str {
        match self {
            TangentialModel::Mindlin => "lammps-mindlin",
            TangentialModel::MindlinRescale => "lammps-mindlin-rescale",
            TangentialModel::MindlinForce => "lammps-mindlin-force",
            TangentialModel::MindlinRescaleForce => "lammps-mindlin-rescale-force",
        }
    }

    /// One line: the law.
    pub fn description(self) -> &'static str {
        match self {
            TangentialModel::Mindlin => {
                "LAMMPS pair granular, Hertz + tangential mindlin: stored displacement × current k_t = 8G*a, Coulomb cap"
            }
            TangentialModel::MindlinRescale => {
                "LAMMPS pair granular, Hertz + tangential mindlin_rescale: as mindlin, displacement scaled by a/a_old on unloading"
            }
            TangentialModel::MindlinForce => {
                "LAMMPS pair granular, Hertz + tangential mindlin/force: incremental force Q += 8G*a Δs, Coulomb cap"
            }
            TangentialModel::MindlinRescaleForce => {
                "LAMMPS pair granular, Hertz + tangential mindlin_rescale/force: as mindlin/force, force scaled by a/a_old on unloading"
            }
        }
    }
}

/// LAMMPS with one tangential model, as a solver.
#[derive(Clone, Debug)]
pub struct Lammps {
    /// The tangential model.
    pub model: TangentialModel,
    /// The executables.
    pub toolchain: Toolchain,
    /// The timestep [s]: a bookkeeping unit of a quasi-static run (one per increment); changing
    /// it changes nothing but the velocities (shown by a test).
    pub timestep: f64,
}

impl Lammps {
    /// LAMMPS from the default toolchain with `model`, timestep 1 s.
    pub fn new(model: TangentialModel) -> Self {
        Self {
            model,
            toolchain: Toolchain::default(),
            timestep: 1.0,
        }
    }
}

impl Solver for Lammps {
    fn name(&self) -> &str {
        self.model.solver_name()
    }

    fn kind(&self) -> Kind {
        Kind::DemCode
    }

    fn description(&self) -> &str {
        self.model.description()
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        super::two_finite_spheres(scene, "LAMMPS pair granular")?;
        let version = self
            .toolchain
            .require(Tool::Lammps)
            .map_err(SolveError::Unavailable)?;
        program::in_run_folder(self.name(), |dir| {
            std::fs::write(dir.join("in.granular"), self.input(scene))
                .map_err(|e| SolveError::Failed(format!("writing the LAMMPS input: {e}")))?;
            let job = Job {
                program: self.toolchain.lammps.clone(),
                args: ["-in", "in.granular", "-log", "none", "-nocite"]
                    .map(String::from)
                    .to_vec(),
                env: Vec::new(),
                timeout: program::time_limit(START_UP, PER_STEP, scene.steps().len()),
            };
            let meaning = |_| "LAMMPS error (see ERROR in its output)";
            let run =
                program::run_to_success(&job, dir, "lammps", "LAMMPS", meaning, &Environment::Inherited)?;
            let (steps, worst) = read_output(dir, scene)?;
            Ok(self.history(&version, steps, worst, run.wall_s))
        })
    }
}

impl Lammps {
    /// The LAMMPS input for `scene`.
    pub fn input(&self, scene: &Scene) -> String {
        let (b1, b2) = (scene.pair.body1, scene.pair.body2);
        let rsum = b1.radius + b2.radius;
        let positions = scene.path.positions();
        let dt = self.timestep;
        let (young, poisson) = equivalent_material(&scene.pair);
        let mut segments = String::new();
        for (pair, &m) in positions.windows(2).zip(scene.path.substeps()) {
            let m_f = m as f64;
            // Approach grows ⇒ sphere 2 moves down; slip δt of sphere 1's surface: ω R1 per unit time.
            let vz = -(pair[1].delta_n - pair[0].delta_n) / (m_f * dt);
            let omega = (pair[1].delta_t - pair[0].delta_t) / (m_f * dt * b1.radius);
            segments.push_str(&format!(
                "set             atom 1 omega 0 {omega:e} 0\nfix             move2 sphere2 move linear 0 0 {vz:e}\nrun             {m}\nunfix           move2\n"
            ));
        }
        if segments.is_empty() {
            segments.push_str("run             0\n");
        }
        let keys = [
            ("@SOLVER@", self.name().to_owned()),
            ("@SCENE@", scene.name.replace('\n', " ")),
            ("@BOX@", format!("{:e}", 2.0 * rsum)),
            ("@Z0@", format!("{:e}", rsum - positions[0].delta_n)),
            ("@D1@", format!("{:e}", 2.0 * b1.radius)),
            ("@D2@", format!("{:e}", 2.0 * b2.radius)),
            ("@E@", format!("{young:e}")),
            ("@NU@", format!("{poisson:e}")),
            ("@MU@", format!("{:e}", scene.friction)),
            ("@MODEL@", self.model.keyword().to_owned()),
            ("@SKIN@", format!("{:e}", 0.1 * b1.radius.min(b2.radius))),
            ("@DT@", format!("{dt:e}")),
            ("@RSUM@", format!("{rsum:e}")),
            ("@SEGMENTS@", segments),
        ];
        keys.iter()
            .fold(TEMPLATE.to_owned(), |text, (key, value)| text.replace(key, value))
    }

    fn history(&self, version: &str, steps: Vec<StepResult>, worst_delta_n: f64, wall_s: f64) -> History {
        let mut metadata = Metadata {
            version: format!("LAMMPS {version}"),
            model: format!(
                "{}; two spheres driven kinematically (overlap by position, slip by spin), no integration, no damping",
                self.description()
            ),
            resolution: format!("one timestep per path increment ({} increments)", steps.len().saturating_sub(1)),
            ..Metadata::default()
        };
        metadata
            .warnings
            .push("contact radius and peak pressure are not output by LAMMPS (empty)".into());
        let extra = &mut metadata.extra;
        extra.insert(
            "pair_style".into(),
            json!(format!(
                "granular hertz/material … tangential {} NULL 0 μ",
                self.model.keyword()
            )),
        );
        extra.insert("largest_delta_n_deviation_m".into(), json!(worst_delta_n));
        extra.insert("timestep_s".into(), json!(self.timestep));
        extra.insert("lammps_wall_s".into(), json!(wall_s));
        History {
            metadata,
            steps,
            fields: Vec::new(),
        }
    }
}

/// The one material (E', ν') whose identical pair has `pair`'s E* and Mindlin's G* (also used by
/// the dynamic runs of `spherecontact-impact`, where a rigid flat is a sphere of 2E and the same ν).
///
/// LAMMPS's hertz/material for one type gives E* = E'/2(1 − ν'²) and G* = E'/4(2 − ν')(1 + ν'),
/// so G*/E* = (1 − ν')/2(2 − ν'): with r = 2G*/E*, ν' = (1 − 2r)/(1 − r) and E' = 2E*(1 − ν'²).
/// For identical spheres this is their own E and ν (to rounding).
pub fn equivalent_material(pair: &ContactPair) -> (f64, f64) {
    let (e_star, g_star) = (pair.effective_modulus(), pair.mindlin_shear_modulus());
    let r = 2.0 * g_star / e_star;
    let poisson = (1.0 - 2.0 * r) / (1.0 - r);
    (2.0 * e_star * (1.0 - poisson * poisson), poisson)
}

/// The rows LAMMPS printed ([`super::path_rows`]: comments skipped, the first of each step
/// kept, checked against the path); and the largest |δn − δn_path| [m].
fn read_output(dir: &Path, scene: &Scene) -> Result<(Vec<StepResult>, f64), SolveError> {
    let is_data = |line: &str| !(line.starts_with('#') || line.trim().is_empty());
    let (rows, worst) = path_rows::read(&dir.join(OUTPUT), scene, 4, is_data)?;
    Ok((path_rows::steps(scene, &rows, |_, _| ()), worst))
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_model::pair::Material;

    #[test]
    fn the_equivalent_material_keeps_e_star_and_g_star() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        let (young, poisson) = equivalent_material(&scene.pair);
        assert!((young / 70e9 - 1.0).abs() < 1e-14 && (poisson - 0.3).abs() < 1e-14);
        scene.pair.body2.material = Material {
            young: 210e9,
            poisson: 0.28,
        };
        let (young, poisson) = equivalent_material(&scene.pair);
        // LAMMPS's own formulas for one type (mix_stiffnessE, mix_stiffnessG of pair granular).
        let e_star = young / (2.0 * (1.0 - poisson * poisson));
        let g_star = young / (4.0 * (2.0 - poisson) * (1.0 + poisson));
        assert!((e_star / scene.pair.effective_modulus() - 1.0).abs() < 1e-14);
        assert!((g_star / scene.pair.mindlin_shear_modulus() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn every_key_of_the_template_is_filled() {
        let scene = spherecontact_model::fixtures::test_scene(&[0.0, 10.0, 17.0]);
        let input = Lammps::new(TangentialModel::MindlinRescaleForce).input(&scene);
        assert!(!input.contains('@'), "{input}");
        assert_eq!(input.matches("\nrun ").count(), 2);
        assert!(input.contains("tangential mindlin_rescale/force NULL 0"));
    }
}
