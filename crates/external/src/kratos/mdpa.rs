//! Writing the MDPA (Kratos' model part file) of `kratos-3d`: both spheres' first-order
//! tetrahedra ([`LinearBody`]; sphere 2 the mirror image of sphere 1 through the contact plane
//! z = 0, numbered after it), the candidate contact faces as `SurfaceCondition3D3N` skins in the
//! sub-model-parts `Slave` (sphere 1) and `Master` (sphere 2), and the node sets the driver holds:
//! `Far1`, `Far2` (the far faces) and `Symmetry` (the plane y = 0).
//!
//! Units: mm (the deck's units; the body is in m). Every number is written by Rust's formatting
//! of an `f64` or a `usize`; the only names are this module's own.

use std::fmt::Write;

use super::linear::LinearBody;
use spherecontact_model::kratos_settings::Element;

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

/// The mesh's file stem (`spheres.mdpa`; ProjectParameters names it without the extension).
pub const STEM: &str = "spheres";

/// What the MDPA is written from.
pub struct MdpaSpec<'a> {
    /// The half body [m].
    pub body: &'a LinearBody,
    /// Sphere 1's candidate faces (outward), from [`LinearBody::candidate_faces`].
    pub slave_faces: &'a [[usize; 3]],
    /// The element.
    pub element: Element,
    /// Whether the master's candidate nodes on the symmetry plane are left free in y (frictional
    /// contact: there the stick condition ties them to the slave's nodes, which are held; holding
    /// both would repeat one constraint and make Kratos' system singular).
    pub free_master_plane: bool,
}

impl MdpaSpec<'_> {
    /// The number of nodes of one sphere.
    fn count(&self) -> usize {
        self.body.nodes.len()
    }

    /// The MDPA text.
    pub fn text(&self) -> String {
        let n = self.count();
        let e = self.body.tetrahedra.len();
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
        let _ = write!(text, "End Nodes\n\nBegin Elements {}\n", self.element.keyword());
        for (body, offset) in [(1, 0), (2, n)] {
            for (k, t) in self.body.tetrahedra.iter().enumerate() {
                // Mirroring turns a tetrahedron inside out: corners 2 and 3 swapped.
                let t = if body == 1 { *t } else { [t[0], t[2], t[1], t[3]] };
                let [a, b, cc, d] = t.map(|v| v + offset + 1);
                let _ = writeln!(text, "{} 1 {a} {b} {cc} {d}", (body - 1) * e + k + 1);
            }
        }
        let _ = write!(
            text,
            "End Elements\n\nBegin Conditions {}\n",
            self.element.face_keyword()
        );
        for (body, offset) in [(1, 0), (2, n)] {
            for (k, f) in self.slave_faces.iter().enumerate() {
                // The mirror image of an outward face is inward: reversed.
                let f = if body == 1 { *f } else { [f[0], f[2], f[1]] };
                let [a, b, cc] = f.map(|v| v + offset + 1);
                let _ = writeln!(text, "{} 0 {a} {b} {cc}", (body - 1) * c + k + 1);
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
        sub_model_part(&mut text, SYMMETRY, &self.held_on_plane(&skin), &[], &[]);
        text
    }

    /// The plane's nodes of both spheres held at u_y = 0 (1-based ids): all of them, but for the
    /// master's candidate nodes when [`MdpaSpec::free_master_plane`].
    fn held_on_plane(&self, skin: &[usize]) -> Vec<usize> {
        let n = self.count();
        let mut held: Vec<usize> = self.body.symmetry.iter().map(|v| v + 1).collect();
        held.extend(
            self.body
                .symmetry
                .iter()
                .filter(|v| !(self.free_master_plane && skin.binary_search(v).is_ok()))
                .map(|v| v + n + 1),
        );
        held
    }
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

    fn body() -> LinearBody {
        LinearBody {
            nodes: vec![
                [0.0, 0.0, 0.0],
                [1e-3, 0.0, 0.0],
                [0.0, 1e-3, 0.0],
                [0.0, 0.0, 1e-3],
            ],
            tetrahedra: vec![[0, 1, 2, 3]],
            contact: vec![[0, 2, 1]],
            far: vec![1, 2, 3],
            symmetry: vec![0, 1, 3],
        }
    }

    /// Requirement: both spheres, sphere 2 mirrored and right side out, the skins in their
    /// sub-model-parts, the master's plane nodes free only under friction; exact text.
    #[test]
    fn both_spheres_their_skins_and_the_held_nodes_are_written() {
        let body = body();
        let spec = MdpaSpec {
            body: &body,
            slave_faces: &body.contact,
            element: Element::Tet4,
            free_master_plane: true,
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
        // The plane's nodes 1, 2, 4 of sphere 1 and of sphere 2 (5, 6, 8), less the master's
        // candidate nodes 5 and 6 (node 4's image 8 is not a candidate).
        assert!(part(SYMMETRY).starts_with("  Begin SubModelPartNodes\n    1\n    2\n    4\n    8\n  End"));
        let held = MdpaSpec {
            free_master_plane: false,
            ..spec
        }
        .text();
        assert!(held.contains("    4\n    5\n    6\n    8\n  End SubModelPartNodes"));
    }
}
