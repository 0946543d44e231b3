//! Closed-form and incremental contact models: the references every numerical solver is
//! checked against, and the DEM laws whose distance from them the harness measures.
//!
//! | solver | model | along a general path |
//! |---|---|---|
//! | `hertz` | Hertz normal contact | exact (frictionless normal part) |
//! | `cattaneo-mindlin` | Cattaneo–Mindlin + Masing | only at constant normal load |
//! | `mdr` | method of dimensionality reduction | exact Mindlin–Deresiewicz |
//! | `mdr-domain` ([`mdr_series`], run by `fem::axisym`) | MDR in series with a finite body's compliances | exact MD for the modelled finite body, to first order |
//! | `hertz-mindlin-spring` | no-slip spring with Coulomb cap | approximate (DEM) |
//! | `thornton` | Thornton (1991): M–D increments, T*, T** | approximate (DEM) |
//! | `md-incremental` | Mindlin–Deresiewicz incremental cases (the basis of Zhang & Vu-Quoc 2007), Masing memory | approximate (DEM) |
//! | `walton-braun` | Walton & Braun (1986), T* scaled with N | approximate (DEM) |

pub mod cattaneo_mindlin;
pub mod hertz;
pub mod hertz_mindlin_spring;
pub mod incremental;
pub mod md_cases;
pub mod md_incremental;
pub mod mdr;
pub mod mdr_series;
pub mod thornton;
pub mod walton_braun;

use crate::solver::Solver;
use incremental::IncrementalSolver;

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
/// path as solvers, and as the contact law of an impact (`crate::impact`).
pub fn dem_laws() -> Vec<IncrementalSolver> {
    vec![
        IncrementalSolver {
            name: "hertz-mindlin-spring",
            description: "no-slip Hertz–Mindlin spring k_t = 8G*c with a Coulomb cap (LIGGGHTS, YADE)",
            make_law: |scene| Box::new(hertz_mindlin_spring::HertzMindlinSpring::new(scene)),
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
