//! The settings of the CalculiX solvers that a case chooses (`[calculix]`): the contact
//! formulation, the penalty stiffness and the 3D element, each with its allowed set, recorded in
//! every history's metadata. Code_Aster calls such variants of one physical test its
//! "modelings"; here they are a case axis (docs/external-decks.md, "CalculiX: formulations").
//!
//! ```toml
//! [calculix]
//! contact = "face-to-face"    # node-to-face, face-to-face, mortar, linmortar, pglinmortar
//! penalty = 1e3               # K = penalty · E / h (*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR)
//! element = "tet10"           # the 3D decks' element: tet10 (C3D10), hex20 (C3D20), hex20r (C3D20R)
//! ```
//!
//! The formulations are those of CalculiX 2.20's `*CONTACT PAIR, TYPE=…` (its manual, "Contact":
//! node-to-face penalty, face-to-face penalty, and face-to-face mortar with dual Lagrange
//! multipliers in three variants, MORTAR, LINMORTAR and PGLINMORTAR; the Debian binary's keyword
//! table has all five). The axisymmetric deck has one element, CAX6 on the shared mesh's
//! quadratic triangles ([`AXISYMMETRIC_ELEMENT`]); `element` chooses the 3D decks'.

use crate::choice::{self, choices};

choices!(Formulation, Element);

/// How CalculiX enforces contact between the sphere (slave) and the plane (master).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// `TYPE=NODE TO SURFACE`: a penalty spring at each slave node.
    NodeToFace,
    /// `TYPE=SURFACE TO SURFACE`: the penalty integrated over the slave faces.
    FaceToFace,
    /// `TYPE=MORTAR`: face-to-face with dual Lagrange multipliers (quadratic ones).
    Mortar,
    /// `TYPE=LINMORTAR`: mortar with linear dual multipliers (none at the midside nodes).
    LinMortar,
    /// `TYPE=PGLINMORTAR`: mortar, the multiplier's variation by linear standard functions
    /// (Petrov–Galerkin).
    PgLinMortar,
}

impl Formulation {
    /// Every formulation, in the order error messages list them.
    pub const ALL: [Formulation; 5] = [
        Formulation::FaceToFace,
        Formulation::NodeToFace,
        Formulation::Mortar,
        Formulation::LinMortar,
        Formulation::PgLinMortar,
    ];

    /// The name in case files and metadata.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::NodeToFace => "node-to-face",
            Formulation::FaceToFace => "face-to-face",
            Formulation::Mortar => "mortar",
            Formulation::LinMortar => "linmortar",
            Formulation::PgLinMortar => "pglinmortar",
        }
    }

    /// CalculiX's keyword value (`*CONTACT PAIR, TYPE=…`).
    pub fn keyword(self) -> &'static str {
        match self {
            Formulation::NodeToFace => "NODE TO SURFACE",
            Formulation::FaceToFace => "SURFACE TO SURFACE",
            Formulation::Mortar => "MORTAR",
            Formulation::LinMortar => "LINMORTAR",
            Formulation::PgLinMortar => "PGLINMORTAR",
        }
    }

    /// True for the mortar variants.
    pub fn mortar(self) -> bool {
        matches!(
            self,
            Formulation::Mortar | Formulation::LinMortar | Formulation::PgLinMortar
        )
    }

    /// True for the face-to-face families (penalty or mortar), whose contact totals
    /// `*CONTACT PRINT … CF` prints; node-to-face has none.
    pub fn face_to_face(self) -> bool {
        self != Formulation::NodeToFace
    }
}

/// The axisymmetric deck's element: CAX6 on the shared meridian mesh's quadratic triangles (the
/// mesh every axisymmetric solver shares, so that p(r) is compared node by node; CAX8 would need
/// a recombined meridian mesh of its own).
pub const AXISYMMETRIC_ELEMENT: &str = "CAX6";

/// The mesh a 3D element needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshKind {
    /// gmsh's quadratic tetrahedra (`crates/solvers/src/fem/mesh/solid_geo.rs`, as fem-3d).
    Tet10,
    /// 20-node hexahedra of the same body (`crates/external/src/calculix/hex_mesh.rs`).
    Hex20,
}

/// The 3D decks' element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Element {
    /// C3D10: the 10-node tetrahedron, on fem-3d's mesh.
    Tet10,
    /// C3D20: the 20-node brick, full integration (27 points), the paper's kind (ANSYS SOLID186).
    Hex20,
    /// C3D20R: the 20-node brick, reduced integration (8 points).
    Hex20r,
}

impl Element {
    /// Every element, in the order error messages list them.
    pub const ALL: [Element; 3] = [Element::Tet10, Element::Hex20, Element::Hex20r];

    /// The name in case files and metadata.
    pub fn name(self) -> &'static str {
        match self {
            Element::Tet10 => "tet10",
            Element::Hex20 => "hex20",
            Element::Hex20r => "hex20r",
        }
    }

    /// CalculiX's element type (`*ELEMENT, TYPE=…`).
    pub fn keyword(self) -> &'static str {
        match self {
            Element::Tet10 => "C3D10",
            Element::Hex20 => "C3D20",
            Element::Hex20r => "C3D20R",
        }
    }

    /// The mesh it needs.
    pub fn mesh(self) -> MeshKind {
        match self {
            Element::Tet10 => MeshKind::Tet10,
            Element::Hex20 | Element::Hex20r => MeshKind::Hex20,
        }
    }

    /// Its keyword and mesh: what a 3D deck asks of the setting.
    pub fn spec(self) -> (&'static str, MeshKind) {
        (self.keyword(), self.mesh())
    }
}

/// The allowed penalty factors (K = factor · E / h). Reason: below 1 the penalty's penetration
/// at the pole, p0/K, is of the order of the pole element's own deformation (the answer is the
/// penalty's, not the contact's); above 1e6 the contact springs are 1e6 times stiffer than the
/// elements they hold and the solves lose as many digits. The default 1e3 leaves 2.8e-5 of P
/// (measured: the sweep 1e2, 1e3, 1e4 in docs/external-decks.md).
pub const PENALTY_RANGE: [f64; 2] = [1.0, 1e6];

/// The CalculiX solvers' settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The contact formulation.
    pub formulation: Formulation,
    /// The penalty factor: K = penalty · E / h, h the pole element size.
    pub penalty: f64,
    /// The 3D decks' element.
    pub element: Element,
}

impl Default for Settings {
    /// Face-to-face (CalculiX's advice for quadratic elements: node-to-face puts springs at the
    /// corner and midside nodes whose pressures alternate), penalty 1e3, C3D10 (fem-3d's mesh).
    fn default() -> Self {
        Self {
            formulation: Formulation::FaceToFace,
            penalty: 1e3,
            element: Element::Tet10,
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
    /// A penalty factor out of range.
    #[error("penalty factor {0} is out of range (allowed: {low} ≤ penalty ≤ {high}: K = penalty · E / h)", low = PENALTY_RANGE[0], high = PENALTY_RANGE[1])]
    Penalty(f64),
}

impl Settings {
    /// The penalty stiffness K = penalty · E / h [MPa/mm] of a body of Young's modulus `young`
    /// [Pa] meshed at pole element size `h` [m] (the decks are in mm–N–MPa).
    pub fn stiffness_mpa_per_mm(&self, young: f64, h: f64) -> f64 {
        self.penalty * young * 1e-6 / (h * 1e3)
    }

    /// The formulation called `name`.
    pub fn formulation(name: &str) -> Result<Formulation, SettingError> {
        choice::by_name(name).ok_or_else(|| SettingError::Formulation(name.to_owned()))
    }

    /// The element called `name`.
    pub fn element(name: &str) -> Result<Element, SettingError> {
        choice::by_name(name).ok_or_else(|| SettingError::Element(name.to_owned()))
    }

    /// The penalty factor `value`, within [`PENALTY_RANGE`].
    pub fn penalty(value: f64) -> Result<f64, SettingError> {
        choice::within(value, PENALTY_RANGE).ok_or(SettingError::Penalty(value))
    }

    /// The facts every history records: formulation, penalty factor and element.
    pub fn describe(&self) -> serde_json::Value {
        serde_json::json!({
            "contact": self.formulation.name(),
            "contact_keyword": self.formulation.keyword(),
            "penalty_factor": self.penalty,
            "element": self.element.name(),
            "element_keyword": self.element.keyword(),
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
        let e = Settings::formulation("augmented-lagrange")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("face-to-face, node-to-face, mortar, linmortar, pglinmortar"),
            "{e}"
        );
        let e = Settings::element("cax6").unwrap_err().to_string();
        assert!(e.contains("allowed: tet10, hex20, hex20r"), "{e}");
        assert_eq!(Settings::penalty(1e3), Ok(1e3));
        for bad in [0.5, 2e6, f64::NAN, f64::INFINITY] {
            let e = Settings::penalty(bad).unwrap_err().to_string();
            assert!(e.contains("1 ≤ penalty ≤ 1000000"), "{e}");
        }
    }

    #[test]
    fn the_element_axis_gives_the_keyword_and_the_mesh_a_3d_deck_needs() {
        assert_eq!(Element::Tet10.spec(), ("C3D10", MeshKind::Tet10));
        assert_eq!(Element::Hex20.spec(), ("C3D20", MeshKind::Hex20));
        assert_eq!(Element::Hex20r.spec(), ("C3D20R", MeshKind::Hex20));
        for f in Formulation::ALL {
            assert_eq!(f.mortar(), f.keyword().contains("MORTAR"), "{f:?}");
        }
        assert!(!Formulation::NodeToFace.face_to_face() && Formulation::Mortar.face_to_face());
    }
}
