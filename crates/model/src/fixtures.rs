//! Fixtures for tests and examples: the paper's spheres (R = 0.1 m, E = 70 GPa, ν = 0.3, μ = 0.2)
//! and scenes of them along a path given in µm, built without a case file.

use crate::pair::{Body, ContactPair, Material};
use crate::path::{LoadingPath, Position};
use crate::scene::Scene;

/// The paper's two spheres: R = 0.1 m, E = 70 GPa, ν = 0.3.
pub fn paper_pair() -> ContactPair {
    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.3,
        },
    };
    ContactPair {
        body1: body,
        body2: body,
    }
}

/// The paper's spheres with μ = 0.2 along the positions (`delta_n_um`, `delta_t_um`) [µm], each
/// segment in `substeps` increments; the hemisphere domain and no fields, as a case without
/// `[domain]` or `fields` gives.
pub fn paper_scene(delta_n_um: &[f64], delta_t_um: &[f64], substeps: usize) -> Scene {
    let positions: Vec<Position> = delta_n_um
        .iter()
        .zip(delta_t_um)
        .map(|(&n, &t)| Position {
            delta_n: n * 1e-6,
            delta_t: t * 1e-6,
        })
        .collect();
    let segments = vec![substeps; positions.len() - 1];
    Scene {
        name: "test".into(),
        pair: paper_pair(),
        friction: 0.2,
        path: LoadingPath::try_new(positions, segments).expect("a valid test path"),
        domain: Default::default(),
        fields: Default::default(),
    }
}

/// [`paper_scene`] along a normal path through `delta_n_um` [µm], four increments a segment.
pub fn test_scene(delta_n_um: &[f64]) -> Scene {
    paper_scene(delta_n_um, &vec![0.0; delta_n_um.len()], 4)
}

/// The repository's root folder (its `cases/`, `reference/`, `examples/`), for the tests of every
/// crate: a unit test runs in its own crate's folder, `crates/<name>`.
pub fn repository() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}
