//! The paper's discretisation: a mesh of 20-node hexahedra (CalculiX's C3D20/C3D20R, the
//! counterpart of ANSYS's SOLID186) of the same half body as fem-3d's tetrahedra, graded towards
//! the contact alike, read back in CalculiX's node order.
//!
//! How: [`crate::bricks`] (the mesher `kratos-3d`'s 8-node bricks share), at
//! [`Order::Serendipity`] (`Mesh.ElementOrder = 2`, `Mesh.SecondOrderIncomplete = 1`: 20-node
//! bricks, 8-node faces, midside nodes on the sphere), graded by [`bricks::graded`].
//!
//! The faces of each group are 8-node quadrangles (gmsh's order is CalculiX's); the bricks are
//! permuted to CalculiX's order ([`hex20::GMSH_TO_CCX`]) and turned round where inverted.

use std::path::Path;

use mshio::mshfile::ElementType;

use super::hex20;
use crate::bricks::{self, Order};
use spherecontact_model::solver::SolveError;
use spherecontact_solvers::fem::mesh::groups;
use spherecontact_solvers::fem::mesh::solid::{BODY, CONTACT, FAR, SYMMETRY};
use spherecontact_solvers::fem::mesh::solid_geo::{SolidGeometry, SolidMeshFiles};
use spherecontact_system::toolchain::Toolchain;

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

/// Meshes `geometry` into `<dir>/<stem>.msh` and reads it back.
pub fn mesh(
    geometry: &SolidGeometry,
    dir: &Path,
    stem: &str,
    toolchain: &Toolchain,
) -> Result<(HexMesh, SolidMeshFiles), SolveError> {
    let files = bricks::mesh(geometry, Order::Serendipity, dir, stem, toolchain)?;
    let mesh = read(&files.msh).map_err(SolveError::Failed)?;
    Ok((mesh, files))
}

/// Reads the MSH 4.1 file at `path`; the error names the file.
pub fn read(path: &Path) -> Result<HexMesh, String> {
    let bytes = spherecontact_solvers::fem::mesh::msh::file_bytes(path).map_err(|e| e.to_string())?;
    parse(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses MSH 4.1 bytes of 20-node bricks and 8-node faces; the error says what is missing.
pub fn parse(bytes: &[u8]) -> Result<HexMesh, String> {
    let kinds = groups::Kinds {
        element: ElementType::Hex20,
        face: ElementType::Qua8,
        skipped: &[ElementType::Pnt, ElementType::Lin3],
        wanted: "20-node hexahedra and 8-node quadrangles: Mesh.SubdivisionAlgorithm = 2, \
                 Mesh.ElementOrder = 2, Mesh.SecondOrderIncomplete = 1",
        body: BODY,
    };
    let mut read = groups::parse::<20, 8>(bytes, &kinds)?;
    if read.elements.is_empty() {
        return Err(format!(
            "no 20-node hexahedra in physical volume {BODY} (\"body\")"
        ));
    }
    let what = "8-node quadrangles";
    let mut mesh = HexMesh {
        contact: read.take(CONTACT, "contact", what)?,
        far: read.take(FAR, "far", what)?,
        symmetry: read.take(SYMMETRY, "symmetry", what)?,
        hexahedra: read
            .elements
            .iter()
            .map(|row| hex20::GMSH_TO_CCX.map(|k| row[k]))
            .collect(),
        nodes: read.nodes,
    };
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
        assert!((mesh.area(&mesh.far) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn tetrahedra_are_refused_by_name() {
        let e = parse(msh(11).as_bytes()).unwrap_err();
        assert!(e.contains("Tet10") && e.contains("SubdivisionAlgorithm"), "{e}");
    }
}
