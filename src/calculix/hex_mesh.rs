//! The paper's discretisation: a mesh of 20-node hexahedra (CalculiX's C3D20/C3D20R, the
//! counterpart of ANSYS's SOLID186) of the same half body as fem-3d's tetrahedra, graded towards
//! the contact alike, read back in CalculiX's node order.
//!
//! How: the body, its physical groups and its size field are [`SolidGeometry::geo`]'s (the half
//! hemisphere or cap y ≥ 0: surface 1 the contact candidate, 2 the gripped far face, 3 the
//! symmetry plane y = 0, volume 10 the body), meshed with tetrahedra of twice the size and
//! subdivided by gmsh into hexahedra (`Mesh.SubdivisionAlgorithm = 2`: each tetrahedron into four
//! bricks through its edge midpoints, face centroids and centroid, so the bricks' edges are
//! about the size asked for), quadratic serendipity (`Mesh.ElementOrder = 2`,
//! `Mesh.SecondOrderIncomplete = 1`: 20-node bricks, 8-node faces, midside nodes on the sphere).
//! Why not transfinite: the body is a boolean of a sphere and a box whose faces are not
//! four-sided, so a transfinite (structured) hex mesh would need a hand-made block decomposition
//! of the quarter ball, different for the cap and the hemisphere; the subdivision keeps the one
//! geometry and the one grading of fem-3d's mesh.
//!
//! The faces of each group are 8-node quadrangles (gmsh's order is CalculiX's); the bricks are
//! permuted to CalculiX's order ([`hex20::GMSH_TO_CCX`]) and turned round where inverted.

use std::collections::HashMap;
use std::path::Path;

use mshio::mshfile::ElementType;

use super::hex20;
use crate::external::solid_geo::{self, SolidGeometry, SolidMeshFiles};
use crate::external::toolchain::Toolchain;
use crate::fem::mesh::solid::{BODY, CONTACT, FAR, SYMMETRY};
use crate::solver::SolveError;

/// The options appended to the tetrahedral `.geo`: subdivision into hexahedra, 20-node bricks.
const HEX_OPTIONS: &str = "// spherecontact: 20-node hexahedra by subdividing the tetrahedra (each into 4)
Mesh.SubdivisionAlgorithm = 2;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
";

/// A half body of 20-node bricks with its boundary groups.
#[derive(Clone, Debug, Default)]
pub struct HexMesh {
    /// Node coordinates [m].
    pub nodes: Vec<[f64; 3]>,
    /// Bricks in CalculiX's node order, positively oriented.
    pub hexahedra: Vec<[usize; 20]>,
    /// The 8-node faces of the contact candidate surface.
    pub contact: Vec<[usize; 8]>,
    /// The faces of the gripped far face.
    pub far: Vec<[usize; 8]>,
    /// The faces on the symmetry plane y = 0.
    pub symmetry: Vec<[usize; 8]>,
}

/// The Jacobian's figures over every brick's 27 Gauss points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quality {
    /// The smallest determinant [m³ per unit reference volume].
    pub min_jacobian: f64,
    /// The smallest ratio of a point's determinant to its element's largest (1 for a
    /// parallelepiped; near 0 for a brick about to fold).
    pub min_ratio: f64,
    /// The body's volume by the 27-point rule [m³].
    pub volume: f64,
}

/// The `.geo` of the hexahedral mesh of `geometry` (whose pole size and largest size are the
/// bricks'): the tetrahedral geometry at twice the sizes, subdivided.
pub fn geo(geometry: &SolidGeometry) -> Result<String, String> {
    let tetrahedra = SolidGeometry {
        pole_size: 2.0 * geometry.pole_size,
        max_size: 2.0 * geometry.max_size,
        ..*geometry
    };
    Ok(tetrahedra.geo()? + HEX_OPTIONS)
}

/// Meshes `geometry` into `<dir>/<stem>.msh` and reads it back.
pub fn mesh(
    geometry: &SolidGeometry,
    dir: &Path,
    stem: &str,
    toolchain: &Toolchain,
) -> Result<(HexMesh, SolidMeshFiles), SolveError> {
    let text = geo(geometry).map_err(SolveError::NotApplicable)?;
    let files = solid_geo::mesh_geo(&text, dir, stem, toolchain)?;
    let bytes = std::fs::read(&files.msh)
        .map_err(|e| SolveError::Failed(format!("reading {}: {e}", files.msh.display())))?;
    let mesh = parse(&bytes).map_err(|e| SolveError::Failed(format!("{}: {e}", files.msh.display())))?;
    Ok((mesh, files))
}

/// Parses MSH 4.1 bytes of 20-node bricks and 8-node faces; the error says what is missing.
pub fn parse(bytes: &[u8]) -> Result<HexMesh, String> {
    let msh = mshio::parse_msh_bytes(bytes).map_err(|e| format!("not MSH 4.1: {e}"))?;
    let data = msh.data;
    let (Some(entities), Some(nodes), Some(elements)) = (data.entities, data.nodes, data.elements) else {
        return Err("needs $Entities, $Nodes and $Elements sections".into());
    };
    let (coords, node) = crate::fem::mesh::msh::node_table(&nodes, |n| [n.x, n.y, n.z]);
    let groups = |tags: &mut dyn Iterator<Item = (i32, &Vec<i32>)>| -> HashMap<i32, Vec<i32>> {
        tags.map(|(t, g)| (t, g.clone())).collect()
    };
    let surface_groups = groups(&mut entities.surfaces.iter().map(|s| (s.tag, &s.physical_tags)));
    let volume_groups = groups(&mut entities.volumes.iter().map(|v| (v.tag, &v.physical_tags)));
    let mut mesh = HexMesh {
        nodes: coords,
        ..HexMesh::default()
    };
    let mut faces: HashMap<i32, Vec<[usize; 8]>> = HashMap::new();
    for block in &elements.element_blocks {
        let rows = || {
            block
                .elements
                .iter()
                .map(|e| e.nodes.iter().map(&node).collect::<Result<Vec<usize>, _>>())
        };
        match block.element_type {
            ElementType::Hex20 => {
                if volume_groups
                    .get(&block.entity_tag)
                    .is_some_and(|g| g.contains(&BODY))
                {
                    for row in rows() {
                        let row = row?;
                        mesh.hexahedra.push(hex20::GMSH_TO_CCX.map(|k| row[k]));
                    }
                }
            }
            ElementType::Qua8 => {
                for group in surface_groups.get(&block.entity_tag).into_iter().flatten() {
                    for row in rows() {
                        let row = row?;
                        faces
                            .entry(*group)
                            .or_default()
                            .push(std::array::from_fn(|k| row[k]));
                    }
                }
            }
            ElementType::Pnt | ElementType::Lin3 => {}
            other => {
                return Err(format!(
                    "element type {other:?} is not supported (20-node hexahedra and 8-node quadrangles: \
                     Mesh.SubdivisionAlgorithm = 2, Mesh.ElementOrder = 2, Mesh.SecondOrderIncomplete = 1)"
                ))
            }
        }
    }
    if mesh.hexahedra.is_empty() {
        return Err(format!(
            "no 20-node hexahedra in physical volume {BODY} (\"body\")"
        ));
    }
    let mut group = |tag: i32, name: &str| {
        faces
            .remove(&tag)
            .filter(|f| !f.is_empty())
            .ok_or_else(|| format!("no 8-node quadrangles in physical surface {tag} (\"{name}\")"))
    };
    mesh.contact = group(CONTACT, "contact")?;
    mesh.far = group(FAR, "far")?;
    mesh.symmetry = group(SYMMETRY, "symmetry")?;
    mesh.orient()?;
    Ok(mesh)
}

impl HexMesh {
    /// The coordinates of brick `e`.
    pub fn coords(&self, e: usize) -> [[f64; 3]; 20] {
        self.hexahedra[e].map(|n| self.nodes[n])
    }

    /// Turns every brick with a negative Jacobian at its centre round ([`hex20::mirror`]);
    /// refuses one whose Jacobian changes sign within it.
    fn orient(&mut self) -> Result<(), String> {
        let mirror = hex20::mirror();
        for e in 0..self.hexahedra.len() {
            if hex20::jacobian(&self.coords(e), [0.0; 3]) < 0.0 {
                let h = self.hexahedra[e];
                self.hexahedra[e] = mirror.map(|k| h[k]);
            }
            if hex20::jacobians(&self.coords(e)).any(|j| j <= 0.0) {
                return Err(format!(
                    "brick {e} is folded: its Jacobian is not positive at every Gauss point"
                ));
            }
        }
        Ok(())
    }

    /// The Jacobian's figures and the volume.
    pub fn quality(&self) -> Quality {
        let mut quality = Quality {
            min_jacobian: f64::INFINITY,
            min_ratio: f64::INFINITY,
            volume: 0.0,
        };
        for e in 0..self.hexahedra.len() {
            let coords = self.coords(e);
            let j: Vec<f64> = hex20::jacobians(&coords).collect();
            let (low, high) = j
                .iter()
                .fold((f64::INFINITY, 0.0_f64), |(l, h), &x| (l.min(x), h.max(x)));
            quality.min_jacobian = quality.min_jacobian.min(low);
            quality.min_ratio = quality.min_ratio.min(low / high);
            quality.volume += hex20::volume(&coords);
        }
        quality
    }

    /// The total area of some faces [m²].
    pub fn area(&self, faces: &[[usize; 8]]) -> f64 {
        faces
            .iter()
            .map(|f| hex20::quad_area(&f.map(|n| self.nodes[n])))
            .sum()
    }

    /// Each face's brick and its face number (1–6, CalculiX's S1–S6), as `*SURFACE,
    /// TYPE=ELEMENT` names them (both 0-based brick and 1-based face).
    pub fn element_faces(&self, faces: &[[usize; 8]]) -> Result<Vec<(usize, usize)>, String> {
        let key = |corners: [usize; 4]| {
            let mut k = corners;
            k.sort_unstable();
            k
        };
        let mut index: HashMap<[usize; 4], (usize, usize)> = HashMap::new();
        for (e, h) in self.hexahedra.iter().enumerate() {
            for (f, face) in hex20::FACES.iter().enumerate() {
                index.insert(key([0, 1, 2, 3].map(|k| h[face[k]])), (e, f + 1));
            }
        }
        faces
            .iter()
            .map(|q| {
                index
                    .get(&key([q[0], q[1], q[2], q[3]]))
                    .copied()
                    .ok_or_else(|| format!("face {q:?} is the side of no brick"))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One reference brick (gmsh type 17; 11: a 10-node tetrahedron on its first nodes), its nodes
    /// tagged in gmsh's order, with one face in each group.
    fn msh(brick_type: u32) -> String {
        let ccx_of_gmsh: [usize; 20] =
            std::array::from_fn(|g| hex20::GMSH_TO_CCX.iter().position(|&k| k == g).unwrap());
        let mut s = String::from(
            "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 3 1\n\
             1 0 0 0 1 1 1 1 1 0\n2 0 0 0 1 1 1 1 2 0\n3 0 0 0 1 1 1 1 3 0\n\
             1 0 0 0 1 1 1 1 10 0\n$EndEntities\n$Nodes\n1 20 1 20\n3 1 0 20\n",
        );
        for tag in 1..=20 {
            s += &format!("{tag}\n");
        }
        for k in ccx_of_gmsh {
            let [a, b, c] = hex20::NODES[k];
            s += &format!("{a} {b} {c}\n");
        }
        s += "$EndNodes\n$Elements\n4 4 1 4\n";
        for (surface, face) in [1, 2, 3].into_iter().zip([0, 1, 2]) {
            let nodes: Vec<String> = hex20::FACES[face]
                .iter()
                .map(|&k| (hex20::GMSH_TO_CCX[k] + 1).to_string())
                .collect();
            s += &format!("2 {surface} 16 1\n{surface} {}\n", nodes.join(" "));
        }
        let count = if brick_type == 17 { 20 } else { 10 };
        let nodes: Vec<String> = (1..=count).map(|t: usize| t.to_string()).collect();
        s += &format!("3 1 {brick_type} 1\n4 {}\n$EndElements\n", nodes.join(" "));
        s
    }

    #[test]
    fn a_brick_in_gmshs_order_is_read_in_calculixs() {
        let mesh = parse(msh(17).as_bytes()).unwrap();
        let coords = mesh.coords(0);
        assert_eq!(coords, hex20::NODES);
        let q = mesh.quality();
        assert!((q.volume - 8.0).abs() < 1e-12 && (q.min_ratio - 1.0).abs() < 1e-12);
        assert_eq!(mesh.element_faces(&mesh.contact), Ok(vec![(0, 1)]));
        assert_eq!(mesh.element_faces(&mesh.symmetry), Ok(vec![(0, 3)]));
        assert!((mesh.area(&mesh.far) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn tetrahedra_are_refused_by_name() {
        let e = parse(msh(11).as_bytes()).unwrap_err();
        assert!(e.contains("Tet10") && e.contains("SubdivisionAlgorithm"), "{e}");
    }

    #[test]
    fn the_geo_subdivides_tetrahedra_of_twice_the_size() {
        let g = SolidGeometry {
            radius: 0.1,
            height: 0.1,
            pole_size: 1e-4,
            fine_radius: 1.2e-3,
            fine_depth: 2e-4,
            growth: 0.3,
            max_size: 0.015,
        };
        let text = geo(&g).unwrap();
        assert!(
            text.contains("h = 2e-4;") && text.contains("hmax = 3e-2;"),
            "{text}"
        );
        assert!(text.ends_with(HEX_OPTIONS));
    }
}
