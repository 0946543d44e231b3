//! The tangential problem's fields as VTU files: the Fourier n = 1 displacement amplitudes on the
//! meridian, and the contact surface reconstructed in 3D with its tractions.
//!
//! Displacement of the mode n = 1 ([`crate::fem::element::tri6_n1`]): the far face is shifted
//! rigidly by S along x (the body's share of δt), which is A = S everywhere; the contact ring
//! forces f act on the surface. The engine's multiplier q is the traction that holds the body's
//! surface against the shift (its slip increment is w − C Δq: the surface moves by −C q relative
//! to the far face), so the force on the body is −f and
//!
//! ```text
//! (A, B, W) = S e_A − K⁻¹ f,       U = A + B,  V = A − B
//! u_x = A + B cos 2θ,   u_y = B sin 2θ,   u_z = W cos θ        (mode n = 1)
//! u_x = u_r cos θ,      u_y = u_r sin θ,  u_z = u_z            (mode n = 0)
//! ```
//! At a node that has stuck since the shift began, A equals the accumulated slip of the surface
//! against the symmetry plane (zero), which `tests/fem_friction.rs` checks.
//!
//! The 3D surface shows what the model assumes, not more: Mindlin–Deresiewicz's traction along x
//! everywhere (q_x(r, θ) = q(r), q_y = 0) and a circular stick zone.

use std::f64::consts::PI;
use std::path::Path;

use faer::Mat;

use super::model::{BodyModel, Model};
use super::output;
use super::tangential::ShearBody;
use crate::fem::element::tri6_n1::COMPONENTS;
use crate::vtu::{CellType, Grid, PointData, VtuError};
use spherecontact_model::history::SurfaceField;

/// Samples around the circumference of the reconstructed surface (7.5° apart).
const SECTORS: usize = 48;

/// Nodal (A, B, W) of `body` under the contact ring forces `forces` at its candidates, with its
/// far face shifted by `shift` [m] along x.
pub fn displacement(body: &BodyModel, shear: &ShearBody, forces: &[f64], shift: f64) -> Vec<[f64; 3]> {
    let dofs = &shear.system.dofs;
    let mut rhs = Mat::<f64>::zeros(dofs.count(), 1);
    for (&n, &f) in body.candidates.iter().zip(forces) {
        if let Some(d) = dofs.free(COMPONENTS * n) {
            rhs[(d, 0)] = -f;
        }
    }
    shear.factor.solve_in_place(rhs.as_mut());
    let value = |dof: usize| dofs.free(dof).map_or(0.0, |d| rhs[(d, 0)]);
    (0..body.mesh.nodes.len())
        .map(|n| {
            let k = COMPONENTS * n;
            [shift + value(k), value(k + 1), value(k + 2)]
        })
        .collect()
}

/// What the tangential VTU files show at one path position.
pub struct TangentialState<'a> {
    /// The normal ring forces λ at the candidates [N].
    pub normal: &'a [f64],
    /// The tangential ring forces q at the candidates [N].
    pub tangential: &'a [f64],
    /// The condensed problem's approach [m] (shared equally by two bodies).
    pub approach: f64,
    /// The condensed problem's total shift [m] (shared equally by two bodies).
    pub shift: f64,
    /// The surface field recorded at this position (pressure, traction, stick, slip).
    pub field: &'a SurfaceField,
}

/// Writes `dir/<stem>-n1.vtu` (the meridian with the n = 1 amplitudes; `-n1-bodyK.vtu` with two
/// bodies) and `dir/<stem>-surface.vtu` (body 1's contact surface in 3D).
pub fn write(model: &Model, state: &TangentialState, dir: &Path, stem: &str) -> Result<(), VtuError> {
    let Some(shear) = &model.shear else {
        return Ok(());
    };
    let share = model.bodies.len() as f64;
    let named = |suffix: &str| dir.join(format!("{stem}{suffix}"));
    let mut first = None;
    for (k, (body, shear_body)) in model.bodies.iter().zip(&shear.bodies).enumerate() {
        let amplitudes = displacement(body, shear_body, state.tangential, state.shift / share);
        let target = if model.bodies.len() == 1 {
            named("-n1.vtu")
        } else {
            named(&format!("-n1-body{}.vtu", k + 1))
        };
        meridian(body, &amplitudes).write(&target)?;
        first.get_or_insert(amplitudes);
    }
    let body = &model.bodies[0];
    let axial = output::displacement(body, state.normal, state.approach / share);
    let amplitudes = first.unwrap_or_default();
    surface(body, &axial, &amplitudes, state.field).write(&named("-surface.vtu"))
}

/// The meridian grid (x = r, y = z) with the amplitudes (A, B, W) and (U, V, W).
fn meridian(body: &BodyModel, amplitudes: &[[f64; 3]]) -> Grid {
    output::meridian_grid(
        &body.mesh,
        vec![
            PointData {
                name: "n1_ABW".into(),
                components: 3,
                values: amplitudes.iter().flatten().copied().collect(),
            },
            PointData {
                name: "n1_UVW".into(),
                components: 3,
                values: amplitudes
                    .iter()
                    .flat_map(|[a, b, w]| [a + b, a - b, *w])
                    .collect(),
            },
        ],
    )
}

/// Body 1's candidate surface swept around the axis: points (r cos θ, r sin θ, z) at the
/// candidates' (r, z), triangles between neighbouring rings (one point on the axis), with the
/// displacement of modes 0 and 1, the pressure, the traction (q(r), 0, 0) and the stick status
/// (1 stick, 0 slip, −1 out of contact) and the slip along x.
fn surface(body: &BodyModel, axial: &[[f64; 2]], amplitudes: &[[f64; 3]], field: &SurfaceField) -> Grid {
    let rings: Vec<usize> = body.candidates.clone();
    let mut points = Vec::new();
    let mut sample = Vec::new(); // (candidate index, θ) of each point
    let mut first_of_ring = Vec::new();
    for (i, &n) in rings.iter().enumerate() {
        let [r, z] = body.mesh.nodes[n];
        first_of_ring.push(points.len());
        let count = if r == 0.0 { 1 } else { SECTORS };
        for j in 0..count {
            let theta = 2.0 * PI * j as f64 / SECTORS as f64;
            points.push([r * theta.cos(), r * theta.sin(), z]);
            sample.push((i, theta));
        }
    }
    let mut cells = Vec::new();
    for i in 0..rings.len().saturating_sub(1) {
        let (a, b) = (first_of_ring[i], first_of_ring[i + 1]);
        let inner_single = first_of_ring[i + 1] - a == 1;
        for j in 0..SECTORS {
            let next = (j + 1) % SECTORS;
            if inner_single {
                cells.push(vec![a, b + j, b + next]);
            } else {
                cells.push(vec![a + j, b + j, b + next]);
                cells.push(vec![a + j, b + next, a + next]);
            }
        }
    }
    let at = |f: &dyn Fn(usize, f64) -> [f64; 3]| -> Vec<f64> {
        sample.iter().flat_map(|&(i, t)| f(i, t)).collect()
    };
    let scalar = |name: &str, f: &dyn Fn(usize) -> f64| PointData {
        name: name.into(),
        components: 1,
        values: sample.iter().map(|&(i, _)| f(i)).collect(),
    };
    let displacement = at(&|i, t| {
        let n = rings[i];
        let ([ur, uz], [a, b, w]) = (axial[n], amplitudes[n]);
        [
            ur * t.cos() + a + b * (2.0 * t).cos(),
            ur * t.sin() + b * (2.0 * t).sin(),
            uz + w * t.cos(),
        ]
    });
    let traction = |i: usize| field.traction.as_ref().map_or(0.0, |q| q[i][0]);
    let slip = |i: usize| field.slip.as_ref().map_or(0.0, |s| s[i][0]);
    let status = |i: usize| match (field.pressure[i] > 0.0, field.stick.as_ref().map(|s| s[i])) {
        (false, _) => -1.0,
        (true, Some(true)) => 1.0,
        (true, _) => 0.0,
    };
    Grid {
        points,
        cell_type: CellType::Triangle,
        cells,
        point_data: vec![
            PointData {
                name: "displacement".into(),
                components: 3,
                values: displacement,
            },
            scalar("pressure", &|i| field.pressure[i]),
            PointData {
                name: "traction".into(),
                components: 3,
                values: at(&|i, _| [traction(i), 0.0, 0.0]),
            },
            scalar("stick", &status),
            scalar("slip_x", &slip),
        ],
    }
}
