//! External solvers: gmsh meshes, FreeFEM and FEniCSx (dolfinx) decks written from the scene,
//! run as subprocesses, their results read back into the same [`History`](crate::history::History)
//! as every other solver.
//!
//! - [`toolchain`]: finding the tools, their versions, how to install them (`doctor`);
//! - [`process`]: one run in its own directory and process group, with a timeout;
//!   [`descendants`]: every process it started, found and killed; [`reap`]: waiting for one, and
//!   the CPU time of those reaped; [`bounded_log`]: its output;
//!   [`mask`]: the secrets masked in it; [`excerpt`]: what of it a message shows;
//! - [`command`]: a program a case names as a solver, run only with [`permission`], its
//!   command filled under the rule of [`placeholder`];
//! - [`geo`]: the gmsh geometry of a scene and its meshes (also for the in-crate FEM);
//! - [`solid_geo`]: the 3D geometry (half of a hemisphere or cap) and its quadratic tetrahedra;
//! - [`deck`]: filling a template, interpreting a tool's exit; [`freefem`], [`fenicsx`]: the decks;
//! - [`plan`]: what a scene asks of a deck (steps, modes, grip, candidate zone, penalty);
//! - [`axisym`]: the shared run (mesh → deck → read back), [`record`]: the History it gives;
//! - [`readback`]: the decks' per-step CSV, each result file read as foreign input;
//!   [`field_files`]: the field files, checked, then read through meshio;
//! - [`surface`]: the contact line's nodal state at every step, and what is measured from it;
//! - [`fenicsx3d`]: the 3D deck under MPI (heavy), [`surface3d`]: its contact surface read back;
//! - [`split`]: a deck's folder for a run elsewhere (`deck write|read`: manifest, README, script);
//! - [`calculix`]: the CalculiX deck `ccx-axisym` (its `.inp` writer, `.dat`/`.frd` reader, settings).
//!
//! Install the tools with `scripts/setup.sh`. A missing tool makes the solver
//! [`Unavailable`](crate::solver::SolveError::Unavailable), never a pass.

pub mod axisym;
pub mod bounded_log;
pub mod command;
pub mod deck;
pub mod descendants;
pub mod excerpt;
pub mod fenicsx;
pub mod fenicsx3d;
pub mod field_files;
pub mod freefem;
pub mod geo;
pub mod mask;
pub mod permission;
pub mod placeholder;
pub mod plan;
pub mod process;
pub mod program;
pub mod readback;
pub mod reap;
pub mod record;
pub mod solid_geo;
pub mod split;
pub mod stored;
pub mod surface;
pub mod surface3d;
pub mod toolchain;

use crate::solver::Solver;
use axisym::AxisymSolver;

/// The external solvers, with default options (the 3D deck on one rank).
pub fn solvers() -> Vec<Box<dyn Solver>> {
    vec![
        Box::new(AxisymSolver::new(freefem::FreeFem)),
        Box::new(AxisymSolver::new(fenicsx::Fenicsx)),
        Box::new(fenicsx3d::Solid3dDeck::new(1)),
    ]
}
