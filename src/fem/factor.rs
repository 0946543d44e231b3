//! Sparse Cholesky factorisation of the stiffness (faer), computed once per mesh.
//!
//! The fill-reducing ordering matters more than anything else for the factor's cost. Two are
//! offered and measured by `examples/fem_timing.rs`: faer's approximate minimum degree, and the
//! generator's natural order (ring by ring from the pole, a banded matrix).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::SparseColMat;
use faer::{Conj, MatMut, Par, Side};

/// The fill-reducing ordering of the factorisation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree (Amestoy, Davis & Duff 1996).
    Amd,
    /// The mesh's own numbering (rings from the pole: banded).
    Natural,
}

/// L Lᵀ = P K Pᵀ of a symmetric positive definite matrix.
pub struct Factor {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
}

impl Factor {
    /// Factors `lower` (the lower triangle of K) with `ordering`.
    pub fn new(lower: &SparseColMat<usize, f64>, ordering: Ordering) -> Result<Self, String> {
        let ord = match ordering {
            Ordering::Amd => SymmetricOrdering::Amd,
            Ordering::Natural => SymmetricOrdering::Identity,
        };
        let symbolic =
            factorize_symbolic_cholesky(lower.symbolic(), Side::Lower, ord, Default::default())
                .map_err(|e| format!("symbolic Cholesky: {e:?}"))?;
        let mut values = vec![0.0; symbolic.len_val()];
        let par = Par::Seq;
        let mut buffer = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|e| format!("Cholesky workspace: {e:?}"))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                lower.as_ref(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut buffer),
                Default::default(),
            )
            .map_err(|e| format!("the stiffness is not positive definite: {e:?}"))?;
        Ok(Self { symbolic, values })
    }

    /// Entries of the factor L.
    pub fn factor_entries(&self) -> usize {
        self.values.len()
    }

    /// Overwrites each column of `rhs` with K⁻¹ times it.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let par = Par::Seq;
        let mut buffer =
            MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(rhs.ncols(), par));
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            par,
            MemStack::new(&mut buffer),
        );
    }
}
