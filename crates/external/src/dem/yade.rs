//! YADE along the path: `yade-mindlin` (`Law2_ScGeom_MindlinPhys_Mindlin`, Hertz normal force and
//! an incremental no-slip spring k_t = 8 G* c with a Coulomb cap, no damping).
//!
//! The script (`templates/yade_mindlin.py`) is a command solver: it reads the scene file and
//! writes the History CSV ([`crate::exchange`]), run by `yade -n -x` in its own folder with the
//! process handling of every external program; every YADE run (this solver's, the impact
//! sweeps') is made by [`job`], which leaves nothing outside that folder.
//!
//! YADE's `Law2_ScGeom_MindlinPhys_MindlinDeresiewitz` is not a solver here: it gives no
//! tangential force at all. In YADE 2023.02a (the Debian build) its shear-force update sits
//! inside `#if 0` (HertzMindlin.cpp), so only `usTotal` accumulates and `shearForce` stays zero;
//! [`YadeLaw::MindlinDeresiewitz`] exists so that a test shows it (Q = 0 at every step of a
//! sliding path, P still Hertz).

use std::path::Path;
use std::time::Duration;

use crate::program;
use spherecontact_model::history::History;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use spherecontact_system::process::Job;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// The script template.
pub const TEMPLATE: &str = include_str!("templates/yade_mindlin.py");

/// The script's file name in the run folder.
const SCRIPT: &str = "yade_mindlin.py";

/// What every YADE script starts with ([`job`]): YADE's own `/tmp/yade-XXXXXX` removed.
const PRELUDE: &str = include_str!("templates/yade_prelude.py");

/// The folder in the run folder where YADE's IPython keeps its profile (`IPYTHONDIR`), instead of
/// the user's `~/.ipython`.
const IPYTHON_DIR: &str = "ipython";

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

/// The job that runs the YADE script `text` as `dir/script` (written there, [`PRELUDE`] first):
/// `yade -n -x script` within `timeout`. Every YADE run goes through it (the path solver here, the
/// impact sweeps of `code_run (spherecontact-impact)`), so that none leaves anything outside `dir`: the
/// prelude removes the `/tmp/yade-XXXXXX` YADE makes at its start, and its IPython keeps its
/// profile and history in `dir/ipython` (`IPYTHONDIR`: an absolute path, so `dir` must be UTF-8).
pub fn job(yade: &Path, dir: &Path, script: &str, text: &str, timeout: Duration) -> std::io::Result<Job> {
    let ipython = dir.join(IPYTHON_DIR);
    let ipython = ipython.to_str().ok_or_else(|| {
        std::io::Error::other(format!(
            "the run folder {} is not UTF-8 (YADE's IPYTHONDIR is text)",
            dir.display()
        ))
    })?;
    std::fs::write(dir.join(script), format!("{PRELUDE}{text}"))?;
    Ok(Job {
        program: yade.to_path_buf(),
        args: ["-n", "-x", script].map(String::from).to_vec(),
        env: vec![("IPYTHONDIR".into(), ipython.into())],
        timeout,
    })
}

impl Solver for Yade {
    fn name(&self) -> &str {
        self.law.solver_name()
    }

    fn kind(&self) -> Kind {
        Kind::DemCode
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
            let timeout = program::time_limit(START_UP, PER_STEP, scene.steps().len());
            let job = job(&self.toolchain.yade, dir, SCRIPT, &self.script(), timeout)
                .map_err(|e| SolveError::Failed(format!("writing the YADE script: {e}")))?;
            let model = format!(
                "{}; two spheres driven kinematically (overlap by position, slip by spin), non-dynamic bodies",
                self.description()
            );
            let mut history = super::scripted::run(scene, dir, &job, "YADE", model, self.law.class())?;
            if !scene.pair.body1.material.eq(&scene.pair.body2.material) {
                history.metadata.warnings.push(
                    "YADE's Ip2_FrictMat_FrictMat_MindlinPhys averages the two materials' G and ν: \
                     its tangential stiffness is not Mindlin's 8G*c for different materials"
                        .into(),
                );
            }
            Ok(history)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_yade_job_removes_yades_temporary_folder_and_keeps_ipython_in_its_run_folder() {
        let dir = tempfile::tempdir().unwrap();
        let job = job(
            Path::new("yade"),
            dir.path(),
            "s.py",
            "print(1)\n",
            Duration::from_secs(1),
        )
        .unwrap();
        assert_eq!(job.args, ["-n", "-x", "s.py"]);
        let script = std::fs::read_to_string(dir.path().join("s.py")).unwrap();
        assert!(
            script.starts_with(PRELUDE) && script.ends_with("\nprint(1)\n"),
            "{script}"
        );
        assert!(PRELUDE.contains("rmdir(") && PRELUDE.contains("O.tmpFilename()"));
        let ipython = dir.path().join(IPYTHON_DIR);
        assert_eq!(
            job.env,
            [("IPYTHONDIR".to_owned(), ipython.to_str().unwrap().to_owned())]
        );
    }
}
