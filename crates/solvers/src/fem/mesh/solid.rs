//! The 3D mesh of one body: 10-node tetrahedra and the 6-node faces of its boundary groups, read
//! from a gmsh MSH 4.1 file (ASCII or binary) through `mshio`.
//!
//! Frame and conventions (those of the `.geo` that `crates/solvers/src/fem/mesh/solid_geo.rs` writes): the body
//! touches the contact plane z = 0 at its pole (the origin) and lies in z ≥ 0; the shift is along
//! x and the half body y ≥ 0 is meshed. Physical groups: surface [`CONTACT`] (the contact
//! candidate surface), surface [`FAR`] (the gripped far face), surface [`SYMMETRY`] (the plane
//! y = 0) and a volume [`BODY`]. Elements: 10-node tetrahedra (gmsh type 11) in the body,
//! 6-node triangles (type 9) on the surfaces (`Mesh.ElementOrder = 2`).

use std::path::{Path, PathBuf};

use mshio::mshfile::ElementType;

use super::groups;
use crate::fem::element::tet10;

/// Physical surface tag of the contact candidate surface.
pub const CONTACT: i32 = 1;
/// Physical surface tag of the gripped far face.
pub const FAR: i32 = 2;
/// Physical surface tag of the symmetry plane y = 0.
pub const SYMMETRY: i32 = 3;
/// Physical volume tag of the body.
pub const BODY: i32 = 10;

/// A body's mesh of 10-node tetrahedra with its boundary groups.
#[derive(Clone, Debug, Default)]
pub struct SolidMesh {
    /// Node coordinates [m].
    pub nodes: Vec<[f64; 3]>,
    /// Elements in gmsh's node order ([`tet10`]), positively oriented.
    pub tetrahedra: Vec<[usize; 10]>,
    /// The faces of the contact candidate surface (gmsh's 6-node triangle order).
    pub contact: Vec<[usize; 6]>,
    /// The faces of the gripped far face.
    pub far: Vec<[usize; 6]>,
    /// The faces on the symmetry plane y = 0.
    pub symmetry: Vec<[usize; 6]>,
}

impl SolidMesh {
    /// The distinct nodes of some faces, sorted.
    pub fn nodes_of(faces: &[[usize; 6]]) -> Vec<usize> {
        let mut nodes: Vec<usize> = faces.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// The coordinates of element `e`.
    pub fn coords(&self, e: usize) -> tet10::Coords {
        self.tetrahedra[e].map(|n| self.nodes[n])
    }

    /// The coordinates of a face.
    pub fn face_coords(&self, face: &[usize; 6]) -> [[f64; 3]; 6] {
        face.map(|n| self.nodes[n])
    }
}

/// Why a solid mesh cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum SolidMeshError {
    /// A file that cannot be read or does not hold what this model needs.
    #[error("mesh file {}: {problem}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        problem: String,
    },
    /// An element with a non-positive Jacobian.
    #[error("element {0} is inverted or degenerate")]
    Inverted(usize),
}

/// Reads the MSH 4.1 file at `path`.
pub fn read(path: &Path) -> Result<SolidMesh, SolidMeshError> {
    let file_error = |problem: String| SolidMeshError::File {
        path: path.to_path_buf(),
        problem,
    };
    let bytes =
        super::msh::file_bytes(path).map_err(|e| file_error(format!("cannot be read: {}", e.problem)))?;
    parse(&bytes).map_err(file_error)
}

/// Parses MSH 4.1 bytes; the error says what is missing or wrong.
pub fn parse(bytes: &[u8]) -> Result<SolidMesh, String> {
    let kinds = groups::Kinds {
        element: ElementType::Tet10,
        face: ElementType::Tri6,
        skipped: &[
            ElementType::Tet4,
            ElementType::Tri3,
            ElementType::Pnt,
            ElementType::Lin2,
            ElementType::Lin3,
        ],
        wanted: "10-node tetrahedra and 6-node triangles",
        body: BODY,
    };
    let mut read = groups::parse::<10, 6>(bytes, &kinds)?;
    if read.elements.is_empty() {
        if let Some(kind) = read
            .skipped
            .iter()
            .find(|k| matches!(k, ElementType::Tet4 | ElementType::Tri3))
        {
            return Err(format!(
                "first-order elements ({kind:?}): the model needs quadratic ones (gmsh -order 2, or \
                 Mesh.ElementOrder = 2)"
            ));
        }
        return Err(format!(
            "no 10-node tetrahedra in physical volume {BODY} (\"body\")"
        ));
    }
    let what = "6-node triangles";
    let mut mesh = SolidMesh {
        contact: read.take(CONTACT, "contact", what)?,
        far: read.take(FAR, "far", what)?,
        symmetry: read.take(SYMMETRY, "symmetry", what)?,
        nodes: read.nodes,
        tetrahedra: read.elements,
    };
    orient(&mut mesh).map_err(|e| e.to_string())?;
    Ok(mesh)
}

/// Makes every element positively oriented (gmsh's may be either way round) and refuses
/// degenerate ones.
fn orient(mesh: &mut SolidMesh) -> Result<(), SolidMeshError> {
    for e in 0..mesh.tetrahedra.len() {
        let centroid = [0.25; 3];
        if tet10::map(&mesh.coords(e), centroid).is_some() {
            continue;
        }
        // Swap corners 1 and 2: edges 0–1 ↔ 2–0 and 3–1 ↔ 3–2 swap with them.
        let t = &mut mesh.tetrahedra[e];
        t.swap(1, 2);
        t.swap(4, 6);
        t.swap(8, 9);
        if tet10::map(&mesh.coords(e), centroid).is_none() {
            return Err(SolidMeshError::Inverted(e));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An ASCII MSH 4.1 text of the reference 10-node tetrahedron (or, with `first_order`, its
    /// 4-node version) with a 6-node face in each of the physical surfaces `groups`.
    fn msh(groups: &[i32], first_order: bool) -> String {
        let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n");
        s += &format!("0 0 {} 1\n", groups.len());
        for (k, g) in groups.iter().enumerate() {
            s += &format!("{} 0 0 0 1 1 1 1 {g} 0\n", k + 1);
        }
        s += "1 0 0 0 1 1 1 1 10 0\n$EndEntities\n$Nodes\n1 10 1 10\n3 1 0 10\n";
        for tag in 1..=10 {
            s += &format!("{tag}\n");
        }
        for p in tet10::NODES {
            s += &format!("{} {} {}\n", p[0], p[1], p[2]);
        }
        s += &format!(
            "$EndNodes\n$Elements\n{} {} 1 {}\n",
            groups.len() + 1,
            groups.len() + 1,
            groups.len() + 1
        );
        let faces = [[1, 2, 3, 5, 6, 7], [1, 2, 4, 5, 10, 8], [1, 3, 4, 7, 9, 8]];
        for (k, f) in faces.iter().take(groups.len()).enumerate() {
            let f: &[usize] = if first_order { &f[..3] } else { f };
            let nodes: Vec<String> = f.iter().map(ToString::to_string).collect();
            s += &format!(
                "2 {} {} 1\n{} {}\n",
                k + 1,
                if first_order { 2 } else { 9 },
                k + 1,
                nodes.join(" ")
            );
        }
        let (kind, count) = if first_order { (4, 4) } else { (11, 10) };
        let nodes: Vec<String> = (1..=count).map(|t: usize| t.to_string()).collect();
        s += &format!(
            "3 1 {kind} 1\n{} {}\n$EndElements\n",
            groups.len() + 1,
            nodes.join(" ")
        );
        s
    }

    #[test]
    fn a_quadratic_mesh_with_its_groups_is_read() {
        let mesh = parse(msh(&[CONTACT, FAR, SYMMETRY], false).as_bytes()).unwrap();
        assert_eq!(mesh.tetrahedra, vec![[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]]);
        assert_eq!(mesh.contact, vec![[0, 1, 2, 4, 5, 6]]);
        assert_eq!(mesh.far.len(), 1);
        assert_eq!(mesh.symmetry.len(), 1);
    }

    #[test]
    fn missing_groups_and_first_order_elements_are_named() {
        let missing = parse(msh(&[CONTACT, SYMMETRY], false).as_bytes()).unwrap_err();
        assert!(missing.contains("physical surface 2 (\"far\")"), "{missing}");
        let linear = parse(msh(&[CONTACT, FAR, SYMMETRY], true).as_bytes()).unwrap_err();
        assert!(
            linear.contains("first-order") && linear.contains("-order 2"),
            "{linear}"
        );
    }

    #[test]
    fn the_error_names_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("body.msh");
        std::fs::write(&path, msh(&[CONTACT, FAR], false)).unwrap();
        let message = read(&path).unwrap_err().to_string();
        assert!(
            message.contains(&path.display().to_string()) && message.contains("symmetry"),
            "{message}"
        );
        let absent = read(&dir.path().join("absent.msh")).unwrap_err().to_string();
        assert!(
            absent.contains("absent.msh") && absent.contains("cannot be read"),
            "{absent}"
        );
    }

    #[test]
    fn an_inverted_element_is_turned_round() {
        let mut mesh = SolidMesh {
            nodes: tet10::NODES.to_vec(),
            tetrahedra: vec![[0, 2, 1, 3, 6, 5, 4, 7, 9, 8]],
            ..SolidMesh::default()
        };
        orient(&mut mesh).unwrap();
        assert_eq!(mesh.tetrahedra[0], [0, 1, 2, 3, 4, 5, 6, 7, 8, 9]);
    }
}
