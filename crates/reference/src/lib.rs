//! # spherecontact-reference: the exact references, a library
//!
//! **Job.** The answers the harness judges by: Hertz, Cattaneo–Mindlin, Mindlin–Deresiewicz along any path by MDR ([`mdr`]), its finite-body correction ([`mdr_series`]), the exact quasi-static reference of an impact ([`impact`]), and the incremental DEM laws whose distance from them is measured.
//!
//! **May depend on.** `spherecontact-model` and `spherecontact-system` (the impact table's files read by rule, a command's permission) only: no linear algebra, no plotting, no command line.
//!
//! **Offers.** Every model a `Solver` of its own (`solvers()`, `dem_laws()`), usable from any Rust test suite, as the example below does.
//!
//! ## Q along a path, and your own values against it
//!
//! ```
//! use spherecontact_model::fixtures::paper_scene;
//! use spherecontact_model::hertz::Hertz;
//! use spherecontact_model::solver::Solver;
//! use spherecontact_reference::mdr::Mdr;
//!
//! // The paper's spheres (R = 0.1 m, E = 70 GPa, ν = 0.3, μ = 0.2) pressed to δn = 17 µm, then
//! // moved δt = 2 µm sideways at that approach; ten increments a segment.
//! let scene = paper_scene(&[0.0, 17.0, 17.0], &[0.0, 0.0, 2.0], 10);
//! let exact = Mdr::default().solve(&scene).expect("MDR solves any path of two spheres");
//!
//! // Your law's Q at the same steps: here a no-slip spring K = 8 G* c capped at μP, the first
//! // guess of many DEM codes.
//! let hertz = Hertz::of(&scene.pair);
//! let shear = scene.pair.mindlin_shear_modulus();
//! let yours: Vec<f64> = scene
//!     .steps()
//!     .iter()
//!     .map(|s| (8.0 * shear * hertz.contact_radius(s.delta_n) * s.delta_t).min(scene.friction * hertz.force(s.delta_n)))
//!     .collect();
//!
//! // Their distance, on the scale of the sliding force μP at 17 µm.
//! let sliding = scene.friction * hertz.force(17e-6);
//! let mut worst: f64 = 0.0;
//! for (row, q) in exact.steps.iter().zip(&yours) {
//!     let exact_q = row.tangential_force.expect("MDR gives Q at every step");
//!     worst = worst.max((q - exact_q).abs() / sliding);
//! }
//! println!("your law is {:.1} % of μP from exact Mindlin–Deresiewicz", 100.0 * worst);
//! assert!(worst > 0.01, "a no-slip spring is stiffer than a contact whose edge slips");
//!
//! // At constant approach and growing δt, exact MD is Cattaneo–Mindlin's closed form
//! // Q = μP [1 − (1 − δt/δ*)^(3/2)], δ* = 3μP / (16 G* c). Tolerance 1e-3 μP: MDR's
//! // 4000 springs resolve the stick radius to a few 1e-4 of c.
//! let c = hertz.contact_radius(17e-6);
//! let slip_onset = 3.0 * sliding / (16.0 * shear * c);
//! let last = exact.steps.last().unwrap();
//! let closed_form = sliding * (1.0 - (1.0 - last.delta_t / slip_onset).powf(1.5));
//! assert!((last.tangential_force.unwrap() - closed_form).abs() <= 1e-3 * sliding);
//! ```
//!
//! Closed-form and incremental contact models: the references every numerical solver is
//! checked against, and the DEM laws whose distance from them the harness measures.
//!
//! | solver | model | along a general path |
//! |---|---|---|
//! | `hertz` | Hertz normal contact | exact (frictionless normal part) |
//! | `cattaneo-mindlin` | Cattaneo–Mindlin + Masing | only at constant normal load |
//! | `mdr` | method of dimensionality reduction | exact Mindlin–Deresiewicz |
//! | `mdr-domain` ([`mdr_series`], run by `fem::axisym`) | MDR in series with a finite body's compliances | exact MD for the modelled finite body, to first order |
//! | `hertz-mindlin-spring` | no-slip spring with Coulomb cap, incremental | approximate (DEM) |
//! | `hertz-mindlin-spring-rescaled` | the spring, its stored force scaled by c/c_before on unloading | approximate (DEM) |
//! | `hertz-mindlin-total` | no-slip spring with Coulomb cap, total form (stored displacement) | approximate (DEM) |
//! | `thornton` | Thornton (1991): M–D increments, T*, T** | approximate (DEM) |
//! | `md-incremental` | Mindlin–Deresiewicz incremental cases (the basis of Zhang & Vu-Quoc 2007), Masing memory | approximate (DEM) |
//! | `walton-braun` | Walton & Braun (1986), T* scaled with N | approximate (DEM) |

pub mod cattaneo_mindlin;
pub mod hertz;
pub mod hertz_mindlin_spring;
pub mod hertz_mindlin_total;
pub mod impact;
pub mod incremental;
pub mod md_cases;
pub mod md_incremental;
pub mod mdr;
pub mod mdr_series;
pub mod thornton;
pub mod walton_braun;

use incremental::IncrementalSolver;
use spherecontact_model::solver::Solver;

/// The analytic solvers, references first, then the DEM laws.
pub fn solvers() -> Vec<Box<dyn Solver>> {
    let references: Vec<Box<dyn Solver>> = vec![
        Box::new(hertz::HertzSolver),
        Box::new(cattaneo_mindlin::CattaneoMindlin),
        Box::new(mdr::Mdr::default()),
    ];
    let laws = dem_laws().into_iter().map(|law| Box::new(law) as Box<dyn Solver>);
    references.into_iter().chain(laws).collect()
}

/// The incremental DEM laws (Hertz normal force, an incremental tangential law): driven along a
/// path as solvers, and as the contact law of an impact (`spherecontact-impact`).
pub fn dem_laws() -> Vec<IncrementalSolver> {
    vec![
        IncrementalSolver {
            name: "hertz-mindlin-spring",
            description: "no-slip Hertz–Mindlin spring k_t = 8G*c with a Coulomb cap, incremental (YADE, LAMMPS mindlin/force)",
            make_law: |scene| Box::new(hertz_mindlin_spring::HertzMindlinSpring::new(scene)),
        },
        IncrementalSolver {
            name: "hertz-mindlin-spring-rescaled",
            description: "the spring with its stored force scaled by c/c_before on unloading \
                          (Kratos DEM_D_Hertz_viscous_Coulomb, LAMMPS mindlin_rescale/force)",
            make_law: |scene| Box::new(hertz_mindlin_spring::HertzMindlinSpring::rescaled(scene)),
        },
        IncrementalSolver {
            name: "hertz-mindlin-total",
            description: "no-slip Hertz–Mindlin spring in total form: stored displacement × current 8G*c, Coulomb cap \
                          (LIGGGHTS history, LAMMPS mindlin)",
            make_law: |scene| Box::new(hertz_mindlin_total::HertzMindlinTotal::new(scene)),
        },
        IncrementalSolver {
            name: "thornton",
            description: "Thornton (1991): Mindlin–Deresiewicz increments with θ, T*, T** and μΔN(1−θ)",
            make_law: |scene| Box::new(thornton::law(scene)),
        },
        IncrementalSolver {
            name: "md-incremental",
            description: "Mindlin–Deresiewicz incremental cases that Zhang & Vu-Quoc build on, \
                          displacement-driven, Masing memory; not Zhang & Vu-Quoc's own refinements",
            make_law: |scene| Box::new(md_cases::law(scene)),
        },
        IncrementalSolver {
            name: "walton-braun",
            description: "Walton & Braun (1986): softening k_t from the last reversal, T* scaled with N",
            make_law: |scene| Box::new(walton_braun::WaltonBraun::new(scene)),
        },
    ]
}
