//! The gmsh geometry of a scene and its meshes: the meridian of one sphere for an axisymmetric
//! model, graded from the contact pole by the path's largest contact radius.
//!
//! Model: the scene's domain (`[domain]`) of body 1, radius R, seen in its meridian plane
//! (x = r ≥ 0, y = z), touching the plane y = 0 at the pole (0, 0): the cap within H of the
//! pole (H = R: the hemisphere), held on its flat cut face y = H. Physical tags: 1 the spherical
//! surface (contact candidate), the cut face 2 under the axial grip (prescribed approach, free
//! radially) or 4 under the rigid grip (every component prescribed), 3 the symmetry axis, 10 the
//! body. The grip is thus carried by the mesh: a deck applies u_z on 2 and 4 and u_r = 0 on 3
//! and 4. The finite body's offset from Hertz's half-space is computed by `mdr-domain`.
//!
//! Grading: element size h at the pole (the resolution) uniform over a disc of radius
//! 1.5 c_max around it (c_max the largest Hertz contact radius of the path), growing linearly to
//! R/20 at distance R/2 (a gmsh Distance + Threshold field).
//!
//! Files (SI in the geometry): `<stem>.geo` in metres; `<stem>.msh` MSH 4.1, quadratic (curved
//! arc), metres, for the in-crate solver and FEniCSx; `<stem>_p1_mm.msh` MSH 2.2, first order,
//! millimetres, for FreeFEM's `gmshload` (which reads only that, and rejects 20 µm elements
//! in metres as degenerate).

use std::path::{Path, PathBuf};
use std::time::Duration;

use spherecontact_model::domain::Grip;
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::SolveError;
use spherecontact_system::process::{self, Ending, Job};
use spherecontact_system::toolchain::{Tool, Toolchain};

/// Default pole element size: this fraction of the largest contact radius (c_max / 40 ≈ 23 µm
/// for the paper's spheres at δn = 17 µm, where docs/toolchain.md records P within 0.4 % of Hertz).
pub const DEFAULT_ELEMENTS_PER_RADIUS: f64 = 40.0;

/// The time gmsh may take for one mesh (a 2D mesh graded to 20 µm takes under 1 s).
const GMSH_TIMEOUT: Duration = Duration::from_secs(120);

/// Physical tag of the spherical (contact candidate) surface.
pub const TAG_CONTACT: u32 = 1;
/// Physical tag of the loaded flat face under the axial grip.
pub const TAG_TOP: u32 = 2;
/// Physical tag of the loaded flat face under the rigid grip.
pub const TAG_TOP_RIGID: u32 = 4;
/// Physical tag of the symmetry axis.
pub const TAG_AXIS: u32 = 3;

/// The physical tag of the gripped far face: the mesh carries the grip (2 axial, 4 rigid), so that
/// a mesh made for one grip is never read as the other. The `.geo` writer and the decks'
/// templates (`@FAR_TAG@`) both take it from here.
pub fn far_face_tag(grip: Grip) -> u32 {
    match grip {
        Grip::Axial => TAG_TOP,
        Grip::Rigid => TAG_TOP_RIGID,
    }
}

/// The default resolution of a scene: pole element size c_max / 40 [m], or R / 4000 when the
/// path never closes the gap.
pub fn default_resolution(scene: &Scene) -> f64 {
    let c_max = scene.max_contact_radius();
    if c_max > 0.0 {
        c_max / DEFAULT_ELEMENTS_PER_RADIUS
    } else {
        scene.pair.body1.radius / 4000.0
    }
}

pub use spherecontact_model::resolution::parse_length;

/// The gmsh `.geo` text (metres) of body 1's meridian, graded to `resolution` [m] at the pole.
///
/// Not applicable to a flat body 1 (no finite sphere to mesh) or a resolution that is not a
/// small positive fraction of the radius.
pub fn geo_for_scene(scene: &Scene, resolution: f64) -> Result<String, SolveError> {
    let radius = scene.pair.body1.radius;
    if !radius.is_finite() {
        return Err(SolveError::NotApplicable(
            "body 1 is a flat: the axisymmetric mesh is of a sphere".into(),
        ));
    }
    if !(resolution > 0.0 && resolution < radius / 20.0) {
        return Err(SolveError::NotApplicable(format!(
            "resolution {resolution:e} m must be positive and below R/20 = {:e} m",
            radius / 20.0
        )));
    }
    let c_max = scene.max_contact_radius();
    let height = scene.domain.height(radius);
    // Far from the contact: R/20, and at most H/10 so that a shallow cap has elements across it.
    let h_max = (radius / 20.0).min(height / 10.0).max(resolution);
    let d_fine = (1.5 * c_max).max(4.0 * resolution);
    let d_coarse = (height / 2.0).max(2.0 * d_fine);
    let rim = (height * (2.0 * radius - height)).sqrt();
    let top_tag = far_face_tag(scene.domain.grip);
    let top_name = match scene.domain.grip {
        Grip::Axial => "top",
        Grip::Rigid => "top_rigid",
    };
    // The hemisphere's cut passes through the centre: the axis point is the centre itself.
    let axis_point = if height < radius {
        "Point(4) = {0, H, 0, hmax};  // the axis on the cut face"
    } else {
        "// the hemisphere's cut face meets the axis at the centre, Point(2)"
    };
    let axis_end = if height < radius { 4 } else { 2 };
    Ok(format!(
        "// spherecontact: meridian of body 1 of scene `{name}` (metres).
// x = r >= 0, y = z; pole (0,0) touches the plane y = 0; held on the cut face y = H.
// Domain: {domain}.
// Largest Hertz contact radius of the path c_max = {c_max:e} m.
// Mesh: gmsh THIS.geo -2 -order 2 -format msh41   (FreeFEM: -order 1 -format msh22
//       -setnumber Mesh.ScalingFactor 1000 for millimetres)
R = {radius:e};
H = {height:e};        // the cut face's distance from the pole (H = R: the hemisphere)
h = {resolution:e};        // element size at the contact pole (the resolution)
hmax = {h_max:e};     // element size far from the contact
dfine = {d_fine:e};    // uniform size h up to this distance from the pole (1.5 c_max)
dcoarse = {d_coarse:e};  // size grows linearly to hmax at this distance

Point(1) = {{0, 0, 0, hmax}};  // pole
Point(2) = {{0, R, 0, hmax}};  // centre, on the axis
Point(3) = {{{rim:e}, H, 0, hmax}};  // rim: the sphere meets the cut face
{axis_point}
Circle(1) = {{1, 2, 3}};       // spherical surface: contact candidate
Line(2) = {{3, {axis_end}}};            // flat gripped face y = H
Line(3) = {{{axis_end}, 1}};            // symmetry axis r = 0
Curve Loop(1) = {{1, 2, 3}};
Plane Surface(1) = {{1}};

Physical Curve(\"contact\", {TAG_CONTACT}) = {{1}};
Physical Curve(\"{top_name}\", {top_tag}) = {{2}};   // {grip} grip
Physical Curve(\"axis\", {TAG_AXIS}) = {{3}};
Physical Surface(\"body\", 10) = {{1}};

Field[1] = Distance;
Field[1].PointsList = {{1}};
{size_field}",
        size_field = size_field("dfine"),
        name = scene.name,
        domain = scene.domain.describe(),
        grip = scene.domain.grip.name(),
    ))
}

/// The end both `.geo` files share (the meridian's and the solid's): size h up to the distance
/// named `fine` from the contact zone (gmsh field 1), growing linearly to hmax at `dcoarse`, the
/// triangulation algorithm, and midside nodes on the curved boundary.
pub(crate) fn size_field(fine: &str) -> String {
    format!(
        "Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = hmax;
Field[2].DistMin = {fine};
Field[2].DistMax = dcoarse;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;            // Frontal-Delaunay (algorithm 8 segfaults in gmsh 4.8.4)
Mesh.SecondOrderLinear = 0;    // quadratic elements follow the curved boundary
"
    )
}

/// The mesh files of one scene and resolution.
#[derive(Clone, Debug)]
pub struct MeshFiles {
    /// The geometry, metres.
    pub geo: PathBuf,
    /// MSH 4.1, quadratic triangles, metres (in-crate solver, FEniCSx).
    pub msh41: PathBuf,
    /// MSH 2.2, linear triangles, millimetres (FreeFEM).
    pub msh22_mm: PathBuf,
    /// Pole element size [m].
    pub resolution: f64,
    /// Number of linear triangles (the same triangulation in both files).
    pub triangles: usize,
    /// Wall time of the two gmsh runs [s].
    pub wall_s: f64,
}

/// The quadratic mesh of one scene and resolution, without FreeFEM's first-order copy.
#[derive(Clone, Debug)]
pub struct QuadraticMesh {
    /// The geometry, metres.
    pub geo: PathBuf,
    /// MSH 4.1, quadratic triangles, metres (in-crate solver, FEniCSx).
    pub msh41: PathBuf,
    /// Wall time of the gmsh run [s].
    pub wall_s: f64,
}

/// The `.geo` file's name in the mesh folder. gmsh runs inside that folder, so it is handed the
/// files' names, never paths relative to the caller's folder.
const GEO_NAME: &str = "mesh.geo";

/// The quadratic MSH 4.1 file's name in the mesh folder.
const MSH41_NAME: &str = "mesh.msh";

/// FreeFEM's first-order MSH 2.2 file's name in the mesh folder.
const MSH22_MM_NAME: &str = "mesh_p1_mm.msh";

/// A mesh file that [`mesh`] or [`mesh_quadratic`] wrote into `dir`, if something is there (what
/// it is, is judged where it is read: a mesh is read as foreign input, `fem::mesh::msh`).
fn found(dir: &Path, name: &str) -> Result<PathBuf, SolveError> {
    let file = dir.join(name);
    match std::fs::symlink_metadata(&file) {
        Ok(_) => Ok(file),
        Err(_) => Err(SolveError::Failed(format!(
            "{}: mesh file missing (the folder is not the one the deck was written into)",
            file.display()
        ))),
    }
}

impl QuadraticMesh {
    /// The files [`mesh_quadratic`] wrote into `dir` earlier, as found there (gmsh's wall time
    /// 0: not meshed now).
    pub fn in_folder(dir: &Path) -> Result<Self, SolveError> {
        Ok(Self {
            geo: found(dir, GEO_NAME)?,
            msh41: found(dir, MSH41_NAME)?,
            wall_s: 0.0,
        })
    }
}

impl MeshFiles {
    /// The files [`mesh`] wrote into `dir` earlier at pole size `resolution`, as found there
    /// (gmsh's wall time 0: not meshed now).
    pub fn in_folder(dir: &Path, resolution: f64) -> Result<Self, SolveError> {
        let quadratic = QuadraticMesh::in_folder(dir)?;
        let msh22_mm = found(dir, MSH22_MM_NAME)?;
        Ok(Self {
            geo: quadratic.geo,
            msh41: quadratic.msh41,
            triangles: triangle_count(&msh22_mm)?,
            msh22_mm,
            resolution,
            wall_s: 0.0,
        })
    }
}

/// Writes `<dir>/mesh.geo` for the scene and runs gmsh for the quadratic MSH 4.1 file only: what
/// fem-axisym reads (the decks take [`mesh`], which adds FreeFEM's copy).
pub fn mesh_quadratic(
    scene: &Scene,
    resolution: f64,
    dir: &Path,
    toolchain: &Toolchain,
) -> Result<QuadraticMesh, SolveError> {
    toolchain.require(Tool::Gmsh).map_err(SolveError::Unavailable)?;
    let geo = dir.join(GEO_NAME);
    std::fs::write(&geo, geo_for_scene(scene, resolution)?)
        .map_err(|e| SolveError::Failed(format!("writing {}: {e}", geo.display())))?;
    let (msh41, wall_s) = mesh_2d(toolchain, dir, &["-order", "2", "-format", "msh41"], MSH41_NAME)?;
    Ok(QuadraticMesh { geo, msh41, wall_s })
}

/// Writes `<dir>/mesh.geo` for the scene and runs gmsh for both mesh files.
pub fn mesh(
    scene: &Scene,
    resolution: f64,
    dir: &Path,
    toolchain: &Toolchain,
) -> Result<MeshFiles, SolveError> {
    let quadratic = mesh_quadratic(scene, resolution, dir, toolchain)?;
    let linear_mm = [
        "-order",
        "1",
        "-format",
        "msh22",
        "-setnumber",
        "Mesh.ScalingFactor",
        "1000",
    ];
    let (msh22_mm, linear_s) = mesh_2d(toolchain, dir, &linear_mm, MSH22_MM_NAME)?;
    let triangles = triangle_count(&msh22_mm)?;
    Ok(MeshFiles {
        geo: quadratic.geo,
        msh41: quadratic.msh41,
        msh22_mm,
        resolution,
        triangles,
        wall_s: quadratic.wall_s + linear_s,
    })
}

/// The stem of gmsh's logs (`gmsh.stdout`, `gmsh.stderr`) in its working folder.
const LOG_STEM: &str = "gmsh";

/// Meshes the scene as [`mesh`] does, gmsh working in a private temporary folder, then writes
/// the geometry, both meshes and gmsh's logs (these also when gmsh fails) into `out`, each
/// atomically and never through a link ([`spherecontact_system::io::write_atomically`]): gmsh itself never
/// writes into `out`. The answer names the files in `out`.
pub fn mesh_into(
    scene: &Scene,
    resolution: f64,
    out: &Path,
    toolchain: &Toolchain,
) -> Result<MeshFiles, SolveError> {
    let work = tempfile::Builder::new()
        .prefix("spherecontact-mesh-")
        .tempdir()
        .map_err(|e| SolveError::Failed(format!("creating gmsh's working folder: {e}")))?;
    let meshed = mesh(scene, resolution, work.path(), toolchain);
    for log in [format!("{LOG_STEM}.stdout"), format!("{LOG_STEM}.stderr")] {
        let log = work.path().join(log);
        if log.is_file() {
            publish(&log, out)?;
        }
    }
    let files = meshed?;
    Ok(MeshFiles {
        geo: publish(&files.geo, out)?,
        msh41: publish(&files.msh41, out)?,
        msh22_mm: publish(&files.msh22_mm, out)?,
        ..files
    })
}

/// Writes a copy of `file` into the folder `out` atomically: the copy's path.
fn publish(file: &Path, out: &Path) -> Result<PathBuf, SolveError> {
    let target = out.join(file.file_name().unwrap_or_default());
    std::fs::read(file)
        .and_then(|bytes| spherecontact_system::io::write_atomically(&target, &bytes))
        .map_err(|e| SolveError::Failed(format!("writing {}: {e}", target.display())))?;
    Ok(target)
}

/// gmsh's 2D mesh of `<dir>/mesh.geo` with `options`, written to `<dir>/<out_name>`: the file's
/// path and gmsh's wall time [s].
fn mesh_2d(
    toolchain: &Toolchain,
    dir: &Path,
    options: &[&str],
    out_name: &str,
) -> Result<(PathBuf, f64), SolveError> {
    let out = dir.join(out_name);
    let mut args = vec![GEO_NAME.to_owned(), "-2".into()];
    args.extend(options.iter().map(|s| s.to_string()));
    args.extend(["-o".into(), out_name.to_owned()]);
    let wall_s = run_gmsh(toolchain, dir, args, &out, GMSH_TIMEOUT, "gmsh")?;
    Ok((out, wall_s))
}

/// Runs gmsh with `args` in `dir` for the file `out`, within `timeout`; its wall time [s], or the
/// failure in words (`what` names the mesh; gmsh returns 1 on any error) with gmsh's last lines.
pub(super) fn run_gmsh(
    toolchain: &Toolchain,
    dir: &Path,
    args: Vec<String>,
    out: &Path,
    timeout: Duration,
    what: &str,
) -> Result<f64, SolveError> {
    let job = Job {
        program: toolchain.gmsh.clone(),
        args,
        env: vec![],
        timeout,
    };
    let run = process::run(&job, dir, LOG_STEM)
        .map_err(|e| SolveError::Failed(format!("gmsh could not start: {e}")))?;
    if run.succeeded() && out.is_file() {
        return Ok(run.wall_s);
    }
    let how = match run.ending {
        Ending::Exited(code) => format!("exited with code {code}"),
        Ending::Signalled(s) => format!("crashed with {}", process::signal_name(s)),
        Ending::TimedOut => format!("timed out after {} s and was killed", timeout.as_secs()),
    };
    Err(SolveError::Failed(format!("{what} {how}: {}", run.tail(8))))
}

/// The number of linear triangles (element type 2) in the MSH 2.2 file `msh22`, read as every
/// mesh is ([`spherecontact_system::input::foreign::read_bytes`] at [`spherecontact_model::limits::MAX_MESH_BYTES`]: a regular file of bounded size); 0 where it
/// holds no `$Elements` section.
fn triangle_count(msh22: &Path) -> Result<usize, SolveError> {
    let bytes =
        spherecontact_system::input::foreign::read_bytes(msh22, spherecontact_model::limits::MAX_MESH_BYTES)
            .map_err(|e| SolveError::Failed(e.to_string()))?;
    let text = String::from_utf8_lossy(&bytes);
    Ok(text
        .split("$Elements")
        .nth(1)
        .and_then(|rest| rest.split("$EndElements").next())
        .map_or(0, |block| {
            block
                .lines()
                .skip(2) // the rest of the "$Elements" line, then the count
                .filter(|l| l.split_whitespace().nth(1) == Some("2"))
                .count()
        }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grading_follows_the_largest_contact_radius() {
        let scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        let c = scene.max_contact_radius(); // sqrt(R* δn) = sqrt(0.05 · 17e-6) ≈ 0.922 mm
        assert!((c - (0.05f64 * 17e-6).sqrt()).abs() < 1e-12);
        let h = default_resolution(&scene);
        assert!((h - c / 40.0).abs() < 1e-15);
        let geo = geo_for_scene(&scene, h).unwrap();
        assert!(geo.contains(&format!("h = {h:e};")));
        assert!(geo.contains(&format!("dfine = {:e};", 1.5 * c)));
        assert!(geo.contains("Physical Curve(\"contact\", 1)"));
    }

    #[test]
    fn the_domain_and_its_grip_are_in_the_geometry() {
        use spherecontact_model::domain::{Domain, DomainKind};
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        let h = default_resolution(&scene);
        let geo = geo_for_scene(&scene, h).unwrap();
        // The default: the hemisphere (cut at R, through the centre), gripped rigidly (tag 4).
        assert!(
            geo.contains("H = 1e-1;") && geo.contains("Line(3) = {2, 1};"),
            "{geo}"
        );
        assert!(geo.contains("Physical Curve(\"top_rigid\", 4) = {2};"), "{geo}");
        scene.domain = Domain {
            kind: DomainKind::Cap { height: 0.02 },
            grip: Grip::Axial,
            ..Domain::default()
        };
        let geo = geo_for_scene(&scene, h).unwrap();
        // The cap's rim at √(H(2R − H)) = 0.06 m on the cut face y = H, its axis point on the face.
        let rim = (0.02f64 * (2.0 * 0.1 - 0.02)).sqrt();
        assert!(
            geo.contains(&format!("Point(3) = {{{rim:e}, H, 0, hmax}};")),
            "{geo}"
        );
        assert!(geo.contains("Point(4) = {0, H, 0, hmax};") && geo.contains("Line(3) = {4, 1};"));
        assert!(geo.contains("Physical Curve(\"top\", 2) = {2};"), "{geo}");
    }

    #[test]
    fn a_flat_or_a_bad_resolution_is_not_applicable() {
        let mut scene = spherecontact_model::fixtures::test_scene(&[0.0, 17.0]);
        assert!(matches!(
            geo_for_scene(&scene, 0.0),
            Err(SolveError::NotApplicable(_))
        ));
        assert!(matches!(
            geo_for_scene(&scene, f64::NAN),
            Err(SolveError::NotApplicable(_))
        ));
        scene.pair.body1.radius = f64::INFINITY;
        assert!(matches!(
            geo_for_scene(&scene, 2e-5),
            Err(SolveError::NotApplicable(_))
        ));
    }

    #[test]
    fn lengths_parse_with_units() {
        assert!((parse_length("20um").unwrap() - 20e-6).abs() < 1e-18);
        assert!((parse_length("0.02mm").unwrap() - 2e-5).abs() < 1e-18);
        assert_eq!(parse_length("2e-5").unwrap(), 2e-5);
        assert_eq!(parse_length("20μm").unwrap(), parse_length("20µm").unwrap());
        assert!(parse_length("-1um").is_err());
        assert!(parse_length("inf").unwrap_err().contains("finite and positive"));
        assert!(parse_length("abc").is_err());
    }
}
