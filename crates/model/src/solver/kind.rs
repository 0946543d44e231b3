//! What kind of model a solver is: the place every table, figure and scoreboard gives it.
//!
//! A built-in solver knows its kind; a solver a case defines itself (a program, stored results)
//! is given one by the case (`kind = "dem-law"`), so that the user's own law stands in the DEM
//! scoreboard beside the built-in laws and the real codes, and the user's own FE code in the
//! continuum panels beside fem-3d.

use std::fmt;

/// The kind of model a solver is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// A closed form or an exact theory (Hertz, Cattaneo–Mindlin, MDR and its finite-body form).
    Analytic,
    /// An incremental contact force law of the kind DEM codes use, evaluated in-process.
    DemLaw,
    /// A DEM program (LAMMPS, YADE, …) run as its users run it.
    DemCode,
    /// Finite elements.
    FiniteElement,
    /// Boundary elements.
    BoundaryElement,
}

impl Kind {
    /// Every kind, in the order tables list them.
    pub const ALL: [Kind; 5] = [
        Kind::Analytic,
        Kind::DemLaw,
        Kind::DemCode,
        Kind::FiniteElement,
        Kind::BoundaryElement,
    ];

    /// The name a case file gives it.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Analytic => "analytic",
            Kind::DemLaw => "dem-law",
            Kind::DemCode => "dem-code",
            Kind::FiniteElement => "fe",
            Kind::BoundaryElement => "be",
        }
    }

    /// The kind a case file names, if any.
    pub fn from_name(name: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The allowed names, for messages: `analytic, dem-law, dem-code, fe, be`.
    pub fn allowed() -> String {
        Kind::ALL.map(Kind::name).join(", ")
    }

    /// True for the kinds the DEM scoreboards rank against exact Mindlin–Deresiewicz.
    pub fn is_dem(self) -> bool {
        matches!(self, Kind::DemLaw | Kind::DemCode)
    }

    /// True for a discretised continuum (finite or boundary elements): judged against the
    /// reference for the domain it models, drawn in the continuum panels.
    pub fn is_continuum(self) -> bool {
        matches!(self, Kind::FiniteElement | Kind::BoundaryElement)
    }
}

impl fmt::Display for Kind {
    /// In words, for tables: "DEM law", "finite elements", ….
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Kind::Analytic => "analytic",
            Kind::DemLaw => "DEM law",
            Kind::DemCode => "DEM code",
            Kind::FiniteElement => "finite elements",
            Kind::BoundaryElement => "boundary elements",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requirement: every kind's case-file name reads back as that kind, and nothing else does.
    #[test]
    fn names_read_back() {
        for kind in Kind::ALL {
            assert_eq!(Kind::from_name(kind.name()), Some(kind));
        }
        assert_eq!(Kind::from_name("DEM law"), None);
        assert_eq!(Kind::allowed(), "analytic, dem-law, dem-code, fe, be");
    }
}
