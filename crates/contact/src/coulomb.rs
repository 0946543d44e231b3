//! One increment of the tangential problem with Coulomb friction and memory, at a known
//! pressure (Kalker 1990, *Three-Dimensional Elastic Bodies in Rolling Contact*, ch. 2: the
//! "shift" formulation).
//!
//! Over the increment the bodies' far points shift rigidly by w (a uniform vector, one value a
//! component). The slip increment (relative tangential displacement of the surface particles) at
//! point i is
//!
//! ```text
//! Δs_i = w − (C Δq)_i,      Δq = q − q_prev,
//! ```
//! with C the tangential compliance and q the tangential multiplier on body 1 (its resultant is
//! Q, of the sign of the shift). Coulomb: q_i lies in the friction set scaled by g_i = μ p_i
//! (an interval or a disc, [`super::set::FrictionSet`]); stick (|q_i| < g_i) takes the shift up
//! elastically, Δs_i = 0; slip (|q_i| = g_i) has q_i along Δs_i. These are the optimality
//! conditions of the convex programme min ½⟨Δq, CΔq⟩ − ⟨w, Δq⟩ over the scaled sets, whose
//! gradient is G = −Δs. Points with g_i = 0 (out of contact) carry no multiplier; a point entering
//! contact starts at q = 0 and sticks with the relative displacement it arrives with.
//!
//! Two algorithms, one answer:
//! - [`CoulombProblem::solve_iterative`], for any operator: the accelerated projected gradient method (FISTA with
//!   adaptive restart) in the work product, one product a step. Measured on the BEM's Cattaneo
//!   problem it needs 90–130 steps from 32² to 256² panels, where conjugate gradients on the
//!   stick set, restarted at every change of the sets, needed thousands (`examples/bem_timing.rs`).
//! - [`CoulombProblem::solve_direct`], for an operator that holds its matrix: an active-set method on the same
//!   sets — free (stick) points, where G = 0 is solved for, and bound (slip) points, where
//!   q_i = g_i n_i is held with the direction n_i of the slip — each pair of sets solved exactly by
//!   faer's dense Cholesky of the free block, the sets updated until they repeat (for the interval
//!   this is the primal–dual active set method). A point leaves the free set when its multiplier
//!   crosses the bound; it returns when its slip would reverse (G_i·n_i > 0).
//!
//! Tolerance: every point's condition (free: |G_i|; bound: the reversing and the misaligned parts
//! of G_i) below `tolerance · λ_max · g_max`, with λ_max the operator's largest eigenvalue: the
//! displacement the largest admissible multiplier causes, so the tolerance is a fraction of the
//! traction scale, as for a projected-gradient step of length 1/λ_max.

use faer::linalg::solvers::Solve;
use faer::{Col, Mat, Side};

use super::lanes;
use super::operator::{update_after_changes, Compliance};
use super::set::{dot_at, norm_at, scale_at};

/// One increment: the operator and the data.
pub struct CoulombProblem<'a> {
    /// The tangential compliance C.
    pub op: &'a mut dyn Compliance,
    /// g_i = μ p_i ≥ 0 at the end of the increment (one a point).
    pub bound: &'a [f64],
    /// q at the start of the increment (component-major).
    pub previous: &'a [f64],
    /// C q_prev.
    pub previous_displacement: &'a [f64],
    /// The rigid shift increment w, one value a component [m].
    pub shift: &'a [f64],
    /// See the module doc.
    pub tolerance: f64,
    /// Iteration cap.
    pub max_iterations: usize,
}

/// The tangential multipliers, their displacement and the slipping points, carried between
/// increments.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CoulombState {
    /// q (component-major); on entry the starting guess.
    pub traction: Vec<f64>,
    /// C q.
    pub displacement: Vec<f64>,
    /// Points on the bound (slip); on exit exactly the solver's bound set.
    pub slipping: Vec<bool>,
    /// The iterative solver's curvature estimate L (see [`CoulombProblem::solve_iterative`]),
    /// carried to the next increment; `None`: not yet measured.
    pub curvature: Option<f64>,
}

impl CoulombState {
    /// No traction on `m` points of `k` components.
    pub fn zeros(m: usize, k: usize) -> Self {
        Self {
            traction: vec![0.0; m * k],
            displacement: vec![0.0; m * k],
            slipping: vec![false; m],
            curvature: None,
        }
    }
}

/// Why an increment failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CoulombError {
    /// The iteration cap was reached.
    #[error("the tangential problem did not converge in {iterations} iterations (residual {residual:.2e})")]
    NotConverged {
        /// Iterations spent.
        iterations: usize,
        /// The last residual over the tolerance's scale.
        residual: f64,
    },
    /// A free block of C is not positive definite (direct solver).
    #[error("the tangential compliance is not positive definite on the stick set")]
    NotPositiveDefinite,
}

/// What an increment cost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CoulombCost {
    /// Iterations (CG steps, or active-set rounds).
    pub iterations: usize,
    /// Full products with C.
    pub products: usize,
}

/// G = C q − C q_prev − w at every entry.
fn gradient(problem: &CoulombProblem, m: usize, state: &CoulombState, out: &mut [f64]) {
    for (j, g) in out.iter_mut().enumerate() {
        *g = state.displacement[j] - problem.previous_displacement[j] - problem.shift[j / m];
    }
}

/// The slip increment Δs = −G of a solved increment.
pub fn slip_increment(problem: &CoulombProblem, state: &CoulombState) -> Vec<f64> {
    let m = problem.bound.len();
    let mut g = vec![0.0; state.traction.len()];
    gradient(problem, m, state, &mut g);
    g.iter_mut().for_each(|v| *v = -*v);
    g
}

/// The points with g > 0, as runs [start, end) of consecutive indices (on a grid, a run a row of
/// the contact): the iterative solver's loops run over slices.
fn runs(bound: &[f64]) -> Vec<(usize, usize)> {
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for (i, _) in bound.iter().enumerate().filter(|(_, &g)| g > 0.0) {
        match runs.last_mut() {
            Some((_, end)) if *end == i => *end += 1,
            _ => runs.push((i, i + 1)),
        }
    }
    runs
}

/// `out = x + w (x − before)`: an extrapolation along the last step.
fn extrapolated(out: &mut [f64], x: &[f64], before: &[f64], w: f64) {
    for ((o, &x), &b) in out.iter_mut().zip(x).zip(before) {
        *o = x + w * (x - b);
    }
}

/// Puts the guess into the sets: zero where g = 0, on the bound where it reaches it (slipping),
/// free elsewhere; returns the changes made to q.
fn classify(problem: &CoulombProblem, state: &mut CoulombState, k: usize) -> Vec<(usize, f64)> {
    let m = problem.bound.len();
    let mut changes = Vec::new();
    for (i, &g) in problem.bound.iter().enumerate() {
        let norm = norm_at(&state.traction, m, i);
        let target = if g <= 0.0 {
            0.0
        } else if norm >= g * (1.0 - 1e-12) {
            g / norm
        } else {
            1.0
        };
        state.slipping[i] = g > 0.0 && norm >= g * (1.0 - 1e-12);
        if target != 1.0 {
            for c in 0..k {
                let j = c * m + i;
                let next = state.traction[j] * target;
                if next != state.traction[j] {
                    changes.push((j, next - state.traction[j]));
                    state.traction[j] = next;
                }
            }
        }
    }
    changes
}

/// The worst violation of a bound point's conditions: the reversing part G·n (> 0 means the
/// slip would reverse) and the part of G across n; and the reversing part alone.
fn bound_violation(gradient: &[f64], traction: &[f64], g: f64, m: usize, i: usize) -> (f64, f64) {
    let reversing = dot_at(gradient, traction, m, i) / g;
    // The part of G across n = q/g, formed explicitly (a difference of squares would lose it to
    // round-off).
    let across = gradient
        .iter()
        .skip(i)
        .step_by(m)
        .zip(traction.iter().skip(i).step_by(m))
        .map(|(gc, qc)| (gc - reversing * qc / g).powi(2))
        .sum::<f64>()
        .sqrt();
    (reversing.max(across), reversing)
}

/// Projects point `i` of `q` onto its set scaled by `g` (a disc or an interval: the same radial
/// scaling); true when it lies on the bound or within `margin` of it (a traction).
fn project_at(q: &mut [f64], m: usize, i: usize, g: f64, margin: f64) -> bool {
    let norm = norm_at(q, m, i);
    if norm > g {
        scale_at(q, m, i, if norm > 0.0 { g / norm } else { 0.0 });
    }
    norm >= g - margin.max(STICK_MARGIN * g)
}

/// A point whose |q_i| is within this fraction of g_i lies on the bound (slips): the projection
/// puts slipping points exactly on it, so this absorbs rounding (the iterative method widens it
/// to its tolerance, see [`CoulombProblem::solve_iterative`]).
const STICK_MARGIN: f64 = 1e-6;

/// The first curvature estimate of an iterative solve is λ_max over this (backtracking raises it
/// where it is too small, at the cost of one product a raise).
const FIRST_CURVATURE: f64 = 4.0;

/// A step found too curved is taken again with L this many times its curvature: a margin over the
/// curvature seen, so that the next steps, in other directions, rarely need another raise.
const CURVATURE_MARGIN: f64 = 1.1;

/// An increment starts from this fraction of the last one's L, so that L can also fall as the
/// contact changes. Margin and decay measured on the paper path at 128² (3e-5 tolerance): 1.2 and
/// 1 took 4967 iterations, 1.1 and 0.9 take 4116, 1.05 and 0.5–0.8 take 4110–4143.
const CURVATURE_DECAY: f64 = 0.9;

impl CoulombProblem<'_> {
    /// The point weights a, the components k a point and the largest bound g_max.
    fn sizes(&self) -> (Vec<f64>, usize, f64) {
        let g_max = self.bound.iter().copied().fold(0.0, f64::max);
        (self.op.weights().to_vec(), self.op.components(), g_max)
    }

    /// Solves the increment by the accelerated projected gradient method (Nesterov 1983; Beck &
    /// Teboulle 2009, FISTA, with backtracking) with the adaptive restart of O'Donoghue & Candès
    /// (2015, eq. 12), in the work product, from the guess in `state` (`state.displacement` must
    /// be C times `state.traction`).
    ///
    /// Step 1/L: q ← P(y − G(y)/L), P the projection onto the scaled sets (point by point, since
    /// the work product weighs a point's components alike), y the extrapolated iterate. One
    /// product a step, on the new iterate (C y is the same combination of the two last products).
    ///
    /// L: the step is sound (FISTA's sufficient decrease) when L bounds the curvature of the
    /// objective along the step Δ = next − y, ⟨Δ, CΔ⟩ ≤ L ⟨Δ, Δ⟩, which the product of the new
    /// iterate gives for free (CΔ = C next − C y). C's largest eigenvalue λ_max always is such an
    /// L, but it is that of the whole padded grid; on the contact alone the curvature is smaller
    /// (a contact of diameter 0.9 of the BEM window: about 2.5 times), and the iterations fall as
    /// √L. So L starts from the last increment's (times [`CURVATURE_DECAY`]; λ_max/[`FIRST_CURVATURE`] at first), and a step whose
    /// curvature exceeds it is taken again with L raised to [`CURVATURE_MARGIN`] times that
    /// curvature (capped at λ_max, where every step is sound).
    ///
    /// Stops when the step moves no point by more than `tolerance · g_max · λ_max / L` (the
    /// condition on G of `tolerance · λ_max · g_max` of the module doc, whatever L); the points
    /// within `tolerance · g_max` of their bound slip. The iterate approaches the bound from
    /// inside, so a point the exact solution holds on it (slipping) may stop a hair short: where
    /// a newly loaded annulus slips by a small margin (dQ/dP a few per cent above μ, the paper
    /// path's P1 → P2) it stopped 1e-5 of g_i inside the bound at 128², and a margin of rounding
    /// alone ([`STICK_MARGIN`]) flagged half the annulus as sticking (the stick radius at
    /// position 2 went from 7.09e-4 to 7.62e-4 m with f32 products; MDR: 7.03e-4 m). A point
    /// within the tolerance of its bound cannot be told from one on it: it slips.
    pub fn solve_iterative(&mut self, state: &mut CoulombState) -> Result<CoulombCost, CoulombError> {
        let (a, k, g_max) = self.sizes();
        let (m, n) = (a.len(), a.len() * k);
        let largest = self.op.largest_eigenvalue();
        let mut curvature = state
            .curvature
            .map_or(largest / FIRST_CURVATURE, |c| CURVATURE_DECAY * c)
            .min(largest);
        let tolerance = self.tolerance * g_max;
        let mut cost = CoulombCost::default();
        let changes = classify(self, state, k);
        cost.products += usize::from(update_after_changes(
            self.op,
            &changes,
            &state.traction,
            &mut state.displacement,
        ));
        // x: the last iterate (state.traction, its product state.displacement); y, C y: the
        // extrapolated point; next, C next: the new iterate. After a step is taken, next and
        // C next hold the iterate before x until the next pass overwrites them, and y = x + w (x −
        // that iterate) is formed in that pass (`extrapolate` = Some(w)): one pass over the
        // points fewer a step. Points out of contact (g = 0) hold
        // q = 0 in every iterate (the classification and every projection put them there), so the
        // loops run over the contact only; the products stay whole (the displacement everywhere is
        // the next increment's C q_prev).
        let contact = runs(self.bound);
        let (mut y, mut y_product) = (state.traction.clone(), state.displacement.clone());
        let (mut next, mut next_product) = (state.traction.clone(), vec![0.0; n]);
        // Per point: |point|², then the projection's scale; how far the step moves the point.
        let (mut scale, mut moved) = (vec![0.0; m], vec![0.0; m]);
        let (mut momentum, mut residual) = (1.0_f64, f64::INFINITY);
        let mut extrapolate: Option<f64> = None;
        while cost.iterations < self.max_iterations {
            cost.iterations += 1;
            let step = 1.0 / curvature;
            // One sweep of each run: the projected step, how far it moves, and ⟨y − next, next − x⟩
            // (the restart test, below). Each run is swept component by component over slices, so
            // that the loops vectorise.
            let (mut largest_move, mut against) = (0.0_f64, 0.0);
            for &(s, e) in &contact {
                let len = e - s;
                for c in 0..k {
                    let r = c * m + s..c * m + e;
                    if let Some(w) = extrapolate {
                        extrapolated(&mut y[r.clone()], &state.traction[r.clone()], &next[r.clone()], w);
                        extrapolated(
                            &mut y_product[r.clone()],
                            &state.displacement[r.clone()],
                            &next_product[r.clone()],
                            w,
                        );
                    }
                    let shift = self.shift[c];
                    let (y, y_product, previous) = (
                        &y[r.clone()],
                        &y_product[r.clone()],
                        &self.previous_displacement[r.clone()],
                    );
                    for (i, value) in next[r].iter_mut().enumerate() {
                        *value = y[i] - step * (y_product[i] - previous[i] - shift);
                    }
                }
                // |point|² against g²: the square root only where the point is projected.
                let (scale, moved) = (&mut scale[s..e], &mut moved[s..e]);
                scale.fill(0.0);
                moved.fill(0.0);
                for c in 0..k {
                    let r = c * m + s..c * m + e;
                    scale.iter_mut().zip(&next[r]).for_each(|(sq, v)| *sq += v * v);
                }
                for (sq, &g) in scale.iter_mut().zip(&self.bound[s..e]) {
                    *sq = if *sq > g * g { g / sq.sqrt() } else { 1.0 };
                }
                for c in 0..k {
                    let r = c * m + s..c * m + e;
                    let (y, x, a) = (&y[r.clone()], &state.traction[r.clone()], &a[s..e]);
                    let next = &mut next[r];
                    for (i, value) in next.iter_mut().enumerate() {
                        *value *= scale[i];
                        moved[i] += (*value - y[i]).powi(2);
                    }
                    against += lanes::sum(len, |i| a[i] * (y[i] - next[i]) * (next[i] - x[i]));
                }
                largest_move = lanes::max(len, largest_move, |i| moved[i]);
            }
            // y is stored: a step taken again with a larger L (below) starts from it.
            extrapolate = None;
            self.op.apply(&next, &mut next_product);
            cost.products += 1;
            // The curvature along the step, ⟨Δ, CΔ⟩ / ⟨Δ, Δ⟩ (Δ vanishes off the contact).
            let (mut bent, mut length) = (0.0, 0.0);
            for c in 0..k {
                for &(s, e) in &contact {
                    let r = c * m + s..c * m + e;
                    let (a, next, y) = (&a[s..e], &next[r.clone()], &y[r.clone()]);
                    let (next_product, y_product) = (&next_product[r.clone()], &y_product[r]);
                    bent += lanes::sum(e - s, |i| {
                        a[i] * (next[i] - y[i]) * (next_product[i] - y_product[i])
                    });
                    length += lanes::sum(e - s, |i| a[i] * (next[i] - y[i]).powi(2));
                }
            }
            if curvature < largest && bent > curvature * length {
                curvature = (CURVATURE_MARGIN * bent / length).min(largest);
                continue;
            }
            residual = largest_move.sqrt() * curvature / largest;
            if residual <= tolerance {
                state.traction.copy_from_slice(&next);
                state.displacement.copy_from_slice(&next_product);
                for i in 0..m {
                    state.slipping[i] = self.bound[i] > 0.0
                        && project_at(&mut state.traction, m, i, self.bound[i], tolerance);
                }
                state.curvature = Some(curvature);
                return Ok(cost);
            }
            // Restart when the step works against the momentum: ⟨y − next, next − x⟩ > 0.
            let weight = if against > 0.0 {
                momentum = 1.0;
                0.0
            } else {
                let following = 0.5 * (1.0 + (1.0 + 4.0 * momentum * momentum).sqrt());
                let w = (momentum - 1.0) / following;
                momentum = following;
                w
            };
            // y = next + w (next − x) and C y likewise, formed in the next pass on the contact
            // (the gradient is read there only).
            std::mem::swap(&mut state.traction, &mut next);
            std::mem::swap(&mut state.displacement, &mut next_product);
            extrapolate = Some(weight);
        }
        Err(CoulombError::NotConverged {
            iterations: cost.iterations,
            residual: residual / g_max.max(f64::MIN_POSITIVE),
        })
    }

    /// Solves the increment exactly on each pair of sets by dense Cholesky (see the module doc); at
    /// slipping points of a disc the direction is solved for along the circle's tangent and put back
    /// on the circle (a Newton step on the direction, converging quadratically).
    ///
    /// # Panics
    /// When `op` holds no matrix (see [`Compliance::matrix`]).
    pub fn solve_direct(&mut self, state: &mut CoulombState) -> Result<CoulombCost, CoulombError> {
        let (a, k, g_max) = self.sizes();
        let (m, n) = (a.len(), a.len() * k);
        let tolerance = self.tolerance * self.op.largest_eigenvalue() * g_max;
        let mut cost = CoulombCost::default();
        classify(self, state, k);
        let mut grad = vec![0.0; n];
        let mut fixed_displacement = vec![0.0; n];
        while cost.iterations < self.max_iterations {
            cost.iterations += 1;
            // The free directions B: each component of a free point, the tangent of a slipping point
            // of a disc. Solve BᵀaC B x = Bᵀa (w + C q_prev − C q_fixed), q = q_fixed + B x.
            // The circle's curvature stiffens the tangent of a slipping point by κ_i = (slip pressing
            // outward)/g_i: the Newton step on the circle (without it the tangent-line step overshoots).
            self.op.apply(&state.traction, &mut state.displacement);
            cost.products += 1;
            gradient(self, m, state, &mut grad);
            let mut columns: Vec<Vec<(usize, f64)>> = Vec::new();
            let mut curvature = Vec::new();
            for i in (0..m).filter(|&i| self.bound[i] > 0.0) {
                if !state.slipping[i] {
                    for c in 0..k {
                        state.traction[c * m + i] = 0.0;
                        columns.push(vec![(c * m + i, 1.0)]);
                    }
                } else if k == 2 {
                    let g = self.bound[i];
                    let (x, y) = (state.traction[i] / g, state.traction[m + i] / g);
                    curvature.push((
                        columns.len(),
                        a[i] * (-dot_at(&grad, &state.traction, m, i) / g).max(0.0) / g,
                    ));
                    columns.push(vec![(i, -y), (m + i, x)]);
                }
            }
            self.op.apply(&state.traction, &mut fixed_displacement);
            cost.products += 1;
            if !columns.is_empty() {
                let matrix = self
                    .op
                    .matrix()
                    .expect("the direct solver needs the operator's matrix");
                let mut block = Mat::from_fn(columns.len(), columns.len(), |r, c| {
                    let mut sum = 0.0;
                    for &(j1, b1) in &columns[r] {
                        for &(j2, b2) in &columns[c] {
                            sum += a[j1 % m] * b1 * matrix[(j1, j2)] * b2;
                        }
                    }
                    sum
                });
                for &(r, kappa) in &curvature {
                    block[(r, r)] += kappa;
                }
                let mut rhs = Col::from_fn(columns.len(), |r| {
                    columns[r]
                        .iter()
                        .map(|&(j, b)| {
                            a[j % m]
                                * b
                                * (self.shift[j / m] + self.previous_displacement[j] - fixed_displacement[j])
                        })
                        .sum::<f64>()
                });
                let llt = block
                    .llt(Side::Lower)
                    .map_err(|_| CoulombError::NotPositiveDefinite)?;
                llt.solve_in_place(rhs.as_mat_mut());
                for (r, column) in columns.iter().enumerate() {
                    for &(j, b) in column {
                        state.traction[j] += b * rhs[r];
                    }
                }
            }
            // Slipping points back onto their circle, free points beyond the bound onto it.
            let mut changed = false;
            for i in (0..m).filter(|&i| self.bound[i] > 0.0) {
                let g = self.bound[i];
                let norm = norm_at(&state.traction, m, i);
                if state.slipping[i] || norm > g * (1.0 + 1e-12) {
                    changed |= !state.slipping[i];
                    scale_at(&mut state.traction, m, i, g / norm);
                    state.slipping[i] = true;
                }
            }
            self.op.apply(&state.traction, &mut state.displacement);
            cost.products += 1;
            gradient(self, m, state, &mut grad);
            for i in 0..m {
                if state.slipping[i] {
                    let (violation, reversing) = bound_violation(&grad, &state.traction, self.bound[i], m, i);
                    if reversing > tolerance {
                        state.slipping[i] = false;
                    }
                    changed |= violation > tolerance;
                }
            }
            if !changed {
                return Ok(cost);
            }
        }
        Err(CoulombError::NotConverged {
            iterations: cost.iterations,
            residual: 1.0,
        })
    }
}
