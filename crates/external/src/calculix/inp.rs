//! Writing the `.inp` of `ccx-axisym` from the shared gmsh meridian mesh: the template
//! (`templates/calculix_axisym.inp`) filled with the mesh, the held strip, the sets and surfaces,
//! the material, the contact and one `*STEP` per path position.
//!
//! Numbers are written with 13 significant digits (`{:.12e}`, at most 20 characters): CalculiX
//! reads each number of a data line from the first 20 characters of its field, so a longer one
//! is cut — silently wrong when the cut leaves a valid number (`1.234567890123456e-10` read as
//! `…e-1`), a fatal `*ERROR reading *NODE` otherwise (measured with ccx 2.20).

use std::collections::HashMap;
use std::fmt::Write;

use spherecontact_model::calculix_settings::{Formulation, Settings, AXISYMMETRIC_ELEMENT};
use spherecontact_model::domain::Grip;
use spherecontact_solvers::fem::mesh::meridian::Mesh;

/// The deck template.
pub const TEMPLATE: &str = include_str!("templates/calculix_axisym.inp");

/// The strip's cells: this many pole elements wide (a master coarser than the slave, as
/// CalculiX's contact search wants; the plane is flat, so its cells do not shape the contact).
const STRIP_CELL_PER_POLE_ELEMENT: f64 = 2.0;

/// The strip's extent beyond the candidate zone (the slave surface's outermost radius).
const STRIP_MARGIN: f64 = 1.5;

/// Cap on the strip's cells (its extent over twice the pole size is at most 1.5 × 1.25 c_max /
/// (2 c_max/320) = 300 cells at the finest resolution allowed).
const MAX_STRIP_CELLS: usize = 400;

/// One computed path position: its index, its path step, and the approach d = δn/2 [m].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PositionStep {
    /// The path position.
    pub position: usize,
    /// Its step on the path.
    pub step: usize,
    /// The modelled sphere's approach d = δn/2 [m].
    pub d: f64,
}

/// What the deck is written from (lengths in metres; the deck is in mm).
pub struct DeckSpec<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// The domain, in words.
    pub domain: String,
    /// The meridian mesh (metres).
    pub mesh: &'a Mesh,
    /// Young's modulus [Pa] and Poisson ratio.
    pub young: f64,
    /// Poisson ratio.
    pub poisson: f64,
    /// Pole element size h [m].
    pub h: f64,
    /// The grip of the far face.
    pub grip: Grip,
    /// Contact candidates: the surface within this radius [m] is the slave.
    pub candidate_radius: f64,
    /// The settings.
    pub settings: Settings,
    /// The positions, in order.
    pub positions: &'a [PositionStep],
}

/// A number as CalculiX reads it (see the module doc).
pub(crate) fn num(x: f64) -> String {
    format!("{x:.12e}")
}

/// The widest number in the data lines of the deck `text`, in characters: CalculiX reads a
/// field of at most 20, so a deck whose widest number is wider is cut short silently.
pub fn widest_number(text: &str) -> usize {
    text.lines()
        .filter(|l| !l.starts_with('*'))
        .flat_map(|l| l.split(',').map(str::trim))
        .filter(|f| f.parse::<f64>().is_ok())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

impl DeckSpec<'_> {
    /// The penalty stiffness K = factor · E / h [MPa/mm].
    pub fn stiffness_mpa_per_mm(&self) -> f64 {
        self.settings.stiffness_mpa_per_mm(self.young, self.h)
    }

    /// The filled deck.
    pub fn text(&self) -> Result<String, String> {
        let slave = self.slave_faces()?;
        let (plane_nodes, plane_elements, master) = self.strip();
        let k = self.stiffness_mpa_per_mm();
        let behaviour = surface_behavior(&self.settings, self.young, k);
        let grip = match self.grip {
            Grip::Rigid => "NFAR, 1, 1, 0.",
            Grip::Axial => "** axial grip: NFAR free in r",
        };
        let keys: [(&str, String); 22] = [
            ("@SCENE@", self.scene.replace(['\n', '`'], " ")),
            ("@DOMAIN@", self.domain.clone()),
            ("@GRIP@", self.grip.name().to_owned()),
            ("@CANDIDATE_MM@", format!("{:.6}", self.candidate_radius * 1e3)),
            ("@PENALTY_FACTOR@", format!("{:e}", self.settings.penalty)),
            ("@K@", format!("{k:.6e}")),
            ("@TRIANGLES@", self.mesh.triangles.len().to_string()),
            ("@H_MM@", format!("{:.6e}", self.h * 1e3)),
            ("@BODY_NODES@", self.body_nodes()),
            ("@ELEMENT@", AXISYMMETRIC_ELEMENT.to_owned()),
            ("@BODY_ELEMENTS@", self.body_elements()),
            ("@PLANE_NODES@", plane_nodes),
            ("@PLANE_ELEMENTS@", plane_elements),
            ("@AXIS_NODES@", node_set(&self.mesh.axis)),
            ("@FAR_NODES@", node_set(&self.mesh.far)),
            ("@SLAVE_FACES@", slave),
            ("@MASTER_FACES@", master),
            ("@E_MPA@", num(self.young * 1e-6)),
            ("@NU@", num(self.poisson)),
            ("@SURFACE_BEHAVIOR@", behaviour),
            ("@CONTACT_TYPE@", self.settings.formulation.keyword().to_owned()),
            ("@GRIP_BOUNDARY@", grip.to_owned()),
        ];
        let text = keys
            .into_iter()
            .fold(TEMPLATE.to_owned(), |t, (key, value)| t.replace(key, &value));
        Ok(text.replace("@STEPS@", &self.steps()))
    }

    fn body_nodes(&self) -> String {
        let mut text = String::new();
        for (i, [r, z]) in self.mesh.nodes.iter().enumerate() {
            let _ = writeln!(text, "{}, {}, {}", i + 1, num(r * 1e3), num(z * 1e3));
        }
        text.trim_end().to_owned()
    }

    fn body_elements(&self) -> String {
        let mut text = String::new();
        for (e, t) in self.mesh.triangles.iter().enumerate() {
            let nodes: Vec<String> = t.iter().map(|n| (n + 1).to_string()).collect();
            let _ = writeln!(text, "{}, {}", e + 1, nodes.join(", "));
        }
        text.trim_end().to_owned()
    }

    /// The slave surface: the faces (element, S1–S3: corners 1–2, 2–3, 3–1) of the contact
    /// surface's edges within the candidate radius.
    fn slave_faces(&self) -> Result<String, String> {
        let mut faces: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
        for (e, t) in self.mesh.triangles.iter().enumerate() {
            for (f, (a, b)) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])].into_iter().enumerate() {
                faces.insert((a.min(b), a.max(b)), (e + 1, f + 1));
            }
        }
        let mut text = String::new();
        for edge in self.candidate_edges() {
            let (a, b) = (edge[0], edge[2]);
            let (element, face) = faces
                .get(&(a.min(b), a.max(b)))
                .ok_or_else(|| format!("contact edge {a}–{b} is not the side of any triangle"))?;
            let _ = writeln!(text, "{element}, S{face}");
        }
        if text.is_empty() {
            return Err("no contact edge within the candidate radius".into());
        }
        Ok(text.trim_end().to_owned())
    }

    /// The contact surface's edges (start, middle, end) whose far end lies within the candidate
    /// radius, from the pole.
    pub fn candidate_edges(&self) -> impl Iterator<Item = &[usize; 3]> {
        let limit = self.candidate_radius * (1.0 + 1e-9);
        self.mesh
            .surface
            .iter()
            .take_while(move |e| self.mesh.nodes[e[2]][0] <= limit)
    }

    /// The held strip: its nodes (numbered after the sphere's), its CAX4 elements (numbered after
    /// the sphere's) and its top faces (S3: nodes 3–4) as the master surface.
    fn strip(&self) -> (String, String, String) {
        let width = STRIP_MARGIN * self.candidate_radius * 1e3;
        let cell_target = STRIP_CELL_PER_POLE_ELEMENT * self.h * 1e3;
        let cells = ((width / cell_target).ceil() as usize).clamp(1, MAX_STRIP_CELLS);
        let cell = width / cells as f64;
        let first_node = self.mesh.nodes.len() + 1;
        let first_element = self.mesh.triangles.len() + 1;
        let (mut nodes, mut elements, mut master) = (String::new(), String::new(), String::new());
        // Row 0 at y = 0 (nodes first_node …), row 1 at y = −cell.
        for (row, y) in [0.0, -cell].into_iter().enumerate() {
            for i in 0..=cells {
                let id = first_node + row * (cells + 1) + i;
                let _ = writeln!(nodes, "{id}, {}, {}", num(i as f64 * cell), num(y));
            }
        }
        for i in 0..cells {
            let top = first_node + i;
            let bottom = top + cells + 1;
            let id = first_element + i;
            // Counter-clockwise in (r, z): bottom left, bottom right, top right, top left.
            let _ = writeln!(elements, "{id}, {bottom}, {}, {}, {top}", bottom + 1, top + 1);
            let _ = writeln!(master, "{id}, S3");
        }
        let trim = |s: String| s.trim_end().to_owned();
        (trim(nodes), trim(elements), trim(master))
    }

    /// One `*STEP` per path position: the far face's approach, the reaction totals of the far
    /// face and of the plane in the `.dat`, the contact pressure at the slave nodes in the
    /// `.frd` (`OUTPUT=3D`: the coordinates of the expanded nodes, which the contact output
    /// names).
    fn steps(&self) -> String {
        let mut text = String::new();
        // ccx 2.20 stops with "no existing contact pair defined" unless the pair is named;
        // node-to-face has no CF totals at all.
        let contact_totals = if self.settings.formulation.face_to_face() {
            "*CONTACT PRINT, TOTALS=ONLY, SLAVE=SSPHERE, MASTER=SPLANE\nCF\n"
        } else {
            ""
        };
        for p in self.positions {
            let _ = write!(
                text,
                "** path position {} (path step {}): delta_n = {} mm, the far face approaches by d = {} mm\n\
                 *STEP, INC=200\n*STATIC\n1., 1.\n*BOUNDARY\nNFAR, 2, 2, {}\n\
                 *NODE PRINT, NSET=NFAR, TOTALS=ONLY\nRF\n*NODE PRINT, NSET=NPLANE, TOTALS=ONLY\nRF\n\
                 {contact_totals}*NODE FILE, OUTPUT=3D, NSET=NFAR\nU\n*CONTACT FILE\nCDIS, CSTR\n*END STEP\n",
                p.position,
                p.step,
                num(2.0 * p.d * 1e3),
                num(p.d * 1e3),
                num(-p.d * 1e3),
            );
        }
        text.trim_end().to_owned()
    }
}

/// The data line of `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR` for penalty `k` [MPa/mm]
/// and Young's modulus `young` [Pa].
pub(crate) fn surface_behavior(settings: &Settings, young: f64, k: f64) -> String {
    match settings.formulation {
        // Node-to-face also takes the tension at large clearances (CalculiX's default 1 MPa
        // pulled on open nodes near the edge): 1e-6 of E, far below any contact pressure.
        Formulation::NodeToFace => format!("{}, {}", num(k), num(1e-6 * young * 1e-6)),
        _ => num(k),
    }
}

/// A node set's data lines: 1-based ids, 16 a line (CalculiX takes at most 16 entries a line).
pub(crate) fn node_set(nodes: &[usize]) -> String {
    nodes
        .chunks(16)
        .map(|c| {
            let ids: Vec<String> = c.iter().map(|n| (n + 1).to_string()).collect();
            ids.join(", ")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_model::calculix_settings::Formulation;

    /// Two triangles on the unit square's diagonal (mm-sized in metres), the contact surface
    /// along z = 0 from the pole.
    fn square() -> Mesh {
        Mesh {
            nodes: vec![
                [0.0, 0.0],
                [1e-3, 0.0],
                [1e-3, 1e-3],
                [0.0, 1e-3],
                [0.5e-3, 0.0],
                [1e-3, 0.5e-3],
                [0.5e-3, 0.5e-3],
                [0.5e-3, 1e-3],
                [0.0, 0.5e-3],
            ],
            triangles: vec![[0, 1, 2, 4, 5, 6], [0, 2, 3, 6, 7, 8]],
            axis: vec![0, 8, 3],
            far: vec![3, 7, 2],
            surface: vec![[0, 4, 1]],
            grip: None,
        }
    }

    fn spec<'a>(mesh: &'a Mesh, positions: &'a [PositionStep], settings: Settings) -> DeckSpec<'a> {
        DeckSpec {
            scene: "unit",
            domain: "a square".into(),
            mesh,
            young: 70e9,
            poisson: 0.3,
            h: 0.5e-3,
            grip: Grip::Rigid,
            candidate_radius: 1e-3,
            settings,
            positions,
        }
    }

    #[test]
    fn the_deck_holds_the_mesh_sets_contact_and_one_step_per_position() {
        let mesh = square();
        let positions = [
            PositionStep {
                position: 0,
                step: 0,
                d: 0.0,
            },
            PositionStep {
                position: 1,
                step: 4,
                d: 5e-6,
            },
        ];
        let text = spec(&mesh, &positions, Settings::default()).text().unwrap();
        assert!(!text.contains('@'), "unfilled key in\n{text}");
        // mm: node 2 at r = 1 mm; CAX6 with 1-based ids; the slave face is element 1's side 1–2.
        assert!(text.contains("2, 1.000000000000e0, 0.000000000000e0"), "{text}");
        assert!(text.contains("*ELEMENT, TYPE=CAX6, ELSET=EBODY\n1, 1, 2, 3, 5, 6, 7\n2, 1, 3, 4, 7, 8, 9"));
        assert!(
            text.contains("*SURFACE, NAME=SSPHERE, TYPE=ELEMENT\n1, S1\n"),
            "{text}"
        );
        // The strip: 1.5 mm wide in cells of 2 h = 1 mm → 2 cells, elements 3 and 4.
        assert!(
            text.contains("*SURFACE, NAME=SPLANE, TYPE=ELEMENT\n3, S3\n4, S3\n"),
            "{text}"
        );
        assert!(
            text.contains("*ELEMENT, TYPE=CAX4, ELSET=EPLANE\n3, 13, 14, 11, 10\n"),
            "{text}"
        );
        // K = 1e3 · 70 000 MPa / 0.5 mm, face-to-face; the rigid grip holds NFAR radially.
        assert!(text
            .contains("LINEAR\n1.400000000000e8\n*CONTACT PAIR, INTERACTION=PLANE, TYPE=SURFACE TO SURFACE"));
        assert!(text.contains("NFAR, 1, 1, 0.\n"));
        assert_eq!(text.matches("*STEP").count(), 2);
        assert!(text.contains("NFAR, 2, 2, -5.000000000000e-3\n"), "{text}");
        assert!(text.contains("CF\n*NODE FILE, OUTPUT=3D"));
        // Every number of a data line fits the 20 characters CalculiX reads.
        let longest = widest_number(&text);
        assert!((1..=20).contains(&longest), "a field of {longest} characters");
    }

    #[test]
    fn node_to_face_has_the_tension_cap_and_no_contact_totals() {
        let mesh = square();
        let positions = [PositionStep {
            position: 1,
            step: 1,
            d: 5e-6,
        }];
        let settings = Settings {
            formulation: Formulation::NodeToFace,
            ..Settings::default()
        };
        let text = spec(&mesh, &positions, settings).text().unwrap();
        assert!(text.contains(
            "1.400000000000e8, 7.000000000000e-2\n*CONTACT PAIR, INTERACTION=PLANE, TYPE=NODE TO SURFACE"
        ));
        assert!(!text.contains("\nCF\n"));
    }

    #[test]
    fn a_contact_edge_that_no_triangle_has_is_an_error() {
        let mut mesh = square();
        mesh.surface = vec![[1, 5, 3]];
        mesh.nodes[3] = [0.5e-3, 0.0];
        let positions = [PositionStep {
            position: 1,
            step: 1,
            d: 5e-6,
        }];
        let e = spec(&mesh, &positions, Settings::default()).text().unwrap_err();
        assert!(e.contains("not the side of any triangle"), "{e}");
    }
}
