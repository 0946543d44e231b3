//! The MSH 4.1 reader on a hand-written fixture (tests/data/two_quadratic_triangles.msh: the
//! unit square as two 6-node triangles, contact on z = 0, far face z = 1, axis r = 0).
//! Run: `cargo test --test fem_msh`.

use spherecontact::fem::msh;
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
            assert_eq!(
                x[mid],
                [0.5 * (x[p][0] + x[q][0]), 0.5 * (x[p][1] + x[q][1])]
            );
        }
    }
}

#[test]
fn rejects_text_that_is_not_msh() {
    assert!(msh::parse(b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n").is_err());
    assert!(msh::read(Path::new("tests/data/no_such_file.msh")).is_err());
}
