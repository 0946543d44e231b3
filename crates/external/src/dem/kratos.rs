//! Kratos along the path: `kratos-hertz-coulomb` (DEMApplication's `DEM_D_Hertz_viscous_Coulomb`:
//! Hertz normal force, an incremental spring k_t = 8 G* c whose stored force is scaled by
//! √(δ/δ_before) when the overlap decreases, a Coulomb cap; no damping at restitution 1).
//!
//! The script (`templates/kratos_dem.py`) is a command solver: it reads the scene file and writes
//! the History CSV ([`crate::exchange`]), run by the Python of the project's Kratos environment
//! ([`spherecontact_system::toolchain::KRATOS_PYTHON`]) in its own folder with the process
//! handling of every external program, on one OpenMP thread (two threads were ten times slower on
//! this two-core machine, with the same forces).
//!
//! One property of Kratos shows on a spinning contact: the quaternion turn of a contact arm of
//! length ℓ by Δθ moves its end by ℓ(1 − cos Δθ) along the normal as well, and Kratos takes
//! `previous_indentation = indentation + LocalDeltDisp[2]` (spheric_particle.cpp) from that
//! displacement, so at constant overlap it sees an unloading of Δs²/(2ℓ) per step and scales the
//! stored force by √(δ/(δ + Δs²/2ℓ)) ≈ 1 − Δs²/(4ℓδ): a relative loss of 2.5e-9 per 0.1 µm step at
//! δ = 10 µm, second order in the step (measured: tests/suite/dem_codes.rs).

use std::time::Duration;

use crate::program;
use spherecontact_model::history::History;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_system::process::Job;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The script template.
pub const TEMPLATE: &str = include_str!("templates/kratos_dem.py");

/// The script's file name in the run folder.
const SCRIPT: &str = "kratos_dem.py";

/// Kratos' start-up (the import takes about a second), and the time allowed per path increment
/// (about 0.1 ms, a Python callback each).
const START_UP: Duration = Duration::from_secs(120);
const PER_STEP: Duration = Duration::from_millis(10);

/// A Kratos DEM contact law with Coulomb friction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KratosLaw {
    /// `DEM_D_Hertz_viscous_Coulomb`.
    HertzViscousCoulomb,
}

impl KratosLaw {
    /// Every law registered as a solver.
    pub const ALL: [KratosLaw; 1] = [KratosLaw::HertzViscousCoulomb];

    /// The law's name in Kratos' materials file.
    pub fn class(self) -> &'static str {
        match self {
            KratosLaw::HertzViscousCoulomb => "DEM_D_Hertz_viscous_Coulomb",
        }
    }

    /// The solver's name.
    pub fn solver_name(self) -> &'static str {
        match self {
            KratosLaw::HertzViscousCoulomb => "kratos-hertz-coulomb",
        }
    }
}

/// Kratos with one contact law, as a solver.
#[derive(Clone, Debug)]
pub struct Kratos {
    /// The law.
    pub law: KratosLaw,
    /// The executables.
    pub toolchain: Toolchain,
    /// The step [s]: a bookkeeping unit of a quasi-static run (one per increment); changing it
    /// changes nothing but the imposed velocities (shown by a test).
    pub timestep: f64,
}

impl Kratos {
    /// Kratos from the default toolchain with `law`, step 1 s.
    pub fn new(law: KratosLaw) -> Self {
        Self {
            law,
            toolchain: Toolchain::default(),
            timestep: 1.0,
        }
    }

    /// The script for this law (the solver's name, the law's class and the step: the harness's
    /// own constants, never the case's text).
    pub fn script(&self) -> String {
        TEMPLATE
            .replace("@SOLVER@", self.law.solver_name())
            .replace("@LAW@", self.law.class())
            .replace("@DT@", &format!("{:e}", self.timestep))
    }
}

impl Solver for Kratos {
    fn name(&self) -> &str {
        self.law.solver_name()
    }

    fn kind(&self) -> Kind {
        Kind::DemCode
    }

    fn description(&self) -> &str {
        match self.law {
            KratosLaw::HertzViscousCoulomb => {
                "Kratos DEM_D_Hertz_viscous_Coulomb: Hertz + incremental spring 8G*c scaled by √(δ/δ_before) on unloading, Coulomb cap, no damping"
            }
        }
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        super::two_finite_spheres(scene, "Kratos")?;
        self.toolchain
            .require(Tool::KratosDem)
            .map_err(SolveError::Unavailable)?;
        program::in_run_folder(self.name(), |dir| {
            std::fs::write(dir.join(SCRIPT), self.script())
                .map_err(|e| SolveError::Failed(format!("writing the Kratos script: {e}")))?;
            let job = Job {
                program: self.toolchain.kratos_python.clone(),
                args: vec![SCRIPT.into()],
                env: vec![("OMP_NUM_THREADS".into(), "1".into())],
                timeout: program::time_limit(START_UP, PER_STEP, scene.steps().len()),
            };
            let model = format!(
                "{}; two spheres driven kinematically (overlap by position, slip by spin), every velocity fixed",
                self.description()
            );
            super::scripted::run(scene, dir, &job, "Kratos", model, self.law.class())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_script_carries_only_the_harness_constants() {
        let script = Kratos::new(KratosLaw::HertzViscousCoulomb).script();
        assert!(!script.contains('@'), "a placeholder is left: {script}");
        assert!(script.contains("LAW = \"DEM_D_Hertz_viscous_Coulomb\""));
        assert!(script.contains("DT = 1e0"));
        assert!(script.contains("json.load(open(\"scene.json\"))"));
    }
}
