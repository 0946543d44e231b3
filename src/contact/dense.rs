//! A compliance held as a dense matrix (faer `Mat`): the condensed compliance of a finite
//! element model (m contact nodes × 1–2 components, from the factorisation of the stiffness), or
//! any small influence matrix.

use faer::linalg::matmul::matmul;
use faer::{Accum, ColMut, ColRef, Mat, MatRef, Par};

use super::operator::Compliance;

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
        let largest = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| matrix[(i, j)].abs() * (weight(i) / weight(j)).sqrt())
                    .sum::<f64>()
            })
            .fold(0.0, f64::max);
        Ok(Self {
            matrix,
            weights,
            components,
            largest,
        })
    }

    /// A scalar (k = 1) compliance with unit weights (nodal forces).
    pub fn scalar(matrix: Mat<f64>) -> Result<Self, DenseError> {
        let m = matrix.nrows();
        Self::try_new(matrix, vec![1.0; m], 1)
    }
}

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

    fn apply(&mut self, load: &[f64], out: &mut [f64]) {
        matmul(
            ColMut::from_slice_mut(out).as_mat_mut(),
            Accum::Replace,
            self.matrix.as_ref(),
            ColRef::from_slice(load).as_mat(),
            1.0,
            Par::Seq,
        );
    }

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
        // Gershgorin: row sums 3 ≥ the largest eigenvalue 3.
        assert_eq!(op.largest_eigenvalue(), 3.0);
    }
}
