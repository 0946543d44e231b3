//! The half-space compliance of the panel grid as a [`Compliance`] of the contact engine: the
//! Boussinesq (normal, one component) or Cerruti (tangential, two components) influence
//! coefficients applied by zero-padded FFT ([`super::convolution`]).
//!
//! Points are the n² panels (index k = iy·n + ix), each of weight h² (the multipliers are panel
//! pressures and tractions, their resultant Σ h² p). A product costs four (normal: two) real 2D
//! transforms of the 2n × 2n padded grid; a column of the kernel costs n² multiply-adds, so a
//! product after a few changed panels adds those columns instead.
//!
//! The transforms run in the precision `T` ([`Precision`]: f64, or f32 at about half the cost);
//! the symbols are computed in f64 and rounded once, the largest eigenvalue is taken from them in
//! f64, and kernel columns are added in f64. Corrections ([`Compliance::apply_correction`]) may
//! run in f32 while the products run in f64 ([`FftCompliance::with_f32_corrections`]).

use spherecontact_contact::Compliance;

use super::convolution::{Convolver, Precision, Symbol};
use super::grid::Grid;
use super::influence::{Kernels, PairCompliance};

/// Kernel columns cheaper than one FFT product (measured at 64²–256²: a product costs about as
/// much as 20–40 columns).
const COLUMN_BUDGET: usize = 16;

/// A half-space compliance on a panel grid, applied by FFT in precision `T`.
pub struct FftCompliance<T: Precision = f64> {
    grid: Grid,
    /// The kernels in the circulant layout: zz alone, or xx, xy (= yx), yy; the block of
    /// components (c_i, c_j) is kernel c_i + c_j.
    kernels: Vec<Vec<f64>>,
    products: Products<T>,
    /// Corrections in f32 ([`FftCompliance::with_f32_corrections`]); `None`: in `T`.
    corrections: Option<Products<f32>>,
    weights: Vec<f64>,
    largest: f64,
}

/// Products by FFT in one precision: the plans and the kernels' symbols.
struct Products<T: Precision> {
    convolver: Convolver<T>,
    /// The kernels' symbols (spectra), real: every kernel is even in each offset, or (xy) odd in
    /// both.
    symbols: Vec<Symbol<T>>,
}

impl<T: Precision> Products<T> {
    /// Plans for `grid` and the symbols, rounded once from f64.
    fn new(grid: &Grid, symbols: &[Symbol<f64>]) -> Self {
        Self {
            convolver: Convolver::<T>::new(grid.n),
            symbols: symbols.iter().map(Symbol::to).collect(),
        }
    }

    /// `out = C load` (one component, or two: x then y).
    fn apply(&mut self, load: &[f64], out: &mut [f64]) {
        let s = &self.symbols;
        if s.len() == 1 {
            self.convolver.convolve(load, &s[0], out);
            return;
        }
        let len = load.len() / 2;
        let (x, y) = load.split_at(len);
        let (u, v) = out.split_at_mut(len);
        // The yx block is the xy block (the Cerruti kernels are symmetric).
        self.convolver
            .convolve_pair([x, y], [&s[0], &s[1], &s[2]], [u, v]);
    }
}

impl<T: Precision> FftCompliance<T> {
    /// The Boussinesq compliance of `grid` (one component).
    pub fn normal(grid: &Grid, compliance: &PairCompliance) -> Self {
        Self::of(grid, vec![Kernels::normal(grid, compliance)])
    }

    /// The Cerruti compliance of `grid` (two components, x and y).
    pub fn tangential(grid: &Grid, compliance: &PairCompliance) -> Self {
        let t = Kernels::tangential(grid, compliance);
        Self::of(grid, vec![t.xx, t.xy, t.yy])
    }

    fn of(grid: &Grid, kernels: Vec<Vec<f64>>) -> Self {
        let symbols: Vec<Symbol<f64>> = kernels.iter().map(|k| Symbol::of_kernel(grid.n, k)).collect();
        // The symbol at each frequency is real, and the largest eigenvalue of C is the largest
        // over the frequencies of the symbol's (1×1, or symmetric 2×2 [[a, b], [b, c]]) largest
        // eigenvalue, (a+c)/2 + √(((a−c)/2)² + b²) — the padded circulant bounds the window's
        // operator.
        let largest = if symbols.len() == 1 {
            symbols[0].values().iter().copied().fold(0.0, f64::max)
        } else {
            let (a, b, c) = (symbols[0].values(), symbols[1].values(), symbols[2].values());
            (0..a.len())
                .map(|f| 0.5 * (a[f] + c[f]) + (0.25 * (a[f] - c[f]).powi(2) + b[f] * b[f]).sqrt())
                .fold(0.0, f64::max)
        };
        Self {
            grid: *grid,
            products: Products::new(grid, &symbols),
            corrections: None,
            kernels,
            weights: vec![grid.panel_area(); grid.len()],
            largest,
        }
    }

    /// This compliance with its corrections ([`Compliance::apply_correction`]) in f32: about half
    /// the cost of a product, with a relative error of about 1e-7 · log₂(2n) of the correction.
    /// An iterative solver then forms its answer exactly before it stops, so the answer is that
    /// of `T`.
    pub fn with_f32_corrections(mut self) -> Self {
        let symbols: Vec<Symbol<f64>> = self.products.symbols.iter().map(Symbol::to).collect();
        self.corrections = Some(Products::new(&self.grid, &symbols));
        self
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }
}

impl<T: Precision> Compliance for FftCompliance<T> {
    fn points(&self) -> usize {
        self.grid.len()
    }

    fn components(&self) -> usize {
        if self.kernels.len() == 1 {
            1
        } else {
            2
        }
    }

    fn weights(&self) -> &[f64] {
        &self.weights
    }

    fn apply(&mut self, load: &[f64], out: &mut [f64]) {
        self.products.apply(load, out);
    }

    fn apply_correction(&mut self, load: &[f64], out: &mut [f64]) {
        match &mut self.corrections {
            Some(corrections) => corrections.apply(load, out),
            None => self.products.apply(load, out),
        }
    }

    fn rough_corrections(&self) -> bool {
        self.corrections.is_some()
    }

    fn largest_eigenvalue(&self) -> f64 {
        self.largest
    }

    fn column_budget(&self) -> usize {
        COLUMN_BUDGET
    }

    fn add_columns(&mut self, changes: &[(usize, f64)], out: &mut [f64]) {
        let (n, len) = (self.grid.n, self.grid.len());
        let k = self.components();
        let side = 2 * n;
        for &(j, delta) in changes {
            let (cj, panel) = (j / len, j % len);
            let (jx, jy) = (panel % n, panel / n);
            for ci in 0..k {
                let kernel = &self.kernels[ci + cj];
                let out = &mut out[ci * len..(ci + 1) * len];
                for iy in 0..n {
                    // Offset (ix − jx, iy − jy) wraps into the circulant layout: negative x offsets
                    // (ix < jx) at the end of the kernel's row, the others from its start; two
                    // contiguous runs.
                    let row = &kernel[(iy + side - jy) % side * side..][..side];
                    let (before, after) = out[iy * n..(iy + 1) * n].split_at_mut(jx);
                    for (o, k) in before.iter_mut().zip(&row[side - jx..]) {
                        *o += k * delta;
                    }
                    for (o, k) in after.iter_mut().zip(row) {
                        *o += k * delta;
                    }
                }
            }
        }
    }
}
