//! The modelled finite body (`[domain]` in a case file): which part of each sphere a finite
//! element model meshes, and how its far face is held.
//!
//! Hertz, Mindlin–Deresiewicz, MDR and the BEM model half-spaces; a finite element model is a
//! finite body, whose far-field compliance differs from the half-space's (stiffer or softer
//! depending on the domain and the grip). One case means one domain and one grip in every FEM
//! solver and deck; `mdr-domain` is the reference corrected for it.
//!
//! ```toml
//! [domain]
//! kind = "cap"        # "hemisphere" (default) or "cap"
//! height = 0.02       # cap only: the body cut this far from the pole [m]
//! grip = "rigid"      # "rigid" (default) or "axial"
//! mesher = "gmsh"     # "in-crate" (default) or "gmsh"
//! ```
//!
//! - `hemisphere`: each sphere's half on the contact side, held on its flat equatorial face;
//! - `cap`: the part of each sphere within `height` of its pole, held on the flat cut face
//!   (the paper's "part of a sphere"); a cap of height R is the hemisphere;
//! - `rigid`: every displacement component of the far face follows the imposed approach and
//!   shift (the paper's and most FE codes' loading); the default, because it is the only grip
//!   that also poses the tangential (shift) problem;
//! - `axial`: the far face follows the approach along the axis and is free radially (the
//!   loading of the original external decks); frictionless scenes only, since a face free to
//!   slide cannot be shifted.
//!
//! - `mesher`: who meshes the meridian of the axisymmetric FEM solvers. The external decks always
//!   mesh with gmsh from the `.geo` that `spherecontact mesh` writes (`crates/solvers/src/fem/mesh/geo.rs`);
//!   `fem-axisym` by default generates its own graded mesh in-crate (no external tool, fast,
//!   the same numbers on every machine). With `mesher = "gmsh"` it meshes the same `.geo` at its
//!   pole size with the same gmsh, so that every axisymmetric FEM solver of the case — fem-axisym,
//!   freefem-axisym, fenicsx-axisym — runs on one mesh, and their differences measure the solvers
//!   alone. It then needs gmsh: without it, fem-axisym is unavailable (N/A with the reason), never
//!   quietly run on its own mesh, which would change the numbers the case's checks compare.
//!
//! A flat body (R = ∞) is always the region within `fem::axisym::model::FLAT_DOMAIN` (spherecontact-solvers)
//! contact radii of its pole, held on that arc with the case's grip.

use serde::Serialize;

/// Smallest cap height, in units of the path's largest Hertz contact radius.
///
/// Reason: the domain correction treats the finite body as a far-field spring in series with
/// the local contact; the contact then has to be small against the body. At height 10 c_max
/// the far face is ten contact radii away and the candidate contact zone (1.25 c_max) stays
/// well inside the spherical surface (cut radius √(2RH) ≥ 4.5 c_max for R ≥ H).
pub const MIN_CAP_HEIGHT: f64 = 10.0;

/// Which part of each sphere is modelled.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum DomainKind {
    /// The half of the sphere on the contact side, held on its equatorial face.
    Hemisphere,
    /// The part within `height` [m] of the pole, held on the flat cut face.
    Cap {
        /// Distance from the pole to the cut face [m].
        height: f64,
    },
}

/// How the far face is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Grip {
    /// Every displacement component of the far face follows the imposed approach and shift.
    Rigid,
    /// Along the axis only (free radially); frictionless scenes only.
    Axial,
}

impl Grip {
    /// The name used in case files.
    pub fn name(self) -> &'static str {
        match self {
            Grip::Rigid => "rigid",
            Grip::Axial => "axial",
        }
    }
}

/// Who meshes the meridian of the axisymmetric FEM solvers (the decks always use gmsh).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mesher {
    /// fem-axisym generates its own graded mesh (`fem::mesh::meridian`).
    #[default]
    InCrate,
    /// fem-axisym meshes the decks' `.geo` with gmsh: one mesh for every axisymmetric FEM solver.
    Gmsh,
}

impl Mesher {
    /// The name used in case files.
    pub fn name(self) -> &'static str {
        match self {
            Mesher::InCrate => "in-crate",
            Mesher::Gmsh => "gmsh",
        }
    }
}

/// The modelled finite body of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Domain {
    /// The part of each sphere.
    pub kind: DomainKind,
    /// How its far face is held.
    pub grip: Grip,
    /// Who meshes it for the axisymmetric FEM solvers.
    pub mesher: Mesher,
}

impl Default for Domain {
    /// The hemisphere, gripped rigidly, meshed in-crate by fem-axisym.
    fn default() -> Self {
        Self {
            kind: DomainKind::Hemisphere,
            grip: Grip::Rigid,
            mesher: Mesher::InCrate,
        }
    }
}

impl Domain {
    /// The distance from the pole to the far face of a sphere of radius `radius` [m]: the cap's
    /// height, or R for the hemisphere.
    pub fn height(&self, radius: f64) -> f64 {
        match self.kind {
            DomainKind::Hemisphere => radius,
            DomainKind::Cap { height } => height,
        }
    }

    /// In words, for metadata and reports.
    pub fn describe(&self) -> String {
        let kind = match self.kind {
            DomainKind::Hemisphere => "hemisphere (held on its equatorial face)".to_owned(),
            DomainKind::Cap { height } => {
                format!(
                    "cap cut {:.4} mm from the pole (held on the cut face)",
                    height * 1e3
                )
            }
        };
        let grip = match self.grip {
            Grip::Rigid => "gripped rigidly (every component of the far face follows the approach and shift)",
            Grip::Axial => "axial grip (the far face follows the approach, free radially)",
        };
        format!("{kind}, {grip}")
    }
}

/// Whether the solver named `solver` models a finite body (every FEM solver and deck: `fem-*`,
/// `freefem-*`, `fenicsx-*`), whose reference is Mindlin–Deresiewicz corrected for the case's
/// domain rather than the half-space's.
pub fn models_a_finite_body(solver: &str) -> bool {
    ["fem-", "freefem-", "fenicsx-"]
        .iter()
        .any(|prefix| solver.starts_with(prefix))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hemisphere_is_the_cap_of_height_r() {
        let d = Domain::default();
        assert_eq!(d.height(0.1), 0.1);
        let cap = Domain {
            kind: DomainKind::Cap { height: 0.02 },
            ..d
        };
        assert_eq!(cap.height(0.1), 0.02);
        assert!(cap.describe().contains("20.0000 mm") && cap.describe().contains("rigidly"));
    }
}
