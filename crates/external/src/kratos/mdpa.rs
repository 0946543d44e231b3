//! Writing the MDPA (Kratos' model part file) of `kratos-3d`: both spheres' first-order
//! elements ([`LinearBody`], tetrahedra or bricks; sphere 2 the mirror image of sphere 1 through
//! the contact plane z = 0, numbered after it, its elements in [`mirror_order`] to stay right
//! side out), the candidate contact faces as `SurfaceCondition3D3N` or `…3D4N` skins in the
//! sub-model-parts `Slave` (sphere 1) and `Master` (sphere 2), the node sets the driver holds:
//! `Far1`, `Far2` (the far faces) and `Symmetry` (the plane y = 0 of a half body, empty on the
//! whole), and `Reported`, the slave nodes whose surface values the driver writes.
//!
//! Units: mm (the deck's units; the body is in m). Every number is written by Rust's formatting
//! of an `f64` or a `usize`; the only names are this module's own.

use std::fmt::Write;

use super::linear::{mirror_order, reversed, LinearBody};

/// The sub-model-part of every element (the materials file gives it its properties).
pub const SOLID: &str = "Solid";
/// The slave skin: sphere 1's candidate faces.
pub const SLAVE: &str = "Slave";
/// The master skin: sphere 2's candidate faces.
pub const MASTER: &str = "Master";
/// The far faces' nodes of sphere 1 and sphere 2.
pub const FAR: [&str; 2] = ["Far1", "Far2"];
/// The nodes held at u_y = 0 on the plane of symmetry.
pub const SYMMETRY: &str = "Symmetry";
/// The slave nodes whose surface values the driver writes (the half's, y ≥ 0).
pub const REPORTED: &str = "Reported";

/// The mesh's file stem (`spheres.mdpa`; ProjectParameters names it without the extension).
pub const STEM: &str = "spheres";

/// What the MDPA is written from.
pub struct MdpaSpec<'a> {
    /// Sphere 1's body [m]: the half (its symmetry plane held on both spheres) or the whole.
    pub body: &'a LinearBody,
    /// Sphere 1's candidate faces (outward), from [`LinearBody::candidate_faces`].
    pub slave_faces: &'a [Vec<usize>],
    /// The slave nodes reported (indices into `body.nodes`, sorted): the half's candidate nodes.
    pub reported: &'a [usize],
}

impl MdpaSpec<'_> {
    /// The number of nodes of one sphere.
    fn count(&self) -> usize {
        self.body.nodes.len()
    }

    /// The MDPA text.
    pub fn text(&self) -> String {
        let n = self.count();
        let e = self.body.elements.len();
        let c = self.slave_faces.len();
        let mut text = String::from(
            "// spherecontact kratos-3d: both spheres (sphere 2 mirrored through z = 0), mm\n\
             Begin ModelPartData\nEnd ModelPartData\n\
             Begin Properties 0\nEnd Properties\nBegin Properties 1\nEnd Properties\n\nBegin Nodes\n",
        );
        for (offset, sign) in [(0, 1.0), (n, -1.0)] {
            for (i, [x, y, z]) in self.body.nodes.iter().enumerate() {
                let _ = writeln!(
                    text,
                    "{} {:e} {:e} {:e}",
                    offset + i + 1,
                    x * 1e3,
                    y * 1e3,
                    sign * z * 1e3 + 0.0
                );
            }
        }
        let element = self.body.element;
        let _ = write!(text, "End Nodes\n\nBegin Elements {}\n", element.keyword());
        for (body, offset) in [(1, 0), (2, n)] {
            for (k, nodes) in self.body.elements.iter().enumerate() {
                let nodes: Vec<usize> = match body {
                    1 => nodes.clone(),
                    _ => mirror_order(element).iter().map(|&j| nodes[j]).collect(),
                };
                let _ = writeln!(text, "{} 1 {}", (body - 1) * e + k + 1, ids(&nodes, offset));
            }
        }
        let _ = write!(
            text,
            "End Elements\n\nBegin Conditions {}\n",
            element.face_keyword()
        );
        for (body, offset) in [(1, 0), (2, n)] {
            for (k, f) in self.slave_faces.iter().enumerate() {
                // The mirror image of an outward face is inward: reversed.
                let f = if body == 1 { f.clone() } else { reversed(f) };
                let _ = writeln!(text, "{} 0 {}", (body - 1) * c + k + 1, ids(&f, offset));
            }
        }
        text.push_str("End Conditions\n\n");
        let all_nodes: Vec<usize> = (1..=2 * n).collect();
        let all_elements: Vec<usize> = (1..=2 * e).collect();
        sub_model_part(&mut text, SOLID, &all_nodes, &all_elements, &[]);
        let skin = LinearBody::nodes_of(self.slave_faces);
        let slave: Vec<usize> = skin.iter().map(|v| v + 1).collect();
        let master: Vec<usize> = skin.iter().map(|v| v + n + 1).collect();
        sub_model_part(&mut text, SLAVE, &slave, &[], &(1..=c).collect::<Vec<_>>());
        sub_model_part(
            &mut text,
            MASTER,
            &master,
            &[],
            &(c + 1..=2 * c).collect::<Vec<_>>(),
        );
        for (name, offset) in FAR.into_iter().zip([0, n]) {
            let far: Vec<usize> = self.body.far.iter().map(|v| v + offset + 1).collect();
            sub_model_part(&mut text, name, &far, &[], &[]);
        }
        let plane = &self.body.symmetry;
        let held: Vec<usize> = [0, n]
            .into_iter()
            .flat_map(|offset| plane.iter().map(move |v| v + offset + 1))
            .collect();
        sub_model_part(&mut text, SYMMETRY, &held, &[], &[]);
        let reported: Vec<usize> = self.reported.iter().map(|v| v + 1).collect();
        sub_model_part(&mut text, REPORTED, &reported, &[], &[]);
        text
    }
}

/// The 1-based MDPA ids of `nodes` of the sphere numbered from `offset`, space-separated.
fn ids(nodes: &[usize], offset: usize) -> String {
    let ids: Vec<String> = nodes.iter().map(|v| (v + offset + 1).to_string()).collect();
    ids.join(" ")
}

/// Appends a sub-model-part of `nodes`, `elements` and `conditions` (1-based ids).
fn sub_model_part(text: &mut String, name: &str, nodes: &[usize], elements: &[usize], conditions: &[usize]) {
    let _ = writeln!(text, "Begin SubModelPart {name}");
    for (block, ids) in [
        ("Nodes", nodes),
        ("Elements", elements),
        ("Conditions", conditions),
    ] {
        let _ = writeln!(text, "  Begin SubModelPart{block}");
        for id in ids {
            let _ = writeln!(text, "    {id}");
        }
        let _ = writeln!(text, "  End SubModelPart{block}");
    }
    text.push_str("End SubModelPart\n\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kratos::bricks8;
    use crate::kratos::linear::Boundary;
    use spherecontact_model::kratos_settings::Element;

    fn body() -> LinearBody {
        LinearBody {
            element: Element::Tet4,
            nodes: vec![
                [0.0, 0.0, 0.0],
                [1e-3, 0.0, 0.0],
                [0.0, 1e-3, 0.0],
                [0.0, 0.0, 1e-3],
            ],
            elements: vec![vec![0, 1, 2, 3]],
            contact: vec![vec![0, 2, 1]],
            far: vec![1, 2, 3],
            symmetry: vec![0, 1, 3],
        }
    }

    /// Requirement: both spheres, sphere 2 mirrored and right side out, the skins in their
    /// sub-model-parts, both spheres' plane nodes held on the half body and none on the whole,
    /// the reported nodes those asked for; exact text.
    #[test]
    fn both_spheres_their_skins_and_the_held_nodes_are_written() {
        let body = body();
        let spec = MdpaSpec {
            body: &body,
            slave_faces: &body.contact,
            reported: &[0, 2],
        };
        let text = spec.text();
        assert!(text.contains("8 0e0 0e0 -1e0\n"), "{text}");
        assert!(
            text.contains("Begin Elements SmallDisplacementElement3D4N\n1 1 1 2 3 4\n2 1 5 7 6 8\n"),
            "{text}"
        );
        assert!(
            text.contains("Begin Conditions SurfaceCondition3D3N\n1 0 1 3 2\n2 0 5 6 7\n"),
            "{text}"
        );
        let part = |name: &str| {
            text.split(&format!("Begin SubModelPart {name}\n"))
                .nth(1)
                .unwrap()
                .to_owned()
        };
        assert!(part(SLAVE).starts_with("  Begin SubModelPartNodes\n    1\n    2\n    3\n"));
        assert!(part(MASTER).contains("Begin SubModelPartConditions\n    2\n"));
        // The plane's nodes 1, 2, 4 of sphere 1 and their images 5, 6, 8 on sphere 2.
        let held = "  Begin SubModelPartNodes\n    1\n    2\n    4\n    5\n    6\n    8\n  End";
        assert!(part(SYMMETRY).starts_with(held), "{}", part(SYMMETRY));
        assert!(part(REPORTED).starts_with("  Begin SubModelPartNodes\n    1\n    3\n  End"));
        let whole = body.whole();
        let text = MdpaSpec { body: &whole, ..spec }.text();
        let symmetry = text.split("Begin SubModelPart Symmetry\n").nth(1).unwrap();
        assert!(
            symmetry.starts_with("  Begin SubModelPartNodes\n  End"),
            "{symmetry}"
        );
    }

    /// Two bricks of 1 mm side on the contact plane, side by side along x, their bottom faces the
    /// contact candidates, in gmsh's order.
    fn bricks() -> LinearBody {
        let nodes: Vec<[f64; 3]> = (0..12)
            .map(|k| {
                [
                    (k % 3) as f64 * 1e-3,
                    ((k / 3) % 2) as f64 * 1e-3,
                    (k / 6) as f64 * 1e-3,
                ]
            })
            .collect();
        let boundary = Boundary {
            contact: vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]],
            far: vec![vec![6, 7, 10, 9], vec![7, 8, 11, 10]],
            symmetry: vec![vec![0, 1, 7, 6], vec![1, 2, 8, 7]],
        };
        let elements = vec![vec![0, 1, 4, 3, 6, 7, 10, 9], vec![1, 2, 5, 4, 7, 8, 11, 10]];
        LinearBody::new(Element::Hex8, nodes, elements, &boundary).unwrap()
    }

    /// The rows of block `name` of the MDPA `text`, each as its numbers.
    fn block(text: &str, name: &str) -> Vec<Vec<f64>> {
        let body = text.split(&format!("Begin {name}")).nth(1).unwrap();
        let body = body
            .split(&format!("End {}", name.split(' ').next().unwrap()))
            .next()
            .unwrap();
        body.lines()
            .skip(1)
            .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
            .collect()
    }

    /// Requirement: on bricks, the MDPA has Kratos' 8-node element and 4-node skin condition,
    /// both spheres' bricks (2 + 2) and skins (2 + 2), every brick of both spheres positively
    /// oriented (the trilinear Jacobian at the 8 Gauss points of the written node order, sphere 2
    /// the mirror image), the slave skin facing −z (out of sphere 1) and the master's +z (out of
    /// sphere 2). Exact: counts and signs.
    #[test]
    fn bricks_are_written_right_side_out_with_their_quadrangle_skins() {
        let body = bricks();
        let spec = MdpaSpec {
            body: &body,
            slave_faces: &body.contact,
            reported: &[],
        };
        let text = spec.text();
        let nodes: Vec<[f64; 3]> = block(&text, "Nodes").iter().map(|r| [r[1], r[2], r[3]]).collect();
        assert_eq!(nodes.len(), 24);
        let elements = block(&text, "Elements SmallDisplacementElement3D8N");
        assert_eq!(elements.len(), 4);
        for row in &elements {
            assert_eq!(row.len(), 10, "{row:?}");
            let coords: Vec<[f64; 3]> = row[2..].iter().map(|&id| nodes[id as usize - 1]).collect();
            assert!(bricks8::jacobians(&coords).all(|j| j > 0.0), "{row:?}");
        }
        let conditions = block(&text, "Conditions SurfaceCondition3D4N");
        assert_eq!(conditions.len(), 4);
        for (k, row) in conditions.iter().enumerate() {
            let points: Vec<[f64; 3]> = row[2..].iter().map(|&id| nodes[id as usize - 1]).collect();
            let normal = crate::kratos::vector::area_vector(&points);
            let sign = if k < 2 { -1.0 } else { 1.0 };
            assert!(sign * normal[2] > 0.0 && normal[0] == 0.0, "{row:?}: {normal:?}");
        }
    }
}
