//! The MSH 4.1 reader on a hand-written fixture (tests/data/two_quadratic_triangles.msh: the
//! unit square as two 6-node triangles, contact on z = 0, far face z = 1, axis r = 0) and on a
//! gmsh-written mesh of the paper's hemisphere (tests/data/sphere_gmsh_h150um.msh).
//! Run: `cargo test --test suite fem_msh::`.

use spherecontact::fem::mesh::msh;
use std::path::Path;

#[test]
fn reads_the_two_triangle_fixture_with_its_boundaries() {
    let mesh = msh::read(Path::new("tests/data/two_quadratic_triangles.msh")).unwrap();
    assert_eq!(mesh.nodes.len(), 9);
    assert_eq!(mesh.triangles.len(), 2);
    // The contact edge runs from the pole (0, 0) through (0.5, 0) to (1, 0).
    assert_eq!(mesh.surface.len(), 1);
    let [a, m, b] = mesh.surface[0].map(|n| mesh.nodes[n]);
    assert_eq!((a, m, b), ([0.0, 0.0], [0.5, 0.0], [1.0, 0.0]));
    let far: Vec<[f64; 2]> = mesh.far.iter().map(|&n| mesh.nodes[n]).collect();
    assert!(far.len() == 3 && far.iter().all(|x| x[1] == 1.0));
    let axis: Vec<[f64; 2]> = mesh.axis.iter().map(|&n| mesh.nodes[n]).collect();
    assert!(axis.len() == 3 && axis.iter().all(|x| x[0] == 0.0));
    // Both triangles counter-clockwise with their midsides between their corners.
    for t in &mesh.triangles {
        let x = t.map(|n| mesh.nodes[n]);
        for (mid, (p, q)) in [(3, (0, 1)), (4, (1, 2)), (5, (2, 0))] {
            assert_eq!(x[mid], [0.5 * (x[p][0] + x[q][0]), 0.5 * (x[p][1] + x[q][1])]);
        }
    }
}

#[test]
fn rejects_text_that_is_not_msh() {
    assert!(msh::parse(b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n").is_err());
    assert!(msh::read(Path::new("tests/data/no_such_file.msh")).is_err());
}

/// A gmsh 4.8.4 mesh of the paper's hemisphere, written from
/// the `.geo` of `crates/solvers/src/fem/mesh/geo.rs` (the external decks' geometry) by
/// `gmsh axisym_quarter.geo -2 -setnumber hmin 1.5e-4 -setnumber hmax 2e-2 -setnumber dfine 1.3e-3
/// -setnumber dcoarse 0.05 -format msh41`: pole size 150 µm, 6-node triangles.
const GMSH_SPHERE: &str = "tests/data/sphere_gmsh_h150um.msh";

#[test]
fn the_gmsh_mesh_of_the_decks_feeds_the_solver_and_agrees_with_the_generated_mesh() {
    use spherecontact::domain::{Domain, Grip};
    use spherecontact::fem::FemAxisym;
    use spherecontact::pair::{Body, ContactPair, Material};
    use spherecontact::path::{LoadingPath, Position};
    use spherecontact::scene::Scene;
    use spherecontact::solver::run;

    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.3,
        },
    };
    let positions = [0.0, 17e-6]
        .map(|delta_n| Position {
            delta_n,
            delta_t: 0.0,
        })
        .to_vec();
    let scene = Scene {
        name: "gmsh".into(),
        pair: ContactPair {
            body1: body,
            body2: body,
        },
        friction: 0.2,
        path: LoadingPath::try_new(positions, vec![1]).unwrap(),
        // The fixture's far face carries tag 2: it was made for the axial grip.
        domain: Domain {
            grip: Grip::Axial,
            ..Domain::default()
        },
        fields: Default::default(),
    };
    let mesh = msh::read(Path::new(GMSH_SPHERE)).unwrap();
    assert!(
        (mesh.pole_size() - 1.5e-4).abs() < 0.5e-4,
        "pole size {}",
        mesh.pole_size()
    );
    let from_file = FemAxisym {
        mesh_file: Some(GMSH_SPHERE.into()),
        ..FemAxisym::default()
    };
    let generated = FemAxisym::with_pole_size(mesh.pole_size());
    let p = |solver: &FemAxisym| {
        run(solver, &scene)
            .unwrap()
            .at_position(1)
            .unwrap()
            .normal_force
            .unwrap()
    };
    let (p_file, p_generated) = (p(&from_file), p(&generated));
    // A mesh made for another grip, or another cut, is refused with the reason.
    let mut rigid = scene.clone();
    rigid.domain.grip = Grip::Rigid;
    let e = run(&from_file, &rigid).unwrap_err().to_string();
    assert!(e.contains("axial grip") && e.contains("rigid grip"), "{e}");
    let mut cap = scene.clone();
    cap.domain.kind = spherecontact::domain::DomainKind::Cap { height: 0.02 };
    let e = run(&from_file, &cap).unwrap_err().to_string();
    assert!(e.contains("cut at 2e-2 m"), "{e}");
    let hertz = scene.hertz().force(17e-6);
    println!(
        "P against Hertz: gmsh mesh {:+.3} %, generated mesh {:+.3} %",
        100.0 * (p_file / hertz - 1.0),
        100.0 * (p_generated / hertz - 1.0)
    );
    // Same model (hemisphere loaded on its equatorial face), different meshes of 150 µm at the
    // pole: both carry the +0.37 % finite-body offset; their mesh errors at c/6 differ by less
    // than 0.3 % (the generated ladder changes P by ≤ 0.36 % RMS from c/5 to c/10).
    assert!((p_file / p_generated - 1.0).abs() < 3e-3);
}
