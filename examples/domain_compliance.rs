//! The modelled domain's compliances relative to the half-space (normal and tangential), on a
//! ladder of pole sizes and over the contact radii of the paper path: the numbers behind
//! `mdr-domain`, their mesh convergence and their (weak) dependence on the contact radius.
//!
//! Run: `cargo run --release --example domain_compliance`. For each domain (the hemisphere under
//! either grip, the paper's 20 mm cap gripped rigidly) and each level of the uniform ladder
//! (pole size c_max/10 · 2^-k and the grading's growth / 2^k, k = 0 … 3: every element halved
//! per level) it prints λ_n and λ_t [m/N] at the contact radii of δn = 5, 10, 17 and 20 µm
//! (load-weighted, and at the pole).

use spherecontact::domain::{Domain, DomainKind, Grip};
use spherecontact::fem::axisym::compliance::FiniteBody;
use spherecontact::fem::axisym::model::{grading, Settings, GROWTH};
use spherecontact::fem::element::tri6::Integration;
use spherecontact::fem::factor::Ordering;
use spherecontact::fem::mesh::meridian;
use spherecontact::memory::{self, Budget};
use spherecontact::pair::{Body, Material};

fn main() {
    let body = Body {
        radius: 0.1,
        material: Material {
            young: 70e9,
            poisson: 0.3,
        },
    };
    // Contact radii of the paper's spheres (R* = 0.05 m); c_max at δn = 20 µm.
    let c_of = |delta_um: f64| (0.05 * delta_um * 1e-6_f64).sqrt();
    let c_max = c_of(20.0);
    let domains = [
        ("hemisphere, rigid grip", Domain::default()),
        (
            "hemisphere, axial grip",
            Domain {
                grip: Grip::Axial,
                ..Domain::default()
            },
        ),
        (
            "cap 20 mm, rigid grip",
            Domain {
                kind: DomainKind::Cap { height: 0.02 },
                grip: Grip::Rigid,
                ..Domain::default()
            },
        ),
    ];
    let show = |v: Option<f64>| v.map_or("—".to_owned(), |v| format!("{v:+.5e}"));
    for (name, domain) in domains {
        println!("== {name}: λ [m/N] per body (load-weighted / at the pole)");
        for level in 0..4 {
            let refinement = f64::from(1u32 << level);
            let divisions = 10.0 * refinement;
            let settings = Settings {
                pole_size: c_max / divisions,
                candidate_radius: 1.25 * c_max,
                ordering: Ordering::Amd,
                integration: Integration::Full,
                domain,
                growth: GROWTH / refinement,
                shear: false,
                contact_radius: c_max,
            };
            let g = grading(&body, &settings, c_max);
            let mesh = meridian::graded(&g).unwrap();
            let start = std::time::Instant::now();
            let tangential = domain.grip == Grip::Rigid;
            let budget = Budget::new("mdr-domain", c_max, settings.pole_size, memory::MERIDIAN);
            let finite = FiniteBody::new(
                mesh,
                body.material,
                domain.grip,
                Integration::Full,
                tangential,
                &budget,
            )
            .unwrap();
            let factored = start.elapsed().as_secs_f64();
            for delta_um in [5.0, 10.0, 17.0, 20.0] {
                let l = finite.compliance(c_of(delta_um)).unwrap();
                println!(
                    "h = c_max/{divisions:<3} growth/{refinement} δn = {delta_um:4.1} µm  λ_n {:+.5e} / {:+.5e}  λ_t {} / {}",
                    l.normal,
                    l.normal_at_pole,
                    show(l.tangential),
                    show(l.tangential_at_pole),
                );
            }
            println!(
                "   ({} + {} DOFs, factored in {factored:.2} s)",
                finite.dofs()[0],
                finite.dofs()[1]
            );
        }
    }
}
