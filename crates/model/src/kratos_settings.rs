//! The settings of the Kratos FEM deck `kratos-3d` that a case chooses (`[kratos]`): the contact
//! formulation of Kratos' ContactStructuralMechanicsApplication, the element, and the stiffness
//! factors of the augmented Lagrangian and of the penalty, each with its allowed set, recorded in
//! every history's metadata (as `[calculix]` is for the CalculiX decks).
//!
//! ```toml
//! [kratos]
//! contact = "alm-frictional"   # alm-frictional, alm-frictionless, penalty
//! element = "tet4"             # tet4 (SmallDisplacementElement3D4N on fem-3d's tetrahedra's
//!                              # corners) or hex8 (SmallDisplacementElement3D8N on gmsh's bricks)
//! alm_factor = 1.0             # ALM: penalty and scale factor = alm_factor · E / h (Kratos' default 1)
//! penalty = 1e3                # penalty: K = penalty · E / h
//! operator_threshold = 1e-6   # the objective slip's switch [mm²] (Kratos' default 1e-3), 0 to 1e3
//! mixed_ulm_solver = false     # Kratos' MixedULMLinearSolver around the direct solve (its default true)
//! ```
//!
//! The last two are Kratos' own options (`alm_contact_process`'s `operator_threshold`,
//! `contact_settings.use_mixed_ulm_solver`), set by default to the values with which
//! `ALMContactFrictional` converges on the two spheres: with Kratos' defaults its Newton cycles on
//! the normal approach and at the stick/slip transitions (measured, one option at a time:
//! docs/external-decks.md, "Kratos 3D: the frictional options tried"). `operator_threshold` is
//! the mortar operators' change (Frobenius norm) above which a frictional condition takes the
//! objective slip (D − D_old) x₁ − (M − M_old) x₂ rather than D (x₁ − x₁,old) − M (x₂ − x₂,old);
//! `mixed_ulm_solver` condenses the dual multipliers before the direct solve.
//!
//! The formulations are Kratos 10.4.4's mortar contact conditions: the augmented Lagrangian
//! (`ALMContactFrictional`, `ALMContactFrictionless`, process `alm_contact_process`) and the
//! penalty (`PenaltyContactFrictional`/`…Frictionless`, process `penalty_contact_process`). Its
//! mortar conditions exist for linear faces only (3-node triangles, 4-node quadrilaterals), so the
//! element is first order.

use crate::choice::{self, choices};

choices!(Formulation, Element);

/// How Kratos enforces contact between sphere 1 (slave) and sphere 2 (master).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// Mortar augmented Lagrangian with Coulomb friction (the paper's kind of contact).
    AlmFrictional,
    /// Mortar augmented Lagrangian, frictionless.
    AlmFrictionless,
    /// Mortar penalty, with Coulomb friction when the path moves tangentially.
    Penalty,
}

impl Formulation {
    /// Every formulation, in the order error messages list them.
    pub const ALL: [Formulation; 3] = [
        Formulation::AlmFrictional,
        Formulation::AlmFrictionless,
        Formulation::Penalty,
    ];

    /// The name in case files and metadata.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::AlmFrictional => "alm-frictional",
            Formulation::AlmFrictionless => "alm-frictionless",
            Formulation::Penalty => "penalty",
        }
    }

    /// Whether friction is modelled (`frictional` for the penalty: the path moves tangentially).
    pub fn frictional(self, tangential: bool) -> bool {
        match self {
            Formulation::AlmFrictional => true,
            Formulation::AlmFrictionless => false,
            Formulation::Penalty => tangential,
        }
    }

    /// Kratos' `contact_settings.mortar_type`.
    pub fn mortar_type(self, tangential: bool) -> &'static str {
        match (self, self.frictional(tangential)) {
            (Formulation::Penalty, true) => "PenaltyContactFrictional",
            (Formulation::Penalty, false) => "PenaltyContactFrictionless",
            (_, true) => "ALMContactFrictional",
            (_, false) => "ALMContactFrictionless",
        }
    }

    /// The contact process's Python module.
    pub fn process(self) -> &'static str {
        match self {
            Formulation::Penalty => "penalty_contact_process",
            _ => "alm_contact_process",
        }
    }
}

/// The element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Element {
    /// `SmallDisplacementElement3D4N` on the corners of fem-3d's tetrahedra (the mortar
    /// conditions `SurfaceCondition3D3N` on their faces).
    Tet4,
    /// `SmallDisplacementElement3D8N` on gmsh's 8-node bricks of the same body (fem-3d's
    /// tetrahedral geometry subdivided, graded as ccx-3d's bricks; `SurfaceCondition3D4N` on
    /// their faces).
    Hex8,
}

impl Element {
    /// Every element, in the order error messages list them.
    pub const ALL: [Element; 2] = [Element::Tet4, Element::Hex8];

    /// The name in case files and metadata.
    pub fn name(self) -> &'static str {
        match self {
            Element::Tet4 => "tet4",
            Element::Hex8 => "hex8",
        }
    }

    /// Kratos' element name.
    pub fn keyword(self) -> &'static str {
        match self {
            Element::Tet4 => "SmallDisplacementElement3D4N",
            Element::Hex8 => "SmallDisplacementElement3D8N",
        }
    }

    /// Kratos' condition on its faces.
    pub fn face_keyword(self) -> &'static str {
        match self {
            Element::Tet4 => "SurfaceCondition3D3N",
            Element::Hex8 => "SurfaceCondition3D4N",
        }
    }

    /// The mesh the element is laid on, in words (the metadata's model).
    pub fn mesh(self) -> &'static str {
        match self {
            Element::Tet4 => "on the corners of gmsh's quadratic tetrahedra (fem-3d's mesh)",
            Element::Hex8 => {
                "on gmsh's 8-node bricks (fem-3d's geometry meshed in tetrahedra of twice the size, \
                 each subdivided into four bricks; graded as ccx-3d's bricks)"
            }
        }
    }

    /// What the elements are called, plural (the metadata's resolution).
    pub fn plural(self) -> &'static str {
        match self {
            Element::Tet4 => "tetrahedra",
            Element::Hex8 => "bricks",
        }
    }
}

/// The allowed ALM factors (penalty and scale factor = factor · E / h). Reason: the ALM converges
/// to the exact contact for any positive factor, but below 1e-2 its active-set iterations see
/// penetrations of order p0 h / (1e-2 E), of the order of the approach itself, and above 1e4 the
/// contact rows are 1e4 times stiffer than the elements' and the direct solve loses as many digits.
pub const ALM_FACTOR_RANGE: [f64; 2] = [1e-2, 1e4];

/// The allowed penalty factors (K = factor · E / h): as CalculiX's
/// ([`crate::calculix_settings::PENALTY_RANGE`], the same reasons).
pub const PENALTY_RANGE: [f64; 2] = crate::calculix_settings::PENALTY_RANGE;

/// The allowed operator thresholds [mm²]. Reason: 0 takes the objective slip at every condition
/// and iteration; the mortar operators of the paper's meshes are of order the faces' areas
/// (1e-2 to 1 mm²), so above 1e3 no condition ever takes it (measured: at 1e3 the run repeats
/// Kratos' default's to the last digit) and a larger value means nothing more.
pub const OPERATOR_THRESHOLD_RANGE: [f64; 2] = [0.0, 1e3];

/// The settings of `kratos-3d`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The contact formulation.
    pub formulation: Formulation,
    /// The element.
    pub element: Element,
    /// The ALM's stiffness factor (Kratos' `advance_ALM_parameters.stiffness_factor`).
    pub alm_factor: f64,
    /// The penalty formulation's stiffness factor (the same Kratos parameter).
    pub penalty: f64,
    /// Kratos' `operator_threshold` [mm²]: where the frictional conditions' mortar operators
    /// change by more, the slip is the objective one.
    pub operator_threshold: f64,
    /// Kratos' `use_mixed_ulm_solver`: condense the dual multipliers before the direct solve.
    pub mixed_ulm_solver: bool,
}

impl Default for Settings {
    /// The augmented Lagrangian with friction (the paper's), tet4, Kratos' default ALM factor 1,
    /// penalty 1e3 (CalculiX's default: its penetration leaves 3e-5 of P), the objective slip
    /// wherever the operators move by 1e-6 mm² and the full system solved (with these two,
    /// every step of the Figure 7 path converges at c_max/2 and /3: module docs).
    fn default() -> Self {
        Self {
            formulation: Formulation::AlmFrictional,
            element: Element::Tet4,
            alm_factor: 1.0,
            penalty: 1e3,
            operator_threshold: 1e-6,
            mixed_ulm_solver: false,
        }
    }
}

/// A setting that is not one of its allowed values: the message lists them.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SettingError {
    /// An unknown formulation.
    #[error("unknown contact formulation `{0}` (allowed: {allowed})", allowed = choice::allowed::<Formulation>())]
    Formulation(String),
    /// An unknown element.
    #[error("unknown element `{0}` (allowed: {allowed})", allowed = choice::allowed::<Element>())]
    Element(String),
    /// An ALM factor out of range.
    #[error("ALM factor {0} is out of range (allowed: {low} ≤ alm_factor ≤ {high}: penalty and scale factor = alm_factor · E / h)", low = ALM_FACTOR_RANGE[0], high = ALM_FACTOR_RANGE[1])]
    AlmFactor(f64),
    /// A penalty factor out of range.
    #[error("penalty factor {0} is out of range (allowed: {low} ≤ penalty ≤ {high}: K = penalty · E / h)", low = PENALTY_RANGE[0], high = PENALTY_RANGE[1])]
    Penalty(f64),
    /// An operator threshold out of range.
    #[error("operator threshold {0} is out of range (allowed: {low} ≤ operator_threshold ≤ {high}, in mm²)", low = OPERATOR_THRESHOLD_RANGE[0], high = OPERATOR_THRESHOLD_RANGE[1])]
    OperatorThreshold(f64),
}

impl Settings {
    /// The formulation called `name`.
    pub fn formulation(name: &str) -> Result<Formulation, SettingError> {
        choice::by_name(name).ok_or_else(|| SettingError::Formulation(name.to_owned()))
    }

    /// The element called `name`.
    pub fn element(name: &str) -> Result<Element, SettingError> {
        choice::by_name(name).ok_or_else(|| SettingError::Element(name.to_owned()))
    }

    /// The ALM factor `value`, within [`ALM_FACTOR_RANGE`].
    pub fn alm_factor(value: f64) -> Result<f64, SettingError> {
        choice::within(value, ALM_FACTOR_RANGE).ok_or(SettingError::AlmFactor(value))
    }

    /// The penalty factor `value`, within [`PENALTY_RANGE`].
    pub fn penalty(value: f64) -> Result<f64, SettingError> {
        choice::within(value, PENALTY_RANGE).ok_or(SettingError::Penalty(value))
    }

    /// The operator threshold `value` [mm²], within [`OPERATOR_THRESHOLD_RANGE`].
    pub fn operator_threshold(value: f64) -> Result<f64, SettingError> {
        choice::within(value, OPERATOR_THRESHOLD_RANGE).ok_or(SettingError::OperatorThreshold(value))
    }

    /// Kratos' stiffness factor of the formulation: the ALM factor or the penalty.
    pub fn stiffness_factor(&self) -> f64 {
        match self.formulation {
            Formulation::Penalty => self.penalty,
            _ => self.alm_factor,
        }
    }

    /// The facts every history records.
    pub fn describe(&self, tangential: bool) -> serde_json::Value {
        serde_json::json!({
            "contact": self.formulation.name(),
            "mortar_type": self.formulation.mortar_type(tangential),
            "process": self.formulation.process(),
            "element": self.element.name(),
            "element_keyword": self.element.keyword(),
            "alm_factor": self.alm_factor,
            "penalty_factor": self.penalty,
            "stiffness_factor": self.stiffness_factor(),
            "operator_threshold_mm2": self.operator_threshold,
            "mixed_ulm_solver": self.mixed_ulm_solver,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_bad_values_list_the_allowed_set() {
        for f in Formulation::ALL {
            assert_eq!(Settings::formulation(f.name()), Ok(f));
        }
        for e in Element::ALL {
            assert_eq!(Settings::element(e.name()), Ok(e));
        }
        assert_eq!(Element::Hex8.keyword(), "SmallDisplacementElement3D8N");
        assert_eq!(Element::Hex8.face_keyword(), "SurfaceCondition3D4N");
        let e = Settings::formulation("mortar").unwrap_err().to_string();
        assert!(
            e.contains("allowed: alm-frictional, alm-frictionless, penalty"),
            "{e}"
        );
        let e = Settings::element("hex20").unwrap_err().to_string();
        assert!(e.contains("allowed: tet4, hex8"), "{e}");
        assert_eq!(Settings::alm_factor(1.0), Ok(1.0));
        for bad in [1e-3, 1e5, f64::NAN, f64::INFINITY] {
            let e = Settings::alm_factor(bad).unwrap_err().to_string();
            assert!(e.contains("0.01 ≤ alm_factor ≤ 10000"), "{e}");
        }
        assert_eq!(Settings::penalty(1e3), Ok(1e3));
        assert_eq!(Settings::operator_threshold(0.0), Ok(0.0));
        for bad in [-1e-9, 1e4, f64::NAN] {
            let e = Settings::operator_threshold(bad).unwrap_err().to_string();
            assert!(e.contains("0 ≤ operator_threshold ≤ 1000"), "{e}");
        }
        for bad in [0.5, 2e6, f64::NAN] {
            let e = Settings::penalty(bad).unwrap_err().to_string();
            assert!(e.contains("1 ≤ penalty ≤ 1000000"), "{e}");
        }
    }

    #[test]
    fn the_formulation_names_kratos_mortar_type_and_process() {
        let f = Formulation::Penalty;
        assert_eq!(f.mortar_type(true), "PenaltyContactFrictional");
        assert_eq!(f.mortar_type(false), "PenaltyContactFrictionless");
        assert_eq!(f.process(), "penalty_contact_process");
        assert_eq!(
            Formulation::AlmFrictional.mortar_type(false),
            "ALMContactFrictional"
        );
        assert_eq!(
            Formulation::AlmFrictionless.mortar_type(true),
            "ALMContactFrictionless"
        );
        let s = Settings {
            formulation: f,
            ..Settings::default()
        };
        assert_eq!(s.stiffness_factor(), 1e3);
        assert_eq!(Settings::default().stiffness_factor(), 1.0);
    }
}
