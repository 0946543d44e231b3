//! The condensed compliance as the engine multiplies it: only the columns of the loaded points.
//!
//! The candidate points are sorted by their distance from the pole ([`super::surface`]), and a
//! contact is a disc around it, so the points that carry a multiplier are (nearly) a leading
//! run of each component's block: a product C λ needs only the columns up to the last loaded
//! point of each block. Every row is still formed (the engine carries C λ everywhere: a point
//! entering contact starts from it). With the contact radius at 0.6–0.9 of the candidate radius
//! along the paper path, a product reads a third to two thirds of the matrix, which is what it
//! costs: the dense product is bound by reading the matrix (37 MB for the tangential compliance
//! of the default mesh).

use faer::linalg::matmul::matmul;
use faer::{Accum, ColMut, ColRef, MatRef, Par};

use crate::contact::operator::work;
use crate::contact::{Compliance, DenseCompliance};

/// A dense compliance multiplied by the columns of its loaded points only.
#[derive(Clone, Debug)]
pub struct LoadedColumns {
    dense: DenseCompliance,
    largest: f64,
}

impl LoadedColumns {
    /// The operator over `dense` (any point order; the saving needs the loaded points first).
    pub fn new(dense: DenseCompliance) -> Self {
        let mut op = Self {
            largest: dense.largest_eigenvalue(),
            dense,
        };
        op.largest = op.largest.min(EIGENVALUE_MARGIN * op.power_estimate());
        op
    }

    /// The largest eigenvalue in the work product by power iteration (the Rayleigh quotient,
    /// which approaches it from below), until it changes by less than 1e-6 in 10 steps or
    /// after [`POWER_STEPS`].
    fn power_estimate(&mut self) -> f64 {
        let a = self.weights().to_vec();
        let n = a.len() * self.components();
        // A positive start: the compliance's top modes (uniform pressure or shift) are.
        let mut x = vec![1.0; n];
        let mut y = vec![0.0; n];
        let (mut estimate, mut checked) = (0.0, 0.0);
        for step in 1..=POWER_STEPS {
            self.dense.apply(&x, &mut y);
            estimate = work(&a, &x, &y) / work(&a, &x, &x);
            let norm = work(&a, &y, &y).sqrt();
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
}

/// Power-iteration steps at most.
const POWER_STEPS: usize = 300;
/// The step bound the engine is given over the power estimate of the largest eigenvalue. The
/// engine's steps are 1/λ_max; the Gershgorin bound the dense compliance offers is 1.34 (normal)
/// and 1.47 (tangential) times the power estimate at the default mesh
/// (`examples/fem3d_timing.rs`), and accelerated gradients take steps in proportion to the
/// square root of it. The estimate converges from below to 1e-6; 5 % above it keeps the bound
/// an upper bound with room for a slowly converging top mode (the x and y shift modes of the
/// tangential compliance are nearly degenerate, which leaves the Rayleigh quotient unaffected).
const EIGENVALUE_MARGIN: f64 = 1.05;

impl Compliance for LoadedColumns {
    fn points(&self) -> usize {
        self.dense.points()
    }

    fn components(&self) -> usize {
        self.dense.components()
    }

    fn weights(&self) -> &[f64] {
        self.dense.weights()
    }

    /// out = Σ over components c of C[:, block c up to its last loaded point] · load[same].
    fn apply(&mut self, load: &[f64], out: &mut [f64]) {
        let m = self.points();
        let matrix = self.dense.matrix().expect("a dense compliance holds its matrix");
        let mut written = false;
        for (c, block) in load.chunks(m).enumerate() {
            let Some(last) = block.iter().rposition(|&v| v != 0.0) else {
                continue;
            };
            matmul(
                ColMut::from_slice_mut(out).as_mat_mut(),
                if written { Accum::Add } else { Accum::Replace },
                matrix.subcols(c * m, last + 1),
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

    /// [`EIGENVALUE_MARGIN`] times the power estimate, at most the Gershgorin bound.
    fn largest_eigenvalue(&self) -> f64 {
        self.largest
    }

    fn column_budget(&self) -> usize {
        self.dense.column_budget()
    }

    fn add_columns(&mut self, changes: &[(usize, f64)], out: &mut [f64]) {
        self.dense.add_columns(changes, out);
    }

    fn matrix(&self) -> Option<MatRef<'_, f64>> {
        self.dense.matrix()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    #[test]
    fn the_product_equals_the_whole_matrix_s() {
        // A symmetric 2-component compliance on 3 points, loads with trailing zeros per block.
        let n = 6;
        let matrix = Mat::from_fn(n, n, |i, j| {
            1.0 / (1.0 + (i as f64 - j as f64).abs()) + if i == j { 1.0 } else { 0.0 }
        });
        let dense = DenseCompliance::try_new(matrix, vec![1.0; 3], 2).unwrap();
        let mut whole = dense.clone();
        let mut loaded = LoadedColumns::new(dense);
        for load in [
            [1.0, 0.0, 0.0, 2.0, -1.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, 3.0, 0.0],
            [0.0; 6],
            [0.5, 1.0, -2.0, 1.0, 0.0, 4.0],
        ] {
            let (mut a, mut b) = (vec![7.0; n], vec![9.0; n]);
            whole.apply(&load, &mut a);
            loaded.apply(&load, &mut b);
            for (x, y) in a.iter().zip(&b) {
                assert!((x - y).abs() <= 1e-14 * (1.0 + x.abs()), "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn the_step_bound_lies_just_above_the_largest_eigenvalue() {
        // diag(1, 2, 3) with unit weights: λ_max = 3, Gershgorin also 3 (the bound is the least).
        let diagonal = Mat::from_fn(3, 3, |i, j| if i == j { (i + 1) as f64 } else { 0.0 });
        let op = LoadedColumns::new(DenseCompliance::scalar(diagonal).unwrap());
        assert_eq!(op.largest_eigenvalue(), 3.0);
        // [[3,1,0],[1,3,1],[0,1,3]]: eigenvalues 3 ± √2 and 3, Gershgorin bound 5: the power
        // estimate with its margin lies between λ_max and 1.05 λ_max.
        let tridiagonal = Mat::from_fn(3, 3, |i, j| match i.abs_diff(j) {
            0 => 3.0,
            1 => 1.0,
            _ => 0.0,
        });
        let op = LoadedColumns::new(DenseCompliance::scalar(tridiagonal).unwrap());
        let exact = 3.0 + 2f64.sqrt();
        assert!(op.largest_eigenvalue() >= exact, "{}", op.largest_eigenvalue());
        assert!(op.largest_eigenvalue() <= EIGENVALUE_MARGIN * exact * (1.0 + 1e-9));
    }
}
