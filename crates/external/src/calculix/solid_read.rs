//! Reading back a `ccx-3d` run: P and Q at every computed step from the reaction totals of the
//! far face in `job.dat` (checked against the other sphere's), and the contact surface at the
//! corners of the candidate faces ([`Body::corners`]: on the tetrahedra fem-3d's weights and
//! triangles, on the bricks each face's corners and two triangles), the layout of fem-3d's fields
//! ([`Surface3`]), from `job.frd`:
//! - pressure and traction: the hat averages of the contact's nodal forces, recovered from the
//!   `DISP` blocks as sphere 1's internal forces ([`ForceRecovery`]; why not CalculiX's nodal
//!   CPRESS and CSHEAR: [`super::nodal_forces`]);
//! - gap, slip and the stick state: the `CONTACT` blocks (COPEN, CSLIP1, CSLIP2 at the slave
//!   nodes; a node sticks where CalculiX's own |CSHEAR| < μ CPRESS, [`STICK_MARGIN`]).

use std::path::Path;

use super::body::Corners;
use super::nodal_forces::ForceRecovery;
use super::results::{self, ContactBlock};
use super::solid_inp::SolidDeckSpec;
use crate::readback::read_output;
use crate::surface3d::{Node3, Surface3};
use spherecontact_model::limits::MAX_CCX_RESULTS_BYTES;
use spherecontact_model::pair::Material;
use spherecontact_solvers::fem::element::tri6::Lame;

/// Largest disagreement between the reactions of the far face and of the plate (x and z),
/// relative to the larger of the two and 1 N: the body's equilibrium, which CalculiX reaches to
/// its residual tolerance (measured below 1e-6 of P on `cases/ccx-3d.toml`).
pub const EQUILIBRIUM: f64 = 1e-4;

/// A node sticks when |q| < μ p (1 − this): CalculiX's return mapping puts a sliding
/// integration point's traction on the cone |q| = μ p, and the `.frd` keeps 6 digits; nodal
/// values average the neighbouring faces' integration points, so a node at the stick edge sits
/// a little inside the cone (measured on `cases/ccx-3d.toml`: sliding nodes at |q|/μp ≥ 0.995,
/// sticking ones below 0.98).
pub const STICK_MARGIN: f64 = 1e-2;

/// What one run left, read back (SI).
#[derive(Clone, Debug)]
pub struct SolidRun {
    /// (P, Q) of the whole sphere at each computed step [N]: twice the half model's far-face
    /// reaction.
    pub forces: Vec<[f64; 2]>,
    /// (P, Q) from sphere 2's far-face reaction [N].
    pub forces_plane: Vec<[f64; 2]>,
    /// The contact surface at each step.
    pub surfaces: Vec<Surface3>,
    /// fem-3d's triangles of the corners (indices of the surface's nodes).
    pub triangles: Vec<[usize; 3]>,
    /// (P, Q) that the maps carry at each computed step [N]: twice the recovered forces' sums
    /// over the corners, to be compared with [`SolidRun::forces`] (equal to the `.frd`'s digits
    /// when the contact lies within the candidate faces).
    pub forces_map: Vec<[f64; 2]>,
}

impl SolidRun {
    /// The largest disagreement of the maps' P and Q with the reaction's, relative to the
    /// largest P and 1 N.
    pub fn map_mismatch(&self) -> f64 {
        let scale = self.forces.iter().map(|f| f[0].abs()).fold(1.0, f64::max);
        self.forces
            .iter()
            .zip(&self.forces_map)
            .flat_map(|(f, m)| [(f[0] - m[0]).abs(), (f[1] - m[1]).abs()])
            .fold(0.0, f64::max)
            / scale
    }
}

/// Reads `job.dat` and `job.frd` in `dir` for the deck written from `spec`.
pub fn read_back(dir: &Path, spec: &SolidDeckSpec) -> Result<SolidRun, String> {
    let n = spec.steps.len();
    let dat = read_output(dir, "job.dat", MAX_CCX_RESULTS_BYTES)?;
    let far = results::last_per_step(&results::totals(&dat, "NFAR1")?, |t| t.time, n, "job.dat NFAR1")?;
    let other = results::last_per_step(&results::totals(&dat, "NFAR2")?, |t| t.time, n, "job.dat NFAR2")?;
    let frd = results::parse_frd(&read_output(dir, "job.frd", MAX_CCX_RESULTS_BYTES)?)?;
    let surface = spec.mesh.corners(spec.candidate_radius)?;
    let lame = Lame::of(&Material {
        young: spec.young,
        poisson: spec.poisson,
    });
    let recovery = ForceRecovery::try_new(
        spec.mesh,
        spec.settings.element,
        lame,
        &spec.slave_faces(),
        &surface,
    )?;
    let mut run = SolidRun {
        forces: Vec::with_capacity(n),
        forces_plane: Vec::with_capacity(n),
        forces_map: Vec::with_capacity(n),
        surfaces: Vec::with_capacity(n),
        triangles: surface.triangles.clone(),
    };
    for (k, (step, (far, other))) in spec.steps.iter().zip(far.iter().zip(&other)).enumerate() {
        // The half model's reactions, doubled; `+ 0.0` turns −0 into 0.
        let on_far = [-2.0 * far.force[2] + 0.0, 2.0 * far.force[0] + 0.0];
        let on_other = [2.0 * other.force[2] + 0.0, -2.0 * other.force[0] + 0.0];
        let scale = on_far[0].abs().max(on_other[0].abs()).max(1.0);
        for (what, a, b) in [("P", on_far[0], on_other[0]), ("Q", on_far[1], on_other[1])] {
            let departure = (a - b).abs() / scale;
            if departure > EQUILIBRIUM {
                return Err(format!(
                    "job.dat step {}: {what} from sphere 1's far face and from sphere 2's differ by \
                     {departure:.1e} of the larger P and 1 N: not in equilibrium (allowed: {EQUILIBRIUM:e})",
                    k + 1
                ));
            }
        }
        let empty = ContactBlock::default();
        let block = match frd.contact_at_step(k) {
            Some(block) => block,
            None if on_far[0].abs() <= EQUILIBRIUM => &empty,
            None => {
                return Err(format!(
                    "job.frd: no contact output at step {} although the far face carries a load \
                     (allowed: none only below {EQUILIBRIUM} N)",
                    k + 1
                ))
            }
        };
        let displacement = frd
            .displacement_at_step(k)
            .ok_or_else(|| format!("job.frd: no displacements (DISP of NREAD1) at step {}", k + 1))?;
        let forces = recovery.corner_forces(displacement, k + 1)?;
        let sum = |a: usize| 2.0 * forces.iter().map(|f| f[a]).sum::<f64>() + 0.0;
        run.forces_map.push([sum(2), -sum(0) + 0.0]);
        let values = recovery.hat_values(&forces);
        let nodes = corner_values(block, &surface, &values, spec.friction);
        run.forces.push(on_far);
        run.forces_plane.push(on_other);
        run.surfaces.push(Surface3 {
            step: step.step,
            nodes,
        });
    }
    Ok(run)
}

/// The contact state at the surface's corner points: pressure and traction from the corner
/// `values` of the contact's recovered forces on sphere 1 (f_z, f_x, f_y per area,
/// [`ForceRecovery::hat_values`]), the rest from one `CONTACT` block (a point without a record
/// is open and unloaded). The pressure pushes sphere 1 along +z; the traction is signed so that
/// ∫ q_x dA = Q, the force on the far face, opposite to the contact's force on the sphere.
/// CalculiX's tangential directions on the plate's faces are global x and y (its master faces lie
/// in z = 0); its shear is the traction on the slave, the sphere, and its slip that of the sphere
/// against the plate, half the relative slip of the two spheres.
fn corner_values(block: &ContactBlock, surface: &Corners, values: &[Vec<f64>; 3], mu: f64) -> Vec<Node3> {
    surface
        .nodes
        .iter()
        .zip(&surface.points)
        .zip(&surface.weights)
        .enumerate()
        .map(|(j, ((&node, point), &weight))| {
            let [open, slip1, slip2, pressure, shear1, shear2] =
                block.values.get(&(node as u64 + 1)).copied().unwrap_or_default();
            let stick = pressure > 0.0 && shear1.hypot(shear2) < mu * pressure * (1.0 - STICK_MARGIN);
            Node3 {
                point: [point[0], point[1]],
                weight,
                gap: open * 1e-3,
                pressure: values[0][j],
                traction: [-values[1][j], -values[2][j]],
                stick,
                slip: [slip1 * 1e-3, slip2 * 1e-3],
            }
        })
        .collect()
}
