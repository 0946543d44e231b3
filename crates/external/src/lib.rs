//! # spherecontact-external: external programs as solvers
//!
//! **Job.** The solvers that are programs: the FreeFEM and FEniCSx decks, the CalculiX decks, the DEM codes LAMMPS and YADE ([`dem`]), a program a case names ([`command`]) and stored results ([`stored`], [`exchange`]): each deck written from the scene, run, and read back as foreign input into the same `History` as every other solver.
//!
//! **May depend on.** `spherecontact-model`, `spherecontact-system` (files and programs, by rule) and `spherecontact-solvers` (the meshes the decks share with the in-crate FEM).
//!
//! **Offers.** `solvers()`, the deck writers and readers, and `split` (a deck's folder for a run elsewhere).
//!
//! External solvers: gmsh meshes, FreeFEM and FEniCSx (dolfinx) decks written from the scene,
//! run as subprocesses, their results read back into the same [`History`](spherecontact_model::history::History)
//! as every other solver.
//!
//! - finding the tools and running them (the toolchain, one run in its own process group with a
//!   timeout, its descendants, its output bounded, masked and excerpted) is `spherecontact-system`'s;
//! - [`command`]: a program a case names as a solver, run only with [`permission`], its
//!   command filled under the rule of [`placeholder`];
//! - the gmsh geometries of a scene and their meshes are `spherecontact-solvers`' (`fem::mesh`),
//!   which the in-crate FEM reads too;
//! - [`deck`]: filling a template, interpreting a tool's exit; [`freefem`], [`fenicsx`]: the decks;
//! - [`plan`]: what a scene asks of a deck (steps, modes, grip, candidate zone, penalty);
//! - [`axisym`]: the shared run (mesh → deck → read back), [`record`]: the History it gives;
//! - [`readback`]: the decks' per-step CSV, each result file read as foreign input ([`csv_lines`]:
//!   the line a message names);
//!   [`field_files`]: the field files, checked, then read through meshio;
//! - [`surface`]: the contact line's nodal state at every step, and what is measured from it;
//! - [`fenicsx3d`]: the 3D deck under MPI (heavy), [`surface3d`]: its contact surface read back;
//! - [`split`]: a deck's folder for a run elsewhere (`deck write|read`: manifest, README, script);
//! - [`calculix`]: the CalculiX deck `ccx-axisym` (its `.inp` writer, `.dat`/`.frd` reader, settings);
//! - [`kratos`]: the Kratos FEM deck `kratos-3d` (MDPA, ProjectParameters, the driver, its convergence record).
//!
//! Install the tools with `scripts/setup.sh`. A missing tool makes the solver
//! [`Unavailable`](spherecontact_model::solver::SolveError::Unavailable), never a pass.

pub mod calculix;
pub mod dem;
pub mod exchange;
pub mod kratos;

pub mod axisym;
pub mod bricks;
pub mod command;
pub mod csv_lines;
pub mod deck;
pub mod fenicsx;
pub mod fenicsx3d;
pub mod field_files;
pub mod freefem;
pub use spherecontact_system::permission;
pub mod placeholder;
pub mod plan;
pub mod program;
pub mod readback;
pub mod record;
pub mod split;
pub mod stored;
pub mod surface;
pub mod surface3d;

use axisym::AxisymSolver;
use spherecontact_model::solver::Solver;

/// The external solvers, with default options (the 3D deck on one rank).
pub fn solvers() -> Vec<Box<dyn Solver>> {
    vec![
        Box::new(AxisymSolver::new(freefem::FreeFem)),
        Box::new(AxisymSolver::new(fenicsx::Fenicsx)),
        Box::new(fenicsx3d::Solid3dDeck::new(1)),
    ]
}
