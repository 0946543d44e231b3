//! The half body of `kratos-3d` in first-order elements ([`Element`]): 4-node tetrahedra on the
//! corners of fem-3d's quadratic tetrahedra ([`SolidMesh`], gmsh's mesh of
//! [`spherecontact_solvers::fem::mesh::solid_geo`]), or gmsh's 8-node bricks of the same body
//! ([`super::bricks8`]); their contact faces (3-node triangles or 4-node quadrangles) turned
//! outward, the far face's and the symmetry plane's nodes. Kratos 10.4.4 has mortar contact
//! conditions on linear faces only, so the body is first order (the tetrahedra: the quadratic
//! mesh's corners, the same geometry, the same nodes on the sphere).
//!
//! Under friction the half is completed to the whole body ([`LinearBody::whole`]). The half is
//! exact in the continuum (u_y is odd in y for a shift along x), but not as a mortar model:
//! holding u_y = 0 on both spheres' plane nodes leaves the y component of the tangential
//! multiplier at the slave's plane nodes undetermined (Kratos' system is singular), and freeing
//! the master's plane nodes instead breaks the symmetry (Q/P at gross sliding 0.15–0.18 for
//! μ = 0.2, against 0.1997 on the whole body: docs/external-decks.md, "Kratos 3D").

use std::collections::HashMap;

use super::vector::{area_vector, centroid, dot, sub};
use spherecontact_model::kratos_settings::Element;
use spherecontact_solvers::fem::mesh::solid::SolidMesh;

/// A first-order mesh of one sphere's body [m]: the half (y ≥ 0) as meshed, or the whole.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearBody {
    /// The element kind.
    pub element: Element,
    /// Node coordinates [m].
    pub nodes: Vec<[f64; 3]>,
    /// The elements' nodes (4 or 8, Kratos' order: gmsh's), positively oriented.
    pub elements: Vec<Vec<usize>>,
    /// The contact surface's faces (3 or 4 nodes), each ordered so that its normal points out of
    /// the body.
    pub contact: Vec<Vec<usize>>,
    /// The far face's nodes, sorted.
    pub far: Vec<usize>,
    /// The symmetry plane's (y = 0) nodes, sorted; none on the whole body.
    pub symmetry: Vec<usize>,
}

/// The faces of a tetrahedron (the one opposite each corner) as its local nodes.
const TET4_FACES: [&[usize]; 4] = [&[1, 2, 3], &[0, 2, 3], &[0, 1, 3], &[0, 1, 2]];
/// The faces of an 8-node brick (corners 0–3 on ζ = −1, 4–7 above them) as its local nodes.
const HEX8_FACES: [&[usize]; 6] = [
    &[0, 1, 2, 3],
    &[4, 5, 6, 7],
    &[0, 1, 5, 4],
    &[1, 2, 6, 5],
    &[2, 3, 7, 6],
    &[3, 0, 4, 7],
];

/// The local faces of `element`.
fn local_faces(element: Element) -> &'static [&'static [usize]] {
    match element {
        Element::Tet4 => &TET4_FACES,
        Element::Hex8 => &HEX8_FACES,
    }
}

/// The local node order of `element`'s mirror image that keeps it positively oriented: a
/// reflection turns an element inside out, and reversing one face's cycle (and the opposite
/// one's, for the brick) turns it back.
pub fn mirror_order(element: Element) -> &'static [usize] {
    match element {
        Element::Tet4 => &[0, 2, 1, 3],
        Element::Hex8 => &[0, 3, 2, 1, 4, 7, 6, 5],
    }
}

/// `face` with its cycle reversed (its normal turned round).
pub fn reversed(face: &[usize]) -> Vec<usize> {
    let mut f = face.to_vec();
    f[1..].reverse();
    f
}

/// The faces of a mesh's boundary groups, as read: contact, far, symmetry.
pub struct Boundary {
    /// The contact candidate surface's faces.
    pub contact: Vec<Vec<usize>>,
    /// The far face's faces.
    pub far: Vec<Vec<usize>>,
    /// The symmetry plane's faces.
    pub symmetry: Vec<Vec<usize>>,
}

impl LinearBody {
    /// The corners of `mesh` as 4-node tetrahedra; fails when a contact face is no element's face.
    pub fn of(mesh: &SolidMesh) -> Result<Self, String> {
        let mut index = HashMap::new();
        let mut nodes = Vec::new();
        let mut renumber = |n: usize| {
            *index.entry(n).or_insert_with(|| {
                nodes.push(mesh.nodes[n]);
                nodes.len() - 1
            })
        };
        let elements: Vec<Vec<usize>> = mesh
            .tetrahedra
            .iter()
            .map(|t| t[..4].iter().map(|&n| renumber(n)).collect())
            .collect();
        let corners = |faces: &[[usize; 6]]| -> Vec<Vec<usize>> {
            faces
                .iter()
                .map(|f| f[..3].iter().map(|n| index[n]).collect())
                .collect()
        };
        let boundary = Boundary {
            contact: corners(&mesh.contact),
            far: corners(&mesh.far),
            symmetry: corners(&mesh.symmetry),
        };
        Self::new(Element::Tet4, nodes, elements, &boundary)
    }

    /// The body of `element`s (positively oriented) and its `boundary`; fails when a contact face
    /// is no element's face.
    pub fn new(
        element: Element,
        nodes: Vec<[f64; 3]>,
        elements: Vec<Vec<usize>>,
        boundary: &Boundary,
    ) -> Result<Self, String> {
        let mut body = Self {
            element,
            nodes,
            elements,
            contact: Vec::new(),
            far: distinct(&boundary.far),
            symmetry: distinct(&boundary.symmetry),
        };
        body.contact = body.outward(&boundary.contact)?;
        Ok(body)
    }

    /// `faces` each ordered so that its normal points away from the element it bounds.
    fn outward(&self, faces: &[Vec<usize>]) -> Result<Vec<Vec<usize>>, String> {
        let mut owner = HashMap::new();
        for (e, nodes) in self.elements.iter().enumerate() {
            for local in local_faces(self.element) {
                let mut key: Vec<usize> = local.iter().map(|&k| nodes[k]).collect();
                key.sort_unstable();
                owner.insert(key, e);
            }
        }
        faces
            .iter()
            .map(|face| {
                let mut key = face.clone();
                key.sort_unstable();
                let e = *owner.get(&key).ok_or_else(|| {
                    format!("contact face {face:?} is the face of no {}", self.element.name())
                })?;
                let points: Vec<[f64; 3]> = face.iter().map(|&n| self.nodes[n]).collect();
                let inner = centroid(self.elements[e].iter().map(|&n| self.nodes[n]));
                let out = sub(centroid(points.iter().copied()), inner);
                Ok(match dot(area_vector(&points), out) > 0.0 {
                    true => face.clone(),
                    false => reversed(face),
                })
            })
            .collect()
    }

    /// The whole body of this half: its mirror image through y = 0 joined on the plane (the
    /// plane's nodes shared). The half's nodes keep their indices, the image's off-plane nodes
    /// follow them; the image's elements are in [`mirror_order`] and its faces reversed (a
    /// reflection turns both inside out); no symmetry plane is left.
    pub fn whole(&self) -> Self {
        let mut nodes = self.nodes.clone();
        let image: Vec<usize> = (0..self.nodes.len())
            .map(|n| match self.symmetry.binary_search(&n) {
                Ok(_) => n,
                Err(_) => {
                    let [x, y, z] = self.nodes[n];
                    nodes.push([x, -y, z]);
                    nodes.len() - 1
                }
            })
            .collect();
        let order = mirror_order(self.element);
        let mut elements = self.elements.clone();
        elements.extend(
            self.elements
                .iter()
                .map(|e| order.iter().map(|&k| image[e[k]]).collect()),
        );
        let mut contact = self.contact.clone();
        contact.extend(
            self.contact
                .iter()
                .map(|f| reversed(&f.iter().map(|&n| image[n]).collect::<Vec<_>>())),
        );
        let mut far = self.far.clone();
        far.extend(self.far.iter().map(|&n| image[n]));
        far.sort_unstable();
        far.dedup();
        Self {
            element: self.element,
            nodes,
            elements,
            contact,
            far,
            symmetry: Vec::new(),
        }
    }

    /// The contact faces wholly within `radius` of the axis (distance in the plane z = 0).
    pub fn candidate_faces(&self, radius: f64) -> Vec<Vec<usize>> {
        self.contact
            .iter()
            .filter(|f| {
                f.iter()
                    .all(|&n| self.nodes[n][0].hypot(self.nodes[n][1]) <= radius)
            })
            .cloned()
            .collect()
    }

    /// The distinct nodes of `faces`, sorted.
    pub fn nodes_of(faces: &[Vec<usize>]) -> Vec<usize> {
        distinct(faces)
    }
}

/// The distinct nodes of some faces, sorted.
fn distinct(faces: &[Vec<usize>]) -> Vec<usize> {
    let mut nodes: Vec<usize> = faces.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
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
        assert_eq!(body.elements, vec![vec![0, 1, 2, 3]]);
        assert_eq!(body.contact, vec![vec![0, 2, 1]]);
        assert_eq!(
            (body.far.clone(), body.symmetry.clone()),
            (vec![1, 2, 3], vec![0, 1, 3])
        );
        assert_eq!(body.candidate_faces(1.1e-3).len(), 1);
        assert!(body.candidate_faces(0.9e-3).is_empty());
    }

    /// Requirement: the whole body of the half tetrahedron is it and its mirror image through
    /// y = 0 sharing the plane's nodes (0, 1, 3), the image positively oriented (signed volume
    /// +1/6 mm³ as the original's) with its contact face pointing out (−z), the far face both
    /// halves', no symmetry plane left. Exact: indices; the volumes to round-off (1e-25 m³ on
    /// 1.7e-10 m³).
    #[test]
    fn the_whole_body_is_the_half_and_its_mirror_image_joined_on_the_plane() {
        let half = LinearBody::of(&tetrahedron()).unwrap();
        let whole = half.whole();
        assert_eq!(whole.nodes.len(), 5);
        assert_eq!(whole.nodes[4], [0.0, -1e-3, 0.0]);
        assert_eq!(whole.elements, vec![vec![0, 1, 2, 3], vec![0, 4, 1, 3]]);
        let volume = |e: &[usize]| {
            let p: Vec<[f64; 3]> = e.iter().map(|&n| whole.nodes[n]).collect();
            let [a, b, c] = [1, 2, 3].map(|k| sub(p[k], p[0]));
            dot(a, crate::kratos::vector::cross(b, c)) / 6.0
        };
        for e in &whole.elements {
            assert!((volume(e) - 1e-9 / 6.0).abs() < 1e-25, "{e:?}: {}", volume(e));
        }
        assert_eq!(whole.contact, vec![vec![0, 2, 1], vec![0, 1, 4]]);
        for f in &whole.contact {
            let p: Vec<[f64; 3]> = f.iter().map(|&n| whole.nodes[n]).collect();
            assert!(area_vector(&p)[2] < 0.0, "{f:?}");
        }
        assert_eq!(whole.far, vec![1, 2, 3, 4]);
        assert!(whole.symmetry.is_empty());
    }

    /// Requirement: a brick's bottom face (z = 0), listed with its normal up (into the brick), is
    /// turned round to point down, out of it, and a face of no brick is refused by name; exact.
    #[test]
    fn a_bricks_contact_face_points_out_and_a_stray_face_is_refused() {
        let nodes: Vec<[f64; 3]> = (0..8)
            .map(|k| {
                let [x, y] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]][k % 4];
                [x * 1e-3, y * 1e-3, (k / 4) as f64 * 1e-3]
            })
            .collect();
        let boundary = |contact: Vec<usize>| Boundary {
            contact: vec![contact],
            far: vec![vec![4, 5, 6, 7]],
            symmetry: vec![vec![0, 1, 5, 4]],
        };
        let bricks = vec![(0..8).collect::<Vec<usize>>()];
        let body = LinearBody::new(
            Element::Hex8,
            nodes.clone(),
            bricks.clone(),
            &boundary(vec![0, 1, 2, 3]),
        )
        .unwrap();
        assert_eq!(body.contact, vec![vec![0, 3, 2, 1]]);
        assert_eq!(body.far, vec![4, 5, 6, 7]);
        let e = LinearBody::new(Element::Hex8, nodes, bricks, &boundary(vec![0, 1, 6, 7])).unwrap_err();
        assert!(e.contains("face of no hex8"), "{e}");
    }
}
