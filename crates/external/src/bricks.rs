//! The brick mesher of the 3D decks: gmsh's hexahedra of the same half body as fem-3d's
//! tetrahedra, graded towards the contact alike, in the order a deck needs — 20-node serendipity
//! bricks for `ccx-3d` (`calculix::hex_mesh`), 8-node bricks for `kratos-3d` (`kratos::bricks8`).
//! Each deck reads gmsh's file into its own node order.
//!
//! How: the body, its physical groups and its size field are [`SolidGeometry::geo`]'s (the half
//! hemisphere or cap y ≥ 0: surface 1 the contact candidate, 2 the gripped far face, 3 the
//! symmetry plane y = 0, volume 10 the body), meshed with tetrahedra of twice the size and
//! subdivided by gmsh into hexahedra (`Mesh.SubdivisionAlgorithm = 2`: each tetrahedron into four
//! bricks through its edge midpoints, face centroids and centroid, so the bricks' edges are
//! about the size asked for), of the [`Order`] asked (`Mesh.ElementOrder`, set after the
//! geometry's own, so it is the one gmsh uses: with the first order, gmsh writes 8-node bricks
//! even under the `-order 2` of its command line).
//! Why not transfinite: the body is a boolean of a sphere and a box whose faces are not
//! four-sided, so a transfinite (structured) hex mesh would need a hand-made block decomposition
//! of the quarter ball, different for the cap and the hemisphere; the subdivision keeps the one
//! geometry and the one grading of fem-3d's mesh.

use std::path::Path;

use spherecontact_model::solver::SolveError;
use spherecontact_solvers::fem::mesh::solid_geo::{self, SolidGeometry, SolidMeshFiles};
use spherecontact_system::toolchain::Toolchain;

/// The bricks' order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Order {
    /// 8-node bricks, 4-node faces (`Mesh.ElementOrder = 1`).
    Linear,
    /// 20-node serendipity bricks, 8-node faces, midside nodes on the sphere
    /// (`Mesh.ElementOrder = 2`, `Mesh.SecondOrderIncomplete = 1`).
    Serendipity,
}

impl Order {
    /// The options appended to the tetrahedral `.geo`: subdivision into hexahedra of this order.
    pub fn options(self) -> &'static str {
        match self {
            Order::Linear => {
                "// spherecontact: 8-node hexahedra by subdividing the tetrahedra (each into 4)
Mesh.SubdivisionAlgorithm = 2;
Mesh.ElementOrder = 1;
"
            }
            Order::Serendipity => {
                "// spherecontact: 20-node hexahedra by subdividing the tetrahedra (each into 4)
Mesh.SubdivisionAlgorithm = 2;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
"
            }
        }
    }
}

/// The bricks' grading: the size grows from the fine zone at this rate (fem-3d's tetrahedra grow
/// at [`solid_geo::GROWTH`] = 0.3) …
pub const GROWTH: f64 = 1.0;
/// … up to this size, in units of the sphere radius (fem-3d's: [`solid_geo::MAX_SIZE`] = 0.15).
/// Measured for `ccx-3d` on the paper's hemispheres at pole brick c_max/2 (δn = 17 µm then
/// δt = 3 µm, C3D20R, penalty 1e3): fem-3d's grading gives 7 020 bricks and 32 654 nodes a body;
/// this one 1 248 bricks and 6 410 nodes, P within +3.0e-3 and Q −1.1 % of mdr-domain, 68 s of
/// ccx CPU; growth 2 up to 0.5 R gives 316 bricks and 1 764 nodes (9 s) but coarsens the contact
/// zone to 2 candidate faces: P −4 %, Q −58 %.
pub const MAX_SIZE: f64 = 0.3;

/// `geometry` with the bricks' faster grading ([`GROWTH`], [`MAX_SIZE`]): the contact zone
/// keeps its size and depth, the far body has fewer bricks.
pub fn graded(geometry: &SolidGeometry) -> SolidGeometry {
    SolidGeometry {
        growth: GROWTH,
        max_size: MAX_SIZE * geometry.radius,
        ..*geometry
    }
}

/// The `.geo` of the hexahedral mesh of `geometry` (whose pole size and largest size are the
/// bricks'): the tetrahedral geometry at twice the sizes, subdivided into bricks of `order`.
pub fn geo(geometry: &SolidGeometry, order: Order) -> Result<String, String> {
    let tetrahedra = SolidGeometry {
        pole_size: 2.0 * geometry.pole_size,
        max_size: 2.0 * geometry.max_size,
        ..*geometry
    };
    Ok(tetrahedra.geo()? + order.options())
}

/// Meshes `geometry` into bricks of `order` in `<dir>/<stem>.msh` (MSH 4.1).
pub fn mesh(
    geometry: &SolidGeometry,
    order: Order,
    dir: &Path,
    stem: &str,
    toolchain: &Toolchain,
) -> Result<SolidMeshFiles, SolveError> {
    let text = geo(geometry, order).map_err(SolveError::NotApplicable)?;
    solid_geo::mesh_geo(&text, dir, stem, toolchain)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requirement: the geometry is meshed at twice the sizes and subdivided, the order's options
    /// last (gmsh uses the last setting); exact text.
    #[test]
    fn the_geo_subdivides_tetrahedra_of_twice_the_size_in_the_order_asked() {
        let g = SolidGeometry {
            radius: 0.1,
            height: 0.1,
            pole_size: 1e-4,
            fine_radius: 1.2e-3,
            fine_depth: 2e-4,
            growth: 0.3,
            max_size: 0.015,
        };
        for order in [Order::Linear, Order::Serendipity] {
            let text = geo(&g, order).unwrap();
            assert!(
                text.contains("h = 2e-4;") && text.contains("hmax = 3e-2;"),
                "{text}"
            );
            assert!(text.ends_with(order.options()));
        }
        assert!(Order::Linear.options().contains("Mesh.ElementOrder = 1;"));
        assert!(Order::Serendipity
            .options()
            .contains("Mesh.ElementOrder = 2;\nMesh.SecondOrderIncomplete = 1;"));
    }
}
