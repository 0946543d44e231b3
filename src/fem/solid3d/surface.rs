//! The contact candidate surface of the 3D body and its contact rule.
//!
//! Candidates: the 6-node faces of the contact surface lying wholly within the candidate radius
//! of the pole (r = √(x² + y²)), and their nodes. On them the contact pressure and traction are
//! interpolated on the faces' sub-triangulation ([`crate::fem::element::face6`]): the unknown of
//! node j is a force-like multiplier λ_j = w_j p_j (w_j = ∫ φ_j dA > 0), which acts on the body as
//! the nodal forces f_k = Σ_j A_jk λ_j and sees the averaged displacement (A u)_j, with
//! A_jk = ∫ φ_j N_k dA / w_j. Every row of A sums to one, so Σ_k f_k = Σ_j λ_j: P and Q are the
//! sums of the multipliers.

use crate::fem::element::face6;
use crate::fem::mesh::solid::SolidMesh;

/// The candidate surface.
#[derive(Clone, Debug)]
pub struct Surface {
    /// Candidate nodes (mesh node indices), by increasing distance from the pole.
    pub nodes: Vec<usize>,
    /// Their coordinates [m].
    pub points: Vec<[f64; 3]>,
    /// Whether each lies on the symmetry plane y = 0 (u_y fixed, q_y = 0 by symmetry).
    pub on_symmetry: Vec<bool>,
    /// Weights w_j = ∫ φ_j dA [m²].
    pub weights: Vec<f64>,
    /// The averaging operator by rows: A_jk as (k, A_jk), k indexing the candidates.
    pub average: Vec<Vec<(usize, f64)>>,
    /// The sub-triangles of the candidate faces, as candidate indices (the layout of the surface
    /// fields: the pressure is linear on each).
    pub triangles: Vec<[usize; 3]>,
    /// The candidate faces, as candidate indices.
    pub faces: Vec<[usize; 6]>,
}

impl Surface {
    /// The candidate surface of `mesh` within `radius` of the pole.
    pub fn new(mesh: &SolidMesh, radius: f64) -> Result<Self, String> {
        let r = |n: usize| mesh.nodes[n][0].hypot(mesh.nodes[n][1]);
        let faces: Vec<[usize; 6]> = mesh
            .contact
            .iter()
            .filter(|f| f.iter().all(|&n| r(n) <= radius))
            .copied()
            .collect();
        // Sorted by distance from the pole: a contact's points lead, so the engine's products
        // read only the loaded columns ([`super::operator`]).
        let mut nodes = SolidMesh::nodes_of(&faces);
        nodes.sort_by(|&a, &b| r(a).total_cmp(&r(b)).then(a.cmp(&b)));
        if nodes.is_empty() {
            return Err(format!("no contact face lies within {radius:e} m of the pole"));
        }
        let mut local = vec![usize::MAX; mesh.nodes.len()];
        nodes.iter().enumerate().for_each(|(j, &n)| local[n] = j);
        let m = nodes.len();
        let mut coupling: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
        let faces: Vec<[usize; 6]> = faces.iter().map(|f| f.map(|n| local[n])).collect();
        for face in &faces {
            let d = face6::coupling(&mesh.face_coords(&face.map(|j| nodes[j])));
            for (a, row) in d.iter().enumerate() {
                for (b, &v) in row.iter().enumerate() {
                    coupling[face[a]].push((face[b], v));
                }
            }
        }
        let mut weights = Vec::with_capacity(m);
        let average = coupling
            .into_iter()
            .map(|mut row| {
                row.sort_unstable_by_key(|e| e.0);
                let mut merged: Vec<(usize, f64)> = Vec::with_capacity(row.len());
                for (k, v) in row {
                    match merged.last_mut() {
                        Some(last) if last.0 == k => last.1 += v,
                        _ => merged.push((k, v)),
                    }
                }
                let w: f64 = merged.iter().map(|e| e.1).sum();
                weights.push(w);
                merged.into_iter().map(|(k, v)| (k, v / w)).collect()
            })
            .collect();
        if let Some(j) = weights.iter().position(|&w| w.is_nan() || w <= 0.0) {
            return Err(format!("contact node {} has no positive weight", nodes[j]));
        }
        let symmetry = SolidMesh::nodes_of(&mesh.symmetry);
        let on_symmetry = nodes.iter().map(|n| symmetry.binary_search(n).is_ok()).collect();
        let triangles = faces
            .iter()
            .flat_map(|f| face6::SUB_TRIANGLES.map(|s| s.map(|k| f[k])))
            .collect();
        Ok(Self {
            points: nodes.iter().map(|&n| mesh.nodes[n]).collect(),
            nodes,
            on_symmetry,
            weights,
            average,
            triangles,
            faces,
        })
    }

    /// The number of candidates.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// True without candidates (never, once built).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// (A v)_j for nodal values v_k.
    pub fn averaged(&self, values: &[f64]) -> Vec<f64> {
        self.average
            .iter()
            .map(|row| row.iter().map(|&(k, a)| a * values[k]).sum())
            .collect()
    }

    /// The averaged initial heights (A z)_j of the surface above the contact plane [m].
    pub fn heights(&self) -> Vec<f64> {
        let z: Vec<f64> = self.points.iter().map(|p| p[2]).collect();
        self.averaged(&z)
    }

    /// The largest distance of a candidate from the axis [m].
    pub fn radius(&self) -> f64 {
        self.points.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max)
    }
}
