//! The solvers an impact case may name.

use spherecontact_reference::impact::problem as impact;

/// The names of the solvers an impact case may run: the exact references, the DEM laws, then
/// the DEM codes (LAMMPS per tangential model, YADE), named as their kinematic adapters.
pub fn solver_names() -> Vec<&'static str> {
    [
        impact::REFERENCE,
        impact::LAMMPS_REFERENCE,
        impact::YADE_REFERENCE,
    ]
    .into_iter()
    .chain(
        spherecontact_reference::dem_laws()
            .into_iter()
            .map(|law| law.name),
    )
    .chain(spherecontact_external::dem::lammps::TangentialModel::ALL.map(|m| m.solver_name()))
    .chain(std::iter::once(
        spherecontact_external::dem::yade::YadeLaw::Mindlin.solver_name(),
    ))
    .collect()
}
