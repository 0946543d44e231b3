//! The frictionless normal problem at a prescribed approach: exact non-penetration.
//!
//! Unknowns: the multipliers λ ≥ 0 (pressures or nodal forces) at m points. Gap at point i:
//! g_i = o_i + (C λ)_i, with o_i = h_i − δ the opening of the undeformed surfaces (h: initial
//! separation, δ: approach). Conditions: g ≥ 0, λ ≥ 0, λ_i g_i = 0 at every point. λ minimises
//! ½⟨λ, Cλ⟩ + ⟨o, λ⟩ over λ ≥ 0 (C self-adjoint positive definite in the work product, so the
//! solution is unique), and g is the gradient.
//!
//! Two algorithms, one answer:
//! - [`NormalProblem::solve_iterative`], for any operator: the constrained conjugate gradient of Polonsky &
//!   Keer (1999, Wear 231, 206–219) in its displacement-controlled form (Bugnicourt et al. 2018,
//!   Tribol. Lett. 66:29): CG on the points in contact, negative multipliers clamped to zero,
//!   penetrating points re-admitted (restarting the conjugate directions). One product with C a
//!   step; the displacement u = Cλ is carried between calls, and changes at a few points are
//!   added column by column where the operator makes that cheaper. The step's product is a
//!   correction ([`Compliance::apply_correction`]: u moves by step × product); where the operator
//!   computes corrections in a lower precision, u is formed exactly before the solver stops.
//! - [`NormalProblem::solve_direct`], for an operator that holds its matrix: the primal–dual active set method
//!   (Hintermüller, Ito & Kunisch 2003, a semi-smooth Newton method), C_AA λ_A = −o_A on the
//!   active set A by faer's dense Cholesky, λ = 0 off it, until A repeats: exact to round-off.

use faer::linalg::solvers::Solve;
use faer::{Col, Mat, Side};

use super::operator::{update_after_changes, Compliance};

/// The multipliers and the displacement they cause, carried from one solve to the next.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NormalState {
    /// λ ≥ 0 at each point.
    pub multipliers: Vec<f64>,
    /// u = C λ.
    pub displacement: Vec<f64>,
}

impl NormalState {
    /// No contact on `m` points.
    pub fn zeros(m: usize) -> Self {
        Self {
            multipliers: vec![0.0; m],
            displacement: vec![0.0; m],
        }
    }

    /// The gap o + u at each point.
    pub fn gaps(&self, opening: &[f64]) -> Vec<f64> {
        opening
            .iter()
            .zip(&self.displacement)
            .map(|(o, u)| o + u)
            .collect()
    }
}

/// One normal problem: the operator and the data.
pub struct NormalProblem<'a> {
    /// The compliance C.
    pub op: &'a mut dyn Compliance,
    /// o_i = h_i − δ [m].
    pub opening: &'a [f64],
    /// The length the tolerance is relative to (the approach δ) [m].
    pub scale: f64,
    /// Iterative solver: stops when the weighted rms gap on the contact is below
    /// `tolerance · scale` and no open point penetrates by more than that.
    pub tolerance: f64,
    /// Iteration cap.
    pub max_iterations: usize,
    /// Multiplier per unit penetration that seeds a contact from nothing [multiplier/m].
    pub seed_stiffness: f64,
}

/// Why a normal solve failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NormalError {
    /// The iteration cap was reached.
    #[error("the normal problem did not converge in {iterations} iterations (residual {residual:.2e})")]
    NotConverged {
        /// Iterations spent.
        iterations: usize,
        /// The last residual.
        residual: f64,
    },
    /// The active set did not settle (direct solver).
    #[error("the contact set did not settle in {iterations} active-set iterations")]
    NotSettled {
        /// Iterations spent.
        iterations: usize,
    },
    /// An active block of C is not positive definite (direct solver).
    #[error("the compliance is not positive definite on the contact set")]
    NotPositiveDefinite,
}

/// Iteration cap of the active set method; it settles in a few iterations when warm-started.
const MAX_ACTIVE_SET_ITERATIONS: usize = 200;

impl NormalProblem<'_> {
    /// Solves by Polonsky–Keer constrained CG from `state` (updated in place, `state.displacement`
    /// must be C times `state.multipliers`); returns the products with C spent.
    pub fn solve_iterative(&mut self, state: &mut NormalState) -> Result<usize, NormalError> {
        let a = self.op.weights().to_vec();
        let m = a.len();
        let (p, u) = (&mut state.multipliers, &mut state.displacement);
        let tolerance = self.tolerance * self.scale;
        let mut direction = vec![0.0; m];
        let mut product = vec![0.0; m];
        let mut gap = vec![0.0; m];
        let mut changes: Vec<(usize, f64)> = Vec::new();
        let (mut previous_norm, mut restart, mut residual) = (1.0, true, f64::INFINITY);
        let mut products = 0;
        // Whether u carries rough corrections (see `Compliance::rough_corrections`) since it was
        // last formed exactly.
        let mut rough = false;
        for _ in 0..self.max_iterations {
            // One pass: the gaps, the residual on the contact, and whether an open point
            // penetrates.
            let (mut norm, mut active, mut penetrates) = (0.0, 0.0, false);
            for i in 0..m {
                gap[i] = u[i] + self.opening[i];
                if p[i] > 0.0 {
                    norm += a[i] * gap[i] * gap[i];
                    active += a[i];
                } else if gap[i] < -tolerance {
                    penetrates = true;
                }
            }
            if active == 0.0 {
                // Nothing in contact: done unless a point penetrates, which seeds the contact.
                if gap.iter().all(|&g| g >= 0.0) {
                    return Ok(products);
                }
                for (p, g) in p.iter_mut().zip(&gap) {
                    *p = (-g).max(0.0) * self.seed_stiffness;
                }
                self.op.apply(p, u);
                products += 1;
                restart = true;
                continue;
            }
            residual = (norm / active).sqrt();
            if residual < tolerance && !penetrates {
                if !rough {
                    return Ok(products);
                }
                // Converged on a displacement that carries the corrections' round-off: form it
                // exactly and test again, going on (with a new conjugate sequence) if the exact
                // gaps miss the tolerance. Each correction's error is relative to the correction,
                // which shrinks as the iteration converges, so the exact test passes after few
                // such rounds (iterative refinement).
                self.op.apply(p, u);
                products += 1;
                rough = false;
                restart = true;
                continue;
            }
            // Conjugate direction on the contact set (Polonsky & Keer, eq. 10).
            let beta = if restart { 0.0 } else { norm / previous_norm };
            for i in 0..m {
                direction[i] = if p[i] > 0.0 {
                    gap[i] + beta * direction[i]
                } else {
                    0.0
                };
            }
            previous_norm = norm;
            self.op.apply_correction(&direction, &mut product);
            products += 1;
            rough |= self.op.rough_corrections();
            // The direction vanishes off the contact: the sums run over every point.
            let (num, den) = (0..m).fold((0.0, 0.0), |(x, y), i| {
                (
                    x + a[i] * gap[i] * direction[i],
                    y + a[i] * product[i] * direction[i],
                )
            });
            let step = if den > 0.0 { num / den } else { 0.0 };
            // One pass over the points: the step, negative multipliers clamped to zero, points out
            // of contact that penetrate re-entering (P&K, eq. 13; restarting the CG), and the
            // displacement. When the contact set is already solved (zero gaps: step 0, e.g. one
            // point in contact), −step·gap would keep penetrating points out for ever: they enter
            // with the seed stiffness instead.
            changes.clear();
            restart = false;
            let entry = if step > 0.0 { step } else { self.seed_stiffness };
            for i in 0..m {
                if p[i] > 0.0 {
                    let next = p[i] - step * direction[i];
                    if next < 0.0 {
                        changes.push((i, -next)); // clamped to zero: λ changed by −next more
                    }
                    p[i] = next.max(0.0);
                }
                if p[i] == 0.0 && gap[i] < 0.0 {
                    p[i] = -entry * gap[i];
                    changes.push((i, p[i]));
                    restart = true;
                }
                u[i] -= step * product[i];
            }
            if update_after_changes(self.op, &changes, p, u) {
                // A full product forms u afresh, exactly.
                products += 1;
                rough = false;
            }
        }
        Err(NormalError::NotConverged {
            iterations: self.max_iterations,
            residual: residual / self.scale.max(f64::MIN_POSITIVE),
        })
    }

    /// Solves by the primal–dual active set method with dense Cholesky on the active block, starting
    /// from the contact set of `state` (updated in place); returns the iterations.
    ///
    /// # Panics
    /// When `op` holds no matrix (see [`Compliance::matrix`]).
    pub fn solve_direct(&mut self, state: &mut NormalState) -> Result<usize, NormalError> {
        let a = self.op.weights().to_vec();
        let m = a.len();
        // Gaps below this count as penetration: round-off of C λ relative to the problem's lengths.
        let scale = self.opening.iter().fold(self.scale.abs(), |s, o| s.max(o.abs()));
        let tolerance = 1e-12 * scale;
        let mut active: Vec<bool> = state.multipliers.iter().map(|&p| p > 0.0).collect();
        for iteration in 1..=MAX_ACTIVE_SET_ITERATIONS {
            let set: Vec<usize> = (0..m).filter(|&i| active[i]).collect();
            let matrix = self
                .op
                .matrix()
                .expect("the direct solver needs the operator's matrix");
            // a_A C_AA is symmetric positive definite; (a_A C_AA) λ_A = −a_A o_A.
            let block = Mat::from_fn(set.len(), set.len(), |r, c| a[set[r]] * matrix[(set[r], set[c])]);
            let mut rhs = Col::from_fn(set.len(), |r| -a[set[r]] * self.opening[set[r]]);
            if !set.is_empty() {
                let llt = block
                    .llt(Side::Lower)
                    .map_err(|_| NormalError::NotPositiveDefinite)?;
                llt.solve_in_place(rhs.as_mat_mut());
            }
            state.multipliers.fill(0.0);
            for (r, &i) in set.iter().enumerate() {
                state.multipliers[i] = rhs[r];
            }
            self.op.apply(&state.multipliers, &mut state.displacement);
            let next: Vec<bool> = (0..m)
                .map(|i| {
                    if active[i] {
                        state.multipliers[i] > 0.0
                    } else {
                        self.opening[i] + state.displacement[i] < -tolerance
                    }
                })
                .collect();
            if next == active {
                return Ok(iteration);
            }
            active = next;
        }
        Err(NormalError::NotSettled {
            iterations: MAX_ACTIVE_SET_ITERATIONS,
        })
    }
}
