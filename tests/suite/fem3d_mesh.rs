//! The 3D body's gmsh mesh: gmsh's node order is the element's, the groups are where the model
//! needs them, on the hemisphere and on a cap; a first-order mesh is refused naming the file.
//! Needs gmsh (skips with the reason where it is absent). Run: `cargo test --test suite fem3d_mesh::`.

use spherecontact::fem::element::tet10::EDGES;
use spherecontact::fem::mesh::solid::{self, SolidMesh};
use spherecontact::fem::mesh::solid_geo::{self, SolidGeometry};
use spherecontact::fem::solid3d::meshing::{self, Zones};
use spherecontact::toolchain::{Tool, Toolchain};

fn gmsh_present(test: &str) -> bool {
    let probe = Toolchain::default().probe(Tool::Gmsh);
    if !probe.available() {
        eprintln!("{test}: skipped, {}", probe.line());
    }
    probe.available()
}

/// A coarse mesh of the paper's sphere (R = 0.1 m) cut at `height`, contact radius 1 mm.
fn geometry(height: f64) -> SolidGeometry {
    let (c, h) = (1e-3, 2.5e-4);
    meshing::geometry(0.1, height, h, Zones::new(c, h))
}

fn check_groups(mesh: &SolidMesh, g: &SolidGeometry) {
    let tol = 1e-9 * g.radius;
    let on_sphere = |p: [f64; 3]| (p[0].hypot(p[1]).hypot(p[2] - g.radius) - g.radius).abs() < tol;
    assert!(SolidMesh::nodes_of(&mesh.contact)
        .iter()
        .all(|&n| on_sphere(mesh.nodes[n])));
    assert!(SolidMesh::nodes_of(&mesh.far)
        .iter()
        .all(|&n| (mesh.nodes[n][2] - g.height).abs() < tol));
    assert!(SolidMesh::nodes_of(&mesh.symmetry)
        .iter()
        .all(|&n| mesh.nodes[n][1].abs() < tol));
    assert!(mesh
        .nodes
        .iter()
        .all(|p| p[1] > -tol && p[2] > -tol && p[2] < g.height + tol));
}

#[test]
fn gmsh_node_order_is_the_elements_and_the_groups_are_in_place() {
    if !gmsh_present("gmsh_node_order_is_the_elements_and_the_groups_are_in_place") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    for height in [0.1, 0.02] {
        let g = geometry(height);
        let files = solid_geo::mesh(&g, dir.path(), "body", &Toolchain::default()).unwrap();
        let mesh = solid::read(&files.msh).unwrap();
        // Every midside node lies near the middle of the edge the element's order gives it
        // (exactly on straight edges, off by the sagitta ≈ h²/8R ≪ h on the sphere).
        for t in &mesh.tetrahedra {
            for (k, [i, j]) in EDGES.iter().enumerate() {
                let (a, b, m) = (mesh.nodes[t[*i]], mesh.nodes[t[*j]], mesh.nodes[t[4 + k]]);
                let length = (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt();
                let off = (0..3)
                    .map(|c| (m[c] - 0.5 * (a[c] + b[c])).powi(2))
                    .sum::<f64>()
                    .sqrt();
                assert!(
                    off < 0.05 * length,
                    "midside {k} is {off} off an edge of {length}"
                );
            }
        }
        check_groups(&mesh, &g);
    }
}

#[test]
fn a_first_order_mesh_is_refused_naming_the_file() {
    if !gmsh_present("a_first_order_mesh_is_refused_naming_the_file") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let geo = dir.path().join("body.geo");
    let text = geometry(0.1).geo().unwrap();
    assert!(text.contains("Mesh.ElementOrder = 2;"));
    std::fs::write(
        &geo,
        text.replace("Mesh.ElementOrder = 2;", "Mesh.ElementOrder = 1;"),
    )
    .unwrap();
    let msh = dir.path().join("linear.msh");
    let status = std::process::Command::new("gmsh")
        .args([
            geo.to_str().unwrap(),
            "-3",
            "-format",
            "msh41",
            "-o",
            msh.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(status.status.success());
    let Err(error) = solid::read(&msh) else {
        panic!("a first-order mesh was accepted");
    };
    let message = error.to_string();
    assert!(
        message.contains("linear.msh") && message.contains("first-order"),
        "{message}"
    );
}
