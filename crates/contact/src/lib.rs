//! # spherecontact-contact: the contact engine
//!
//! **Job.** The frictionless normal problem and the incremental Coulomb problem over any compliance operator.
//!
//! **May depend on.** `spherecontact-model`.
//!
//! **Offers.** The solvers of the normal and tangential problems, generic over the operator (the BEM's influence coefficients, a condensed FEM compliance) and the friction set.
//!
//! The contact engine shared by every numerical solver: the frictionless normal problem with
//! exact non-penetration and the incremental Coulomb problem with memory, generic over the
//! compliance operator and the friction set.
//!
//! | file | concept |
//! |---|---|
//! | [`operator`] | the [`Compliance`] trait: u = C λ on m points × k components, point weights |
//! | [`dense`] | [`DenseCompliance`]: C held as a faer `Mat` (a condensed FEM compliance) |
//! | [`lanes`] | sums and maxima in interleaved accumulators (the iterative solvers' loops) |
//! | [`set`] | [`FrictionSet`]: an interval (1 tangential component) or a disc (2) |
//! | [`normal`] | the normal problem: Polonsky–Keer CG (any operator), active set + dense Cholesky |
//! | [`coulomb`] | one tangential increment: accelerated projected gradients (any operator), or active sets + dense Cholesky |
//! | [`state`] | [`Contact`]: both problems advanced one increment at a time, with memory |
//!
//! # Using it
//!
//! A solver provides the compliances and the initial separation of its contact points, then
//! advances the contact along its path:
//!
//! ```
//! use faer::Mat;
//! use spherecontact_contact::{Contact, DenseCompliance, FrictionSet, Settings};
//!
//! // Two independent springs of compliance 1 m/N (normal) and 2 m/N (tangential), the second
//! // point 1 m further away.
//! let normal = DenseCompliance::scalar(Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.0 })).unwrap();
//! let shear = DenseCompliance::scalar(Mat::from_fn(2, 2, |i, j| if i == j { 2.0 } else { 0.0 })).unwrap();
//! let mut contact = Contact::new(normal, vec![0.0, 1.0], Settings::default())
//!     .unwrap()
//!     .with_friction(shear, FrictionSet::Interval, 0.5)
//!     .unwrap();
//! contact.advance(0.5, &[0.0]).unwrap(); // approach 0.5 m: point 0 closes with λ = 0.5 N
//! assert!((contact.normal_force() - 0.5).abs() < 1e-12);
//! contact.advance(0.5, &[0.1]).unwrap(); // shift 0.1 m: q = 0.05 N < μλ = 0.25 N, stick
//! assert!((contact.tangential_force(0) - 0.05).abs() < 1e-12);
//! assert_eq!(contact.stick(), vec![true, false]);
//! contact.advance(0.5, &[1.0]).unwrap(); // gross sliding at μλ
//! assert!((contact.tangential_force(0) - 0.25).abs() < 1e-12);
//! ```
//!
//! - **Points, components, weights.** A compliance has m points and k components a point,
//!   vectors component-major (entry c·m + i), and point weights a_i: the resultant is Σ a_i λ_i
//!   and C is self-adjoint in ⟨x, y⟩ = Σ a_i x_i·y_i. Nodal forces: a_i = 1. Panel pressures:
//!   a_i = panel area (times a point's multiplicity in a symmetric reduction).
//! - **Normal.** [`Contact::new`] takes the normal compliance (k = 1; for two bodies the sum of
//!   theirs on common points) and the initial separation h_i of the surfaces; the gap at approach
//!   δ is h_i − δ + (Cλ)_i. [`Contact::pressure`] gives λ, [`Contact::normal_force`] Σ a_i λ_i,
//!   [`Contact::gaps`] the gaps.
//! - **Friction.** [`Contact::with_friction`] adds the tangential compliance on the same points
//!   (k = 1 with [`FrictionSet::Interval`] for a 1D or Fourier n = 1 tangential model, k = 2 with
//!   [`FrictionSet::Disc`] for a surface), and μ. The bound is g_i = μ λ_i, or μ s_i λ_i with
//!   [`Contact::with_bound_scale`] where the tangential multiplier is measured differently from
//!   the normal one. Dissimilar bodies (Dundurs β ≠ 0) couple the two problems; the engine
//!   solves them uncoupled and the solver must say so.
//! - **Increments.** [`Contact::advance`]`(δ, w)` solves the normal problem at approach δ, then
//!   the tangential increment for a rigid shift increment w (one value a tangential component;
//!   the far points' relative tangential displacement change). Memory: the traction at the start
//!   of the increment (partial slip, reversal, Masing loops follow), the slip since contact
//!   ([`Contact::slip`]); a point out of contact carries nothing and forgets; a point entering
//!   contact starts at q = 0. [`Contact::traction`], [`Contact::tangential_force`],
//!   [`Contact::stick`] give the answer.
//! - **Algorithms** ([`Method`]): an operator that holds its matrix ([`Compliance::matrix`]) of
//!   at most [`state::DIRECT_LIMIT`] rows is solved by active sets with faer's dense Cholesky of
//!   the active block (exact to round-off); any other iteratively: the normal problem by
//!   Polonsky–Keer's constrained conjugate gradients, the tangential one by accelerated projected
//!   gradients (tolerances in [`Settings`]). A solver with a fast product (the BEM's FFT) implements
//!   [`Compliance`] itself; [`Compliance::add_columns`] lets it update a product after a few
//!   points changed without a full product.
//! - **Errors** are typed ([`ContactError`]): a problem that does not converge within the cap, a
//!   block that is not positive definite, operators that do not fit together.

pub mod coulomb;
pub mod dense;
pub(crate) mod lanes;
pub mod normal;
pub mod operator;
pub mod set;
pub mod state;

pub use dense::{DenseCompliance, DenseError};
pub use operator::Compliance;
pub use set::FrictionSet;
pub use state::{Contact, ContactError, IncrementCost, Method, Settings};

#[cfg(test)]
mod tests;
