//! Writing the `.inp` of `ccx-3d` from fem-3d's gmsh mesh of the half body
//! ([`spherecontact_solvers::fem::mesh::solid_geo`]): the template (`templates/calculix_3d.inp`) filled with the
//! elements of both spheres (sphere 2 the mirror image of sphere 1 through the contact
//! plane), the node sets and surfaces, the material, the penalty contact with Coulomb friction,
//! and one `*STEP` per computed path step.
//!
//! The element is the case's `[calculix] element` on the mesh of its kind ([`Body`]: C3D10 on
//! the tetrahedra, C3D20 or C3D20R on the 20-node bricks); the contact keyword its
//! `[calculix] contact`.

use std::collections::HashMap;
use std::fmt::Write;

use super::body::Body;
use super::inp::{node_set, num, surface_behavior};
use super::nodal_forces;
use crate::deck::ComputedStep;
use spherecontact_model::calculix_settings::{MeshKind, Settings};
use spherecontact_model::domain::Grip;

/// The deck template.
pub const TEMPLATE: &str = include_str!("templates/calculix_3d.inp");

/// CalculiX reads at most 16 entries on a data line: an element's id and its first 15 nodes go
/// on the first line, the rest (a 20-node brick's last 5) on the next.
const NODES_ON_FIRST_LINE: usize = 15;

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
    /// The half body's mesh [m], of the element kind of `settings.element`.
    pub mesh: &'a Body,
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
    /// The case's CalculiX settings (contact formulation, penalty factor, element).
    pub settings: Settings,
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
    pub fn slave_faces(&self) -> Vec<Vec<usize>> {
        self.mesh.candidate_faces(self.candidate_radius)
    }

    /// The filled deck.
    pub fn text(&self) -> Result<String, String> {
        let kind = match self.mesh {
            Body::Tet10(_) => MeshKind::Tet10,
            Body::Hex20(_) => MeshKind::Hex20,
        };
        if self.settings.element.mesh() != kind {
            return Err(format!(
                "element {} does not fit the mesh ({kind:?})",
                self.settings.element.name()
            ));
        }
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
        let keys: [(&str, String); 26] = [
            ("@SCENE@", self.scene.replace(['\n', '`'], " ")),
            ("@DOMAIN@", self.domain.clone()),
            ("@GRIP@", self.grip.name().to_owned()),
            ("@CANDIDATE_MM@", format!("{:.6}", self.candidate_radius * 1e3)),
            ("@CONTACT_NAME@", self.settings.formulation.name().to_owned()),
            ("@PENALTY_FACTOR@", format!("{:e}", self.settings.penalty)),
            ("@K@", format!("{k:.6e}")),
            ("@LAMBDA@", format!("{:.6e}", self.stick_slope_mpa_per_mm())),
            ("@MU@", format!("{}", self.friction)),
            ("@ELEMENTS@", self.mesh.element_count().to_string()),
            ("@MESH@", self.mesh.describe().to_owned()),
            ("@H_MM@", format!("{:.6e}", self.h * 1e3)),
            ("@BODY1_NODES@", self.body_nodes(1)),
            ("@BODY2_NODES@", self.body_nodes(2)),
            ("@BODY1_ELEMENTS@", self.body_elements(1)),
            ("@BODY2_ELEMENTS@", self.body_elements(2)),
            ("@SYMMETRY_NODES@", self.node_sets(&self.mesh.symmetry_nodes())),
            ("@FAR1_NODES@", node_set(&self.of_body(&self.mesh.far_nodes(), 1))),
            ("@FAR2_NODES@", node_set(&self.of_body(&self.mesh.far_nodes(), 2))),
            (
                "@READ_NODES@",
                node_set(&nodal_forces::read_nodes(self.mesh, &self.slave_faces())),
            ),
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
            .replace("@ELEMENT@", self.settings.element.keyword())
            .replace("@CONTACT_TYPE@", self.settings.formulation.keyword())
            .replace("@STEPS@", &self.steps_text()))
    }

    /// The (0-based) node ids `nodes` of body 1 as ids of body `body` (1 or 2).
    fn of_body(&self, nodes: &[usize], body: usize) -> Vec<usize> {
        let offset = (body - 1) * self.mesh.nodes().len();
        nodes.iter().map(|n| n + offset).collect()
    }

    /// The nodes `nodes` on both bodies, as data lines.
    fn node_sets(&self, nodes: &[usize]) -> String {
        [1, 2].map(|b| node_set(&self.of_body(nodes, b))).join("\n")
    }

    /// Body `body`'s nodes [mm]: body 2's are body 1's mirrored (z → −z), numbered after them.
    fn body_nodes(&self, body: usize) -> String {
        let nodes = self.mesh.nodes();
        let (offset, sign) = if body == 1 { (0, 1.0) } else { (nodes.len(), -1.0) };
        let mut text = String::new();
        for (i, [x, y, z]) in nodes.iter().enumerate() {
            let (x, y, z) = (num(x * 1e3), num(y * 1e3), num(sign * z * 1e3));
            let _ = writeln!(text, "{}, {x}, {y}, {z}", offset + i + 1);
        }
        text.trim_end().to_owned()
    }

    /// Body `body`'s elements in CalculiX's node order (0-based node ids): body 2's mirrored.
    fn elements(&self, body: usize) -> impl Iterator<Item = Vec<usize>> + '_ {
        let offset = (body - 1) * self.mesh.nodes().len();
        (0..self.mesh.element_count()).map(move |e| {
            let element = self.mesh.element(e, body == 2);
            element.into_iter().map(|n| n + offset).collect()
        })
    }

    /// Body `body`'s element lines, numbered after body 1's for body 2.
    fn body_elements(&self, body: usize) -> String {
        let first = (body - 1) * self.mesh.element_count() + 1;
        let mut text = String::new();
        for (e, element) in self.elements(body).enumerate() {
            let ids: Vec<String> = element.iter().map(|n| (n + 1).to_string()).collect();
            let split = ids.len().min(NODES_ON_FIRST_LINE);
            let _ = write!(text, "{}, {}", first + e, ids[..split].join(", "));
            if split < ids.len() {
                let _ = write!(text, ",\n{}", ids[split..].join(", "));
            }
            text.push('\n');
        }
        text.trim_end().to_owned()
    }

    /// Every element face of both bodies by its sorted corners (0-based node ids): (element id,
    /// face number).
    fn face_index(&self) -> HashMap<Vec<usize>, (usize, usize)> {
        let mut faces = HashMap::new();
        let corners_of = self.mesh.face_corners();
        for body in [1, 2] {
            let first = (body - 1) * self.mesh.element_count() + 1;
            for (e, element) in self.elements(body).enumerate() {
                for (k, corners) in corners_of.iter().enumerate() {
                    faces.insert(sorted(corners.iter().map(|&c| element[c])), (first + e, k + 1));
                }
            }
        }
        faces
    }

    /// The candidate faces of body `body` as `element, S<k>` lines: body 1's the slave, body 2's
    /// the master.
    fn face_lines(&self, faces: &HashMap<Vec<usize>, (usize, usize)>, body: usize) -> Result<String, String> {
        let offset = (body - 1) * self.mesh.nodes().len();
        let corners = self.mesh.face_corner_count();
        let mut text = String::new();
        for face in self.slave_faces() {
            let key = sorted(face[..corners].iter().map(|n| n + offset));
            let (element, k) = faces.get(&key).ok_or_else(|| {
                format!(
                    "contact face {:?} is not the face of any element",
                    &face[..corners]
                )
            })?;
            let _ = writeln!(text, "{element}, S{k}");
        }
        if text.is_empty() {
            return Err("no contact face lies within the candidate radius".into());
        }
        Ok(text.trim_end().to_owned())
    }

    /// One `*STEP` per computed step: the far face's approach and shift (total values), the
    /// reaction totals of both far faces in the `.dat`, the contact output and the displacements
    /// of `NREAD1` in the `.frd`.
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
                 *NODE FILE, NSET=NREAD1\nU\n*CONTACT FILE\nCDIS, CSTR\n*END STEP\n",
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

/// The ids in increasing order.
fn sorted(corners: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut corners: Vec<usize> = corners.collect();
    corners.sort_unstable();
    corners
}
