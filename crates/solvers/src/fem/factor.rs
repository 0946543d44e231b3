//! Sparse Cholesky factorisation of the stiffness (faer), computed once per mesh.
//!
//! The fill-reducing ordering matters more than anything else for the factor's cost. Two are
//! offered and measured by `examples/fem_timing.rs`: faer's approximate minimum degree, and
//! reverse Cuthill–McKee, which makes the matrix of a graded 2D ring mesh banded; any other
//! (the 3D model's, with its contact unknowns last) is given as a permutation.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::SparseColMat;
use faer::{Conj, Mat, MatMut, Par, Side};
use std::collections::VecDeque;

use spherecontact_model::memory::{Estimate, WORD};

/// The fill-reducing ordering of the factorisation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree (Amestoy, Davis & Duff 1996).
    Amd,
    /// Reverse Cuthill–McKee (George & Liu 1981, §4.3): a narrow band.
    ReverseCuthillMcKee,
}

/// L Lᵀ = P K Pᵀ of a symmetric positive definite matrix.
pub struct Factor {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
}

/// The symbolic factorisation of a matrix: the factor's structure, known before its values are
/// allocated, so that its memory can be judged first ([`Plan::estimate`]).
pub struct Plan {
    symbolic: SymbolicCholesky<usize>,
}

impl Plan {
    /// The symbolic factorisation of `lower` (the lower triangle of K) with `ordering`.
    pub fn new(lower: &SparseColMat<usize, f64>, ordering: Ordering) -> Result<Self, String> {
        match ordering {
            Ordering::Amd => Self::symbolic(lower, SymmetricOrdering::Amd),
            Ordering::ReverseCuthillMcKee => Self::with_permutation(lower, &reverse_cuthill_mckee(lower)),
        }
    }

    /// The symbolic factorisation of `lower` with a given fill-reducing order: row `forward[k]`
    /// of K becomes row k of P K Pᵀ (e.g. a nested dissection, or an order that puts chosen
    /// unknowns last so that [`Factor::trailing_block`] is their Schur complement's factor).
    pub fn with_permutation(lower: &SparseColMat<usize, f64>, forward: &[usize]) -> Result<Self, String> {
        let n = lower.nrows();
        if forward.len() != n {
            return Err(format!(
                "the ordering has {} entries for {n} unknowns",
                forward.len()
            ));
        }
        let mut inverse = vec![usize::MAX; n];
        for (k, &i) in forward.iter().enumerate() {
            if i >= n || inverse[i] != usize::MAX {
                return Err(format!("the ordering is not a permutation of 0..{n}"));
            }
            inverse[i] = k;
        }
        Self::symbolic(
            lower,
            SymmetricOrdering::Custom(PermRef::new_checked(forward, &inverse, n)),
        )
    }

    fn symbolic(lower: &SparseColMat<usize, f64>, ord: SymmetricOrdering<'_, usize>) -> Result<Self, String> {
        let symbolic = factorize_symbolic_cholesky(lower.symbolic(), Side::Lower, ord, Default::default())
            .map_err(|e| format!("symbolic Cholesky: {e}"))?;
        Ok(Self { symbolic })
    }

    /// Entries of the factor L.
    pub fn factor_entries(&self) -> usize {
        self.symbolic.len_val()
    }

    /// The memory of a solve of `columns` right-hand sides through the factor [bytes]: the
    /// right-hand sides and the solve's workspace (which holds their permuted copy).
    pub fn solve_bytes(&self, columns: usize) -> u64 {
        let workspace = self
            .symbolic
            .solve_in_place_scratch::<f64>(columns, Par::Seq)
            .layout()
            .map_or(usize::MAX, |layout| layout.size());
        WORD * (self.symbolic.nrows() * columns) as u64 + workspace as u64
    }

    fn scratch(&self) -> Result<usize, String> {
        let request = self
            .symbolic
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default());
        request
            .layout()
            .map(|layout| layout.size())
            .map_err(|_| "the Cholesky workspace overflows the address space".to_owned())
    }

    /// The memory of the numeric factorisation of `lower` [bytes]: the factor's values, its
    /// workspace (which holds a permuted copy of K) and the symbolic structure's indices, as
    /// parts named after `what`; an `Err` when the workspace cannot even be sized.
    pub fn estimate(&self, what: &str, lower: &SparseColMat<usize, f64>) -> Result<Estimate, String> {
        let mut estimate = Estimate::default();
        estimate.add(format!("{what} factor"), WORD * self.symbolic.len_val() as u64);
        estimate.add_transient(format!("{what} factorisation workspace"), self.scratch()? as u64);
        let indices = match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => s.row_idx().len(),
            SymbolicCholeskyRaw::Simplicial(s) => s.row_idx().len(),
        };
        estimate.add(
            format!("{what} stiffness and factor indices"),
            WORD * (2 * lower.compute_nnz() + indices + 4 * lower.nrows()) as u64,
        );
        Ok(estimate)
    }

    /// The numeric factorisation of `lower` (the matrix this plan was made for).
    pub fn factor(self, lower: &SparseColMat<usize, f64>) -> Result<Factor, String> {
        let symbolic = self.symbolic;
        let mut values = Vec::new();
        values
            .try_reserve_exact(symbolic.len_val())
            .map_err(|e| format!("the Cholesky factor ({} entries): {e}", symbolic.len_val()))?;
        values.resize(symbolic.len_val(), 0.0);
        let par = Par::Seq;
        let mut buffer =
            MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()))
                .map_err(|e| format!("Cholesky workspace: {e}"))?;
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
            .map_err(|e| format!("the stiffness is not positive definite: {e}"))?;
        Ok(Factor { symbolic, values })
    }
}

impl Factor {
    /// Factors `lower` (the lower triangle of K) with `ordering` ([`Plan::new`], then
    /// [`Plan::factor`]).
    pub fn new(lower: &SparseColMat<usize, f64>, ordering: Ordering) -> Result<Self, String> {
        Plan::new(lower, ordering)?.factor(lower)
    }

    /// Factors `lower` with a given fill-reducing order ([`Plan::with_permutation`]).
    pub fn with_permutation(lower: &SparseColMat<usize, f64>, forward: &[usize]) -> Result<Self, String> {
        Plan::with_permutation(lower, forward)?.factor(lower)
    }

    /// The trailing m × m block L₂₂ of the factor (rows and columns n − m … n − 1 of P K Pᵀ).
    ///
    /// With P K Pᵀ = [K₁₁ K₁₂; K₂₁ K₂₂] and L = [L₁₁ 0; L₂₁ L₂₂], L₂₂ L₂₂ᵀ = K₂₂ − K₂₁ K₁₁⁻¹ K₁₂,
    /// the Schur complement: the stiffness of the last m unknowns with all others condensed out,
    /// so (L₂₂ L₂₂ᵀ)⁻¹ is the corresponding block of K⁻¹, read without a solve through the
    /// whole factor.
    pub fn trailing_block(&self, m: usize) -> Mat<f64> {
        let n = self.symbolic.nrows();
        let t = n - m.min(n);
        let mut block = Mat::<f64>::zeros(n - t, n - t);
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => {
                let l = SupernodalLltRef::new(s, &self.values);
                for k in 0..s.n_supernodes() {
                    let (begin, end) = (s.supernode_begin()[k], s.supernode_end()[k]);
                    if end <= t {
                        continue;
                    }
                    let node = l.supernode(k);
                    let val = node.val();
                    let rows = (begin..end).chain(node.pattern().iter().copied());
                    for (r, row) in rows.enumerate() {
                        for c in begin.max(t)..end.min(row + 1) {
                            block[(row - t, c - t)] = val[(r, c - begin)];
                        }
                    }
                }
            }
            SymbolicCholeskyRaw::Simplicial(s) => {
                let (col_ptr, row_idx) = (s.col_ptr(), s.row_idx());
                for c in t..n {
                    for p in col_ptr[c]..col_ptr[c + 1] {
                        block[(row_idx[p] - t, c - t)] = self.values[p];
                    }
                }
            }
        }
        block
    }

    /// Entries of the factor L.
    pub fn factor_entries(&self) -> usize {
        self.values.len()
    }

    /// Overwrites each column of `rhs` with K⁻¹ times it.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let par = Par::Seq;
        let mut buffer = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(rhs.ncols(), par));
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            par,
            MemStack::new(&mut buffer),
        );
    }
}

/// Reverse Cuthill–McKee order of the graph of a symmetric matrix given by its lower triangle:
/// breadth-first from a low-degree node at the end of a long path (a pseudo-peripheral node),
/// neighbours by increasing degree, the whole order reversed.
fn reverse_cuthill_mckee(lower: &SparseColMat<usize, f64>) -> Vec<usize> {
    let n = lower.nrows();
    let mut adjacency = vec![Vec::new(); n];
    for j in 0..n {
        for &i in lower.symbolic().row_idx_of_col_raw(j) {
            if i != j {
                adjacency[i].push(j);
                adjacency[j].push(i);
            }
        }
    }
    let degree: Vec<usize> = adjacency.iter().map(Vec::len).collect();
    for list in &mut adjacency {
        list.sort_by_key(|&k| degree[k]);
    }
    let mut visited = vec![false; n];
    let mut order = Vec::with_capacity(n);
    while let Some(seed) = (0..n).filter(|&i| !visited[i]).min_by_key(|&i| degree[i]) {
        // Two sweeps: the last node reached from the seed starts the real one.
        let start = *breadth_first(seed, &adjacency, &mut visited.clone())
            .last()
            .unwrap_or(&seed);
        order.extend(breadth_first(start, &adjacency, &mut visited));
    }
    order.reverse();
    order
}

/// Nodes reached from `start` breadth-first, marking them in `visited`.
fn breadth_first(start: usize, adjacency: &[Vec<usize>], visited: &mut [bool]) -> Vec<usize> {
    let mut reached = Vec::new();
    let mut queue = VecDeque::from([start]);
    visited[start] = true;
    while let Some(i) = queue.pop_front() {
        reached.push(i);
        for &k in &adjacency[i] {
            if !visited[k] {
                visited[k] = true;
                queue.push_back(k);
            }
        }
    }
    reached
}
