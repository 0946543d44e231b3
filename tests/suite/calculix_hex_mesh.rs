//! The paper's discretisation: gmsh's 20-node hexahedra of the half body (hemisphere and the
//! paper's cap), in CalculiX's node order: four bricks per tetrahedron of the same geometry, every
//! Jacobian positive at the 27 Gauss points, the volume and the named faces' areas against the
//! exact ones, converging as the mesh is refined. Needs gmsh (skips with the reason where it is
//! absent). Run: `cargo test --test suite calculix_hex_mesh:: -- --nocapture` (prints the figures).

use spherecontact::calculix::hex_mesh::{self, HexMesh};
use spherecontact::fem::mesh::solid;
use spherecontact::fem::mesh::solid_geo::{self, SolidGeometry};
use spherecontact::fem::solid3d::meshing::{self, Zones};
use spherecontact::toolchain::{Tool, Toolchain};
use std::f64::consts::PI;

fn gmsh_present(test: &str) -> bool {
    let probe = Toolchain::default().probe(Tool::Gmsh);
    if !probe.available() {
        eprintln!("{test}: skipped, {}", probe.line());
    }
    probe.available()
}

/// The paper's sphere (R = 0.1 m) cut at `height`, contact radius 1 mm, bricks of `h` at the
/// pole and of `largest` (in R) far from it.
fn geometry(height: f64, h: f64, largest: f64) -> SolidGeometry {
    SolidGeometry {
        max_size: largest * 0.1,
        ..meshing::geometry(0.1, height, h, Zones::new(1e-3, h))
    }
}

fn mesh(g: &SolidGeometry) -> HexMesh {
    let dir = tempfile::tempdir().unwrap();
    hex_mesh::mesh(g, dir.path(), "body", &Toolchain::default())
        .unwrap()
        .0
}

/// The exact volume and areas (contact, far face, symmetry plane) of the half cap.
fn exact(g: &SolidGeometry) -> [f64; 4] {
    let (r, h) = (g.radius, g.height);
    let a2 = h * (2.0 * r - h);
    let segment = r * r * ((r - h) / r).acos() - (r - h) * a2.sqrt();
    [
        PI * h * h * (3.0 * r - h) / 6.0,
        PI * r * h,
        PI * a2 / 2.0,
        segment,
    ]
}

fn errors(mesh: &HexMesh, g: &SolidGeometry) -> [f64; 4] {
    let measured = [
        mesh.quality().volume,
        mesh.area(&mesh.contact),
        mesh.area(&mesh.far),
        mesh.area(&mesh.symmetry),
    ];
    let exact = exact(g);
    std::array::from_fn(|k| measured[k] / exact[k] - 1.0)
}

#[test]
#[ignore = "heavy: gmsh hex meshes of two bodies, 4.1 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn four_bricks_per_tetrahedron_in_calculixs_order_with_positive_jacobians() {
    if !gmsh_present("four_bricks_per_tetrahedron") {
        return;
    }
    for height in [0.1, 0.02] {
        let g = geometry(height, 2.5e-4, 0.15);
        let hex = mesh(&g);
        // The same geometry at twice the size, as tetrahedra: gmsh subdivides each into 4
        // bricks and each triangle into 3 quadrangles.
        let dir = tempfile::tempdir().unwrap();
        let tets = SolidGeometry {
            pole_size: 2.0 * g.pole_size,
            max_size: 2.0 * g.max_size,
            ..g
        };
        let files = solid_geo::mesh(&tets, dir.path(), "tets", &Toolchain::default()).unwrap();
        let tet = solid::read(&files.msh).unwrap();
        assert_eq!(hex.hexahedra.len(), 4 * tet.tetrahedra.len());
        assert_eq!(hex.contact.len(), 3 * tet.contact.len());
        // Every midside node in CalculiX's slot lies at its edge's middle (a wrong permutation
        // puts it on another edge, a fair part of an edge length away), or, on the sphere, off
        // it by the sag ρ − √(ρ² − L²/4) of an arc of the tightest curve over the chord L: the
        // rim where the sphere meets the far face, of radius ρ = √(H (2R − H)) ≤ R.
        let edges = [
            (0, 1),
            (1, 2),
            (2, 3),
            (3, 0),
            (4, 5),
            (5, 6),
            (6, 7),
            (7, 4),
            (0, 4),
            (1, 5),
            (2, 6),
            (3, 7),
        ];
        for e in 0..hex.hexahedra.len() {
            let x = hex.coords(e);
            for (k, (a, b)) in edges.into_iter().enumerate() {
                let length = (0..3).map(|d| (x[a][d] - x[b][d]).powi(2)).sum::<f64>().sqrt();
                let off = (0..3)
                    .map(|d| (x[8 + k][d] - 0.5 * (x[a][d] + x[b][d])).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let rho = (g.height * (2.0 * g.radius - g.height)).sqrt();
                let sag = rho - (rho * rho - length * length / 4.0).sqrt();
                assert!(
                    off <= sag * 1.001 + 1e-12,
                    "brick {e} node {}: {off} off, edge {length}",
                    9 + k
                );
            }
        }
        // The reader refuses a brick with a non-positive Jacobian at a Gauss point; measured here.
        let q = hex.quality();
        assert!(q.min_jacobian > 0.0 && q.min_ratio > 0.0);
        // The contact faces are the bricks' own faces, as the deck's *SURFACE names them (the
        // deck refuses a face that is no brick's).
        let faces = crate::calculix_hex20::slave_face_lines(&hex, 1.0);
        assert_eq!(faces.len(), hex.contact.len());
        assert!(faces
            .iter()
            .all(|l| (1..=6).any(|k| l.ends_with(&format!(", S{k}")))));
        let [v, contact, far, symmetry] = errors(&hex, &g);
        eprintln!(
            "H = {height}: {} bricks ({} tetrahedra × 4), {} nodes, smallest Jacobian ratio {:.3}, \
             volume {v:+.2e}, areas: contact {contact:+.2e}, far {far:+.2e}, symmetry {symmetry:+.2e}",
            hex.hexahedra.len(),
            tet.tetrahedra.len(),
            hex.nodes.len(),
            q.min_ratio
        );
    }
}

#[test]
#[ignore = "heavy: three gmsh meshes of the cap, 11 s (two test threads); .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn volume_and_areas_converge_to_the_exact_cap() {
    if !gmsh_present("volume_and_areas_converge") {
        return;
    }
    // The volume's error is the coarse far region's (the sphere between its quadratic nodes):
    // it falls as the largest brick is halved (measured +2.6e-4, +1.8e-4, +6.7e-5: the largest
    // size is not reached everywhere, so the fall is slower than the quadratic arc's own order).
    let mut previous = [f64::INFINITY; 4];
    for largest in [0.3, 0.15, 0.075] {
        let g = geometry(0.1, 5e-4, largest);
        let hex = mesh(&g);
        let e = errors(&hex, &g);
        eprintln!(
            "largest brick {largest} R: {} bricks, volume {:+.2e}, contact {:+.2e}, far {:+.2e}, symmetry {:+.2e}",
            hex.hexahedra.len(),
            e[0],
            e[1],
            e[2],
            e[3]
        );
        // Quadratic bricks of size ≤ 0.3 R on a sphere of radius R: the midside nodes take up the
        // chord's sag, leaving less than 1e-3 of the volume and areas (measured ≤ 2.6e-4).
        for (k, err) in e.iter().enumerate() {
            assert!(err.abs() < 1e-3, "quantity {k}: {err:e}");
        }
        // The flat faces are exact whatever the size (planar bricks' faces).
        assert!(e[2].abs() < 1e-9 || e[2].abs() <= previous[2].abs());
        assert!(e[0].abs() <= previous[0].abs() * 1.01, "{e:?} after {previous:?}");
        previous = e;
    }
}
