//! fem-axisym's meshes: generated in-crate (the default), read from a gmsh MSH 4.1 file, or
//! meshed by gmsh from the external decks' `.geo` when the case's `[domain]` asks for
//! `mesher = "gmsh"` ([`spherecontact_model::domain::Mesher`]).
//!
//! The gmsh route writes the very `.geo` text the decks mesh (`crate::fem::mesh::geo`, the same
//! pole size c_max/40 by default, the same grading, the same physical tags) and runs the same
//! gmsh on it with the same options, so fem-axisym, freefem-axisym and fenicsx-axisym compute on
//! one mesh: gmsh 4.8.4 is deterministic for a given `.geo` (Frontal-Delaunay, one thread), so
//! two runs give the same nodes and triangles (`tests/fem_msh.rs` compares the files). FEniCSx
//! reads that quadratic mesh itself; FreeFEM reads its first-order twin (the same vertices,
//! straight edges, the gap taken from the exact sphere).
//!
//! A case that asks for gmsh gets gmsh or nothing: without it the solver is unavailable (N/A),
//! never quietly run on its own mesh, since that would change what the case's checks compare.

use std::path::Path;

use super::model::{Model, Reduction, Settings};
use crate::fem::element::tri6::Lame;
use crate::fem::mesh::geo;
use crate::fem::mesh::meridian::Mesh;
use crate::fem::mesh::msh;
use spherecontact_model::domain::{Grip, Mesher};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::SolveError;
use spherecontact_system::toolchain::{Tool, Toolchain};

/// Where a model's mesh came from, for the history's metadata.
#[derive(Clone, Debug, PartialEq)]
pub struct Origin {
    /// In words.
    pub description: String,
    /// Wall time of the gmsh runs [s], when gmsh meshed it.
    pub gmsh_s: Option<f64>,
}

/// The model of `scene`: on `mesh_file` when given, else on the mesh the case's `[domain]`
/// asks for (in-crate, or gmsh through `toolchain`).
pub fn model(
    scene: &Scene,
    settings: &Settings,
    mesh_file: Option<&Path>,
    toolchain: &Toolchain,
) -> Result<(Model, Origin), SolveError> {
    let origin = |description: String| Origin {
        description,
        gmsh_s: None,
    };
    match (mesh_file, scene.domain.mesher) {
        (Some(file), _) => Ok((
            read_model(scene, file, settings).map_err(SolveError::Failed)?,
            origin(format!("read from {}", file.display())),
        )),
        (None, Mesher::InCrate) => Ok((
            Model::generate(scene, settings).map_err(SolveError::Failed)?,
            origin("generated in-crate (graded from the pole, fem::mesh::meridian)".to_owned()),
        )),
        (None, Mesher::Gmsh) => gmsh_model(scene, settings, toolchain),
    }
}

/// Meshes the decks' `.geo` of `scene` with gmsh at the pole size of `settings` in a temporary
/// directory, and builds the model on it.
fn gmsh_model(
    scene: &Scene,
    settings: &Settings,
    toolchain: &Toolchain,
) -> Result<(Model, Origin), SolveError> {
    let version = toolchain.require(Tool::Gmsh).map_err(|e| {
        SolveError::Unavailable(format!(
            "the case's [domain] asks for mesher = \"gmsh\" (one mesh for every axisymmetric FEM solver): {e}"
        ))
    })?;
    let dir = tempfile::Builder::new()
        .prefix("spherecontact-fem-axisym-")
        .tempdir()
        .map_err(|e| SolveError::Failed(format!("no temporary directory: {e}")))?;
    let mesh = geo::mesh_quadratic(scene, settings.pole_size, dir.path(), toolchain)?;
    let model = read_model(scene, &mesh.msh41, settings).map_err(SolveError::Failed)?;
    let origin = Origin {
        description: format!(
            "gmsh {version} from the external decks' .geo (mesher = \"gmsh\"; {} triangles)",
            model.bodies[0].mesh.triangles.len()
        ),
        gmsh_s: Some(mesh.wall_s),
    };
    Ok((model, origin))
}

/// The symmetric model on the sphere mesh in `file`.
fn read_model(scene: &Scene, file: &Path, settings: &Settings) -> Result<Model, String> {
    if Reduction::of(scene) != Reduction::Symmetric {
        return Err("a mesh file is supported for identical spheres (one body) only".into());
    }
    let mesh = msh::read(file).map_err(|e| e.to_string())?;
    matches_domain(&mesh, scene, file)?;
    let lame = Lame::of(&scene.pair.body1.material);
    Model::from_meshes(Reduction::Symmetric, vec![mesh], vec![lame], settings)
}

/// Refuses a mesh file made for another grip or another cut than the scene's domain.
fn matches_domain(mesh: &Mesh, scene: &Scene, file: &Path) -> Result<(), String> {
    let grip = scene.domain.grip;
    if mesh.grip != Some(grip) {
        let declared = mesh.grip.map_or("none", Grip::name);
        return Err(format!(
            "{}: the mesh is made for the {declared} grip (far-face tag) but the case asks for the {} grip",
            file.display(),
            grip.name()
        ));
    }
    let height = scene.domain.height(scene.pair.body1.radius);
    let far_height = mesh.far.iter().map(|&n| mesh.nodes[n][1]).fold(0.0, f64::max);
    // The cut face is flat at z = H: its nodes lie there to the file's rounding.
    if (far_height - height).abs() > 1e-6 * height {
        return Err(format!(
            "{}: the far face lies {far_height:e} m from the pole but the case's domain is cut at {height:e} m",
            file.display()
        ));
    }
    Ok(())
}
