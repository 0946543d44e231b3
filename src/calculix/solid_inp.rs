//! Writing the `.inp` of `ccx-3d` from fem-3d's gmsh mesh of the half body
//! ([`crate::external::solid_geo`]): the template (`templates/calculix_3d.inp`) filled with the
//! 10-node tetrahedra of both spheres (sphere 2 the mirror image of sphere 1 through the contact
//! plane), the node sets and surfaces, the material, the penalty contact with Coulomb friction,
//! and one `*STEP` per computed path step.
//!
//! The element and contact keywords are chosen in one place, [`Keywords`], so that the element
//! and the formulation can become settings.

use std::collections::HashMap;
use std::fmt::Write;

use super::inp::{node_set, num, surface_behavior};
use crate::calculix_settings::Settings;
use crate::domain::Grip;
use crate::external::deck::ComputedStep;
use crate::fem::element::tet10;
use crate::fem::mesh::solid::SolidMesh;

/// The deck template.
pub const TEMPLATE: &str = include_str!("templates/calculix_3d.inp");

/// The body's element and the contact pair's keywords.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Keywords {
    /// `*ELEMENT, TYPE=…` of the body.
    pub element: &'static str,
    /// The body's node order from gmsh's (`order[k]` = gmsh's index of CalculiX's node k).
    pub order: [usize; 10],
    /// CalculiX's faces of that element by their corners (gmsh's indices), face k+1 = `S{k+1}`.
    pub faces: [[usize; 3]; 4],
}

/// C3D10 on gmsh's 10-node tetrahedra: CalculiX's (Abaqus's) node order is VTK's (gmsh's midside
/// nodes 8 and 9 swapped), its faces S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1.
pub const C3D10: Keywords = Keywords {
    element: "C3D10",
    order: tet10::VTK_ORDER,
    faces: [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]],
};

/// Body 2 is body 1 mirrored through the contact plane (z → −z); mirroring turns a tetrahedron
/// inside out, so its corners 1 and 2 are swapped (and with them the midside nodes): `MIRROR[i]`
/// is the gmsh index, in body 1's element, of the mirrored element's node i.
const MIRROR: [usize; 10] = [0, 2, 1, 3, 6, 5, 4, 7, 9, 8];

/// The stick slope λ of `*FRICTION` as a fraction of the normal penalty K. λ = K diverged on the
/// first loaded step (two spheres at c_max/3 and c_max/2: CalculiX's residual grew from 360 % to
/// 770 % of the mean force over 27 iterations, and to 1100 % at c_max/2, with the contact set
/// unchanged); K/100 converged (the frictionless deck on the same mesh converged as well). The
/// price is an elastic slip μ p / λ before sliding: 100 times the normal penetration.
pub const STICK_SLOPE_FRACTION: f64 = 1e-2;

/// What the deck is written from (SI; the deck is in mm).
pub struct SolidDeckSpec<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// The domain, in words.
    pub domain: String,
    /// The half body's mesh [m].
    pub mesh: &'a SolidMesh,
    /// Young's modulus [Pa].
    pub young: f64,
    /// Poisson ratio.
    pub poisson: f64,
    /// Coulomb friction coefficient (0: frictionless, no `*FRICTION`).
    pub friction: f64,
    /// Pole element size h [m].
    pub h: f64,
    /// The far face's grip.
    pub grip: Grip,
    /// The contact faces wholly within this radius of the pole [m] are the slave.
    pub candidate_radius: f64,
    /// The case's CalculiX settings (contact formulation, penalty factor).
    pub settings: Settings,
    /// The body's element and its faces.
    pub keywords: Keywords,
    /// The computed steps, in order.
    pub steps: &'a [ComputedStep],
}

impl SolidDeckSpec<'_> {
    /// The penalty stiffness K = factor · E / h [MPa/mm].
    pub fn stiffness_mpa_per_mm(&self) -> f64 {
        self.settings.stiffness_mpa_per_mm(self.young, self.h)
    }

    /// The stick slope λ = [`STICK_SLOPE_FRACTION`] · K [MPa/mm].
    pub fn stick_slope_mpa_per_mm(&self) -> f64 {
        STICK_SLOPE_FRACTION * self.stiffness_mpa_per_mm()
    }

    /// The contact faces within the candidate radius (fem-3d's candidates, `Surface::new`).
    pub fn slave_faces(&self) -> Vec<[usize; 6]> {
        let r = |n: usize| self.mesh.nodes[n][0].hypot(self.mesh.nodes[n][1]);
        self.mesh
            .contact
            .iter()
            .filter(|f| f.iter().all(|&n| r(n) <= self.candidate_radius))
            .copied()
            .collect()
    }

    /// The filled deck.
    pub fn text(&self) -> Result<String, String> {
        let faces = self.face_index();
        let slave = self.face_lines(&faces, 1)?;
        let master = self.face_lines(&faces, 2)?;
        let k = self.stiffness_mpa_per_mm();
        let friction = if self.friction > 0.0 {
            format!(
                "*FRICTION\n{}, {}",
                num(self.friction),
                num(self.stick_slope_mpa_per_mm())
            )
        } else {
            "** frictionless (the path has no tangential motion)".to_owned()
        };
        let keys: [(&str, String); 24] = [
            ("@SCENE@", self.scene.replace(['\n', '`'], " ")),
            ("@DOMAIN@", self.domain.clone()),
            ("@GRIP@", self.grip.name().to_owned()),
            ("@CANDIDATE_MM@", format!("{:.6}", self.candidate_radius * 1e3)),
            ("@CONTACT_NAME@", self.settings.formulation.name().to_owned()),
            ("@PENALTY_FACTOR@", format!("{:e}", self.settings.penalty)),
            ("@K@", format!("{k:.6e}")),
            ("@LAMBDA@", format!("{:.6e}", self.stick_slope_mpa_per_mm())),
            ("@MU@", format!("{}", self.friction)),
            ("@ELEMENTS@", self.mesh.tetrahedra.len().to_string()),
            ("@H_MM@", format!("{:.6e}", self.h * 1e3)),
            ("@BODY1_NODES@", self.body_nodes(1)),
            ("@BODY2_NODES@", self.body_nodes(2)),
            ("@BODY1_ELEMENTS@", self.body_elements(1)),
            ("@BODY2_ELEMENTS@", self.body_elements(2)),
            ("@SYMMETRY_NODES@", self.node_sets(&self.mesh.symmetry)),
            ("@FAR1_NODES@", node_set(&self.of_body(&self.mesh.far, 1))),
            ("@FAR2_NODES@", node_set(&self.of_body(&self.mesh.far, 2))),
            ("@SLAVE_FACES@", slave),
            ("@MASTER_FACES@", master),
            ("@E_MPA@", num(self.young * 1e-6)),
            ("@NU@", num(self.poisson)),
            ("@K_VALUE@", surface_behavior(&self.settings, self.young, k)),
            ("@FRICTION@", friction),
        ];
        let text = keys
            .into_iter()
            .fold(TEMPLATE.to_owned(), |t, (key, value)| t.replace(key, &value));
        Ok(text
            .replace("@ELEMENT@", self.keywords.element)
            .replace("@CONTACT_TYPE@", self.settings.formulation.keyword())
            .replace("@STEPS@", &self.steps_text()))
    }

    /// The mesh's node ids (0-based) of `faces`, as 0-based ids of body `body` (1 or 2).
    fn of_body(&self, faces: &[[usize; 6]], body: usize) -> Vec<usize> {
        let offset = (body - 1) * self.mesh.nodes.len();
        SolidMesh::nodes_of(faces)
            .into_iter()
            .map(|n| n + offset)
            .collect()
    }

    /// The nodes of `faces` on both bodies, as data lines.
    fn node_sets(&self, faces: &[[usize; 6]]) -> String {
        [1, 2].map(|b| node_set(&self.of_body(faces, b))).join("\n")
    }

    /// Body `body`'s nodes [mm]: body 2's are body 1's mirrored (z → −z), numbered after them.
    fn body_nodes(&self, body: usize) -> String {
        let (offset, sign) = if body == 1 {
            (0, 1.0)
        } else {
            (self.mesh.nodes.len(), -1.0)
        };
        let mut text = String::new();
        for (i, [x, y, z]) in self.mesh.nodes.iter().enumerate() {
            let (x, y, z) = (num(x * 1e3), num(y * 1e3), num(sign * z * 1e3));
            let _ = writeln!(text, "{}, {x}, {y}, {z}", offset + i + 1);
        }
        text.trim_end().to_owned()
    }

    /// Body `body`'s elements in gmsh's node order (0-based node ids): body 2's mirrored.
    fn elements(&self, body: usize) -> impl Iterator<Item = [usize; 10]> + '_ {
        let offset = (body - 1) * self.mesh.nodes.len();
        self.mesh.tetrahedra.iter().map(move |t| {
            let element = if body == 1 { *t } else { MIRROR.map(|i| t[i]) };
            element.map(|n| n + offset)
        })
    }

    /// Body `body`'s element lines in CalculiX's node order, numbered after body 1's for body 2.
    fn body_elements(&self, body: usize) -> String {
        let first = (body - 1) * self.mesh.tetrahedra.len() + 1;
        let mut text = String::new();
        for (e, t) in self.elements(body).enumerate() {
            let nodes: Vec<String> = self
                .keywords
                .order
                .iter()
                .map(|&k| (t[k] + 1).to_string())
                .collect();
            // CalculiX reads at most 16 entries a line: the id and ten nodes fit.
            let _ = writeln!(text, "{}, {}", first + e, nodes.join(", "));
        }
        text.trim_end().to_owned()
    }

    /// Every element face of both bodies by its sorted corners (0-based node ids): (element id,
    /// face number).
    fn face_index(&self) -> HashMap<[usize; 3], (usize, usize)> {
        let mut faces = HashMap::new();
        for body in [1, 2] {
            let first = (body - 1) * self.mesh.tetrahedra.len() + 1;
            for (e, t) in self.elements(body).enumerate() {
                for (k, corners) in self.keywords.faces.iter().enumerate() {
                    faces.insert(sorted(corners.map(|c| t[c])), (first + e, k + 1));
                }
            }
        }
        faces
    }

    /// The candidate faces of body `body` as `element, S<k>` lines: body 1's the slave, body 2's
    /// the master.
    fn face_lines(&self, faces: &HashMap<[usize; 3], (usize, usize)>, body: usize) -> Result<String, String> {
        let offset = (body - 1) * self.mesh.nodes.len();
        let mut text = String::new();
        for face in self.slave_faces() {
            let corners = sorted([face[0], face[1], face[2]].map(|n| n + offset));
            let (element, k) = faces
                .get(&corners)
                .ok_or_else(|| format!("contact face {:?} is not the face of any element", &face[..3]))?;
            let _ = writeln!(text, "{element}, S{k}");
        }
        if text.is_empty() {
            return Err("no contact face lies within the candidate radius".into());
        }
        Ok(text.trim_end().to_owned())
    }

    /// One `*STEP` per computed step: the far face's approach and shift (total values), the
    /// reaction totals of both far faces in the `.dat`, the contact output in the
    /// `.frd`.
    fn steps_text(&self) -> String {
        let mut text = String::new();
        for s in self.steps {
            let grip = match self.grip {
                Grip::Rigid => format!(
                    "NFAR1, 1, 1, {}\nNFAR1, 2, 2, 0.\nNFAR2, 1, 1, {}\nNFAR2, 2, 2, 0.\n",
                    num(s.t * 1e3),
                    num(-s.t * 1e3)
                ),
                Grip::Axial => String::new(),
            };
            let position = s
                .position
                .map_or_else(String::new, |p| format!(", path position {p}"));
            let _ = write!(
                text,
                "** path step {}{position}: delta_n = {} mm, delta_t = {} mm: the far faces at \
                 u_z = -+{} mm, u_x = +-{} mm\n\
                 *STEP, INC=200\n*STATIC\n1., 1.\n*BOUNDARY\n{grip}NFAR1, 3, 3, {}\nNFAR2, 3, 3, {}\n\
                 *NODE PRINT, NSET=NFAR1, TOTALS=ONLY\nRF\n*NODE PRINT, NSET=NFAR2, TOTALS=ONLY\nRF\n\
                 *CONTACT FILE\nCDIS, CSTR\n*END STEP\n",
                s.step,
                num(2.0 * s.d * 1e3),
                num(2.0 * s.t * 1e3),
                num(s.d * 1e3),
                num(s.t * 1e3),
                num(-s.d * 1e3),
                num(s.d * 1e3),
            );
        }
        text.trim_end().to_owned()
    }
}

/// The three ids in increasing order.
fn sorted(mut corners: [usize; 3]) -> [usize; 3] {
    corners.sort_unstable();
    corners
}
