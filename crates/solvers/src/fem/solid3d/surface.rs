//! The contact candidate surface of the 3D body and its contact rule.
//!
//! Candidates: the 6-node faces of the contact surface lying wholly within the candidate radius
//! of the pole (r = √(x² + y²)), and their nodes. On them the contact pressure and traction are
//! interpolated by hats φ_j of the multiplier points ([`Rule`]: linear on each face from its
//! corners, or on its sub-triangulation from all its nodes; [`crate::fem::element::face6`]): the
//! unknown of point j is a force-like multiplier λ_j = w_j p_j (w_j = ∫ φ_j dA > 0), which acts
//! on the body as the nodal forces f_k = Σ_j A_jk λ_j and sees the averaged displacement
//! (A u)_j, with A_jk = ∫ φ_j N_k dA / w_j. Every row of A sums to one, so Σ_k f_k = Σ_j λ_j: P
//! and Q are the sums of the multipliers.

use crate::fem::element::face6;
use crate::fem::mesh::solid::SolidMesh;

/// Where the contact multipliers live on the 6-node faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// At the corners only, linear on each face ([`face6::corner_coupling`]): a multiplier space
    /// one order below the displacements', stable (no node-to-node oscillation of p and q), with
    /// a quarter of the nodes.
    Corners,
    /// At every node, linear on the face's four sub-triangles ([`face6::coupling`]): as many
    /// multipliers as surface nodes; the multipliers oscillate from node to node
    /// (`examples/fem3d_transverse.rs`: at position 5 a sample departs from its neighbours' mean
    /// by 0.23 of max p and 1.08 of max|q_y|, against 0.04 and 0.21 in the BEM).
    SubTriangles,
}

/// The candidate surface.
#[derive(Clone, Debug)]
pub struct Surface {
    /// Candidate nodes (mesh node indices): every node of the candidate faces, by increasing
    /// distance from the pole; their DOFs are the condensed ones.
    pub nodes: Vec<usize>,
    /// The multiplier points (mesh node indices): the candidate faces' corners or all their
    /// nodes ([`Rule`]), by increasing distance from the pole.
    pub point_nodes: Vec<usize>,
    /// The multiplier points' coordinates [m].
    pub points: Vec<[f64; 3]>,
    /// Whether each point lies on the symmetry plane y = 0 (u_y fixed, q_y = 0 by symmetry).
    pub on_symmetry: Vec<bool>,
    /// Weights w_j = ∫ φ_j dA [m²].
    pub weights: Vec<f64>,
    /// The averaging operator by rows (one a point): A_jk as (k, A_jk), k indexing
    /// [`Surface::nodes`].
    pub average: Vec<Vec<(usize, f64)>>,
    /// The triangles on which the multipliers are linear, as point indices (the layout of the
    /// surface fields).
    pub triangles: Vec<[usize; 3]>,
    /// The candidate faces, as indices into [`Surface::nodes`].
    pub faces: Vec<[usize; 6]>,
    /// The heights of [`Surface::nodes`] above the contact plane [m].
    node_heights: Vec<f64>,
}

impl Surface {
    /// The candidate surface of `mesh` within `radius` of the pole, multipliers by `rule`.
    pub fn new(mesh: &SolidMesh, radius: f64, rule: Rule) -> Result<Self, String> {
        let r = |n: usize| mesh.nodes[n][0].hypot(mesh.nodes[n][1]);
        let by_radius = |mut nodes: Vec<usize>| {
            // Sorted by distance from the pole: a contact's points lead, so the engine's
            // products read only the loaded columns ([`spherecontact_contact::dense`]).
            nodes.sort_by(|&a, &b| r(a).total_cmp(&r(b)).then(a.cmp(&b)));
            nodes
        };
        let faces: Vec<[usize; 6]> = mesh
            .contact
            .iter()
            .filter(|f| f.iter().all(|&n| r(n) <= radius))
            .copied()
            .collect();
        let nodes = by_radius(SolidMesh::nodes_of(&faces));
        if nodes.is_empty() {
            return Err(format!("no contact face lies within {radius:e} m of the pole"));
        }
        let point_nodes = match rule {
            Rule::SubTriangles => nodes.clone(),
            Rule::Corners => {
                let mut corners: Vec<usize> = faces.iter().flat_map(|f| [f[0], f[1], f[2]]).collect();
                corners.sort_unstable();
                corners.dedup();
                by_radius(corners)
            }
        };
        let index = |list: &[usize]| {
            let mut local = vec![usize::MAX; mesh.nodes.len()];
            list.iter().enumerate().for_each(|(j, &n)| local[n] = j);
            local
        };
        let (node_index, point_index) = (index(&nodes), index(&point_nodes));
        let mut coupling: Vec<Vec<(usize, f64)>> = vec![Vec::new(); point_nodes.len()];
        let mut triangles = Vec::new();
        for face in &faces {
            let x = mesh.face_coords(face);
            let local = face.map(|n| node_index[n]);
            let mut add = |rows: &[[f64; 6]], points: &[usize]| {
                for (row, &n) in rows.iter().zip(points) {
                    for (b, &v) in row.iter().enumerate() {
                        coupling[point_index[n]].push((local[b], v));
                    }
                }
            };
            match rule {
                Rule::SubTriangles => {
                    add(&face6::coupling(&x), face);
                    triangles.extend(face6::SUB_TRIANGLES.map(|t| t.map(|k| point_index[face[k]])));
                }
                Rule::Corners => {
                    add(&face6::corner_coupling(&x), &face[..3]);
                    triangles.push([0, 1, 2].map(|k| point_index[face[k]]));
                }
            }
        }
        let mut weights = Vec::with_capacity(point_nodes.len());
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
            return Err(format!("contact node {} has no positive weight", point_nodes[j]));
        }
        let symmetry = SolidMesh::nodes_of(&mesh.symmetry);
        Ok(Self {
            on_symmetry: point_nodes
                .iter()
                .map(|n| symmetry.binary_search(n).is_ok())
                .collect(),
            points: point_nodes.iter().map(|&n| mesh.nodes[n]).collect(),
            node_heights: nodes.iter().map(|&n| mesh.nodes[n][2]).collect(),
            faces: faces.iter().map(|f| f.map(|n| node_index[n])).collect(),
            nodes,
            point_nodes,
            weights,
            average,
            triangles,
        })
    }

    /// The number of multiplier points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True without points (never, once built).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// (A v)_j for values v_k at [`Surface::nodes`].
    pub fn averaged(&self, values: &[f64]) -> Vec<f64> {
        self.average
            .iter()
            .map(|row| row.iter().map(|&(k, a)| a * values[k]).sum())
            .collect()
    }

    /// The averaged initial heights (A z)_j of the surface above the contact plane [m].
    pub fn heights(&self) -> Vec<f64> {
        self.averaged(&self.node_heights)
    }

    /// The largest distance of a point from the axis [m].
    pub fn radius(&self) -> f64 {
        self.points.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max)
    }
}
