//! Reading a body's meridian mesh from a gmsh MSH 4.1 file (ASCII or binary, via `mshio`), so
//! that the same mesh feeds this solver and the external decks.
//!
//! Conventions (those of the `.geo` that `spherecontact mesh` writes, `crates/solvers/src/fem/mesh/geo.rs`): x = r, y = z, the body
//! touching the plane z = 0 at its pole; 6-node triangles (gmsh type 9, `Mesh.ElementOrder = 2`);
//! 3-node lines (type 8) in physical curves [`CONTACT`], [`AXIS`] (r = 0) and the far face:
//! [`FAR`] under the axial grip (displaced along z, free radially) or [`FAR_RIGID`] under the
//! rigid grip (every component follows the imposed motion). The tag records the grip the mesh
//! was made for ([`Mesh::grip`]), so that a solver can refuse a mesh made for another.

use std::collections::HashMap;
use std::path::Path;

use mshio::error::MshParserErrorKind;
use mshio::mshfile::ElementType;

use super::meridian::{self, Mesh, MeshError};
use spherecontact_model::domain::Grip;
use spherecontact_model::limits::MAX_MESH_BYTES;
use spherecontact_system::input::foreign::{self, ForeignError};

/// Physical curve tag of the contact surface.
pub const CONTACT: i32 = 1;
/// Physical curve tag of the far boundary under the axial grip (displaced along the axis).
pub const FAR: i32 = 2;
/// Physical curve tag of the far boundary under the rigid grip (every component imposed).
pub const FAR_RIGID: i32 = 4;
/// Physical curve tag of the symmetry axis.
pub const AXIS: i32 = 3;

/// The nodes of an MSH file: each node's coordinates as `point` takes them (the meridian mesh its
/// x and y, the solid mesh all three), and the lookup from a node tag to its index (tags explicit
/// per block, or consecutive from `min_node_tag`), which names an unknown tag.
pub fn node_table<P>(
    nodes: &mshio::Nodes<u64, i32, f64>,
    point: impl Fn(&mshio::Node<f64>) -> P,
) -> (Vec<P>, impl Fn(&u64) -> Result<usize, String>) {
    let mut index: HashMap<u64, usize> = HashMap::new();
    let mut coords = Vec::new();
    for block in &nodes.node_blocks {
        let base = coords.len();
        match &block.node_tags {
            Some(tags) => index.extend(tags.iter().map(|(&t, &i)| (t, base + i))),
            None => index
                .extend((0..block.nodes.len()).map(|i| (nodes.min_node_tag + (base + i) as u64, base + i))),
        }
        coords.extend(block.nodes.iter().map(&point));
    }
    let lookup = move |tag: &u64| {
        index
            .get(tag)
            .copied()
            .ok_or_else(|| format!("unknown node tag {tag}"))
    };
    (coords, lookup)
}

/// Reads the MSH 4.1 file at `path`.
pub fn read(path: &Path) -> Result<Mesh, MeshError> {
    let bytes = file_bytes(path).map_err(|e| MeshError::File(e.to_string()))?;
    parse(&bytes).map_err(|e| match e {
        MeshError::File(why) => MeshError::File(format!("{}: {why}", path.display())),
        other => other,
    })
}

/// The bytes of the mesh file at `path`, read as a file from elsewhere (a mesh may come back in a
/// deck's folder: docs/security.md, "Deck folders"): a regular file, a link only to a file in its
/// folder, at most [`MAX_MESH_BYTES`].
pub fn file_bytes(path: &Path) -> Result<Vec<u8>, ForeignError> {
    foreign::read_bytes(path, MAX_MESH_BYTES)
}

/// The MSH 4.1 file of `bytes`, parsed by mshio; its error is the line of the fault and mshio's
/// words for it, never the bytes (mshio's own message ends with a hex dump of the file from the
/// fault on).
pub fn parse_msh(bytes: &[u8]) -> Result<mshio::MshFile<u64, i32, f64>, String> {
    mshio::parse_msh_bytes(bytes).map_err(|e| {
        // The deepest fault is the first of the backtrace; its input is the rest of the file.
        let rest = e.backtrace.first().map_or(0, |(rest, _)| rest.len());
        let fault = bytes.len().saturating_sub(rest);
        let line = bytes[..fault].iter().filter(|&&b| b == b'\n').count() + 1;
        let what = match e.first_msh_error() {
            Some(MshParserErrorKind::Context(_) | MshParserErrorKind::NomError(_)) | None => {
                "not in the form MSH 4.1 expects".to_owned()
            }
            Some(kind) => kind.to_string(),
        };
        format!("not MSH 4.1 at line {line}: {what}")
    })
}

/// Parses MSH 4.1 bytes into a mesh.
pub fn parse(bytes: &[u8]) -> Result<Mesh, MeshError> {
    let msh = parse_msh(bytes).map_err(MeshError::File)?;
    let data = msh.data;
    let (Some(entities), Some(nodes), Some(elements)) = (data.entities, data.nodes, data.elements) else {
        return Err(MeshError::File(
            "needs $Entities, $Nodes and $Elements sections".into(),
        ));
    };
    let (coords, lookup) = node_table(&nodes, |n| [n.x, n.y]);
    let physical: HashMap<i32, Vec<i32>> = entities
        .curves
        .iter()
        .map(|c| (c.tag, c.physical_tags.clone()))
        .collect();
    let node = |tag: &u64| lookup(tag).map_err(MeshError::File);
    let mut mesh = Mesh {
        nodes: coords,
        ..Mesh::default()
    };
    let mut edges: HashMap<i32, Vec<[usize; 3]>> = HashMap::new();
    for block in &elements.element_blocks {
        match block.element_type {
            ElementType::Tri6 => {
                for e in &block.elements {
                    let t: Vec<usize> = e.nodes.iter().map(node).collect::<Result<_, _>>()?;
                    mesh.triangles.push(counter_clockwise(
                        &mesh.nodes,
                        [t[0], t[1], t[2], t[3], t[4], t[5]],
                    ));
                }
            }
            ElementType::Lin3 => {
                for group in physical.get(&block.entity_tag).into_iter().flatten() {
                    for e in &block.elements {
                        let l: Vec<usize> = e.nodes.iter().map(node).collect::<Result<_, _>>()?;
                        // gmsh order: two ends, then the middle.
                        edges.entry(*group).or_default().push([l[0], l[2], l[1]]);
                    }
                }
            }
            ElementType::Pnt | ElementType::Lin2 | ElementType::Tri3 => {}
            other => {
                return Err(MeshError::File(format!(
                    "element type {other:?} is not supported (6-node triangles and 3-node lines)"
                )))
            }
        }
    }
    mesh.surface = contact_surface(&mesh.nodes, edges.remove(&CONTACT).unwrap_or_default())?;
    let (axial, rigid) = (edges.remove(&FAR), edges.remove(&FAR_RIGID));
    mesh.grip = match (&axial, &rigid) {
        (Some(_), None) => Some(Grip::Axial),
        (None, Some(_)) => Some(Grip::Rigid),
        (Some(_), Some(_)) => {
            return Err(MeshError::File(format!(
            "the far face is tagged both {FAR} (axial grip) and {FAR_RIGID} (rigid grip): one grip per mesh"
        )))
        }
        (None, None) => None,
    };
    mesh.far = nodes_of(axial.or(rigid).unwrap_or_default());
    mesh.axis = nodes_of(edges.remove(&AXIS).unwrap_or_default());
    if mesh.triangles.is_empty() || mesh.far.is_empty() || mesh.axis.is_empty() {
        return Err(MeshError::File(format!(
            "needs 6-node triangles and 3-node lines in physical curves {CONTACT} (contact), {FAR} or \
             {FAR_RIGID} (far face, axial or rigid grip), {AXIS} (axis)"
        )));
    }
    meridian::validate(&mesh)?;
    Ok(mesh)
}

/// Reorders a 6-node triangle counter-clockwise (gmsh's may be either way round).
fn counter_clockwise(nodes: &[[f64; 2]], t: [usize; 6]) -> [usize; 6] {
    let [a, b, c] = [t[0], t[1], t[2]].map(|n| nodes[n]);
    let area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if area > 0.0 {
        t
    } else {
        [t[0], t[2], t[1], t[5], t[4], t[3]]
    }
}

/// Contact edges oriented outwards from the pole and chained by r; the pole must be on the axis.
fn contact_surface(nodes: &[[f64; 2]], mut edges: Vec<[usize; 3]>) -> Result<Vec<[usize; 3]>, MeshError> {
    for e in &mut edges {
        if nodes[e[0]][0] > nodes[e[2]][0] {
            e.swap(0, 2);
        }
    }
    edges.sort_by(|a, b| nodes[a[0]][0].total_cmp(&nodes[b[0]][0]));
    let chained = edges.windows(2).all(|w| w[0][2] == w[1][0]);
    let starts_on_axis = edges.first().is_some_and(|e| nodes[e[0]][0] == 0.0);
    if edges.is_empty() || !chained || !starts_on_axis {
        return Err(MeshError::File(format!(
            "the contact curve (physical {CONTACT}) must be one chain of 3-node lines starting on the axis"
        )));
    }
    Ok(edges)
}

/// The distinct nodes of some edges.
fn nodes_of(edges: Vec<[usize; 3]>) -> Vec<usize> {
    let mut nodes: Vec<usize> = edges.into_iter().flatten().collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}
