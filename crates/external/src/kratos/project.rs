//! `ProjectParameters.json` and `materials.json` of `kratos-3d`: Kratos' static structural solver
//! switched to its contact solver by `contact_settings.mortar_type`, Newton–Raphson with the
//! contact residual criterion, Eigen's sparse LU, and the contact process of the formulation
//! (`[kratos] contact`) on the sub-model-parts of [`super::mdpa`]. Built as JSON values (serde):
//! numbers are `f64`s, names the harness's own ([`Formulation`]'s fixed set); nothing of the case's
//! text reaches the files.
//!
//! The boundary conditions are not here: the driver (`templates/kratos_3d.py`) imposes each path
//! step's far-face displacements from `path.txt` and holds the symmetry plane.

use serde_json::{json, Value};

use super::mdpa::{MASTER, SLAVE, SOLID, STEM};
use spherecontact_model::kratos_settings::{Formulation, Settings};

/// The file names.
pub const PROJECT: &str = "ProjectParameters.json";
/// The materials file.
pub const MATERIALS: &str = "materials.json";

/// Newton iterations allowed per step. Reason: frictionless ALM steps converge in 5–8 (measured
/// on the paper's spheres at c_max/5); a step that has not converged by 30 repeats a cycle of
/// active or slip sets (measured: the ratios alternate between two values from iteration 6 on).
pub const MAX_ITERATIONS: u32 = 30;

/// The convergence tolerances of the contact residual criterion (relative; absolute in the
/// deck's units, mm and N). Reason: relative 1e-6 puts the displacement and multiplier updates
/// at round-off of P's six digits that the checks read; the absolute floors only end a step whose
/// update is below 1e-12 mm or 1e-9 N, far below any judged value.
const RELATIVE: f64 = 1e-6;
const ABSOLUTE_DISPLACEMENT: f64 = 1e-12;
const ABSOLUTE_RESIDUAL: f64 = 1e-9;

/// What the files are written from (SI).
pub struct ProjectSpec {
    /// Young's modulus [Pa].
    pub young: f64,
    /// Poisson ratio.
    pub poisson: f64,
    /// Coulomb friction coefficient of a frictional formulation.
    pub friction: f64,
    /// The case's settings.
    pub settings: Settings,
    /// Whether the path moves tangentially (the penalty's friction).
    pub tangential: bool,
    /// The number of computed steps.
    pub steps: usize,
}

impl ProjectSpec {
    /// Whether friction is modelled.
    pub fn frictional(&self) -> bool {
        self.settings.formulation.frictional(self.tangential)
    }

    /// `ProjectParameters.json`.
    pub fn project(&self) -> Value {
        let formulation = self.settings.formulation;
        json!({
            "problem_data": {
                "problem_name": STEM, "parallel_type": "OpenMP", "echo_level": 0,
                // One step per computed path step at times 1, 2, …: Kratos advances while
                // time < end_time, so half a step past the last one ends exactly there.
                "start_time": 0.0, "end_time": self.steps as f64 - 0.5
            },
            "solver_settings": {
                "solver_type": "Static", "model_part_name": "Structure", "domain_size": 3,
                "echo_level": 1, "analysis_type": "non_linear",
                "model_import_settings": {"input_type": "mdpa", "input_filename": STEM},
                "material_import_settings": {"materials_filename": MATERIALS},
                "time_stepping": {"time_step": 1.0},
                "convergence_criterion": "contact_residual_criterion",
                "displacement_relative_tolerance": RELATIVE,
                "displacement_absolute_tolerance": ABSOLUTE_DISPLACEMENT,
                "residual_relative_tolerance": RELATIVE,
                "residual_absolute_tolerance": ABSOLUTE_RESIDUAL,
                "max_iteration": MAX_ITERATIONS,
                "compute_reactions": true,
                "linear_solver_settings": {"solver_type": "LinearSolversApplication.sparse_lu"},
                "contact_settings": {
                    "mortar_type": formulation.mortar_type(self.tangential),
                    "use_mixed_ulm_solver": self.settings.mixed_ulm_solver
                }
            },
            "processes": {
                "constraints_process_list": [],
                "loads_process_list": [],
                "list_other_processes": [],
                "contact_process_list": [self.contact_process()]
            },
            "output_processes": {}
        })
    }

    /// The contact process of the formulation.
    fn contact_process(&self) -> Value {
        let formulation = self.settings.formulation;
        let name = match formulation {
            Formulation::Penalty => "PenaltyContactProcess",
            _ => "ALMContactProcess",
        };
        let (contact_type, mu) = match self.frictional() {
            true => ("Frictional", self.friction),
            false => ("Frictionless", 0.0),
        };
        json!({
            "python_module": formulation.process(),
            "kratos_module": "KratosMultiphysics.ContactStructuralMechanicsApplication",
            "process_name": name,
            "Parameters": {
                "model_part_name": "Structure",
                "contact_model_part": {"0": [SLAVE, MASTER]},
                "assume_master_slave": {"0": [SLAVE]},
                "friction_coefficients": {"0": mu},
                "contact_type": contact_type,
                // Kratos computes the penalty and the scale factor as this factor · E / h.
                "advance_ALM_parameters": {"stiffness_factor": self.settings.stiffness_factor()},
                "operator_threshold": self.settings.operator_threshold
            }
        })
    }

    /// `materials.json` (MPa: the deck's units).
    pub fn materials(&self) -> Value {
        json!({"properties": [{
            "model_part_name": format!("Structure.{SOLID}"),
            "properties_id": 1,
            "Material": {
                "constitutive_law": {"name": "LinearElastic3DLaw"},
                "Variables": {
                    // Static: the density enters nothing; Kratos requires one.
                    "DENSITY": 1.0,
                    "YOUNG_MODULUS": self.young * 1e-6,
                    "POISSON_RATIO": self.poisson
                },
                "Tables": {}
            }
        }]})
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requirement: the formulation's mortar type, process, friction and factor reach the file,
    /// the steps end where the path does; exact values.
    #[test]
    fn the_files_carry_the_formulation_the_friction_and_the_steps() {
        let mut spec = ProjectSpec {
            young: 70e9,
            poisson: 0.3,
            friction: 0.2,
            settings: Settings::default(),
            tangential: true,
            steps: 4,
        };
        let p = spec.project();
        assert_eq!(p["problem_data"]["end_time"], 3.5);
        assert_eq!(
            p["solver_settings"]["contact_settings"]["mortar_type"],
            "ALMContactFrictional"
        );
        let c = &p["processes"]["contact_process_list"][0];
        assert_eq!(c["python_module"], "alm_contact_process");
        assert_eq!(c["Parameters"]["friction_coefficients"]["0"], 0.2);
        assert_eq!(c["Parameters"]["contact_type"], "Frictional");
        assert_eq!(c["Parameters"]["operator_threshold"], 1e-6);
        assert_eq!(
            p["solver_settings"]["contact_settings"]["use_mixed_ulm_solver"],
            false
        );
        spec.settings.formulation = Formulation::Penalty;
        spec.tangential = false;
        let c = spec.project()["processes"]["contact_process_list"][0].clone();
        assert_eq!(c["process_name"], "PenaltyContactProcess");
        assert_eq!(c["Parameters"]["contact_type"], "Frictionless");
        assert_eq!(c["Parameters"]["advance_ALM_parameters"]["stiffness_factor"], 1e3);
        assert_eq!(
            spec.materials()["properties"][0]["Material"]["Variables"]["YOUNG_MODULUS"],
            7e4
        );
    }
}
