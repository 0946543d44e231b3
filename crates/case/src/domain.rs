//! Validation of the `[domain]` table (see [`spherecontact_model::domain`]).

use super::raw::RawDomain;
use crate::{CaseError, Validator};
use spherecontact_model::domain::{Domain, DomainKind, Grip, Mesher, MIN_CAP_HEIGHT};
use spherecontact_model::scene::Scene;

impl Validator<'_> {
    /// The `[domain]` table: kind, cap height within [10 c_max, smallest finite radius], grip
    /// (axial only where the tangential problem is void), mesher.
    pub(super) fn domain(&self, raw: &RawDomain, scene: &Scene) -> Result<Domain, CaseError> {
        let c_max = scene.max_contact_radius();
        let kind = match (raw.kind.as_ref().map(|k| k.get_ref().as_str()), &raw.height) {
            (None | Some("hemisphere"), None) => DomainKind::Hemisphere,
            (None | Some("hemisphere"), Some(height)) => {
                return Err(self.error(
                    height,
                    "domain.height",
                    "applies to kind = \"cap\" only (a hemisphere is cut at its radius)",
                ))
            }
            (Some("cap"), Some(height)) => {
                let radius = scene.pair.body1.radius.min(scene.pair.body2.radius);
                let lowest = MIN_CAP_HEIGHT * c_max;
                let allowed = format!(
                    "{MIN_CAP_HEIGHT} c_max = {lowest:.4e} m ≤ height ≤ {radius:.4e} m, the smallest sphere radius: \
                     the cut face must be far from the contact (c_max = {c_max:.4e} m, the path's largest Hertz \
                     contact radius) and a cap no larger than the hemisphere"
                );
                let h = self.number(
                    height,
                    "domain.height",
                    |h| h.is_finite() && h > 0.0 && h >= lowest && h <= radius,
                    &allowed,
                )?;
                DomainKind::Cap { height: h }
            }
            (Some("cap"), None) => {
                let at = raw.kind.as_ref().expect("kind is cap");
                return Err(self.error(at, "domain.height", "missing (required for kind = \"cap\", in m)"));
            }
            (Some(other), _) => {
                let at = raw.kind.as_ref().expect("kind given");
                return Err(self.error(
                    at,
                    "domain.kind",
                    format!("unknown domain kind `{other}` (allowed: hemisphere, cap)"),
                ));
            }
        };
        let grip = match raw.grip.as_ref().map(|g| (g, g.get_ref().as_str())) {
            None | Some((_, "rigid")) => Grip::Rigid,
            Some((at, "axial")) if !scene.is_frictionless() => {
                return Err(self.error(
                    at,
                    "domain.grip",
                    "`axial` leaves the far face free to slide, so a tangential shift cannot be imposed \
                     (allowed: rigid; axial only with friction = 0 or a path without delta_t)",
                ))
            }
            Some((_, "axial")) => Grip::Axial,
            Some((at, other)) => {
                return Err(self.error(
                    at,
                    "domain.grip",
                    format!("unknown grip `{other}` (allowed: rigid, axial)"),
                ))
            }
        };
        let mesher = match raw.mesher.as_ref().map(|m| (m, m.get_ref().as_str())) {
            None | Some((_, "in-crate")) => Mesher::InCrate,
            Some((_, "gmsh")) => Mesher::Gmsh,
            Some((at, other)) => {
                return Err(self.error(
                    at,
                    "domain.mesher",
                    format!("unknown mesher `{other}` (allowed: in-crate, gmsh)"),
                ))
            }
        };
        Ok(Domain { kind, grip, mesher })
    }
}

#[cfg(test)]
mod tests {
    use crate::Case;
    use spherecontact_model::domain::{DomainKind, Grip, Mesher};
    use std::path::Path;

    /// The paper's spheres to δn = 17 µm (c_max = 0.922 mm), optionally sheared, with `domain`.
    fn case(domain: &str, shear: bool) -> Result<Case, crate::CaseError> {
        let delta_t = if shear { "[0, 1]" } else { "[0, 0]" };
        let text = format!(
            "friction = 0.2\nsolvers = [\"hertz\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
             [path]\nunit = \"um\"\ndelta_n = [0, 17]\ndelta_t = {delta_t}\nsubsteps = 2\n{domain}"
        );
        Case::parse(Path::new("d.toml"), &text)
    }

    fn message(domain: &str, shear: bool) -> String {
        let e = case(domain, shear).unwrap_err();
        assert!(e.field.starts_with("domain"), "{e}");
        e.to_string()
    }

    #[test]
    fn the_default_is_the_hemisphere_gripped_rigidly() {
        let d = case("", true).unwrap().scene.domain;
        assert_eq!((d.kind, d.grip), (DomainKind::Hemisphere, Grip::Rigid));
        assert_eq!(d.mesher, Mesher::InCrate);
        let d = case("[domain]\nmesher = \"gmsh\"", true).unwrap().scene.domain;
        assert_eq!(d.mesher, Mesher::Gmsh);
        let d = case("[domain]\nkind = \"cap\"\nheight = 0.02\ngrip = \"axial\"", false)
            .unwrap()
            .scene
            .domain;
        assert_eq!((d.kind, d.grip), (DomainKind::Cap { height: 0.02 }, Grip::Axial));
    }

    #[test]
    fn bad_domains_name_the_field_and_the_allowed_range() {
        let m = message("[domain]\nkind = \"cap\"\nheight = 0.005", false);
        assert!(
            m.contains("domain.height") && m.contains("10 c_max = 9.2195e-3 m"),
            "{m}"
        );
        let m = message("[domain]\nkind = \"cap\"\nheight = 0.2", false);
        assert!(m.contains("≤ 1.0000e-1 m"), "{m}");
        assert!(message("[domain]\nkind = \"cap\"", false).contains("missing"));
        assert!(message("[domain]\nheight = 0.02", false).contains("cap\" only"));
        assert!(message("[domain]\nkind = \"cube\"", false).contains("hemisphere, cap"));
        assert!(message("[domain]\ngrip = \"glue\"", false).contains("rigid, axial"));
        let m = message("[domain]\nmesher = \"netgen\"", false);
        assert!(m.contains("domain.mesher") && m.contains("in-crate, gmsh"), "{m}");
        let m = message("[domain]\ngrip = \"axial\"", true);
        assert!(m.contains("domain.grip") && m.contains("friction = 0"), "{m}");
        let e = case("[domain]\nshape = 1", false).unwrap_err();
        assert!(e.to_string().contains("shape"), "{e}");
    }
}
