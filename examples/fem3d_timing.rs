//! Set-up cost and normal-contact accuracy of the 3D model (`fem-3d`) on the paper's spheres
//! (R 0.1 m, E 70 GPa, ν 0.3), half hemisphere gripped rigidly on its equatorial face.
//!
//! Run: `cargo run --release --example fem3d_timing -- [DIVISIONS…] [--variants]`
//! (DIVISIONS: pole size = c_max / DIVISIONS, c_max the contact radius at δn = 20 µm; default 10).
//! For each mesh: gmsh's time, nodes, DOFs, candidates, the times of assembly, ordering,
//! factorisation and condensation, the factor's entries, the peak resident memory, and P at
//! δn = 17 µm against Hertz (the raw offset: finite body against half-space). With
//! `--variants`, also the factorisation with faer's minimum degree on the whole DOF graph and the
//! condensation by blocked solves, side by side.

use std::time::Instant;

use spherecontact::contact::{Contact, DenseCompliance, Settings as ContactSettings};
use spherecontact::external::toolchain::Toolchain;
use spherecontact::fem::element::tri6::Lame;
use spherecontact::fem::mesh::solid::SolidMesh;
use spherecontact::fem::solid3d::condense::Condensation;
use spherecontact::fem::solid3d::meshing::{self, Zones};
use spherecontact::fem::solid3d::model::{Elimination, Model, Settings};
use spherecontact::fem::solid3d::ordering::NodeOrder;
use spherecontact::pair::{Body, ContactPair, Material};

/// Peak resident memory of this process so far [GB] (Linux VmHWM).
fn peak_memory_gb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse::<f64>().ok()))
        })
        .map_or(f64::NAN, |kb| kb / 1048576.0)
}

fn report(label: &str, model: &Model, pair: &ContactPair) {
    let t = model.times;
    let operator = DenseCompliance::scalar(model.condensed.normal.clone()).unwrap();
    let hertz = spherecontact::hertz::Hertz::of(pair);
    let d = 17e-6;
    let start = Instant::now();
    let mut contact: Contact<DenseCompliance, DenseCompliance> =
        Contact::new(operator, model.surface.heights(), ContactSettings::default()).unwrap();
    contact.advance(0.5 * d, &[]).unwrap();
    let solve = start.elapsed().as_secs_f64();
    let force = 2.0 * contact.normal_force();
    println!(
        "  {label}: assembly {:.2} s, ordering {:.2} s, factor {:.2} s ({:.1} M entries), condense {:.2} s; \
         P(17 µm) {:+.3} % against Hertz (normal solve {:.3} s); peak memory {:.2} GB",
        t.assembly,
        t.ordering,
        t.factor,
        model.factor.factor_entries() as f64 / 1e6,
        t.condense,
        100.0 * (force / hertz.force(d) - 1.0),
        solve,
        peak_memory_gb()
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let variants = args.iter().any(|a| a == "--variants");
    let divisions: Vec<f64> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let divisions = if divisions.is_empty() {
        vec![10.0]
    } else {
        divisions
    };
    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.3,
        },
    };
    let pair = ContactPair {
        body1: body,
        body2: body,
    };
    let radius = pair.body1.radius;
    let c_max = spherecontact::hertz::Hertz::of(&pair).contact_radius(20e-6);
    let lame = Lame::of(&pair.body1.material);
    for n in divisions {
        let h = c_max / n;
        let zones = Zones::new(c_max, h);
        let geometry = meshing::geometry(radius, radius, h, zones);
        let (mesh, mesh_s): (SolidMesh, f64) = match meshing::generate(&geometry, &Toolchain::default()) {
            Ok(m) => m,
            Err(e) => {
                println!("c/{n}: {e}");
                continue;
            }
        };
        println!(
            "pole size c_max/{n} = {:.1} µm: gmsh + read {:.2} s, {} nodes, {} tetrahedra",
            1e6 * h,
            mesh_s,
            mesh.nodes.len(),
            mesh.tetrahedra.len()
        );
        let mut runs = vec![(
            Elimination::ContactLast(NodeOrder::MinimumDegree),
            Condensation::TrailingBlock,
        )];
        if variants {
            runs.push((
                Elimination::ContactLast(NodeOrder::NestedDissection),
                Condensation::TrailingBlock,
            ));
            runs.push((Elimination::DofAmd, Condensation::BlockedSolves));
        }
        for (elimination, condensation) in runs {
            let settings = Settings {
                candidate_radius: zones.candidate_radius,
                elimination,
                condensation,
            };
            let model = Model::build(mesh.clone(), lame, &settings).unwrap();
            println!(
                "  {} DOFs, {} candidate nodes ({} tangential unknowns)",
                model.dofs(),
                model.surface.len(),
                model.condensed.tangential_unknowns.len()
            );
            report(&format!("{elimination:?} + {condensation:?}"), &model, &pair);
        }
    }
}
