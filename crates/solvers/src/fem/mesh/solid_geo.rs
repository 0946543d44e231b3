//! The gmsh geometry of a 3D body and its quadratic tetrahedral mesh: half of a hemisphere (or
//! of a cap), graded from the contact pole by the path's largest contact radius.
//!
//! Model: body 1, radius R, centre (0, 0, R), touching the plane z = 0 at the pole (the origin);
//! the part 0 ≤ z ≤ H (H = R: the hemisphere; H < R: a cap cut at that distance from the pole)
//! and y ≥ 0 (the plane y = 0 contains the shift along x and is a plane of symmetry). Physical
//! groups, as `crates/solvers/src/fem/mesh/solid.rs` reads them: surface 1 the spherical surface (contact
//! candidate), surface 2 the flat far face z = H (gripped), surface 3 the symmetry plane y = 0,
//! volume 10 the body.
//!
//! Grading: element size h (the resolution) within distance `tfine` of the disc of radius
//! `rfine` around the pole on the contact plane, growing linearly with that distance at rate
//! `growth` up to `hmax` (a MathEval distance field and a Threshold field). The disc covers the
//! candidate contact zone, so the contact surface is uniformly fine there, while the size grows
//! with depth below it: the stresses of a contact of radius c vary over depths of order c, and
//! a fine ball instead of a fine layer would hold most of the mesh's nodes.
//!
//! Files (metres): `<stem>.geo`, and `<stem>.msh` in MSH 4.1 with 10-node tetrahedra and 6-node
//! triangles whose midside nodes lie on the sphere (`-order 2`), for the in-crate `fem-3d` and a
//! FEniCSx 3D deck on the same mesh.

use std::path::{Path, PathBuf};
use std::time::Duration;

use spherecontact_model::solver::SolveError;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// What to mesh and how finely.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidGeometry {
    /// Sphere radius R [m].
    pub radius: f64,
    /// Height H of the far face above the pole [m]: R for the hemisphere, less for a cap.
    pub height: f64,
    /// Element size h at the pole [m].
    pub pole_size: f64,
    /// Radius of the disc around the pole (on the contact plane) where the surface is fine [m].
    pub fine_radius: f64,
    /// Distance from that disc within which the size is h [m].
    pub fine_depth: f64,
    /// Growth of the element size per unit distance beyond it.
    pub growth: f64,
    /// The largest element size [m].
    pub max_size: f64,
}

impl std::fmt::Display for SolidGeometry {
    /// The parameters by name (lengths in m), as messages show them.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let named: Vec<String> = self.named().iter().map(|(n, v)| format!("{n} {v:e}")).collect();
        write!(f, "{} (lengths in m)", named.join(", "))
    }
}

impl SolidGeometry {
    /// Every parameter with its name.
    fn named(&self) -> [(&'static str, f64); 7] {
        [
            ("R", self.radius),
            ("H", self.height),
            ("pole size", self.pole_size),
            ("fine radius", self.fine_radius),
            ("fine depth", self.fine_depth),
            ("growth", self.growth),
            ("largest size", self.max_size),
        ]
    }

    /// Checks the parameters: a sphere, a far face between the fine zone and the equator, a
    /// pole size below the fine distance.
    pub fn check(&self) -> Result<(), String> {
        let finite = self.named().iter().all(|(_, v)| v.is_finite() && *v > 0.0);
        if !finite {
            return Err(format!(
                "every mesh parameter must be positive and finite: {self}"
            ));
        }
        let fine = self.fine_radius + self.fine_depth;
        if self.height > self.radius * (1.0 + 1e-12) || self.height < 2.0 * fine {
            return Err(format!(
                "the far face at {:e} m must lie between twice the fine zone ({:e} m) and the equator ({:e} m)",
                self.height,
                2.0 * fine,
                self.radius
            ));
        }
        if self.pole_size > 0.5 * self.fine_radius || self.max_size < self.pole_size {
            return Err(format!(
                "need pole size ≤ half the fine radius and ≤ the largest size: {self}"
            ));
        }
        Ok(())
    }

    /// The distance from the fine disc at which the size reaches `max_size`.
    fn coarse_distance(&self) -> f64 {
        self.fine_depth + (self.max_size - self.pole_size) / self.growth
    }

    /// The gmsh `.geo` text (metres).
    pub fn geo(&self) -> Result<String, String> {
        self.check()?;
        Ok(format!(
            "// spherecontact: half body y >= 0 of a sphere cut at z = H (metres), for fem-3d.
// Sphere radius R, centre (0,0,R), pole (0,0,0) on the contact plane z = 0.
// Mesh: gmsh THIS.geo -3 -order 2 -format msh41
SetFactory(\"OpenCASCADE\");
R = {r:e};
H = {h_far:e};        // far face z = H (H = R: the hemisphere)
h = {h:e};        // element size at the pole (the resolution)
rfine = {rfine:e};    // radius of the fine disc around the pole on the contact plane
tfine = {tfine:e};    // size h up to this distance from the disc
dcoarse = {dcoarse:e};  // size grows linearly to hmax at this distance (growth {growth})
hmax = {hmax:e};

Sphere(1) = {{0, 0, R, R}};
Box(2) = {{-R, 0, 0, 2*R, R, H}};
BooleanIntersection(3) = {{ Volume{{1}}; Delete; }}{{ Volume{{2}}; Delete; }};

e = 1e-3 * R;
far() = Surface In BoundingBox{{-R-e, -e, H-e, R+e, R+e, H+e}};
sym() = Surface In BoundingBox{{-R-e, -e, -e, R+e, e, H+e}};
contact() = Abs(Boundary{{ Volume{{3}}; }});
contact() -= far();
contact() -= sym();
Physical Surface(\"contact\", 1) = contact();
Physical Surface(\"far\", 2) = far();
Physical Surface(\"symmetry\", 3) = sym();
Physical Volume(\"body\", 10) = {{3}};

// Distance from the disc {{z = 0, x² + y² <= rfine²}}.
Field[1] = MathEval;
Field[1].F = Sprintf(\"Sqrt(z*z + Max(0, Sqrt(x*x + y*y) - %g)^2)\", rfine);
{size_field}Mesh.Algorithm3D = 1;          // Delaunay
Mesh.Optimize = 1;
Mesh.ElementOrder = 2;
",
            size_field = super::geo::size_field("tfine"),
            r = self.radius,
            h_far = self.height,
            h = self.pole_size,
            rfine = self.fine_radius,
            tfine = self.fine_depth,
            dcoarse = self.coarse_distance(),
            growth = self.growth,
            hmax = self.max_size,
        ))
    }
}

/// The time gmsh may take for one 3D mesh (the default mesh takes a few seconds; a mesh ten
/// times finer about a minute).
const GMSH_TIMEOUT: Duration = Duration::from_secs(600);

/// The files of one mesh.
#[derive(Clone, Debug)]
pub struct SolidMeshFiles {
    /// The geometry (metres).
    pub geo: PathBuf,
    /// MSH 4.1, quadratic, metres.
    pub msh: PathBuf,
    /// Wall time of gmsh [s].
    pub wall_s: f64,
}

/// Writes `<dir>/<stem>.geo` and runs gmsh for `<dir>/<stem>.msh`.
pub fn mesh(
    geometry: &SolidGeometry,
    dir: &Path,
    stem: &str,
    toolchain: &Toolchain,
) -> Result<SolidMeshFiles, SolveError> {
    let text = geometry.geo().map_err(SolveError::NotApplicable)?;
    mesh_geo(&text, dir, stem, toolchain)
}

/// Writes the geometry `text` (one of [`SolidGeometry::geo`]'s, perhaps with options appended)
/// to `<dir>/<stem>.geo` and runs gmsh for `<dir>/<stem>.msh` (MSH 4.1, quadratic).
pub fn mesh_geo(
    text: &str,
    dir: &Path,
    stem: &str,
    toolchain: &Toolchain,
) -> Result<SolidMeshFiles, SolveError> {
    toolchain.require(Tool::Gmsh).map_err(SolveError::Unavailable)?;
    let geo = dir.join(format!("{stem}.geo"));
    std::fs::write(&geo, text).map_err(|e| SolveError::Failed(format!("writing {}: {e}", geo.display())))?;
    let msh = dir.join(format!("{stem}.msh"));
    let args = [
        &geo.display().to_string(),
        "-3",
        "-order",
        "2",
        "-format",
        "msh41",
        "-o",
        &msh.display().to_string(),
    ]
    .map(str::to_owned)
    .to_vec();
    let wall_s = super::geo::run_gmsh(toolchain, dir, args, &msh, GMSH_TIMEOUT, "gmsh (3D mesh)")?;
    Ok(SolidMeshFiles { geo, msh, wall_s })
}

// The mesh zones and geometry of a scene's solid (fem-3d and fenicsx-3d mesh alike).

/// Growth of the element size per unit distance beyond the fine zone. Measured on the paper's
/// spheres (`examples/fem3d_timing.rs`): 0.3 keeps the tetrahedra's quality above gmsh's 0.2
/// threshold and the DOFs a third of those at 0.15.
pub const GROWTH: f64 = 0.3;
/// The largest element size, in units of the sphere radius.
pub const MAX_SIZE: f64 = 0.15;
/// Depth of the uniformly fine layer below the contact zone, in units of the largest contact
/// radius.
pub const FINE_DEPTH: f64 = 0.25;

/// The candidate contact zone and the fine zone of a mesh for contact radii up to `c_max` at
/// pole size `h`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Zones {
    /// Surface radius within which faces are contact candidates [m]: 10 % beyond c_max (the
    /// finite body's contact is a little larger than Hertz's) plus one element (faces are
    /// candidates only wholly inside).
    pub candidate_radius: f64,
    /// Radius of the disc around the pole where the surface has the pole size [m]: the
    /// candidate zone plus one element.
    pub fine_radius: f64,
    /// Depth of the layer below that disc with the pole size [m].
    pub fine_depth: f64,
}

impl Zones {
    /// The zones for contact radii up to `c_max` at pole size `h`.
    pub fn new(c_max: f64, h: f64) -> Self {
        let candidate_radius = 1.1 * c_max + h;
        Self {
            candidate_radius,
            fine_radius: candidate_radius + h,
            fine_depth: (FINE_DEPTH * c_max).max(h),
        }
    }
}

/// The geometry of a sphere of radius `radius` cut at `height`, with pole size `h` over `zones`.
pub fn geometry(radius: f64, height: f64, h: f64, zones: Zones) -> SolidGeometry {
    SolidGeometry {
        radius,
        height,
        pole_size: h,
        fine_radius: zones.fine_radius,
        fine_depth: zones.fine_depth,
        growth: GROWTH,
        max_size: MAX_SIZE * radius,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn geometry() -> SolidGeometry {
        SolidGeometry {
            radius: 0.1,
            height: 0.1,
            pole_size: 1e-4,
            fine_radius: 1.2e-3,
            fine_depth: 2e-4,
            growth: 0.4,
            max_size: 0.02,
        }
    }

    #[test]
    fn the_geo_names_the_groups_the_reader_needs() {
        let g = geometry();
        let geo = g.geo().unwrap();
        for group in [
            "Physical Surface(\"contact\", 1)",
            "Physical Surface(\"far\", 2)",
            "Physical Surface(\"symmetry\", 3)",
            "Physical Volume(\"body\", 10)",
        ] {
            assert!(geo.contains(group), "{group}");
        }
        assert!(geo.contains(&format!("dcoarse = {:e};", 2e-4 + (0.02 - 1e-4) / 0.4)));
    }

    #[test]
    fn parameters_out_of_range_are_refused() {
        let cases = [
            SolidGeometry {
                height: 0.2,
                ..geometry()
            },
            SolidGeometry {
                height: 1e-3,
                ..geometry()
            },
            SolidGeometry {
                pole_size: 1e-3,
                ..geometry()
            },
            SolidGeometry {
                growth: f64::NAN,
                ..geometry()
            },
            SolidGeometry {
                max_size: 0.0,
                ..geometry()
            },
        ];
        for g in cases {
            assert!(g.geo().is_err(), "{g:?}");
        }
    }
}
