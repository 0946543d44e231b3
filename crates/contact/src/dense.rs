//! A compliance held as a dense matrix (faer `Mat`): the condensed compliance of a finite
//! element model (m contact nodes × 1–2 components, from the factorisation of the stiffness), or
//! any small influence matrix.
//!
//! **Products over the loaded columns only.** The FEM solvers order their candidate points by
//! their distance from the pole, and a contact is a disc around it, so the points that carry a
//! multiplier are (nearly) a leading run of each component's block: a product C λ needs only the
//! columns up to the last loaded point of each block. Every row is still formed (the engine
//! carries C λ everywhere: a point entering contact starts from it). A dense product is bound by
//! reading the matrix, so it costs in proportion to the columns read: with the contact at
//! 0.6–0.9 of the candidate radius, a third to two thirds of a whole product. Any point order is
//! correct; the saving needs the loaded points first.
//!
//! **The largest eigenvalue** (the step bound of the iterative solvers and the scale of the
//! tangential tolerance) is the least of Gershgorin's bound and [`EIGENVALUE_MARGIN`] times a
//! power-iteration estimate: Gershgorin's is 1.34 (normal) and 1.47 (tangential) times the
//! estimate for fem-3d's default mesh, and accelerated gradients take steps in proportion to the
//! square root of the bound.

use faer::linalg::matmul::matmul;
use faer::{Accum, ColMut, ColRef, Mat, MatRef, Par};

use super::operator::{work, Compliance};

/// Why a matrix is not a compliance.
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum DenseError {
    /// The matrix is not square of side m·k.
    #[error("the compliance is {rows}×{cols}, expected {expected}×{expected} ({points} points × {components} components)")]
    Shape {
        /// Rows given.
        rows: usize,
        /// Columns given.
        cols: usize,
        /// m·k.
        expected: usize,
        /// m.
        points: usize,
        /// k.
        components: usize,
    },
    /// An entry or a weight is not finite, or a weight is not positive.
    #[error("the compliance has a non-finite entry or a non-positive weight")]
    NotFinite,
    /// diag(a)·C is not symmetric.
    #[error("the compliance is not self-adjoint: entries ({0}, {1}) and ({1}, {0}) differ")]
    NotSymmetric(usize, usize),
}

/// Relative asymmetry of a·C tolerated: round-off of the solves that built C.
const SYMMETRY: f64 = 1e-8;

/// A dense compliance C with point weights a.
#[derive(Clone, Debug)]
pub struct DenseCompliance {
    matrix: Mat<f64>,
    weights: Vec<f64>,
    components: usize,
    largest: f64,
}

impl DenseCompliance {
    /// The compliance `matrix` (m·k square, component-major) on points of weights `weights`
    /// (length m), with `components` = k; checks shape, finiteness and self-adjointness.
    pub fn try_new(matrix: Mat<f64>, weights: Vec<f64>, components: usize) -> Result<Self, DenseError> {
        let (points, n) = (weights.len(), weights.len() * components);
        if matrix.nrows() != n || matrix.ncols() != n || components == 0 {
            return Err(DenseError::Shape {
                rows: matrix.nrows(),
                cols: matrix.ncols(),
                expected: n,
                points,
                components,
            });
        }
        let weight = |j: usize| weights[j % points];
        let finite = weights.iter().all(|&a| a.is_finite() && a > 0.0)
            && (0..n).all(|j| (0..n).all(|i| matrix[(i, j)].is_finite()));
        if !finite {
            return Err(DenseError::NotFinite);
        }
        let scale = (0..n)
            .map(|i| weight(i) * matrix[(i, i)].abs())
            .fold(0.0, f64::max);
        for j in 0..n {
            for i in j + 1..n {
                let (a, b) = (weight(i) * matrix[(i, j)], weight(j) * matrix[(j, i)]);
                if (a - b).abs() > SYMMETRY * scale {
                    return Err(DenseError::NotSymmetric(i, j));
                }
            }
        }
        // Gershgorin on the symmetric similar matrix √a C /√a bounds the spectrum.
        let gershgorin = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| matrix[(i, j)].abs() * (weight(i) / weight(j)).sqrt())
                    .sum::<f64>()
            })
            .fold(0.0, f64::max);
        let mut op = Self {
            matrix,
            weights,
            components,
            largest: gershgorin,
        };
        op.largest = gershgorin.min(EIGENVALUE_MARGIN * op.power_estimate());
        Ok(op)
    }

    /// The largest eigenvalue in the work product by power iteration (the Rayleigh quotient,
    /// which approaches it from below), until it changes by less than 1e-6 in 10 steps or
    /// after [`POWER_STEPS`].
    fn power_estimate(&mut self) -> f64 {
        let a = self.weights.clone();
        let n = a.len() * self.components;
        // A positive start: the compliance's top modes (uniform pressure or shift) are.
        let mut x = vec![1.0; n];
        let mut y = vec![0.0; n];
        let (mut estimate, mut checked) = (0.0, 0.0);
        for step in 1..=POWER_STEPS {
            self.apply(&x, &mut y);
            estimate = work(&a, &x, &y) / work(&a, &x, &x);
            let norm = work(&a, &y, &y).sqrt();
            if norm == 0.0 {
                break;
            }
            x.iter_mut().zip(&y).for_each(|(x, y)| *x = y / norm);
            if step % 10 == 0 {
                if (estimate - checked).abs() <= 1e-6 * estimate {
                    break;
                }
                checked = estimate;
            }
        }
        estimate
    }

    /// A scalar (k = 1) compliance with unit weights (nodal forces).
    pub fn scalar(matrix: Mat<f64>) -> Result<Self, DenseError> {
        let m = matrix.nrows();
        Self::try_new(matrix, vec![1.0; m], 1)
    }
}

/// Power-iteration steps at most.
const POWER_STEPS: usize = 300;

/// The step bound over the power estimate of the largest eigenvalue. The estimate converges from
/// below to 1e-6; 5 % above it keeps the bound an upper bound with room for a slowly converging
/// top mode (the x and y shift modes of a tangential compliance are nearly degenerate, which
/// leaves the Rayleigh quotient unaffected).
const EIGENVALUE_MARGIN: f64 = 1.05;

impl Compliance for DenseCompliance {
    fn points(&self) -> usize {
        self.weights.len()
    }

    fn components(&self) -> usize {
        self.components
    }

    fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// out = Σ over components c of C[:, block c up to its last loaded point] · load[same] (see
    /// the module doc).
    fn apply(&mut self, load: &[f64], out: &mut [f64]) {
        let m = self.weights.len();
        let mut written = false;
        for (c, block) in load.chunks(m).enumerate() {
            let Some(last) = block.iter().rposition(|&v| v != 0.0) else {
                continue;
            };
            matmul(
                ColMut::from_slice_mut(out).as_mat_mut(),
                if written { Accum::Add } else { Accum::Replace },
                self.matrix.as_ref().subcols(c * m, last + 1),
                ColRef::from_slice(&block[..=last]).as_mat(),
                1.0,
                Par::Seq,
            );
            written = true;
        }
        if !written {
            out.fill(0.0);
        }
    }

    /// The least of Gershgorin's bound and [`EIGENVALUE_MARGIN`] times the power estimate.
    fn largest_eigenvalue(&self) -> f64 {
        self.largest
    }

    /// A column costs n of the n² operations of a product.
    fn column_budget(&self) -> usize {
        self.matrix.nrows() / 4
    }

    fn add_columns(&mut self, changes: &[(usize, f64)], out: &mut [f64]) {
        for &(j, delta) in changes {
            let column = self.matrix.col(j);
            for (o, c) in out.iter_mut().zip(column.iter()) {
                *o += c * delta;
            }
        }
    }

    fn matrix(&self) -> Option<MatRef<'_, f64>> {
        Some(self.matrix.as_ref())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_wrong_shapes_and_asymmetry() {
        let m = Mat::from_fn(2, 2, |i, j| if i == j { 2.0 } else { 1.0 });
        assert!(DenseCompliance::try_new(m.clone(), vec![1.0; 3], 1).is_err());
        let bad = Mat::from_fn(2, 2, |i, j| (i + 2 * j) as f64 + 1.0);
        assert_eq!(
            DenseCompliance::scalar(bad).unwrap_err(),
            DenseError::NotSymmetric(1, 0)
        );
        let mut op = DenseCompliance::scalar(m).unwrap();
        let mut out = vec![0.0; 2];
        op.apply(&[1.0, 2.0], &mut out);
        assert_eq!(out, vec![4.0, 5.0]);
        // Gershgorin: row sums 3 = the largest eigenvalue 3 (the least of the two bounds).
        assert_eq!(op.largest_eigenvalue(), 3.0);
    }

    #[test]
    fn the_product_over_loaded_columns_equals_the_whole_matrix_s() {
        // A symmetric 2-component compliance on 3 points, loads with trailing zeros per block.
        let n = 6;
        let matrix = Mat::from_fn(n, n, |i, j| {
            1.0 / (1.0 + (i as f64 - j as f64).abs()) + if i == j { 1.0 } else { 0.0 }
        });
        let mut op = DenseCompliance::try_new(matrix.clone(), vec![1.0; 3], 2).unwrap();
        for load in [
            [1.0, 0.0, 0.0, 2.0, -1.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, 3.0, 0.0],
            [0.0; 6],
            [0.5, 1.0, -2.0, 1.0, 0.0, 4.0],
        ] {
            let mut out = vec![9.0; n];
            op.apply(&load, &mut out);
            for (i, o) in out.iter().enumerate() {
                let whole: f64 = (0..n).map(|j| matrix[(i, j)] * load[j]).sum();
                assert!((o - whole).abs() <= 1e-14 * (1.0 + whole.abs()), "{out:?}");
            }
        }
    }

    #[test]
    fn the_step_bound_lies_just_above_the_largest_eigenvalue() {
        // [[3,1,0],[1,3,1],[0,1,3]]: eigenvalues 3 ± √2 and 3, Gershgorin bound 5: the power
        // estimate with its margin lies between λ_max and 1.05 λ_max.
        let tridiagonal = Mat::from_fn(3, 3, |i, j| match i.abs_diff(j) {
            0 => 3.0,
            1 => 1.0,
            _ => 0.0,
        });
        let op = DenseCompliance::scalar(tridiagonal).unwrap();
        let exact = 3.0 + 2f64.sqrt();
        assert!(op.largest_eigenvalue() >= exact, "{}", op.largest_eigenvalue());
        assert!(op.largest_eigenvalue() <= EIGENVALUE_MARGIN * exact * (1.0 + 1e-9));
    }
}
