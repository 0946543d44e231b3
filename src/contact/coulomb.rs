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
//! Both algorithms are active-set methods on the same sets: free (stick) points, where G = 0 is
//! solved for, and bound (slip) points, where q_i = g_i n_i is held with the direction n_i of the
//! slip. A point leaves the free set when its multiplier crosses the bound (projected onto it,
//! direction q_i/|q_i|); it returns when its slip would reverse (G_i·n_i > 0); a slipping point's
//! direction follows its slip (n_i ← −G_i/|G_i|) until they agree to the tolerance.
//! - [`solve_iterative`], for any operator: conjugate gradients on the free set, merged with the
//!   set changes as Polonsky & Keer merge them for the normal problem (a point crossing the bound
//!   is projected without a restart; a release or a change of direction restarts); the bound
//!   points' conditions are revisited once the free residual has fallen below their violation.
//! - [`solve_direct`], for an operator that holds its matrix: each set solved exactly by faer's
//!   dense Cholesky of the free block, the sets updated until they repeat (for the interval this
//!   is the primal–dual active set method).
//!
//! Tolerance: every point's condition (free: |G_i|; bound: the reversing and the misaligned parts
//! of G_i) below `tolerance · λ_max · g_max`, with λ_max the operator's largest eigenvalue: the
//! displacement the largest admissible multiplier causes, so the tolerance is a fraction of the
//! traction scale, as for a projected-gradient step of length 1/λ_max.

use faer::linalg::solvers::Solve;
use faer::{Col, Mat, Side};

use super::operator::{update_after_changes, work, Compliance};
use super::set::{dot_at, norm_at, scale_at};

/// One increment's data.
#[derive(Clone, Copy, Debug)]
pub struct CoulombProblem<'a> {
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
}

impl CoulombState {
    /// No traction on `m` points of `k` components.
    pub fn zeros(m: usize, k: usize) -> Self {
        Self {
            traction: vec![0.0; m * k],
            displacement: vec![0.0; m * k],
            slipping: vec![false; m],
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

/// Keeps of `v` what the sets leave free: everything at free points, the part along the circle's
/// tangent at slipping points (nothing for an interval), nothing where g = 0.
fn project_on_freedom(bound: &[f64], state: &CoulombState, m: usize, k: usize, v: &mut [f64]) {
    for i in 0..m {
        if bound[i] > 0.0 && !state.slipping[i] {
            continue;
        }
        if k == 2 && bound[i] > 0.0 {
            let (x, y) = (state.traction[i] / bound[i], state.traction[m + i] / bound[i]);
            let along = -y * v[i] + x * v[m + i];
            v[i] = -y * along;
            v[m + i] = x * along;
        } else {
            for c in 0..k {
                v[c * m + i] = 0.0;
            }
        }
    }
}

/// Solves the increment by conjugate gradients on the free set (see the module doc), from the
/// guess in `state` (`state.displacement` must be C times `state.traction`).
pub fn solve_iterative(
    op: &mut dyn Compliance,
    problem: &CoulombProblem,
    state: &mut CoulombState,
) -> Result<CoulombCost, CoulombError> {
    let a = op.weights().to_vec();
    let (m, k) = (a.len(), op.components());
    let n = m * k;
    let g_max = problem.bound.iter().copied().fold(0.0, f64::max);
    let tolerance = problem.tolerance * op.largest_eigenvalue() * g_max;
    let mut cost = CoulombCost::default();
    let mut changes = classify(problem, state, k);
    cost.products += usize::from(update_after_changes(
        op,
        &changes,
        &state.traction,
        &mut state.displacement,
    ));
    let free = |state: &CoulombState, i: usize| problem.bound[i] > 0.0 && !state.slipping[i];
    let (mut grad, mut direction, mut product) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut work_gradient = vec![0.0; n];
    let (mut restart, mut previous_norm, mut residual) = (true, 1.0, f64::INFINITY);
    while cost.iterations < problem.max_iterations {
        gradient(problem, m, state, &mut grad);
        // Free conditions: G = 0 at free points, G along n at slipping ones; the reversing part
        // of G at slipping points is the release condition.
        let (mut free_residual, mut reversing_residual) = (0.0_f64, 0.0_f64);
        for i in 0..m {
            if free(state, i) {
                free_residual = free_residual.max(norm_at(&grad, m, i));
            } else if state.slipping[i] {
                let (violation, reversing) = bound_violation(&grad, &state.traction, problem.bound[i], m, i);
                reversing_residual = reversing_residual.max(reversing);
                free_residual = free_residual.max(if reversing > 0.0 { 0.0 } else { violation });
            }
        }
        residual = free_residual.max(reversing_residual);
        if residual <= tolerance {
            return Ok(cost);
        }
        changes.clear();
        if reversing_residual > tolerance && free_residual <= reversing_residual {
            // Release the slipping points whose slip would reverse.
            for i in 0..m {
                if state.slipping[i] {
                    let (_, reversing) = bound_violation(&grad, &state.traction, problem.bound[i], m, i);
                    state.slipping[i] = reversing <= tolerance;
                }
            }
            restart = true;
            cost.iterations += 1;
            continue;
        }
        // A conjugate gradient step on the free points and along the circle at slipping points.
        project_on_freedom(problem.bound, state, m, k, &mut grad);
        let norm = work(&a, &grad, &grad);
        let beta = if restart { 0.0 } else { norm / previous_norm };
        previous_norm = norm;
        for (d, r) in direction.iter_mut().zip(&grad) {
            *d = r + beta * *d;
        }
        project_on_freedom(problem.bound, state, m, k, &mut direction);
        op.apply(&direction, &mut product);
        cost.products += 1;
        cost.iterations += 1;
        // The curvature of the circle adds κ_i = (slip pressing outward)/g_i to the tangent
        // stiffness of a slipping point: without it the linear step overshoots the turn.
        let mut den = work(&a, &direction, &product);
        if k == 2 {
            gradient(problem, m, state, &mut work_gradient);
            for i in (0..m).filter(|&i| state.slipping[i]) {
                let g = problem.bound[i];
                let kappa = (-dot_at(&work_gradient, &state.traction, m, i) / g).max(0.0) / g;
                den += a[i] * kappa * norm_at(&direction, m, i).powi(2);
            }
        }
        let step = if den > 0.0 {
            work(&a, &grad, &direction) / den
        } else {
            0.0
        };
        for j in 0..n {
            state.traction[j] -= step * direction[j];
            state.displacement[j] -= step * product[j];
        }
        // Points pushed beyond the bound are projected onto it and slip from now on; slipping
        // points moved along their circle's tangent return onto it.
        for i in 0..m {
            let g = problem.bound[i];
            if g <= 0.0 {
                continue;
            }
            let norm = norm_at(&state.traction, m, i);
            if norm > g || (state.slipping[i] && norm != g) {
                for c in 0..k {
                    let j = c * m + i;
                    changes.push((j, state.traction[j] * (g / norm - 1.0)));
                }
                scale_at(&mut state.traction, m, i, g / norm);
                state.slipping[i] = true;
            }
        }
        cost.products += usize::from(update_after_changes(
            op,
            &changes,
            &state.traction,
            &mut state.displacement,
        ));
        // A turn leaves the tangent line by a second-order amount that the conjugate directions
        // do not know of: they restart after any turn beyond the round-off.
        restart =
            (0..m).any(|i| state.slipping[i] && (step * norm_at(&direction, m, i) / problem.bound[i]) > 1e-6);
    }
    Err(CoulombError::NotConverged {
        iterations: cost.iterations,
        residual: residual / tolerance.max(f64::MIN_POSITIVE) * problem.tolerance,
    })
}

/// Solves the increment exactly on each pair of sets by dense Cholesky (see the module doc); at
/// slipping points of a disc the direction is solved for along the circle's tangent and put back
/// on the circle (a Newton step on the direction, converging quadratically).
///
/// # Panics
/// When `op` holds no matrix (see [`Compliance::matrix`]).
pub fn solve_direct(
    op: &mut dyn Compliance,
    problem: &CoulombProblem,
    state: &mut CoulombState,
) -> Result<CoulombCost, CoulombError> {
    let a = op.weights().to_vec();
    let (m, k) = (a.len(), op.components());
    let n = m * k;
    let g_max = problem.bound.iter().copied().fold(0.0, f64::max);
    let tolerance = problem.tolerance * op.largest_eigenvalue() * g_max;
    let mut cost = CoulombCost::default();
    classify(problem, state, k);
    let mut grad = vec![0.0; n];
    let mut fixed_displacement = vec![0.0; n];
    while cost.iterations < problem.max_iterations {
        cost.iterations += 1;
        // The free directions B: each component of a free point, the tangent of a slipping point
        // of a disc. Solve BᵀaC B x = Bᵀa (w + C q_prev − C q_fixed), q = q_fixed + B x.
        // The circle's curvature stiffens the tangent of a slipping point by κ_i = (slip pressing
        // outward)/g_i: the Newton step on the circle (without it the tangent-line step overshoots).
        op.apply(&state.traction, &mut state.displacement);
        cost.products += 1;
        gradient(problem, m, state, &mut grad);
        let mut columns: Vec<Vec<(usize, f64)>> = Vec::new();
        let mut curvature = Vec::new();
        for i in (0..m).filter(|&i| problem.bound[i] > 0.0) {
            if !state.slipping[i] {
                for c in 0..k {
                    state.traction[c * m + i] = 0.0;
                    columns.push(vec![(c * m + i, 1.0)]);
                }
            } else if k == 2 {
                let g = problem.bound[i];
                let (x, y) = (state.traction[i] / g, state.traction[m + i] / g);
                curvature.push((
                    columns.len(),
                    a[i] * (-dot_at(&grad, &state.traction, m, i) / g).max(0.0) / g,
                ));
                columns.push(vec![(i, -y), (m + i, x)]);
            }
        }
        op.apply(&state.traction, &mut fixed_displacement);
        cost.products += 1;
        if !columns.is_empty() {
            let matrix = op
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
                            * (problem.shift[j / m] + problem.previous_displacement[j]
                                - fixed_displacement[j])
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
        for i in (0..m).filter(|&i| problem.bound[i] > 0.0) {
            let g = problem.bound[i];
            let norm = norm_at(&state.traction, m, i);
            if state.slipping[i] || norm > g * (1.0 + 1e-12) {
                changed |= !state.slipping[i];
                scale_at(&mut state.traction, m, i, g / norm);
                state.slipping[i] = true;
            }
        }
        op.apply(&state.traction, &mut state.displacement);
        cost.products += 1;
        gradient(problem, m, state, &mut grad);
        for i in 0..m {
            if state.slipping[i] {
                let (violation, reversing) = bound_violation(&grad, &state.traction, problem.bound[i], m, i);
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
