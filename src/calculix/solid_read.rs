//! Reading back a `ccx-3d` run: P and Q at every computed step from the reaction totals of the
//! far face in `job.dat` (checked against the plate's), and the contact surface from the
//! `CONTACT` blocks of `job.frd` (COPEN, CSLIP1, CSLIP2, CPRESS, CSHEAR1, CSHEAR2 at the slave
//! nodes) at the corners of the candidate faces ([`Body::corners`]: on the tetrahedra fem-3d's
//! weights and triangles, on the bricks each face's corners and two triangles): the layout of
//! fem-3d's fields ([`Surface3`]).

use std::path::Path;

use super::body::{Body, Corners};
use super::results::{self, ContactBlock};
use crate::external::deck::ComputedStep;
use crate::external::readback::read_output;
use crate::external::surface3d::{Node3, Surface3};

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
}

/// Reads `job.dat` and `job.frd` in `dir` for the deck written on `mesh` with candidates within
/// `candidate_radius` [m], friction `mu`, and the computed `steps`.
pub fn read_back(
    dir: &Path,
    mesh: &Body,
    candidate_radius: f64,
    mu: f64,
    steps: &[ComputedStep],
) -> Result<SolidRun, String> {
    let n = steps.len();
    let dat = read_output(dir, "job.dat")?;
    let far = results::last_per_step(&results::totals(&dat, "NFAR1")?, |t| t.time, n, "job.dat NFAR1")?;
    let other = results::last_per_step(&results::totals(&dat, "NFAR2")?, |t| t.time, n, "job.dat NFAR2")?;
    let frd = results::parse_frd(&read_output(dir, "job.frd")?)?;
    let surface = mesh.corners(candidate_radius)?;
    let mut run = SolidRun {
        forces: Vec::with_capacity(n),
        forces_plane: Vec::with_capacity(n),
        surfaces: Vec::with_capacity(n),
        triangles: surface.triangles.clone(),
    };
    for (k, (step, (far, other))) in steps.iter().zip(far.iter().zip(&other)).enumerate() {
        // The half model's reactions, doubled; `+ 0.0` turns −0 into 0.
        let on_far = [-2.0 * far.force[2] + 0.0, 2.0 * far.force[0] + 0.0];
        let on_other = [2.0 * other.force[2] + 0.0, -2.0 * other.force[0] + 0.0];
        let scale = on_far[0].abs().max(on_other[0].abs()).max(1.0);
        for (what, a, b) in [("P", on_far[0], on_other[0]), ("Q", on_far[1], on_other[1])] {
            if (a - b).abs() > EQUILIBRIUM * scale {
                return Err(format!(
                    "job.dat step {}: {what} = {a} N from sphere 1's far face, {b} N from sphere 2's: not in equilibrium",
                    k + 1
                ));
            }
        }
        let block = frd.contact_at_step(k);
        let nodes = match block {
            Some(block) => corner_values(block, &surface, mu)?,
            None if on_far[0].abs() <= EQUILIBRIUM => corner_values(&ContactBlock::default(), &surface, mu)?,
            None => {
                return Err(format!(
                    "job.frd: no contact output at step {} although P = {} N",
                    k + 1,
                    on_far[0]
                ))
            }
        };
        run.forces.push(on_far);
        run.forces_plane.push(on_other);
        run.surfaces.push(Surface3 {
            step: step.step,
            nodes,
        });
    }
    Ok(run)
}

/// The contact state at the surface's corner points from one `CONTACT` block (a point without a
/// record is open and unloaded). CalculiX's tangential directions on the plate's faces are
/// global x and y (its master faces lie in z = 0); its shear is the traction on the slave, the
/// sphere, opposite to ∫ q_x dA = Q's sign convention, and its slip that of the sphere against
/// the plate, half the relative slip of the two spheres.
fn corner_values(block: &ContactBlock, surface: &Corners, mu: f64) -> Result<Vec<Node3>, String> {
    surface
        .nodes
        .iter()
        .zip(&surface.points)
        .zip(&surface.weights)
        .map(|((&node, point), &weight)| {
            let [open, slip1, slip2, pressure, shear1, shear2] =
                block.values.get(&(node as u64 + 1)).copied().unwrap_or_default();
            let pressure = pressure.max(0.0) * 1e6;
            let traction = [-shear1 * 1e6, -shear2 * 1e6];
            let stick =
                pressure > 0.0 && traction[0].hypot(traction[1]) < mu * pressure * (1.0 - STICK_MARGIN);
            Ok(Node3 {
                point: [point[0], point[1]],
                weight,
                gap: open * 1e-3,
                pressure,
                traction,
                stick,
                slip: [slip1 * 1e-3, slip2 * 1e-3],
            })
        })
        .collect()
}
