//! The settings of the CalculiX solvers that a case chooses (`[calculix]`): the contact
//! formulation, the penalty stiffness and the element, each with its allowed set, recorded in
//! every history's metadata.
//!
//! ```toml
//! [calculix]
//! contact = "face-to-face"    # or "node-to-face" (*CONTACT PAIR, TYPE=SURFACE TO SURFACE or NODE TO SURFACE)
//! penalty = 1e3               # K = penalty · E / h (*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR)
//! element = "cax6"            # the element on the meridian's 6-node triangles
//! ```

/// How CalculiX enforces contact between the sphere (slave) and the plane (master).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// `TYPE=NODE TO SURFACE`: a penalty spring at each slave node.
    NodeToFace,
    /// `TYPE=SURFACE TO SURFACE`: the penalty integrated over the slave faces.
    FaceToFace,
}

impl Formulation {
    /// Every formulation, in the order error messages list them.
    pub const ALL: [Formulation; 2] = [Formulation::FaceToFace, Formulation::NodeToFace];

    /// The name in case files and metadata.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::NodeToFace => "node-to-face",
            Formulation::FaceToFace => "face-to-face",
        }
    }

    /// CalculiX's keyword value (`*CONTACT PAIR, TYPE=…`).
    pub fn keyword(self) -> &'static str {
        match self {
            Formulation::NodeToFace => "NODE TO SURFACE",
            Formulation::FaceToFace => "SURFACE TO SURFACE",
        }
    }
}

/// The element on the meridian mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Element {
    /// CAX6: the 6-node axisymmetric triangle, on gmsh's quadratic triangles as they are (the
    /// shared mesh of every axisymmetric solver, so that p(r) is compared node by node).
    Cax6,
}

impl Element {
    /// Every element, in the order error messages list them.
    pub const ALL: [Element; 1] = [Element::Cax6];

    /// The name in case files and metadata.
    pub fn name(self) -> &'static str {
        match self {
            Element::Cax6 => "cax6",
        }
    }

    /// CalculiX's element type.
    pub fn keyword(self) -> &'static str {
        match self {
            Element::Cax6 => "CAX6",
        }
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
    /// The element.
    pub element: Element,
}

impl Default for Settings {
    /// Face-to-face (CalculiX's advice for quadratic elements: node-to-face puts springs at the
    /// corner and midside nodes whose pressures alternate), penalty 1e3, CAX6.
    fn default() -> Self {
        Self {
            formulation: Formulation::FaceToFace,
            penalty: 1e3,
            element: Element::Cax6,
        }
    }
}

/// A setting that is not one of its allowed values: the message lists them.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SettingError {
    /// An unknown formulation.
    #[error("unknown contact formulation `{0}` (allowed: {allowed})", allowed = names(&Formulation::ALL.map(Formulation::name)))]
    Formulation(String),
    /// An unknown element.
    #[error("unknown element `{0}` (allowed: {allowed})", allowed = names(&Element::ALL.map(Element::name)))]
    Element(String),
    /// A penalty factor out of range.
    #[error("penalty factor {0} is out of range (allowed: {low} ≤ penalty ≤ {high}: K = penalty · E / h)", low = PENALTY_RANGE[0], high = PENALTY_RANGE[1])]
    Penalty(f64),
}

fn names(all: &[&str]) -> String {
    all.join(", ")
}

impl Settings {
    /// The formulation called `name`.
    pub fn formulation(name: &str) -> Result<Formulation, SettingError> {
        Formulation::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| SettingError::Formulation(name.to_owned()))
    }

    /// The element called `name`.
    pub fn element(name: &str) -> Result<Element, SettingError> {
        Element::ALL
            .into_iter()
            .find(|e| e.name() == name)
            .ok_or_else(|| SettingError::Element(name.to_owned()))
    }

    /// The penalty factor `value`, within [`PENALTY_RANGE`].
    pub fn penalty(value: f64) -> Result<f64, SettingError> {
        if (PENALTY_RANGE[0]..=PENALTY_RANGE[1]).contains(&value) {
            Ok(value)
        } else {
            Err(SettingError::Penalty(value))
        }
    }

    /// The facts every history records: formulation, penalty factor and element.
    pub fn describe(&self) -> serde_json::Value {
        serde_json::json!({
            "contact": self.formulation.name(),
            "contact_keyword": self.formulation.keyword(),
            "penalty_factor": self.penalty,
            "element": self.element.name(),
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
        let e = Settings::formulation("mortar").unwrap_err().to_string();
        assert!(e.contains("face-to-face, node-to-face"), "{e}");
        let e = Settings::element("cax8").unwrap_err().to_string();
        assert!(e.contains("allowed: cax6"), "{e}");
        assert_eq!(Settings::penalty(1e3), Ok(1e3));
        for bad in [0.5, 2e6, f64::NAN, f64::INFINITY] {
            let e = Settings::penalty(bad).unwrap_err().to_string();
            assert!(e.contains("1 ≤ penalty ≤ 1000000"), "{e}");
        }
    }
}
