//! Frictionless contact on the condensed contact-surface system, solved by a semi-smooth
//! Newton (primal–dual active set) method.
//!
//! With the stiffness factored once, the compliance of the m candidate contact nodes,
//! C_ij = e_zi · K⁻¹ e_zj (z-displacement of node i under a unit upward ring force at node j),
//! takes m solves, done once as one multi-column solve. A body pushed down by Δ onto the
//! contact plane then has at its candidate nodes u_z = −Δ + C λ, with λ ≥ 0 the contact ring
//! forces (the multipliers). For a sphere against a rigid plane, and for two bodies whose
//! compliances add (C = C₁ + C₂ on common node radii, forces equal and opposite), the gap is
//!
//! ```text
//! g(λ) = h − δ + C λ,    g ≥ 0,  λ ≥ 0,  λ·g = 0
//! ```
//! with h the initial separation of the surfaces at each node and δ the approach. C is
//! symmetric positive definite, so this linear complementarity problem has one solution.
//! The primal–dual active set method (Hintermüller, Ito & Kunisch 2003, a semi-smooth Newton
//! method for max(0, λ − κg) = λ) fixes g = 0 exactly on the active set A and λ = 0 off it:
//!
//! ```text
//! C_AA λ_A = δ − h_A,   λ_I = 0,   g_I = h_I − δ + C_IA λ_A
//! A ← {i ∈ A : λ_i > 0} ∪ {i ∉ A : g_i < 0}
//! ```
//! until A repeats. Non-penetration holds to round-off on A and by the stopping rule off it; no
//! penalty parameter enters the answer.

use faer::Mat;

use crate::fem::assembly::System;
use crate::fem::factor::Factor;

/// The condensed response of one body at its candidate contact nodes.
#[derive(Clone, Debug)]
pub struct Condensed {
    /// Compliance C (m × m, row-major) [m/N].
    pub compliance: Vec<f64>,
    /// Far-boundary normal reaction per unit force at each candidate: P_reaction = ρ · λ.
    pub reaction: Vec<f64>,
}

/// Candidate columns solved at once (a blocked multi-right-hand-side solve).
const BLOCK: usize = 64;

/// Condenses `system` onto the z-DOFs `dofs` (free indices) of the candidate nodes.
pub fn condense(system: &System, factor: &Factor, dofs: &[usize]) -> Condensed {
    let (n, m) = (system.dofs.count(), dofs.len());
    let mut compliance = vec![0.0; m * m];
    let mut reaction = vec![0.0; m];
    for start in (0..m).step_by(BLOCK) {
        let cols = BLOCK.min(m - start);
        let mut x = Mat::<f64>::zeros(n, cols);
        for c in 0..cols {
            x[(dofs[start + c], c)] = 1.0;
        }
        factor.solve_in_place(x.as_mut());
        for c in 0..cols {
            let j = start + c;
            for (i, &dof) in dofs.iter().enumerate() {
                compliance[i * m + j] = x[(dof, c)];
            }
            reaction[j] = system.reaction.iter().map(|&(d, v)| v * x[(d, c)]).sum();
        }
    }
    Condensed { compliance, reaction }
}

/// The contact problem on m candidate nodes.
#[derive(Clone, Debug)]
pub struct Problem {
    /// Compliance of the pair (m × m, row-major) [m/N].
    pub compliance: Vec<f64>,
    /// Initial separation h_i of the surfaces at each candidate [m].
    pub heights: Vec<f64>,
}

/// The contact state at one approach.
#[derive(Clone, Debug, Default)]
pub struct State {
    /// Contact ring forces λ ≥ 0 [N].
    pub forces: Vec<f64>,
    /// Gaps g ≥ 0 [m] (zero to round-off where λ > 0).
    pub gaps: Vec<f64>,
    /// Semi-smooth Newton iterations taken.
    pub iterations: usize,
}

/// Iteration cap; the active set settles in a few iterations when warm-started.
const MAX_ITERATIONS: usize = 200;

impl Problem {
    /// The number of candidates.
    pub fn len(&self) -> usize {
        self.heights.len()
    }

    /// True without candidates.
    pub fn is_empty(&self) -> bool {
        self.heights.is_empty()
    }

    /// Solves the contact at approach `delta`, starting from (and updating) the active set
    /// `active` (one flag per candidate).
    pub fn solve(&self, delta: f64, active: &mut [bool]) -> Result<State, String> {
        let m = self.len();
        // Gaps below this count as penetration: round-off of C λ relative to the approach.
        let tolerance = 1e-12 * (delta.abs() + self.heights.iter().fold(0.0_f64, |a, &h| a.max(h)));
        for iteration in 1..=MAX_ITERATIONS {
            let set: Vec<usize> = (0..m).filter(|&i| active[i]).collect();
            let forces = self.active_forces(&set, delta)?;
            let mut lambda = vec![0.0; m];
            for (&i, f) in set.iter().zip(&forces) {
                lambda[i] = *f;
            }
            let gaps: Vec<f64> = (0..m)
                .map(|i| {
                    let row = &self.compliance[i * m..(i + 1) * m];
                    let cl: f64 = set.iter().map(|&j| row[j] * lambda[j]).sum();
                    self.heights[i] - delta + cl
                })
                .collect();
            let next: Vec<bool> = (0..m)
                .map(|i| {
                    if active[i] {
                        lambda[i] > 0.0
                    } else {
                        gaps[i] < -tolerance
                    }
                })
                .collect();
            if next == active {
                return Ok(State {
                    forces: lambda,
                    gaps,
                    iterations: iteration,
                });
            }
            active.copy_from_slice(&next);
        }
        Err(format!(
            "the contact active set did not settle in {MAX_ITERATIONS} semi-smooth Newton iterations"
        ))
    }

    /// λ_A from C_AA λ_A = δ − h_A by a dense Cholesky factorisation.
    fn active_forces(&self, set: &[usize], delta: f64) -> Result<Vec<f64>, String> {
        let (m, k) = (self.len(), set.len());
        let mut a: Vec<f64> = set
            .iter()
            .flat_map(|&i| set.iter().map(move |&j| (i, j)))
            .map(|(i, j)| self.compliance[i * m + j])
            .collect();
        let mut b: Vec<f64> = set.iter().map(|&i| delta - self.heights[i]).collect();
        cholesky_solve(&mut a, k, &mut b)?;
        Ok(b)
    }
}

/// Solves A x = b in place for a dense symmetric positive definite A (k × k, row-major).
pub(super) fn cholesky_solve(a: &mut [f64], k: usize, b: &mut [f64]) -> Result<(), String> {
    for j in 0..k {
        let d = a[j * k + j] - (0..j).map(|p| a[j * k + p] * a[j * k + p]).sum::<f64>();
        if d.is_nan() || d <= 0.0 {
            return Err("the condensed compliance is not positive definite".into());
        }
        let d = d.sqrt();
        a[j * k + j] = d;
        for i in j + 1..k {
            let s: f64 = (0..j).map(|p| a[i * k + p] * a[j * k + p]).sum();
            a[i * k + j] = (a[i * k + j] - s) / d;
        }
    }
    for i in 0..k {
        let s: f64 = (0..i).map(|p| a[i * k + p] * b[p]).sum();
        b[i] = (b[i] - s) / a[i * k + i];
    }
    for i in (0..k).rev() {
        let s: f64 = (i + 1..k).map(|p| a[p * k + i] * b[p]).sum();
        b[i] = (b[i] - s) / a[i * k + i];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn active_set_solves_a_small_complementarity_problem() {
        // Two uncoupled springs of compliance 1 and a coupled pair: h = (0, 1), δ = 0.5:
        // node 0 closes (λ0 = 0.5), node 1 stays open with gap 0.5.
        let p = Problem {
            compliance: vec![1.0, 0.0, 0.0, 1.0],
            heights: vec![0.0, 1.0],
        };
        let mut active = vec![false; 2];
        let s = p.solve(0.5, &mut active).unwrap();
        assert!((s.forces[0] - 0.5).abs() < 1e-15 && s.forces[1] == 0.0);
        assert!(s.gaps[0].abs() < 1e-15 && (s.gaps[1] - 0.5).abs() < 1e-15);
        assert_eq!(active, vec![true, false]);
    }

    #[test]
    fn a_gap_gives_no_force() {
        let p = Problem {
            compliance: vec![2.0],
            heights: vec![0.0],
        };
        let s = p.solve(-1.0, &mut [true]).unwrap();
        assert_eq!(s.forces, vec![0.0]);
    }
}
