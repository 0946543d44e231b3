//! fem-3d's peak pressure p0 under refinement: the fit to the hat averages of the contact rule's
//! pressure (`fit::surface::peak_by_moments`, what fem-3d reports) beside the same fit to its
//! nodal values (`fit::profile::peak_pressure`), both against fem-axisym on the same finite body
//! (the paper's spheres, hemisphere gripped axially, δn = 17 and 25 µm), with P and c.
//!
//! Run: `cargo run --release --example fem3d_peak -- [DIVISIONS…]` (pole size c_max/DIVISIONS;
//! default 6 8 10 14; c_max/14 takes about 2.7 GB). Needs gmsh.

use spherecontact::domain::Grip;
use spherecontact::fem::{FemAxisym, FemSolid3d};
use spherecontact::fit::profile::peak_pressure;
use spherecontact::history::History;
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::solver::{self, Solver};

/// The paper's spheres loaded to δn = 17 and 25 µm, gripped axially (fem-axisym's domain).
fn scene() -> Scene {
    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.3,
        },
    };
    let positions = [0.0, 17.0, 25.0]
        .map(|d| Position {
            delta_n: d * 1e-6,
            delta_t: 0.0,
        })
        .to_vec();
    let mut scene = Scene {
        name: "fem3d-peak".into(),
        pair: ContactPair {
            body1: body,
            body2: body,
        },
        friction: 0.2,
        path: LoadingPath::try_new(positions, vec![1, 1]).expect("a path"),
        domain: Default::default(),
        fields: Default::default(),
    };
    scene.domain.grip = Grip::Axial;
    scene
}

fn run(solver: &dyn Solver, scene: &Scene) -> History {
    solver::run(solver, scene).unwrap_or_else(|e| panic!("{}: {e}", solver.name()))
}

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("DIVISIONS: a number"))
        .collect();
    let divisions = if args.is_empty() {
        vec![6.0, 8.0, 10.0, 14.0]
    } else {
        args
    };
    let scene = scene();
    let axisym = run(&FemAxisym::default(), &scene);
    println!("fem-3d against fem-axisym (c_max/40) on the axially gripped hemisphere, in %:");
    for n in divisions {
        let solid = run(
            &FemSolid3d::with_pole_size(scene.max_contact_radius() / n),
            &scene,
        );
        for position in [1, 2] {
            let (a, s) = (
                axisym.at_position(position).expect("a row"),
                solid.at_position(position).expect("a row"),
            );
            let rel = |v: Option<f64>, r: Option<f64>| {
                100.0 * (v.expect("a value") / r.expect("a reference") - 1.0)
            };
            let field = solid.field_at(position).expect("a field");
            let radii: Vec<f64> = field.points.iter().map(|p| p[0].hypot(p[1])).collect();
            let c = s.contact_radius.expect("c");
            let nodal = peak_pressure(&radii, &field.pressure, &field.pressure, c);
            println!(
                "c_max/{n} δn {:>2.0} µm (h = c/{:.1}): P {:+.4}, c {:+.4}, p0 hat averages {:+.4}, p0 nodal {:+.4}",
                1e6 * s.delta_n,
                c * n / scene.max_contact_radius(),
                rel(s.normal_force, a.normal_force),
                rel(s.contact_radius, a.contact_radius),
                rel(s.peak_pressure, a.peak_pressure),
                rel(nodal, a.peak_pressure),
            );
        }
    }
}
