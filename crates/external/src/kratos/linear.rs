//! The half body of `kratos-3d` in first-order elements: the corners of fem-3d's quadratic
//! tetrahedra ([`SolidMesh`], gmsh's mesh of [`spherecontact_solvers::fem::mesh::solid_geo`]) as
//! 4-node tetrahedra, their contact faces as 3-node triangles turned outward, the far face's and
//! the symmetry plane's nodes. Kratos 10.4.4 has mortar contact conditions on linear faces only,
//! so the body is the quadratic mesh's corners (the same geometry, the same nodes on the sphere).

use std::collections::HashMap;

use spherecontact_solvers::fem::mesh::solid::SolidMesh;

/// The half body's first-order mesh [m].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LinearBody {
    /// Node coordinates [m]: the quadratic mesh's corners, in their order there.
    pub nodes: Vec<[f64; 3]>,
    /// 4-node tetrahedra, positively oriented (gmsh's corner order).
    pub tetrahedra: Vec<[usize; 4]>,
    /// The contact surface's triangles, each ordered so that its normal points out of the body.
    pub contact: Vec<[usize; 3]>,
    /// The far face's nodes, sorted.
    pub far: Vec<usize>,
    /// The symmetry plane's (y = 0) nodes, sorted.
    pub symmetry: Vec<usize>,
}

impl LinearBody {
    /// The corners of `mesh`; fails when a contact face is no element's face.
    pub fn of(mesh: &SolidMesh) -> Result<Self, String> {
        let mut index = HashMap::new();
        let mut nodes = Vec::new();
        let mut renumber = |n: usize| {
            *index.entry(n).or_insert_with(|| {
                nodes.push(mesh.nodes[n]);
                nodes.len() - 1
            })
        };
        let tetrahedra: Vec<[usize; 4]> = mesh
            .tetrahedra
            .iter()
            .map(|t| [t[0], t[1], t[2], t[3]].map(&mut renumber))
            .collect();
        let corners = |faces: &[[usize; 6]]| -> Vec<[usize; 3]> {
            faces
                .iter()
                .map(|f| [f[0], f[1], f[2]].map(|n| index[&n]))
                .collect()
        };
        let (contact, far, symmetry) = (
            corners(&mesh.contact),
            corners(&mesh.far),
            corners(&mesh.symmetry),
        );
        let mut body = Self {
            nodes,
            tetrahedra,
            contact: Vec::new(),
            far: distinct(&far),
            symmetry: distinct(&symmetry),
        };
        body.contact = body.outward(&contact)?;
        Ok(body)
    }

    /// `faces` each ordered so that its normal points away from the element it bounds.
    fn outward(&self, faces: &[[usize; 3]]) -> Result<Vec<[usize; 3]>, String> {
        let mut opposite = HashMap::new();
        for t in &self.tetrahedra {
            for k in 0..4 {
                let mut face: Vec<usize> = (0..4).filter(|&j| j != k).map(|j| t[j]).collect();
                face.sort_unstable();
                opposite.insert(face, t[k]);
            }
        }
        faces
            .iter()
            .map(|&[a, b, c]| {
                let mut key = vec![a, b, c];
                key.sort_unstable();
                let inner = *opposite
                    .get(&key)
                    .ok_or_else(|| format!("contact face {:?} is the face of no tetrahedron", [a, b, c]))?;
                let [pa, pb, pc, po] = [a, b, c, inner].map(|n| self.nodes[n]);
                let normal = cross(sub(pb, pa), sub(pc, pa));
                Ok(if dot(normal, sub(pa, po)) > 0.0 {
                    [a, b, c]
                } else {
                    [a, c, b]
                })
            })
            .collect()
    }

    /// The contact faces wholly within `radius` of the axis (distance in the plane z = 0).
    pub fn candidate_faces(&self, radius: f64) -> Vec<[usize; 3]> {
        self.contact
            .iter()
            .filter(|f| {
                f.iter()
                    .all(|&n| self.nodes[n][0].hypot(self.nodes[n][1]) <= radius)
            })
            .copied()
            .collect()
    }

    /// The distinct nodes of `faces`, sorted.
    pub fn nodes_of(faces: &[[usize; 3]]) -> Vec<usize> {
        distinct(faces)
    }
}

/// The distinct nodes of some faces, sorted.
fn distinct(faces: &[[usize; 3]]) -> Vec<usize> {
    let mut nodes: Vec<usize> = faces.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One 10-node tetrahedron whose face on z = 0 is the contact face, listed inward.
    fn tetrahedron() -> SolidMesh {
        let corners = [
            [0.0, 0.0, 0.0],
            [1e-3, 0.0, 0.0],
            [0.0, 1e-3, 0.0],
            [0.0, 0.0, 1e-3],
        ];
        let mut nodes = corners.to_vec();
        for [a, b] in [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]] {
            nodes.push([0, 1, 2].map(|k| 0.5 * (corners[a][k] + corners[b][k])));
        }
        SolidMesh {
            nodes,
            tetrahedra: vec![[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]],
            contact: vec![[0, 1, 2, 4, 5, 6]],
            far: vec![[1, 2, 3, 5, 8, 9]],
            symmetry: vec![[0, 1, 3, 4, 9, 7]],
        }
    }

    /// Requirement: the corners only, the contact face turned outward (its normal along −z, away
    /// from the corner at z = 1 mm); exact.
    #[test]
    fn the_corners_make_the_body_and_the_contact_face_points_out() {
        let body = LinearBody::of(&tetrahedron()).unwrap();
        assert_eq!(body.nodes.len(), 4);
        assert_eq!(body.tetrahedra, vec![[0, 1, 2, 3]]);
        assert_eq!(body.contact, vec![[0, 2, 1]]);
        assert_eq!(
            (body.far.clone(), body.symmetry.clone()),
            (vec![1, 2, 3], vec![0, 1, 3])
        );
        assert_eq!(body.candidate_faces(1.1e-3).len(), 1);
        assert!(body.candidate_faces(0.9e-3).is_empty());
    }
}
