//! The frictionless normal problem at a prescribed approach: the constrained conjugate gradient
//! of Polonsky & Keer (1999, Wear 231, 206–219), in the displacement-controlled form (the
//! approach δ is given, so the mean-pressure constraint of the original is dropped; as in
//! Bugnicourt, Sainsot, Dureisseix, Gauthier & Lubrecht 2018, Tribol. Lett. 66:29).
//!
//! Unknown: the panel pressures p ≥ 0. Gap at panel i: g_i = (K p)_i + h_i − δ, with h_i the
//! initial separation of the surfaces (r²/2R*) and K the Boussinesq influence matrix. Exact
//! non-penetration: g ≥ 0, p ≥ 0, p·g = 0 on every panel. The pressure solves the quadratic
//! programme min ½ pᵀKp + (h − δ)ᵀp, p ≥ 0, whose gradient is g; the algorithm runs conjugate
//! gradients on the panels in contact, clamps negative pressures to zero, and re-admits panels
//! that penetrate (restarting the conjugate directions when the set changes).

use super::convolution::{Convolver, Spectrum};

/// The normal problem's operator p ↦ K p on one grid.
pub struct NormalOperator {
    convolver: Convolver,
    kernel: Spectrum,
}

impl NormalOperator {
    /// The operator with the Boussinesq kernel `zz` (circulant layout).
    pub fn new(mut convolver: Convolver, zz: &[f64]) -> Self {
        let kernel = convolver.kernel_spectrum(zz);
        Self { convolver, kernel }
    }

    /// u = K p.
    pub fn apply(&mut self, p: &[f64]) -> Vec<f64> {
        let spectrum = self.convolver.field_spectrum(p).times(&self.kernel);
        self.convolver.field(spectrum)
    }
}

/// Why a normal solve stopped without converging.
#[derive(Debug, PartialEq)]
pub struct NotConverged {
    /// Iterations spent.
    pub iterations: usize,
    /// The last residual (rms gap on the contact panels over δ).
    pub residual: f64,
}

/// The normal problem at one approach.
pub struct NormalProblem<'a> {
    /// Initial separation h_i of each panel [m].
    pub separation: &'a [f64],
    /// The approach δ [m].
    pub approach: f64,
    /// Convergence: rms gap on the contact panels below `tolerance · δ`, and no panel out of
    /// contact penetrating by more than `tolerance · δ`.
    pub tolerance: f64,
    /// Iteration cap.
    pub max_iterations: usize,
    /// A pressure per unit overlap [Pa/m] of the right order (E*/c) for seeding contact.
    pub stiffness: f64,
}

impl NormalProblem<'_> {
    /// A positive starting pressure on the overlapping panels, `stiffness · (δ − h)`: any positive
    /// guess converges; this one has the right order of magnitude.
    pub fn starting_pressure(&self) -> Vec<f64> {
        self.separation
            .iter()
            .map(|h| (self.approach - h).max(0.0) * self.stiffness)
            .collect()
    }

    /// Solves for the pressure starting from `p` (updated in place); returns the iterations.
    pub fn solve(&self, op: &mut NormalOperator, p: &mut [f64]) -> Result<usize, NotConverged> {
        let count = p.len();
        let mut direction = vec![0.0; count];
        let mut previous_norm = 1.0;
        let mut restart = true;
        let mut residual = f64::INFINITY;
        // u = K p, kept up to date: recomputed after the pressure is clamped or re-admitted, and
        // otherwise advanced as u − τ K t with the product the step needs anyway.
        let mut u = op.apply(p);
        let mut gap = vec![0.0; count];
        for iteration in 0..self.max_iterations {
            let (mut norm, mut active) = (0.0, 0usize);
            for i in 0..count {
                gap[i] = u[i] + self.separation[i] - self.approach;
                if p[i] > 0.0 {
                    norm += gap[i] * gap[i];
                    active += 1;
                }
            }
            if active == 0 {
                // Nothing in contact: done unless a panel penetrates, which seeds the contact.
                if gap.iter().all(|&g| g >= 0.0) {
                    return Ok(iteration);
                }
                for (p, g) in p.iter_mut().zip(&gap) {
                    *p = (-g).max(0.0) * self.stiffness;
                }
                restart = true;
                u = op.apply(p);
                continue;
            }
            residual = (norm / active as f64).sqrt() / self.approach;
            let penetrates = (0..count).any(|i| p[i] == 0.0 && gap[i] < -self.tolerance * self.approach);
            if residual < self.tolerance && !restart && !penetrates {
                return Ok(iteration);
            }
            // Conjugate direction on the contact set (Polonsky & Keer, eq. 10).
            let beta = if restart { 0.0 } else { norm / previous_norm };
            for i in 0..count {
                direction[i] = if p[i] > 0.0 {
                    gap[i] + beta * direction[i]
                } else {
                    0.0
                };
            }
            previous_norm = norm;
            let r = op.apply(&direction);
            let (num, den) = (0..count).filter(|&i| p[i] > 0.0).fold((0.0, 0.0), |(a, b), i| {
                (a + gap[i] * direction[i], b + r[i] * direction[i])
            });
            let step = if den > 0.0 { num / den } else { 0.0 };
            let mut clamped = false;
            for i in 0..count {
                if p[i] > 0.0 {
                    let next = p[i] - step * direction[i];
                    clamped |= next < 0.0;
                    p[i] = next.max(0.0);
                }
            }
            // Panels out of contact that penetrate re-enter (P&K, eq. 13), restarting the CG.
            restart = false;
            for i in 0..count {
                if p[i] == 0.0 && gap[i] < 0.0 {
                    p[i] = -step * gap[i];
                    restart = true;
                }
            }
            if clamped || restart {
                u = op.apply(p);
            } else {
                u.iter_mut().zip(&r).for_each(|(u, r)| *u -= step * r);
            }
        }
        Err(NotConverged {
            iterations: self.max_iterations,
            residual,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::grid::Grid;
    use crate::bem::influence::{Kernels, PairCompliance};

    #[test]
    fn the_solution_satisfies_the_contact_conditions() {
        // A paraboloid h = r²/2R* (R* = 0.05 m, E* = 1/compliance) pressed by δ = 17 µm on 32².
        let compliance = PairCompliance {
            normal: 1.82 / 70e9,
            shear: 0.0,
            poisson_shear: 0.0,
        };
        let c = (0.05_f64 * 17e-6).sqrt();
        let grid = Grid::covering(32, 1.1 * c);
        let zz = Kernels::normal(&grid, &compliance);
        let mut op = NormalOperator::new(Convolver::new(grid.n), &zz);
        let separation: Vec<f64> = grid
            .centres()
            .iter()
            .map(|[x, y]| (x * x + y * y) / 0.1)
            .collect();
        let problem = NormalProblem {
            separation: &separation,
            approach: 17e-6,
            tolerance: 1e-9,
            max_iterations: 1000,
            stiffness: 70e9 / 1.82 / c,
        };
        let mut p = problem.starting_pressure();
        problem.solve(&mut op, &mut p).expect("converges");
        let u = op.apply(&p);
        for k in 0..grid.len() {
            let gap = u[k] + separation[k] - 17e-6;
            assert!(p[k] >= 0.0);
            // Non-penetration and complementarity to the tolerance (1e-9 δ, as rms on the contact).
            assert!(gap > -1e-8 * 17e-6, "panel {k} penetrates by {gap}");
            if p[k] > 0.0 {
                assert!(gap.abs() < 1e-8 * 17e-6, "panel {k} in contact with gap {gap}");
            }
        }
    }
}
