//! The Kratos FEM deck `kratos-3d`: the frictional path in 3D with Kratos'
//! ContactStructuralMechanicsApplication (10.4.4), the paper's kind of contact — mortar
//! augmented Lagrangian with Coulomb friction (`ALMContactFrictional`) — and its frictionless and
//! penalty variants (`[kratos] contact`). Both spheres' halves (y ≥ 0; whole under friction,
//! [`linear`]) on fem-3d's gmsh geometry of the case's `[domain]` body, in first-order elements (Kratos' mortar conditions are linear
//! only; `[kratos] element`): 4-node tetrahedra on the corners of its quadratic mesh
//! ([`linear`]) or gmsh's 8-node bricks of the same body ([`bricks8`]); sphere 2 the mirror image
//! of sphere 1, one Kratos step per path step.
//!
//! The files are readable and run by hand (`spherecontact deck write`): `spheres.mdpa`
//! ([`mdpa`]), `ProjectParameters.json` and `materials.json` ([`project`]), the driver
//! `kratos_3d.py` (`templates/kratos_3d.py`, a fixed file that reads `path.txt`) which keeps what
//! Kratos' `AnalysisStage` discards: each step's converged flag, iterations and residual
//! ([`results`]). A step Kratos did not converge is never a value ([`solid`]).
//!
//! Model and findings: docs/external-decks.md, "Kratos 3D".

pub mod bricks8;
pub mod linear;
pub mod mdpa;
pub mod project;
pub mod results;
pub mod slave;
pub mod solid;
mod vector;

pub use solid::KratosSolid;
