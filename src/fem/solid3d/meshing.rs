//! The mesh of the 3D body from the scene: the geometry's sizes from the path's largest contact
//! radius, gmsh run in a temporary directory, the file read back.

use std::time::Instant;

use crate::external::solid_geo::{self, SolidGeometry};
use crate::external::toolchain::Toolchain;
use crate::fem::mesh::solid::{self, SolidMesh};
use crate::solver::SolveError;

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

/// Meshes `geometry` with gmsh in a temporary directory and reads the mesh; also returns the
/// wall time of gmsh and of the reading [s].
pub fn generate(geometry: &SolidGeometry, toolchain: &Toolchain) -> Result<(SolidMesh, f64), SolveError> {
    let t = Instant::now();
    let dir = tempfile::Builder::new()
        .prefix("spherecontact-fem-3d-")
        .tempdir()
        .map_err(|e| SolveError::Failed(format!("temporary directory: {e}")))?;
    let files = solid_geo::mesh(geometry, dir.path(), "body", toolchain)?;
    let mesh = solid::read(&files.msh).map_err(|e| SolveError::Failed(e.to_string()))?;
    Ok((mesh, t.elapsed().as_secs_f64()))
}
