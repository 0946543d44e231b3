//! The one place that names every solver family of this build.
//!
//! Everything that needs a solver by name (case validation, the command line, `verify`, `bench`)
//! asks here; the solver families themselves know nothing of each other or of this list.

use spherecontact_external as external;
use spherecontact_external::dem;
use spherecontact_model::solver::Solver;
use spherecontact_reference as analytic;
use spherecontact_solvers::bem;
use spherecontact_solvers::fem;

/// Every solver this build knows, in listing order: the in-crate ones, then the external decks,
/// then the DEM codes.
pub fn registry() -> Vec<Box<dyn Solver>> {
    let mut solvers = in_crate();
    // fem-3d computes in this process but meshes with gmsh, and its set-up takes seconds: it
    // runs where a case lists it (cases/fem-3d-normal.toml) and in tests/fem3d_hertz.rs.
    solvers.push(Box::new(fem::FemSolid3d::default()));
    solvers.extend(external::solvers());
    solvers.push(Box::new(spherecontact_external::calculix::CcxAxisym::default()));
    solvers.push(Box::new(spherecontact_external::calculix::CcxSolid::default()));
    solvers.push(Box::new(spherecontact_external::kratos::KratosSolid::default()));
    solvers.extend(dem::solvers());
    solvers
}

/// The solvers that run inside this process (no external program): the analytic models and
/// laws, the BEM and the axisymmetric FEM (not fem-3d, which meshes with gmsh). Tests that must
/// stay fast and self-contained run these.
pub fn in_crate() -> Vec<Box<dyn Solver>> {
    let mut solvers = analytic::solvers();
    solvers.push(Box::new(bem::Bem::default()));
    solvers.push(Box::new(fem::FemAxisym::default()));
    solvers.push(Box::new(fem::MdrDomain::default()));
    solvers
}

/// True when `name` is an in-crate solver of this build (see [`in_crate`]).
pub fn is_in_crate(name: &str) -> bool {
    in_crate().iter().any(|s| s.name() == name)
}

/// The solver called `name`, if this build has it.
pub fn by_name(name: &str) -> Option<Box<dyn Solver>> {
    registry().into_iter().find(|s| s.name() == name)
}

/// The names of every solver of this build, in listing order.
pub fn names() -> Vec<String> {
    registry().iter().map(|s| s.name().to_owned()).collect()
}

/// "unknown solver `NAME`" with [`did_you_mean`] of `known`.
pub fn unknown(name: &str, known: &[String]) -> String {
    format!("unknown solver `{name}`{}", did_you_mean(name, known))
}

/// "; did you mean `KNOWN`?" with the nearest of `known` where one is near enough to be what was
/// meant ([`spherecontact_system::text::nearest`]), else nothing.
pub fn did_you_mean(name: &str, known: &[String]) -> String {
    spherecontact_system::text::nearest(name, known.iter().map(String::as_str))
        .map(|meant| format!("; did you mean `{meant}`?"))
        .unwrap_or_default()
}
