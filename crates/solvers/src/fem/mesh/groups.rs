//! The one reader of gmsh MSH 4.1 solid meshes (ASCII or binary, via `mshio`): the nodes, the
//! body's elements of one type in one physical volume, and the faces of one type of each
//! physical surface. fem-3d's 10-node tetrahedra ([`super::solid`]) and CalculiX's 20-node
//! bricks (`calculix::hex_mesh (spherecontact-external)`) are read through it; each then orders and orients its
//! elements.

use std::collections::HashMap;

use mshio::mshfile::ElementType;

/// The element types a mesh is read for.
#[derive(Clone, Copy, Debug)]
pub struct Kinds<'a> {
    /// The body's elements (in the physical volume `body`).
    pub element: ElementType,
    /// The faces of the physical surfaces.
    pub face: ElementType,
    /// Types passed over (points, edges; the caller may name a first-order mesh from them).
    pub skipped: &'a [ElementType],
    /// What the mesh must hold, in words, for the error on another type.
    pub wanted: &'a str,
    /// The physical volume tag of the body.
    pub body: i32,
}

/// What was read: nodes [m], elements and faces in gmsh's node order (0-based node indices).
#[derive(Clone, Debug)]
pub struct Groups<const E: usize, const F: usize> {
    /// Node coordinates.
    pub nodes: Vec<[f64; 3]>,
    /// The body's elements.
    pub elements: Vec<[usize; E]>,
    /// The faces of each physical surface tag.
    pub faces: HashMap<i32, Vec<[usize; F]>>,
    /// The skipped types that were met.
    pub skipped: Vec<ElementType>,
}

impl<const E: usize, const F: usize> Groups<E, F> {
    /// Takes the faces of the physical surface `tag` (called `name`); an error when it has none.
    pub fn take(&mut self, tag: i32, name: &str, what: &str) -> Result<Vec<[usize; F]>, String> {
        self.faces
            .remove(&tag)
            .filter(|f| !f.is_empty())
            .ok_or_else(|| format!("no {what} in physical surface {tag} (\"{name}\")"))
    }
}

/// Parses MSH 4.1 bytes for `kinds`; the error says what is missing or unsupported.
pub fn parse<const E: usize, const F: usize>(bytes: &[u8], kinds: &Kinds) -> Result<Groups<E, F>, String> {
    let msh = super::msh::parse_msh(bytes)?;
    let data = msh.data;
    let (Some(entities), Some(nodes), Some(elements)) = (data.entities, data.nodes, data.elements) else {
        return Err("needs $Entities, $Nodes and $Elements sections".into());
    };
    let (coords, node) = super::msh::node_table(&nodes, |n| [n.x, n.y, n.z]);
    let physical = |tags: &mut dyn Iterator<Item = (i32, &Vec<i32>)>| -> HashMap<i32, Vec<i32>> {
        tags.map(|(t, g)| (t, g.clone())).collect()
    };
    let surface_groups = physical(&mut entities.surfaces.iter().map(|s| (s.tag, &s.physical_tags)));
    let volume_groups = physical(&mut entities.volumes.iter().map(|v| (v.tag, &v.physical_tags)));
    let mut groups = Groups {
        nodes: coords,
        elements: Vec::new(),
        faces: HashMap::new(),
        skipped: Vec::new(),
    };
    for block in &elements.element_blocks {
        let rows = || {
            block
                .elements
                .iter()
                .map(|e| e.nodes.iter().map(&node).collect::<Result<Vec<usize>, _>>())
        };
        let kind = block.element_type;
        if kind == kinds.element {
            if volume_groups
                .get(&block.entity_tag)
                .is_some_and(|g| g.contains(&kinds.body))
            {
                for row in rows() {
                    groups.elements.push(fixed(&row?)?);
                }
            }
        } else if kind == kinds.face {
            for group in surface_groups.get(&block.entity_tag).into_iter().flatten() {
                for row in rows() {
                    groups.faces.entry(*group).or_default().push(fixed(&row?)?);
                }
            }
        } else if kinds.skipped.contains(&kind) {
            groups.skipped.push(kind);
        } else {
            return Err(format!(
                "element type {kind:?} is not supported ({})",
                kinds.wanted
            ));
        }
    }
    Ok(groups)
}

/// A row of node indices as an array of its element type's size.
fn fixed<const N: usize>(row: &[usize]) -> Result<[usize; N], String> {
    row.try_into()
        .map_err(|_| format!("an element with {} nodes where {N} are expected", row.len()))
}
