//! The mesh of the 3D body from the scene: the geometry's sizes from the path's largest contact
//! radius, gmsh run in a temporary directory, the file read back.

use std::time::Instant;

use crate::fem::mesh::solid::{self, SolidMesh};
use crate::fem::mesh::solid_geo::{self, SolidGeometry};
use spherecontact_model::solver::SolveError;
use spherecontact_system::toolchain::Toolchain;

pub use crate::fem::mesh::solid_geo::{geometry, Zones, FINE_DEPTH, GROWTH, MAX_SIZE};

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
