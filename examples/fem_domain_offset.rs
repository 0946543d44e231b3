//! The finite-body (domain) offset of `fem-axisym`'s P from Hertz on the paper's spheres,
//! separated from the mesh error by Richardson extrapolation in the pole size.
//!
//! Run: `cargo run --release --example fem_domain_offset`. P_h = P_∞ + A h^k: three pole sizes
//! c/20, c/40, c/80 give k and P_∞; P_∞/P_Hertz − 1 is the domain part, P_h/P_∞ − 1 the mesh part.

use spherecontact::fem::FemAxisym;
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::solver::run;

fn main() {
    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.3,
        },
    };
    for delta_um in [17.0, 25.0] {
        let positions = [0.0, delta_um * 1e-6]
            .map(|delta_n| Position {
                delta_n,
                delta_t: 0.0,
            })
            .to_vec();
        let scene = Scene {
            name: "offset".into(),
            pair: ContactPair {
                body1: body,
                body2: body,
            },
            friction: 0.2,
            path: LoadingPath::try_new(positions, vec![1]).unwrap(),
            domain: Default::default(),
            fields: Default::default(),
        };
        let c = scene.max_contact_radius();
        let p: Vec<f64> = [20.0, 40.0, 80.0]
            .iter()
            .map(|n| {
                run(&FemAxisym::with_pole_size(c / n), &scene)
                    .unwrap()
                    .at_position(1)
                    .unwrap()
                    .normal_force
                    .unwrap()
            })
            .collect();
        let k = ((p[0] - p[1]) / (p[1] - p[2])).abs().log2();
        let p_inf = p[2] + (p[2] - p[1]) / (2f64.powf(k) - 1.0);
        let hertz = scene.hertz().force(delta_um * 1e-6);
        println!(
            "δn = {delta_um} µm: P(c/20, c/40, c/80) = {:.4}, {:.4}, {:.4} N; rate {k:.2}; P_∞ = {p_inf:.4} N; Hertz {hertz:.4} N; \
             domain {:+.4} %, mesh at c/40 {:+.4} %",
            p[0], p[1], p[2],
            100.0 * (p_inf / hertz - 1.0),
            100.0 * (p[1] / p_inf - 1.0)
        );
    }
}
