//! Thornton's (1991) incremental Mindlin–Deresiewicz tangential law, as Thornton & Yin (1991)
//! used it for oblique impacts and Thornton, Cummins & Cleary (2011, 2013) summarise it.
//!
//! Form implemented (1D, δt along one axis; see [`super::md_incremental`] for the derivation):
//!
//! ```text
//! ΔT = 8G*a θ Δδ + (−1)^k μΔN (1 − θ)        k = 0 loading, 1 unloading, 2 reloading
//! θ³ = 1 − (T + μΔN)/(μN)                   loading
//! θ³ = 1 − (T* − T + 2μΔN)/(2μN)            unloading (from the turning point T*)
//! θ³ = 1 − (T − T** + 2μΔN)/(2μN)           reloading (from the turning point T**)
//! T* ← T* + μΔN,  T** ← T** − μΔN            after every increment
//! θ = 1 (ΔT = 8G*aΔδ)                        when ΔN > 0 and |ΔT| ≤ μΔN (Mindlin & Deresiewicz's
//!                                            no-slip case)
//! ```
//! with a and N the contact radius and normal force at the end of the increment, T the force at
//! its start, (−1)^k the sign of the motion in the frame of the first loading, and |T| ≤ μN
//! enforced at the end of every increment. Loading, unloading and reloading are decided by the
//! sign of Δδ; reloading that reaches T* continues as loading; unloading that passes −T* becomes
//! loading in the opposite direction; a reversal during reloading starts a new unloading with
//! T* = T and forgets T** (only two turning points are kept).
//!
//! Provenance: the equations above are as the secondary literature gives Thornton's form; the
//! primary texts (Thornton 1991, J. Phys. D 24, 1942; Thornton & Yin 1991, Powder Technol. 65,
//! 153; Thornton, Cummins & Cleary 2011, Powder Technol. 210, 189) were not available to check
//! equation numbers against. What the tests establish independently: at constant N the law
//! reproduces Cattaneo–Mindlin's virgin curve and Masing's unloading to first order in Δδ.

use super::md_incremental::{Evaluation, MdIncremental, Memory};
use spherecontact_model::scene::Scene;

/// Thornton's law for a scene's pair and friction, with no history.
pub fn law(scene: &Scene) -> MdIncremental {
    MdIncremental::new(scene, Memory::TwoTurningPoints, Evaluation::EndWithShift)
}
