//! The half body as `ccx-3d` writes and reads it, over the element kind: fem-3d's 10-node
//! tetrahedra (C3D10, [`SolidMesh`]) or the 20-node bricks of the same body (C3D20, C3D20R,
//! [`HexMesh`]). One deck writer ([`super::solid_inp`]) and one reader ([`super::solid_read`])
//! serve both through this: the elements in CalculiX's node order (and their mirror images for
//! sphere 2), CalculiX's faces S1–S6 by their corners, the candidate faces, the node sets, and
//! the corner points on which the contact output is read back.
//!
//! The read-back surface: CalculiX prints its contact output at the slave nodes; the fields are
//! read at the candidate faces' corners. On the tetrahedra they are fem-3d's multiplier points
//! with fem-3d's weights and triangles ([`Surface`] with [`Rule::Corners`]). On the bricks each
//! 8-node face gives its four corners the integrals of their bilinear hats
//! ([`hex20::quad_corner_weights`]) and is split into two triangles on its diagonal from corner 1
//! to corner 3 (1-2-3 and 1-3-4), on which the measures interpolate linearly.

use std::collections::HashMap;

use super::hex20;
use super::hex_mesh::HexMesh;
use spherecontact_solvers::fem::mesh::solid::SolidMesh;
use spherecontact_solvers::fem::solid3d::surface::{Rule, Surface};

/// CalculiX's faces of C3D10 by their corners (node positions, the same in gmsh's and
/// CalculiX's order): S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1.
const TET_FACES: [&[usize]; 4] = [&[0, 1, 2], &[0, 3, 1], &[1, 3, 2], &[2, 3, 0]];

/// Mirroring through the contact plane turns a tetrahedron inside out: corners 2 and 3 swapped
/// (and with them the midside nodes), in CalculiX's order as in gmsh's.
const TET_MIRROR: [usize; 10] = [0, 2, 1, 3, 6, 5, 4, 7, 9, 8];

/// The half body's mesh, of either element kind.
#[derive(Clone, Debug)]
pub enum Body {
    /// fem-3d's 10-node tetrahedra (gmsh's node order).
    Tet10(SolidMesh),
    /// The 20-node bricks (CalculiX's node order).
    Hex20(HexMesh),
}

/// The candidate faces' corners, where the contact output is read back: fem-3d's surface layout.
#[derive(Clone, Debug, Default)]
pub struct Corners {
    /// The corners' mesh node indices.
    pub nodes: Vec<usize>,
    /// Their coordinates [m].
    pub points: Vec<[f64; 3]>,
    /// Their weights ∫ L dA (L the corner's hat on the faces) [m²].
    pub weights: Vec<f64>,
    /// The triangles on which the fields are linear, as indices of [`Corners::nodes`].
    pub triangles: Vec<[usize; 3]>,
}

impl Body {
    /// Node coordinates [m].
    pub fn nodes(&self) -> &[[f64; 3]] {
        match self {
            Body::Tet10(m) => &m.nodes,
            Body::Hex20(m) => &m.nodes,
        }
    }

    /// The mesh in words.
    pub fn describe(&self) -> &'static str {
        match self {
            Body::Tet10(_) => "quadratic tetrahedral mesh",
            Body::Hex20(_) => "20-node brick mesh (its tetrahedra subdivided, 4 bricks each)",
        }
    }

    /// The number of elements.
    pub fn element_count(&self) -> usize {
        match self {
            Body::Tet10(m) => m.tetrahedra.len(),
            Body::Hex20(m) => m.hexahedra.len(),
        }
    }

    /// Element `e` in CalculiX's node order (0-based node ids), or, `mirrored`, its mirror image
    /// through z = 0 turned right side out (sphere 2's, on the same node ids).
    pub fn element(&self, e: usize, mirrored: bool) -> Vec<usize> {
        let ccx: Vec<usize> = match self {
            Body::Tet10(m) => spherecontact_solvers::fem::element::tet10::VTK_ORDER
                .iter()
                .map(|&k| m.tetrahedra[e][k])
                .collect(),
            Body::Hex20(m) => m.hexahedra[e].to_vec(),
        };
        if !mirrored {
            return ccx;
        }
        match self {
            Body::Tet10(_) => TET_MIRROR.iter().map(|&k| ccx[k]).collect(),
            Body::Hex20(_) => hex20::mirror().iter().map(|&k| ccx[k]).collect(),
        }
    }

    /// CalculiX's faces S1, S2, … of an element by their corners (positions in CalculiX's order).
    pub fn face_corners(&self) -> Vec<&'static [usize]> {
        match self {
            Body::Tet10(_) => TET_FACES.to_vec(),
            Body::Hex20(_) => hex20::FACES.iter().map(|f| &f[..4]).collect(),
        }
    }

    /// The contact faces wholly within `radius` of the axis, each as its nodes, corners first.
    pub fn candidate_faces(&self, radius: f64) -> Vec<Vec<usize>> {
        let nodes = self.nodes();
        let inside = |f: &[usize]| f.iter().all(|&n| nodes[n][0].hypot(nodes[n][1]) <= radius);
        match self {
            Body::Tet10(m) => faces_within(&m.contact, inside),
            Body::Hex20(m) => faces_within(&m.contact, inside),
        }
    }

    /// The number of corners of a face.
    pub fn face_corner_count(&self) -> usize {
        match self {
            Body::Tet10(_) => 3,
            Body::Hex20(_) => 4,
        }
    }

    /// The distinct nodes of the far face, sorted.
    pub fn far_nodes(&self) -> Vec<usize> {
        match self {
            Body::Tet10(m) => SolidMesh::nodes_of(&m.far),
            Body::Hex20(m) => distinct(&m.far),
        }
    }

    /// The distinct nodes of the symmetry plane, sorted.
    pub fn symmetry_nodes(&self) -> Vec<usize> {
        match self {
            Body::Tet10(m) => SolidMesh::nodes_of(&m.symmetry),
            Body::Hex20(m) => distinct(&m.symmetry),
        }
    }

    /// The read-back points of the candidate faces within `radius` (module doc).
    pub fn corners(&self, radius: f64) -> Result<Corners, String> {
        match self {
            Body::Tet10(m) => {
                let s = Surface::new(m, radius, Rule::Corners)?;
                Ok(Corners {
                    nodes: s.point_nodes,
                    points: s.points,
                    weights: s.weights,
                    triangles: s.triangles,
                })
            }
            Body::Hex20(m) => brick_corners(m, &self.candidate_faces(radius)),
        }
    }
}

/// The faces that `inside` accepts, as vectors.
fn faces_within<const N: usize>(faces: &[[usize; N]], inside: impl Fn(&[usize]) -> bool) -> Vec<Vec<usize>> {
    faces
        .iter()
        .filter(|f| inside(&f[..]))
        .map(|f| f.to_vec())
        .collect()
}

/// The distinct nodes of some faces, sorted.
fn distinct<const N: usize>(faces: &[[usize; N]]) -> Vec<usize> {
    let mut nodes: Vec<usize> = faces.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

/// The corners of the 8-node candidate `faces`, weighted by their bilinear hats, each face two
/// triangles on its diagonal 1–3 (module doc), the corners by increasing distance from the axis.
fn brick_corners(mesh: &HexMesh, faces: &[Vec<usize>]) -> Result<Corners, String> {
    if faces.is_empty() {
        return Err("no contact face lies within the candidate radius".into());
    }
    let r = |n: usize| mesh.nodes[n][0].hypot(mesh.nodes[n][1]);
    let mut nodes: Vec<usize> = faces.iter().flat_map(|f| f[..4].to_vec()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes.sort_by(|&a, &b| r(a).total_cmp(&r(b)).then(a.cmp(&b)));
    let index: HashMap<usize, usize> = nodes.iter().enumerate().map(|(j, &n)| (n, j)).collect();
    let mut weights = vec![0.0; nodes.len()];
    let mut triangles = Vec::with_capacity(2 * faces.len());
    for face in faces {
        let coords: [[f64; 3]; 8] = std::array::from_fn(|k| mesh.nodes[face[k]]);
        let local = [0, 1, 2, 3].map(|k| index[&face[k]]);
        for (j, w) in local.iter().zip(hex20::quad_corner_weights(&coords)) {
            weights[*j] += w;
        }
        triangles.push([local[0], local[1], local[2]]);
        triangles.push([local[0], local[2], local[3]]);
    }
    Ok(Corners {
        points: nodes.iter().map(|&n| mesh.nodes[n]).collect(),
        nodes,
        weights,
        triangles,
    })
}
