//! A normal-contact (frictionless) CalculiX deck on the 20-node hexahedra of the half body
//! ([`super::hex_mesh`]): the paper's kind of model (C3D20/C3D20R, face-to-face or mortar
//! contact) at a few path positions, P and c read back. The deck text is written here only; the
//! mesh is the mesh module's.
//!
//! Model (mm, N, MPa): the half body y ≥ 0 (symmetry plane: u_y = 0), its far face pushed down by
//! d = δn/2 (held in x and y too under the rigid grip; under the axial grip one far-face node
//! near the axis is held in x, exact by the x = 0 symmetry of normal contact), one sphere of two
//! identical ones against their plane of symmetry z = 0: a held slab of C3D8 bricks under it (as
//! ccx-axisym's held strip: rigid exactly). P = −2 × the far face's reaction (the half body); c =
//! the largest distance from the axis of a slave node CalculiX reports a contact pressure at (a
//! bound within half a brick).

use std::fmt::Write;

use super::hex_mesh::HexMesh;
use super::inp::{node_set, num};
use crate::calculix_settings::{MeshKind, Settings};
use crate::domain::Grip;

/// What the deck is written from (lengths in metres; the deck is in mm).
pub struct HexDeckSpec<'a> {
    /// The mesh.
    pub mesh: &'a HexMesh,
    /// Young's modulus [Pa].
    pub young: f64,
    /// Poisson ratio.
    pub poisson: f64,
    /// Pole brick size h [m] (the penalty is K = penalty · E / h).
    pub h: f64,
    /// Faces wholly within this distance of the axis are the slave surface [m].
    pub candidate_radius: f64,
    /// The grip of the far face.
    pub grip: Grip,
    /// Formulation, penalty and element (a hexahedral one).
    pub settings: Settings,
    /// The approach d = δn/2 of each step [m].
    pub approaches: &'a [f64],
}

impl HexDeckSpec<'_> {
    /// The distance of node `n` from the axis [m].
    fn radius(&self, n: usize) -> f64 {
        let [x, y, _] = self.mesh.nodes[n];
        x.hypot(y)
    }

    /// The filled deck.
    pub fn text(&self) -> Result<String, String> {
        let element = self.settings.element;
        if element.mesh() != MeshKind::Hex20 {
            return Err(format!(
                "element {} is not a 20-node brick (allowed here: hex20, hex20r)",
                element.name()
            ));
        }
        let mut t = String::from("** spherecontact: normal contact on 20-node hexahedra (ccx 2.20). Run: ccx -i job\n*HEADING\nspherecontact hex20 normal contact\n*NODE, NSET=NBODY\n");
        for (i, [x, y, z]) in self.mesh.nodes.iter().enumerate() {
            let _ = writeln!(
                t,
                "{}, {}, {}, {}",
                i + 1,
                num(x * 1e3),
                num(y * 1e3),
                num(z * 1e3)
            );
        }
        let _ = writeln!(t, "*ELEMENT, TYPE={}, ELSET=EBODY", element.keyword());
        for (e, brick) in self.mesh.hexahedra.iter().enumerate() {
            let ids: Vec<String> = brick.iter().map(|n| (n + 1).to_string()).collect();
            // 21 entries: the id and 15 nodes on the first line, the last 5 on the next.
            let _ = writeln!(
                t,
                "{}, {},\n{}",
                e + 1,
                ids[..15].join(", "),
                ids[15..].join(", ")
            );
        }
        let slab = self.slab(&mut t);
        self.sets_and_surfaces(&mut t, slab)?;
        let k = self.settings.stiffness_mpa_per_mm(self.young, self.h);
        let _ = write!(
            t,
            "*MATERIAL, NAME=SPHERE\n*ELASTIC\n{}, {}\n*SOLID SECTION, ELSET=EBODY, MATERIAL=SPHERE\n\
             *SOLID SECTION, ELSET=EPLANE, MATERIAL=SPHERE\n*SURFACE INTERACTION, NAME=PLANE\n\
             *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{}\n*CONTACT PAIR, INTERACTION=PLANE, TYPE={}\n\
             SSPHERE, SPLANE\n*BOUNDARY\nNPLANE, 1, 3, 0.\nNSYM, 2, 2, 0.\n{}\n",
            num(self.young * 1e-6),
            num(self.poisson),
            num(k),
            self.settings.formulation.keyword(),
            match self.grip {
                Grip::Rigid => "NFAR, 1, 2, 0.",
                Grip::Axial => "NCENTRE, 1, 1, 0.",
            }
        );
        for d in self.approaches {
            let _ = write!(
                t,
                "*STEP, INC=200\n*STATIC\n1., 1.\n*CONTROLS, PARAMETERS=FIELD\n0.02, 0.02\n*BOUNDARY\n\
                 NFAR, 3, 3, {}\n*NODE PRINT, NSET=NFAR, TOTALS=ONLY\nRF\n*CONTACT FILE\nCDIS, CSTR\n*END STEP\n",
                num(-d * 1e3)
            );
        }
        Ok(t)
    }

    /// The held slab under z = 0 (C3D8, every node held; its top faces the master), numbered
    /// after the body: writes its nodes and elements, returns (first element id, cells).
    fn slab(&self, t: &mut String) -> (usize, usize) {
        let width = 1.5 * self.candidate_radius * 1e3;
        let cells = ((width / (2.0 * self.h * 1e3)).ceil() as usize).clamp(1, 200);
        let cell = width / cells as f64;
        let first = self.mesh.nodes.len() + 1;
        let (nx, ny) = (2 * cells + 1, cells + 1);
        let id = |i: usize, j: usize, k: usize| first + k * nx * ny + j * nx + i;
        t.push_str("*NODE, NSET=NPLANE\n");
        for k in 0..2 {
            for j in 0..ny {
                for i in 0..nx {
                    let (x, y, z) = (i as f64 * cell - width, j as f64 * cell, (k as f64 - 1.0) * cell);
                    let _ = writeln!(t, "{}, {}, {}, {}", id(i, j, k), num(x), num(y), num(z));
                }
            }
        }
        let first_element = self.mesh.hexahedra.len() + 1;
        t.push_str("*ELEMENT, TYPE=C3D8, ELSET=EPLANE\n");
        let mut e = first_element;
        for j in 0..cells {
            for i in 0..2 * cells {
                let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
                let ids: Vec<String> = (0..2)
                    .flat_map(|k| corners.map(|(a, b)| id(a, b, k).to_string()))
                    .collect();
                let _ = writeln!(t, "{e}, {}", ids.join(", "));
                e += 1;
            }
        }
        (first_element, 2 * cells * cells)
    }

    /// The node sets (far face, its node nearest the axis, symmetry plane) and the surfaces.
    fn sets_and_surfaces(&self, t: &mut String, (first, count): (usize, usize)) -> Result<(), String> {
        let nodes_of = |faces: &[[usize; 8]]| {
            let mut n: Vec<usize> = faces.iter().flatten().copied().collect();
            n.sort_unstable();
            n.dedup();
            n
        };
        let far = nodes_of(&self.mesh.far);
        let centre = far
            .iter()
            .copied()
            .min_by(|&a, &b| self.radius(a).total_cmp(&self.radius(b)))
            .ok_or("no far face")?;
        let _ = writeln!(t, "*NSET, NSET=NFAR\n{}", node_set(&far));
        let _ = writeln!(t, "*NSET, NSET=NCENTRE\n{}", centre + 1);
        let symmetry = nodes_of(&self.mesh.symmetry);
        let _ = writeln!(t, "*NSET, NSET=NSYM\n{}", node_set(&symmetry));
        let limit = self.candidate_radius * (1.0 + 1e-9);
        let slave: Vec<[usize; 8]> = self
            .mesh
            .contact
            .iter()
            .filter(|f| f[..4].iter().all(|&n| self.radius(n) <= limit))
            .copied()
            .collect();
        if slave.is_empty() {
            return Err("no contact face within the candidate radius".into());
        }
        t.push_str("*SURFACE, NAME=SSPHERE, TYPE=ELEMENT\n");
        for (e, face) in self.mesh.element_faces(&slave)? {
            let _ = writeln!(t, "{}, S{face}", e + 1);
        }
        t.push_str("*SURFACE, NAME=SPLANE, TYPE=ELEMENT\n");
        for e in first..first + count {
            let _ = writeln!(t, "{e}, S2");
        }
        Ok(())
    }

    /// c [m] from the contact pressures of one `.frd` block: the largest distance from the
    /// axis of a body node with a positive pressure (0 when none).
    pub fn contact_radius(&self, block: &super::results::ContactBlock) -> f64 {
        block
            .values
            .iter()
            .filter(|(id, v)| v[3] > 0.0 && (**id as usize) <= self.mesh.nodes.len() && **id > 0)
            .map(|(id, _)| self.radius(*id as usize - 1))
            .fold(0.0, f64::max)
    }
}

/// P [N] and c [m] at each step, as CalculiX computed them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HexResult {
    /// The normal force on the whole body (twice the half body's).
    pub normal_force: f64,
    /// The contact radius (the outermost slave node with a pressure).
    pub contact_radius: f64,
}

/// Writes the deck of `spec` into `dir`, runs ccx there within `timeout` and reads P and c at
/// each step from `job.dat` and `job.frd`.
pub fn run(
    spec: &HexDeckSpec,
    dir: &std::path::Path,
    toolchain: &crate::external::toolchain::Toolchain,
    timeout: std::time::Duration,
) -> Result<Vec<HexResult>, crate::solver::SolveError> {
    use crate::solver::SolveError;
    let text = spec.text().map_err(SolveError::Failed)?;
    let run = crate::external::deck::launch(&super::CcxAxisymDeck, toolchain, dir, &text, &[], timeout)?;
    if let Some(error) = run.stdout.lines().position(|l| l.contains("*ERROR")) {
        let lines: Vec<&str> = run.stdout.lines().skip(error).take(6).collect();
        return Err(SolveError::Failed(format!("ccx: {}", lines.join("\n"))));
    }
    let read = |name: &str| crate::external::readback::read_output(dir, name).map_err(SolveError::Failed);
    let n = spec.approaches.len();
    let far = super::results::totals(&read("job.dat")?, "NFAR").map_err(SolveError::Failed)?;
    let far =
        super::results::last_per_step(&far, |t| t.time, n, "job.dat NFAR").map_err(SolveError::Failed)?;
    let frd = super::results::parse_frd(&read("job.frd")?).map_err(SolveError::Failed)?;
    Ok(far
        .iter()
        .enumerate()
        .map(|(k, total)| {
            let time = (k + 1) as f64;
            let block = frd.contact.iter().rev().find(|b| (b.time - time).abs() < 1e-6);
            HexResult {
                normal_force: -2.0 * total.force[2] + 0.0,
                contact_radius: block.map_or(0.0, |b| spec.contact_radius(b)),
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calculix::hex20;
    use crate::calculix_settings::Element;

    /// One brick [0,1]² × [0,1] mm with its bottom face the contact, its top the far face.
    fn brick() -> HexMesh {
        HexMesh {
            nodes: hex20::NODES
                .map(|[a, b, c]| [0.5e-3 * (1.0 + a), 0.5e-3 * (1.0 + b), 0.5e-3 * (1.0 + c)])
                .to_vec(),
            hexahedra: vec![std::array::from_fn(|k| k)],
            contact: vec![hex20::FACES[0]],
            far: vec![hex20::FACES[1]],
            symmetry: vec![hex20::FACES[2]],
        }
    }

    fn spec<'a>(mesh: &'a HexMesh, approaches: &'a [f64], element: Element) -> HexDeckSpec<'a> {
        HexDeckSpec {
            mesh,
            young: 70e9,
            poisson: 0.3,
            h: 0.5e-3,
            candidate_radius: 2e-3,
            grip: Grip::Axial,
            settings: Settings {
                element,
                ..Settings::default()
            },
            approaches,
        }
    }

    #[test]
    fn the_deck_names_the_element_faces_sets_and_one_step_per_position() {
        let mesh = brick();
        let text = spec(&mesh, &[1e-6, 2e-6], Element::Hex20r).text().unwrap();
        assert!(text.contains("*ELEMENT, TYPE=C3D20R, ELSET=EBODY\n1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15,\n16, 17, 18, 19, 20\n"), "{text}");
        assert!(
            text.contains("*SURFACE, NAME=SSPHERE, TYPE=ELEMENT\n1, S1\n"),
            "{text}"
        );
        assert!(
            text.contains("*NSET, NSET=NFAR\n5, 6, 7, 8, 13, 14, 15, 16\n"),
            "{text}"
        );
        assert!(text.contains("NCENTRE, 1, 1, 0.") && text.contains("TYPE=SURFACE TO SURFACE"));
        assert_eq!(text.matches("*STEP").count(), 2);
        assert!(text.contains("NFAR, 3, 3, -2.000000000000e-3\n"), "{text}");
        // The slab: 3 mm wide in cells of 2 h = 1 mm → 3 × 6 cells; the first one's top is S2.
        assert!(
            text.contains("\n2, S2\n") && text.matches(", S2\n").count() == 18,
            "{text}"
        );
        let e = spec(&mesh, &[1e-6], Element::Tet10).text().unwrap_err();
        assert!(e.contains("hex20, hex20r"), "{e}");
    }
}
