//! YADE along the path: `yade-mindlin` (`Law2_ScGeom_MindlinPhys_Mindlin`, Hertz normal force and
//! an incremental no-slip spring k_t = 8 G* c with a Coulomb cap, no damping).
//!
//! The script (`templates/yade_mindlin.py`) is a command solver: it reads the scene file and
//! writes the History CSV ([`crate::exchange`]), run by `yade -n -x` in its own folder with the
//! process handling of every external program.
//!
//! YADE's `Law2_ScGeom_MindlinPhys_MindlinDeresiewitz` is not a solver here: it gives no
//! tangential force at all. In YADE 2023.02a (the Debian build) its shear-force update sits
//! inside `#if 0` (HertzMindlin.cpp), so only `usTotal` accumulates and `shearForce` stays zero;
//! [`YadeLaw::MindlinDeresiewitz`] exists so that a test shows it (Q = 0 at every step of a
//! sliding path, P still Hertz).

use std::time::Duration;

use serde_json::json;

use crate::exchange::scene_file;
use crate::external::command;
use crate::external::process::{Environment, Job};
use crate::external::program;
use crate::external::toolchain::{Tool, Toolchain};
use crate::history::{History, Metadata};
use crate::scene::Scene;
use crate::solver::{SolveError, Solver};

/// The script template.
pub const TEMPLATE: &str = include_str!("templates/yade_mindlin.py");

/// The script's file name in the run folder.
const SCRIPT: &str = "yade_mindlin.py";

/// YADE's start-up (2–3 s), and the time allowed per path increment (about 0.1 ms).
const START_UP: Duration = Duration::from_secs(120);
const PER_STEP: Duration = Duration::from_millis(10);

/// A YADE contact law for `MindlinPhys`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum YadeLaw {
    /// `Law2_ScGeom_MindlinPhys_Mindlin`: incremental no-slip spring with a Coulomb cap.
    Mindlin,
    /// `Law2_ScGeom_MindlinPhys_MindlinDeresiewitz`: documented as Mindlin–Deresiewicz, computes
    /// no tangential force (see the module documentation); not registered.
    MindlinDeresiewitz,
}

impl YadeLaw {
    /// The law's class name.
    pub fn class(self) -> &'static str {
        match self {
            YadeLaw::Mindlin => "Law2_ScGeom_MindlinPhys_Mindlin",
            YadeLaw::MindlinDeresiewitz => "Law2_ScGeom_MindlinPhys_MindlinDeresiewitz",
        }
    }

    /// The solver's name.
    pub fn solver_name(self) -> &'static str {
        match self {
            YadeLaw::Mindlin => "yade-mindlin",
            YadeLaw::MindlinDeresiewitz => "yade-mindlin-deresiewitz",
        }
    }
}

/// YADE with one contact law, as a solver.
#[derive(Clone, Debug)]
pub struct Yade {
    /// The law.
    pub law: YadeLaw,
    /// The executables.
    pub toolchain: Toolchain,
    /// The step [s]: a bookkeeping unit of a quasi-static run (one per increment); changing it
    /// changes nothing but the spin rates (shown by a test).
    pub timestep: f64,
}

impl Yade {
    /// YADE from the default toolchain with `law`, step 1 s.
    pub fn new(law: YadeLaw) -> Self {
        Self {
            law,
            toolchain: Toolchain::default(),
            timestep: 1.0,
        }
    }

    /// The script for this law.
    pub fn script(&self) -> String {
        TEMPLATE
            .replace("@SOLVER@", self.law.solver_name())
            .replace("@LAW@", self.law.class())
            .replace("@DT@", &format!("{:e}", self.timestep))
    }
}

impl Solver for Yade {
    fn name(&self) -> &str {
        self.law.solver_name()
    }

    fn description(&self) -> &str {
        match self.law {
            YadeLaw::Mindlin => {
                "YADE Law2_ScGeom_MindlinPhys_Mindlin: Hertz + incremental no-slip spring 8G*c, Coulomb cap, no damping"
            }
            YadeLaw::MindlinDeresiewitz => {
                "YADE Law2_ScGeom_MindlinPhys_MindlinDeresiewitz: Hertz normal force, no tangential force computed"
            }
        }
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        super::two_finite_spheres(scene, "YADE")?;
        self.toolchain
            .require(Tool::Yade)
            .map_err(SolveError::Unavailable)?;
        program::in_run_folder(self.name(), |dir| {
            std::fs::write(dir.join(SCRIPT), self.script())
                .map_err(|e| SolveError::Failed(format!("writing the YADE script: {e}")))?;
            let job = Job {
                program: self.toolchain.yade.clone(),
                args: ["-n", "-x", SCRIPT].map(String::from).to_vec(),
                env: Vec::new(),
                timeout: program::time_limit(START_UP, PER_STEP, scene.steps().len()),
            };
            let (steps, told, wall_s) =
                command::run_exchange(scene, dir, &job, "YADE", &Environment::Inherited)?;
            let mut metadata = Metadata {
                version: told.version.unwrap_or_default(),
                model: format!(
                    "{}; two spheres driven kinematically (overlap by position, slip by spin), non-dynamic bodies",
                    self.description()
                ),
                resolution: format!("one YADE step per path increment ({} increments)", steps.len().saturating_sub(1)),
                warnings: told.warnings,
                ..Metadata::default()
            };
            if !scene.pair.body1.material.eq(&scene.pair.body2.material) {
                metadata.warnings.push(
                    "YADE's Ip2_FrictMat_FrictMat_MindlinPhys averages the two materials' G and ν: \
                     its tangential stiffness is not Mindlin's 8G*c for different materials"
                        .into(),
                );
            }
            metadata.extra.insert("law".into(), json!(self.law.class()));
            metadata.extra.insert("yade_wall_s".into(), json!(wall_s));
            metadata
                .extra
                .insert("scene_file".into(), json!(scene_file::FILE_NAME));
            Ok(History {
                metadata,
                steps,
                fields: Vec::new(),
            })
        })
    }
}
