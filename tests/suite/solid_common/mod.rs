//! A structured mesh of 10-node tetrahedra on a box, for the 3D element and surface-rule tests.
#![allow(dead_code)] // each test binary uses a different subset

use spherecontact::fem::element::tet10;
use spherecontact::fem::mesh::solid::SolidMesh;

/// The box [0, size[0]] × [0, size[1]] × [0, size[2]] cut into n³ cubes, each into six
/// tetrahedra around its main diagonal (Kuhn's conforming triangulation); the nodes are the
/// (2n + 1)³ points of the half-step grid, midside nodes at the middles of straight edges.
/// With `distort`, interior corner nodes are moved by up to 0.15 of a cell (midsides follow).
/// Faces: contact z = 0, far z = size[2], symmetry y = 0.
pub fn block(n: usize, size: [f64; 3], distort: bool) -> SolidMesh {
    let m = 2 * n + 1;
    let id = |i: usize, j: usize, k: usize| (i * m + j) * m + k;
    let mut nodes = vec![[0.0; 3]; m * m * m];
    for i in 0..m {
        for j in 0..m {
            for k in 0..m {
                let g = [i, j, k];
                nodes[id(i, j, k)] = std::array::from_fn(|a| size[a] * g[a] as f64 / (m - 1) as f64);
            }
        }
    }
    if distort {
        for i in (2..m - 1).step_by(2) {
            for j in (2..m - 1).step_by(2) {
                for k in (2..m - 1).step_by(2) {
                    let s = ((i * 7 + j * 13 + k * 5) % 7) as f64 / 6.0 - 0.5; // in [−½, ½]
                    let p = &mut nodes[id(i, j, k)];
                    for a in 0..3 {
                        p[a] += 0.3 * s * size[a] / n as f64 * [1.0, -0.7, 0.4][a];
                    }
                }
            }
        }
    }
    let mut tetrahedra = Vec::new();
    let permutations = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                for p in permutations {
                    // Corners on the doubled grid: 0, e_p0, e_p0 + e_p1, (1,1,1).
                    let mut corner = [[2 * i, 2 * j, 2 * k]; 4];
                    for (c, steps) in [(1, 1), (2, 2), (3, 3)] {
                        for s in 0..steps {
                            corner[c][p[s]] += 2;
                        }
                    }
                    let at = |g: [usize; 3]| id(g[0], g[1], g[2]);
                    let mut t = [0; 10];
                    for c in 0..4 {
                        t[c] = at(corner[c]);
                    }
                    for (e, [a, b]) in tet10::EDGES.iter().enumerate() {
                        t[4 + e] = at(std::array::from_fn(|d| (corner[*a][d] + corner[*b][d]) / 2));
                    }
                    tetrahedra.push(t);
                }
            }
        }
    }
    // Midside nodes back to the middle of their (straight) edges after the distortion.
    for t in &tetrahedra {
        for (e, [a, b]) in tet10::EDGES.iter().enumerate() {
            nodes[t[4 + e]] = std::array::from_fn(|d| 0.5 * (nodes[t[*a]][d] + nodes[t[*b]][d]));
        }
    }
    let mut mesh = SolidMesh {
        nodes,
        tetrahedra,
        ..SolidMesh::default()
    };
    for e in 0..mesh.tetrahedra.len() {
        if tet10::map(&mesh.coords(e), [0.25; 3]).is_none() {
            let t = &mut mesh.tetrahedra[e];
            t.swap(1, 2);
            t.swap(4, 6);
            t.swap(8, 9);
        }
    }
    mesh.contact = faces_on(&mesh, 2, 0.0);
    mesh.far = faces_on(&mesh, 2, size[2]);
    mesh.symmetry = faces_on(&mesh, 1, 0.0);
    mesh
}

/// The 6-node element faces lying in the plane x_axis = value (gmsh's triangle order).
pub fn faces_on(mesh: &SolidMesh, axis: usize, value: f64) -> Vec<[usize; 6]> {
    let on = |n: usize| (mesh.nodes[n][axis] - value).abs() < 1e-12;
    let mut faces = Vec::new();
    for t in &mesh.tetrahedra {
        for face in [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]] {
            if face.iter().all(|&c| on(t[c])) {
                let mid = |a: usize, b: usize| {
                    let e = tet10::EDGES
                        .iter()
                        .position(|&[p, q]| (p, q) == (a, b) || (p, q) == (b, a))
                        .expect("every corner pair is an edge");
                    t[4 + e]
                };
                let [a, b, c] = face;
                faces.push([t[a], t[b], t[c], mid(a, b), mid(b, c), mid(c, a)]);
            }
        }
    }
    faces
}
