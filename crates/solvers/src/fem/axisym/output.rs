//! Displacement and stress fields of a contact state, and their VTU files for ParaView.

use std::path::Path;

use faer::Mat;

use super::model::{BodyModel, Model};
use crate::fem::element::tri6::{self, Lame, NODES};
use crate::fem::mesh::meridian::Mesh;
use crate::fem::nodal;
use crate::vtu::{CellType, Grid, PointData, VtuError};

/// Nodal displacements (u_r, u_z) of `body` under contact ring forces `forces` at its candidates,
/// with its far boundary moved by −`shift` along z: u = −shift e_z + K⁻¹ f.
pub fn displacement(body: &BodyModel, forces: &[f64], shift: f64) -> Vec<[f64; 2]> {
    let mut rhs = Mat::<f64>::zeros(body.dofs(), 1);
    for (&n, &f) in body.candidates.iter().zip(forces) {
        if let Some(d) = body.system.dofs.free(2 * n + 1) {
            rhs[(d, 0)] = f;
        }
    }
    body.factor.solve_in_place(rhs.as_mut());
    (0..body.mesh.nodes.len())
        .map(|n| {
            let value = |dof: usize| body.system.dofs.free(dof).map_or(0.0, |d| rhs[(d, 0)]);
            [value(2 * n), value(2 * n + 1) - shift]
        })
        .collect()
}

/// Stress (σ_rr, σ_zz, σ_θθ, τ_rz) at the nodes: each element's value at the node, averaged
/// over the elements sharing it.
pub fn nodal_stress(mesh: &Mesh, lame: Lame, u: &[[f64; 2]]) -> Vec<[f64; 4]> {
    let samples = mesh.triangles.iter().flat_map(|t| {
        let x = t.map(|n| mesh.nodes[n]);
        let ue = t.map(|n| u[n]);
        NODES
            .iter()
            .zip(t)
            .filter_map(move |(at, &n)| tri6::strain(&x, &ue, *at).map(|strain| (n, lame.stress(strain))))
    });
    nodal::average(mesh.nodes.len(), samples)
}

/// Writes each body's displacement and stress under the contact ring forces `forces` (approach `approach`,
/// split equally between two bodies) to `path` (`path-bodyK.vtu` when there are two bodies).
pub fn write_fields(model: &Model, forces: &[f64], approach: f64, path: &Path) -> Result<(), VtuError> {
    let shift = approach / model.bodies.len() as f64;
    for (k, body) in model.bodies.iter().enumerate() {
        let u = displacement(body, forces, shift);
        let stress = nodal_stress(&body.mesh, body.lame, &u);
        let target = if model.bodies.len() == 1 {
            path.to_path_buf()
        } else {
            path.with_extension(format!("body{}.vtu", k + 1))
        };
        grid(&body.mesh, &u, &stress).write(&target)?;
    }
    Ok(())
}

/// The meridian grid (x = r, y = z) with displacement and stress arrays.
fn grid(mesh: &Mesh, u: &[[f64; 2]], stress: &[[f64; 4]]) -> Grid {
    let scalar = |name: &str, f: &dyn Fn(&[f64; 4]) -> f64| PointData {
        name: name.into(),
        components: 1,
        values: stress.iter().map(f).collect(),
    };
    let von_mises = |s: &[f64; 4]| {
        let d = [s[0] - s[1], s[1] - s[2], s[2] - s[0]];
        (0.5 * d.iter().map(|v| v * v).sum::<f64>() + 3.0 * s[3] * s[3]).sqrt()
    };
    meridian_grid(
        mesh,
        vec![
            PointData {
                name: "displacement".into(),
                components: 3,
                values: u.iter().flat_map(|d| [d[0], d[1], 0.0]).collect(),
            },
            scalar("stress_rr", &|s| s[0]),
            scalar("stress_zz", &|s| s[1]),
            scalar("stress_tt", &|s| s[2]),
            scalar("stress_rz", &|s| s[3]),
            scalar("von_mises", &von_mises),
        ],
    )
}

/// A meridian mesh as a VTU grid (x = r, y = z, quadratic triangles) carrying `point_data`.
pub fn meridian_grid(mesh: &Mesh, point_data: Vec<PointData>) -> Grid {
    Grid {
        points: mesh.nodes.iter().map(|p| [p[0], p[1], 0.0]).collect(),
        cell_type: CellType::QuadraticTriangle,
        cells: mesh.triangles.iter().map(|t| t.to_vec()).collect(),
        point_data,
    }
}
