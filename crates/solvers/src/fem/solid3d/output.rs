//! The volume and contact-surface fields of a 3D contact state, and their VTU files for
//! ParaView: the body as 10-node tetrahedra (VTK's node order), the contact surface as the
//! sub-triangles of its candidate faces (on which the pressure and traction are linear).

use std::path::Path;

use faer::Mat;

use super::model::Model;
use crate::fem::element::tet10::{self, VTK_ORDER};
use crate::fem::element::tri6::Lame;
use crate::fem::mesh::solid::SolidMesh;
use crate::fem::nodal;
use crate::vtu::{CellType, Grid, PointData, VtuError};

/// The multipliers of one contact state, acting on the modelled body (force-like: λ_j = w_j p_j).
#[derive(Clone, Copy, Debug)]
pub struct Loads<'a> {
    /// Normal multiplier per candidate (along +z, away from the contact plane) [N].
    pub normal: &'a [f64],
    /// Tangential multiplier per tangential unknown of the model's condensation [N].
    pub tangential: &'a [f64],
    /// The far face's rigid translation (x, y, z) [m].
    pub translation: [f64; 3],
}

/// Nodal displacements u = t + K⁻¹ f, f the nodal forces Aᵀ λ of the multipliers.
pub fn displacement(model: &Model, loads: Loads<'_>) -> Vec<[f64; 3]> {
    let dofs = &model.system.dofs;
    let surface = &model.surface;
    let mut rhs = Mat::<f64>::zeros(dofs.count(), 1);
    let mut add = |j: usize, a: usize, value: f64| {
        for &(k, weight) in &surface.average[j] {
            if let Some(d) = dofs.free(3 * surface.nodes[k] + a) {
                rhs[(d, 0)] += weight * value;
            }
        }
    };
    for (j, &value) in loads.normal.iter().enumerate() {
        add(j, 2, value);
    }
    for (&(j, a), &value) in model.condensed.tangential_unknowns.iter().zip(loads.tangential) {
        add(j, a, value);
    }
    model.factor.solve_in_place(rhs.as_mut());
    (0..model.mesh.nodes.len())
        .map(|n| {
            std::array::from_fn(|a| loads.translation[a] + dofs.free(3 * n + a).map_or(0.0, |d| rhs[(d, 0)]))
        })
        .collect()
}

/// Stress (σ_xx, σ_yy, σ_zz, τ_yz, τ_xz, τ_xy) at the nodes: each element's value at the node,
/// averaged over the elements sharing it.
pub fn nodal_stress(mesh: &SolidMesh, lame: Lame, u: &[[f64; 3]]) -> Vec<[f64; 6]> {
    let samples = mesh.tetrahedra.iter().enumerate().flat_map(|(e, t)| {
        let x = mesh.coords(e);
        let ue = t.map(|n| u[n]);
        tet10::NODES.iter().zip(t).filter_map(move |(at, &n)| {
            tet10::strain(&x, &ue, *at).map(|strain| (n, tet10::stress(lame, strain)))
        })
    });
    nodal::average(mesh.nodes.len(), samples)
}

/// The von Mises stress of (σ_xx, σ_yy, σ_zz, τ_yz, τ_xz, τ_xy).
fn von_mises(s: &[f64; 6]) -> f64 {
    let d = [s[0] - s[1], s[1] - s[2], s[2] - s[0]];
    (0.5 * d.iter().map(|v| v * v).sum::<f64>() + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])).sqrt()
}

/// Writes the body's displacement and stress under `loads` to `path`.
pub fn write_volume(model: &Model, loads: Loads<'_>, path: &Path) -> Result<(), VtuError> {
    let u = displacement(model, loads);
    let stress = nodal_stress(&model.mesh, model.lame, &u);
    let scalar = |name: &str, f: &dyn Fn(&[f64; 6]) -> f64| PointData {
        name: name.into(),
        components: 1,
        values: stress.iter().map(f).collect(),
    };
    Grid {
        points: model.mesh.nodes.clone(),
        cell_type: CellType::QuadraticTetra,
        cells: model
            .mesh
            .tetrahedra
            .iter()
            .map(|t| VTK_ORDER.iter().map(|&k| t[k]).collect())
            .collect(),
        point_data: vec![
            PointData {
                name: "displacement".into(),
                components: 3,
                values: u.iter().flatten().copied().collect(),
            },
            scalar("von_mises", &von_mises),
            scalar("sigma_zz", &|s| s[2]),
            scalar("tau_xz", &|s| s[4]),
            scalar("tau_yz", &|s| s[3]),
        ],
    }
    .write(path)
}

/// The contact-surface values at the candidate nodes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceValues {
    /// Pressure p [Pa].
    pub pressure: Vec<f64>,
    /// Traction (q_x, q_y) [Pa].
    pub traction: Vec<[f64; 2]>,
    /// Relative slip since the contact began (x, y) [m].
    pub slip: Vec<[f64; 2]>,
    /// 1 stick, 0 slip, −1 out of contact.
    pub status: Vec<f64>,
}

/// Writes the contact surface (sub-triangles of the candidate faces, at the nodes' initial
/// positions) with its values to `path`.
pub fn write_surface(model: &Model, values: &SurfaceValues, path: &Path) -> Result<(), VtuError> {
    let vector = |name: &str, v: &[[f64; 2]]| PointData {
        name: name.into(),
        components: 3,
        values: v.iter().flat_map(|q| [q[0], q[1], 0.0]).collect(),
    };
    Grid {
        points: model.surface.points.clone(),
        cell_type: CellType::Triangle,
        cells: model.surface.triangles.iter().map(|t| t.to_vec()).collect(),
        point_data: vec![
            PointData {
                name: "pressure".into(),
                components: 1,
                values: values.pressure.clone(),
            },
            vector("traction", &values.traction),
            vector("slip", &values.slip),
            PointData {
                name: "stick".into(),
                components: 1,
                values: values.status.clone(),
            },
        ],
    }
    .write(path)
}
