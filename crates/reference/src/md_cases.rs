//! `md-incremental`: the Mindlin–Deresiewicz incremental cases on which Zhang & Vu-Quoc (2007,
//! J. Comput. Phys. 225, 730–752) build their displacement-driven law — not their law itself,
//! which is why it does not carry their name. (These are the "loading spring constants given by
//! Zhang and Quoc" that the reproduced paper compares its FEM with.)
//!
//! What is implemented: the force-driven incremental relations of Mindlin & Deresiewicz (1953)
//! for a Hertz contact, in the cases (normal force constant / increasing / decreasing ×
//! tangential force increasing / decreasing) from which Vu-Quoc & Zhang (1999, Mech. Mater. 31,
//! 235) and Zhang & Vu-Quoc (2007) start,
//!
//! ```text
//! ΔN > 0, |ΔT| ≤ μΔN:   Δδ = ΔT / (8G*a)                                    (no slip)
//! otherwise:            Δδ = dμΔN/(8G*a) + (ΔT − dμΔN)/(8G*a θ)             (slip annulus)
//! ```
//! (ΔN = 0 gives Cattaneo–Mindlin–Masing's tangent compliance), made displacement-driven by
//! solving each increment's relation for ΔT exactly (it is linear in ΔT once the branch is known):
//! ΔT = 8G*aΔδ, or ΔT = 8G*aθΔδ + dμΔN(1 − θ). The branch direction d is the sign of Δδ, θ and a
//! are those of the state at the start of the increment (the compliance of the current state, as
//! in the force-driven relations), every turning point is remembered with Masing–Madelung loop
//! closure, and turning points drift by ±μΔN as in Thornton (1991) (see
//! [`super::md_incremental`]).
//!
//! What is not implemented: Zhang & Vu-Quoc's own refinements (their treatment of the
//! elasto-plastic normal force, of the stick factor under varying normal load, and any
//! consistency correction of the displacement-driven form), which could not be reconstructed
//! from available sources. The differences from `thornton` are therefore only the evaluation
//! point of θ and a (start, without the μΔN shift) and the full turning-point memory; both laws
//! have the same limit as the increment shrinks on paths without nested reversals.

use super::md_incremental::{Evaluation, MdIncremental, Memory};
use spherecontact_model::scene::Scene;

/// The Mindlin–Deresiewicz incremental-case law for a scene's pair and friction, no history.
pub fn law(scene: &Scene) -> MdIncremental {
    MdIncremental::new(scene, Memory::Masing, Evaluation::Start)
}
