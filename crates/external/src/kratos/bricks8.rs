//! `kratos-3d`'s 8-node bricks: gmsh's first-order hexahedra of the half body ([`crate::bricks`]
//! at [`Order::Linear`], graded as ccx-3d's bricks) read into a [`LinearBody`], every brick
//! positively oriented (the trilinear map's Jacobian positive at the 2 × 2 × 2 Gauss points;
//! a brick inverted at its centre is turned round, one folded within is refused).
//!
//! Node order: gmsh's 8-node hexahedron is Kratos' `Hexahedra3D8` (corners 0–3 counter-clockwise
//! about +ζ on ζ = −1, 4–7 above them), its 4-node quadrangle Kratos' `Quadrilateral3D4`.

use std::path::Path;

use mshio::mshfile::ElementType;

use super::linear::{mirror_order, Boundary, LinearBody};
use super::vector::{cross, dot};
use crate::bricks::{self, Order};
use spherecontact_model::kratos_settings::Element;
use spherecontact_model::solver::SolveError;
use spherecontact_solvers::fem::mesh::groups;
use spherecontact_solvers::fem::mesh::solid::{BODY, CONTACT, FAR, SYMMETRY};
use spherecontact_solvers::fem::mesh::solid_geo::{SolidGeometry, SolidMeshFiles};
use spherecontact_system::toolchain::Toolchain;

/// The corners' reference coordinates (ξ, η, ζ), in the brick's order.
const CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// The Gauss points of the 2-point rule on [−1, 1].
const GAUSS2: [f64; 2] = [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8];

/// The determinant of the trilinear map's Jacobian of the brick `coords` at `xi`.
pub fn jacobian(coords: &[[f64; 3]], xi: [f64; 3]) -> f64 {
    let mut columns = [[0.0; 3]; 3];
    for (corner, x) in CORNERS.iter().zip(coords) {
        for (j, column) in columns.iter_mut().enumerate() {
            let derivative: f64 = (0..3)
                .map(|k| match k == j {
                    true => corner[k] / 2.0,
                    false => (1.0 + corner[k] * xi[k]) / 2.0,
                })
                .product();
            for i in 0..3 {
                column[i] += x[i] * derivative;
            }
        }
    }
    dot(columns[0], cross(columns[1], columns[2]))
}

/// The Jacobians at the 2 × 2 × 2 Gauss points.
pub fn jacobians(coords: &[[f64; 3]]) -> impl Iterator<Item = f64> + '_ {
    (0..8).map(move |k| jacobian(coords, [GAUSS2[k % 2], GAUSS2[(k / 2) % 2], GAUSS2[k / 4]]))
}

/// Meshes `geometry` into 8-node bricks in `<dir>/<stem>.msh`.
pub fn mesh(
    geometry: &SolidGeometry,
    dir: &Path,
    stem: &str,
    toolchain: &Toolchain,
) -> Result<SolidMeshFiles, SolveError> {
    bricks::mesh(&bricks::graded(geometry), Order::Linear, dir, stem, toolchain)
}

/// Reads the MSH 4.1 file of 8-node bricks at `path`; the error names the file.
pub fn read(path: &Path) -> Result<LinearBody, String> {
    let bytes = spherecontact_solvers::fem::mesh::msh::file_bytes(path).map_err(|e| e.to_string())?;
    parse(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses MSH 4.1 bytes of 8-node bricks and 4-node faces; the error says what is missing.
pub fn parse(bytes: &[u8]) -> Result<LinearBody, String> {
    let kinds = groups::Kinds {
        element: ElementType::Hex8,
        face: ElementType::Qua4,
        skipped: &[ElementType::Pnt, ElementType::Lin2],
        wanted: "8-node hexahedra and 4-node quadrangles: Mesh.SubdivisionAlgorithm = 2, \
                 Mesh.ElementOrder = 1",
        body: BODY,
    };
    let mut read = groups::parse::<8, 4>(bytes, &kinds)?;
    if read.elements.is_empty() {
        return Err(format!(
            "no 8-node hexahedra in physical volume {BODY} (\"body\")"
        ));
    }
    let what = "4-node quadrangles";
    let mut take = |tag, name| -> Result<Vec<Vec<usize>>, String> {
        Ok(read.take(tag, name, what)?.iter().map(|f| f.to_vec()).collect())
    };
    let boundary = Boundary {
        contact: take(CONTACT, "contact")?,
        far: take(FAR, "far")?,
        symmetry: take(SYMMETRY, "symmetry")?,
    };
    let elements = read
        .elements
        .iter()
        .enumerate()
        .map(|(e, brick)| oriented(&read.nodes, brick).ok_or_else(|| folded(e)))
        .collect::<Result<Vec<_>, String>>()?;
    LinearBody::new(Element::Hex8, read.nodes, elements, &boundary)
}

fn folded(e: usize) -> String {
    format!("brick {e} is folded: its Jacobian is not positive at every Gauss point")
}

/// `brick` positively oriented (turned round when inverted at its centre); `None` when its
/// Jacobian is not positive at every Gauss point.
fn oriented(nodes: &[[f64; 3]], brick: &[usize; 8]) -> Option<Vec<usize>> {
    let coords = |order: &[usize]| -> Vec<[f64; 3]> { order.iter().map(|&k| nodes[brick[k]]).collect() };
    let identity: Vec<usize> = (0..8).collect();
    let order = match jacobian(&coords(&identity), [0.0; 3]) < 0.0 {
        true => mirror_order(Element::Hex8).to_vec(),
        false => identity,
    };
    jacobians(&coords(&order))
        .all(|j| j > 0.0)
        .then(|| order.iter().map(|&k| brick[k]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A brick of edges (a, b, c) at the origin, in the reference order.
    fn brick(a: f64, b: f64, c: f64) -> Vec<[f64; 3]> {
        CORNERS
            .iter()
            .map(|x| {
                [
                    a * (x[0] + 1.0) / 2.0,
                    b * (x[1] + 1.0) / 2.0,
                    c * (x[2] + 1.0) / 2.0,
                ]
            })
            .collect()
    }

    /// Requirement: the Jacobian of a box is its volume over the reference volume 8 everywhere,
    /// negative for its mirror image, positive again in the mirror order; exact to round-off
    /// (1e-15 relative: a few operations on numbers of order 1).
    #[test]
    fn the_jacobian_of_a_box_is_its_volume_over_eight_and_the_mirror_order_turns_it_round() {
        let b = brick(2.0, 3.0, 4.0);
        for j in jacobians(&b) {
            assert!((j - 3.0).abs() < 1e-15 * 3.0, "{j}");
        }
        let mirrored: Vec<[f64; 3]> = b.iter().map(|&[x, y, z]| [x, y, -z]).collect();
        assert!(jacobian(&mirrored, [0.1, 0.2, 0.3]) < 0.0);
        let turned: Vec<[f64; 3]> = mirror_order(Element::Hex8).iter().map(|&k| mirrored[k]).collect();
        assert!((jacobian(&turned, [0.1, 0.2, 0.3]) - 3.0).abs() < 1e-15 * 3.0);
    }

    /// Requirement: an inverted brick is turned round, a folded one refused; exact.
    #[test]
    fn an_inverted_brick_is_turned_round_and_a_folded_one_refused() {
        let nodes: Vec<[f64; 3]> = brick(1.0, 1.0, 1.0).iter().map(|&[x, y, z]| [x, y, -z]).collect();
        let order = oriented(&nodes, &[0, 1, 2, 3, 4, 5, 6, 7]).unwrap();
        assert_eq!(order, mirror_order(Element::Hex8));
        let mut folded = brick(1.0, 1.0, 1.0);
        folded[6] = [-2.0, -2.0, -2.0];
        assert_eq!(oriented(&folded, &[0, 1, 2, 3, 4, 5, 6, 7]), None);
    }
}
