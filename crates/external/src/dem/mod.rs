//! Real DEM codes along the path: LAMMPS (`pair_style granular`), YADE (`MindlinPhys` laws),
//! LIGGGHTS (`pair gran`) and Kratos (DEMApplication's laws), driven through input generated from
//! the case and run as subprocesses, their forces read back into the same
//! [`History`](spherecontact_model::history::History) as every other solver.
//!
//! | solver | code and law |
//! |---|---|
//! | `lammps-mindlin` | LAMMPS granular, tangential `mindlin` (stored displacement × current stiffness) |
//! | `lammps-mindlin-rescale` | `mindlin_rescale` (displacement scaled by a/a_old on unloading) |
//! | `lammps-mindlin-force` | `mindlin/force` (incremental force) |
//! | `lammps-mindlin-rescale-force` | `mindlin_rescale/force` (force scaled by a/a_old on unloading) |
//! | `yade-mindlin` | YADE `Law2_ScGeom_MindlinPhys_Mindlin` (incremental no-slip spring) |
//! | `kratos-hertz-coulomb` | Kratos `DEM_D_Hertz_viscous_Coulomb` (incremental spring, force scaled on unloading) |
//! | `liggghts-hertz-history` | LIGGGHTS `pair gran model hertz tangential history` (stored displacement × current stiffness) |
//!
//! How the runs are made quasi-static: the codes move the spheres kinematically, one step per
//! path increment, with no time integration of forces and no damping (see the templates). The
//! normal approach is set by position along the line of centres; the tangential displacement by
//! spinning one sphere, so the contact normal never turns. The codes need `scripts/setup.sh`
//! (Debian's `lammps`, `yade` and `liggghts`, Kratos' wheels in the project's environment);
//! without them these solvers are "not available".

pub mod kratos;
pub mod lammps;
pub mod liggghts;
pub mod path_rows;
pub mod scripted;
pub mod yade;

use kratos::{Kratos, KratosLaw};
use lammps::{Lammps, TangentialModel};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{SolveError, Solver};
use yade::{Yade, YadeLaw};

/// The DEM-code solvers, LAMMPS's models first, then YADE's, LIGGGHTS' and Kratos' laws.
pub fn solvers() -> Vec<Box<dyn Solver>> {
    let mut solvers: Vec<Box<dyn Solver>> = TangentialModel::ALL
        .into_iter()
        .map(|model| Box::new(Lammps::new(model)) as Box<dyn Solver>)
        .collect();
    solvers.push(Box::new(Yade::new(YadeLaw::Mindlin)));
    solvers.push(Box::new(liggghts::Liggghts::default()));
    solvers.extend(
        KratosLaw::ALL
            .into_iter()
            .map(|law| Box::new(Kratos::new(law)) as Box<dyn Solver>),
    );
    solvers
}

/// `NotApplicable` unless both bodies are finite spheres (the codes model sphere–sphere contact).
fn two_finite_spheres(scene: &Scene, code: &str) -> Result<(), SolveError> {
    if scene.pair.body1.radius.is_finite() && scene.pair.body2.radius.is_finite() {
        Ok(())
    } else {
        Err(SolveError::NotApplicable(format!(
            "{code} is driven here as two spheres; a flat (infinite radius) is not modelled"
        )))
    }
}
