//! The solvers an impact case may name.

use spherecontact_model::solver::Kind;
use spherecontact_reference::impact::problem as impact;

/// The names of the solvers an impact case may run: the exact references, the DEM laws, then
/// the DEM codes (LAMMPS per tangential model, YADE, LIGGGHTS, Kratos per law), named as their
/// kinematic adapters.
pub fn solver_names() -> Vec<&'static str> {
    [
        impact::REFERENCE,
        impact::LAMMPS_REFERENCE,
        impact::YADE_REFERENCE,
        impact::LIGGGHTS_REFERENCE,
    ]
    .into_iter()
    .chain(
        spherecontact_reference::dem_laws()
            .into_iter()
            .map(|law| law.name),
    )
    .chain(spherecontact_external::dem::lammps::TangentialModel::ALL.map(|m| m.solver_name()))
    .chain([
        spherecontact_external::dem::yade::YadeLaw::Mindlin.solver_name(),
        spherecontact_external::dem::liggghts::NAME,
    ])
    .chain(spherecontact_external::dem::kratos::KratosLaw::ALL.map(|law| law.solver_name()))
    .collect()
}

/// The kind of the impact solver `name` of `case` in words, for tables: "DEM law", "DEM code",
/// "analytic" (the exact references), or for the case's own solvers "DEM law, yours (a
/// program)".
pub fn impact_kind_in_words(case: &impact::ImpactCase, name: &str) -> String {
    if let Some(own) = case.own_solver(name) {
        return format!("{}, yours ({})", own.kind, own.origin());
    }
    let references = [
        impact::REFERENCE,
        impact::LAMMPS_REFERENCE,
        impact::YADE_REFERENCE,
        impact::LIGGGHTS_REFERENCE,
    ];
    if references.contains(&name) {
        return Kind::Analytic.to_string();
    }
    crate::registry::by_name(name).map_or_else(|| "unknown".to_owned(), |s| s.kind().to_string())
}
