//! The discrete convolution u_i = Σ_j K(x_i − x_j) t_j of an n × n field with an influence
//! kernel, by FFT on the zero-padded 2n × 2n grid (non-periodic: the padding keeps the
//! circular wrap-around off the n × n window; Liu, Wang & Liu 2000, "DC-FFT").
//!
//! A 2D real transform is a real-to-complex transform of each row (realfft, n + 1 frequencies)
//! followed by complex transforms of each of those n + 1 columns (rustfft). Only the n rows that
//! carry data are transformed forward (a row of zeros, out of contact, is a row of zeros: not
//! transformed), and only the n rows of the window backward. A column's forward transform, its
//! product with the kernel's symbol and its inverse run one after the other while the column
//! sits in the cache, so the spectrum of the whole grid is never stored: between the passes only
//! the row transforms of the n data rows are (n + 1 columns of n values).
//!
//! The columns are transformed at their full length 2n although their rows n..2n are zero. With
//! w_j = exp(−iπ j/n), X_{2k} = FFT_n(x)[k] and X_{2k+1} = FFT_n(x_j w_j)[k] (j < n) would save
//! the zero fill and one radix-2 pass, but the twiddled second half costs more than both: one f32
//! convolution at 128² measured 115 µs that way against 107 µs at full length.
//!
//! The transforms run in a chosen [`Precision`] (f64 or f32); fields and kernels are f64 on both
//! sides. In f32 a transform is about twice as fast (twice the SIMD lanes, half the memory) and
//! a product carries a relative error of about 1e-7 · log₂(2n) of its largest value.

use std::sync::Arc;

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftNum, FftPlanner};

/// The floating-point type the transforms run in: f64 or f32.
pub trait Precision: FftNum + Default + Into<f64> {
    /// The nearest value of this type.
    fn of(value: f64) -> Self;
}

impl Precision for f64 {
    fn of(value: f64) -> Self {
        value
    }
}

impl Precision for f32 {
    fn of(value: f64) -> Self {
        value as f32
    }
}

/// Rows transformed and transposed together: each column then takes 16 consecutive values (two
/// cache lines in f32) per block. Measured, one f32 convolution (medians of 7, thread CPU) at
/// 128² (256²), in the layout before columns were multiplied one by one: blocks of 8 rows in a
/// loop of variable length 111 µs (507 µs), of 16 rows unrolled 104 µs (494 µs), of 32 rows
/// unrolled 102 µs (499 µs); 16 rows of 257 f32 frequencies (33 kB) still fit a level-1 cache.
const ROW_BLOCK: usize = 16;

/// The real spectrum of a kernel even in each offset (or odd in both) on the padded grid: n + 1
/// columns (the row frequencies kx ≤ n) of 2n values (ky).
#[derive(Clone, Debug, PartialEq)]
pub struct Symbol<T = f64>(Vec<T>);

impl<T: Precision> Symbol<T> {
    /// The real symbol of a 2n × 2n kernel in the circulant layout of
    /// [`super::influence::Kernels`] (a full, unpadded 2D transform, in f64; the imaginary parts
    /// are round-off).
    pub fn of_kernel(n: usize, kernel: &[f64]) -> Self {
        let m = 2 * n;
        let rows = RealFftPlanner::<f64>::new().plan_fft_forward(m);
        let columns = FftPlanner::<f64>::new().plan_fft_forward(m);
        let mut spectrum = vec![Complex::default(); (n + 1) * m];
        let mut row_in = vec![0.0; m];
        let mut row_out = vec![Complex::default(); n + 1];
        for (ky, row) in kernel.chunks_exact(m).enumerate() {
            row_in.copy_from_slice(row);
            rows.process(&mut row_in, &mut row_out)
                .expect("row lengths match the plan");
            for (kx, &v) in row_out.iter().enumerate() {
                spectrum[kx * m + ky] = v;
            }
        }
        columns.process(&mut spectrum);
        Self(spectrum.iter().map(|v| T::of(v.re)).collect())
    }

    /// The symbol in another precision (rounded once).
    pub fn to<U: Precision>(&self) -> Symbol<U> {
        Symbol(self.0.iter().map(|&v| U::of(v.into())).collect())
    }

    /// The values, column by column: (kx, ky) at kx · 2n + ky.
    pub fn values(&self) -> &[T] {
        &self.0
    }
}

/// The FFT plans of one grid size: rows and columns of the padded grid, both of length 2n.
struct Plans<T: Precision> {
    rows_forward: Arc<dyn RealToComplex<T>>,
    rows_inverse: Arc<dyn ComplexToReal<T>>,
    columns_forward: Arc<dyn Fft<T>>,
    columns_inverse: Arc<dyn Fft<T>>,
}

/// Work buffers.
struct Buffers<T: Precision> {
    real_row: Vec<T>,
    /// `ROW_BLOCK` rows of n + 1 frequencies.
    block: Vec<Complex<T>>,
    scratch: Vec<Complex<T>>,
    /// Per component, one padded column (2n).
    column: [Vec<Complex<T>>; 2],
}

/// FFT plans and work buffers for one grid size, in precision `T`.
pub struct Convolver<T: Precision = f64> {
    n: usize,
    plans: Plans<T>,
    /// Per component, the row transforms: n + 1 columns of the n data rows (column-major).
    half: [Vec<Complex<T>>; 2],
    buffers: Buffers<T>,
}

impl<T: Precision> Convolver<T> {
    /// Plans for an n × n field (padded to 2n × 2n).
    pub fn new(n: usize) -> Self {
        let m = 2 * n;
        let mut real = RealFftPlanner::<T>::new();
        let mut complex = FftPlanner::<T>::new();
        let plans = Plans {
            rows_forward: real.plan_fft_forward(m),
            rows_inverse: real.plan_fft_inverse(m),
            columns_forward: complex.plan_fft_forward(m),
            columns_inverse: complex.plan_fft_inverse(m),
        };
        let scratch_len = [
            plans.rows_forward.get_scratch_len(),
            plans.rows_inverse.get_scratch_len(),
            plans.columns_forward.get_inplace_scratch_len(),
            plans.columns_inverse.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        Self {
            n,
            plans,
            half: [0, 1].map(|_| vec![Complex::default(); (n + 1) * n]),
            buffers: Buffers {
                real_row: vec![T::zero(); m],
                block: vec![Complex::default(); ROW_BLOCK * (n + 1)],
                scratch: vec![Complex::default(); scratch_len],
                column: [0, 1].map(|_| vec![Complex::default(); m]),
            },
        }
    }

    /// `out = K * load` for a kernel of symbol `symbol` (n × n fields).
    pub fn convolve(&mut self, load: &[f64], symbol: &Symbol<T>, out: &mut [f64]) {
        let m = 2 * self.n;
        self.run([load], [out], |kx, [x, _]| {
            let s = &symbol.0[kx * m..(kx + 1) * m];
            x.iter_mut().zip(s).for_each(|(v, &k)| *v = *v * k);
        });
    }

    /// `(u, v) = (A * x + B * y, B * x + C * y)` for kernels of symbols [A, B, C]: the two
    /// components of a symmetric 2 × 2 convolution, in one pass over the columns.
    pub fn convolve_pair(
        &mut self,
        [x, y]: [&[f64]; 2],
        [a, b, c]: [&Symbol<T>; 3],
        [u, v]: [&mut [f64]; 2],
    ) {
        let m = 2 * self.n;
        self.run([x, y], [u, v], |kx, [x, y]| {
            let range = kx * m..(kx + 1) * m;
            let (a, b, c) = (&a.0[range.clone()], &b.0[range.clone()], &c.0[range]);
            for i in 0..m {
                let (xv, yv) = (x[i], y[i]);
                x[i] = xv * a[i] + yv * b[i];
                y[i] = xv * b[i] + yv * c[i];
            }
        });
    }

    /// The three passes for K components (1 or 2): rows forward, columns (forward,
    /// `multiply(kx, spectra of column kx)` in place, inverse), rows inverse into `outs`.
    fn run<const K: usize>(
        &mut self,
        loads: [&[f64]; K],
        outs: [&mut [f64]; K],
        mut multiply: impl FnMut(usize, [&mut [Complex<T>]; 2]),
    ) {
        let (n, plans, buffers) = (self.n, &self.plans, &mut self.buffers);
        for (load, half) in loads.iter().zip(&mut self.half) {
            buffers.rows_forward(plans, n, load, half);
        }
        for kx in 0..=n {
            buffers.column_product(plans, n, kx, &mut self.half[..K], |spectra| multiply(kx, spectra));
        }
        for (out, half) in outs.into_iter().zip(&mut self.half) {
            buffers.rows_inverse(plans, n, half, out);
        }
    }
}

impl<T: Precision> Buffers<T> {
    /// Row transforms of the n × n `field` (zero-padded to 2n) into `half` (column-major, n
    /// values a column): rows are transformed in blocks and written out column by column,
    /// `ROW_BLOCK` values at a time, so the transposition touches each memory page once per block.
    fn rows_forward(&mut self, plans: &Plans<T>, n: usize, field: &[f64], half: &mut [Complex<T>]) {
        let cols = n + 1;
        for (block, rows) in field.chunks(ROW_BLOCK * n).enumerate() {
            let count = rows.len() / n;
            for (r, row) in rows.chunks_exact(n).enumerate() {
                let spectrum_row = &mut self.block[r * cols..(r + 1) * cols];
                // Rounded and tested for zero in one pass.
                let mut nonzero = false;
                for (t, &v) in self.real_row.iter_mut().zip(row) {
                    *t = T::of(v);
                    nonzero |= v != 0.0;
                }
                if !nonzero {
                    spectrum_row.fill(Complex::default());
                    continue;
                }
                self.real_row[n..].fill(T::zero());
                (plans.rows_forward)
                    .process_with_scratch(&mut self.real_row, spectrum_row, &mut self.scratch)
                    .expect("row lengths match the plan");
            }
            transpose::<T, true>(&mut self.block, half, n, block * ROW_BLOCK, count);
        }
    }

    /// Column `kx` of each half (one a component): zero-padded to 2n, transformed, `multiply`,
    /// transformed back, and its first n values (the window) put back.
    fn column_product(
        &mut self,
        plans: &Plans<T>,
        n: usize,
        kx: usize,
        halves: &mut [Vec<Complex<T>>],
        multiply: impl FnOnce([&mut [Complex<T>]; 2]),
    ) {
        for (half, column) in halves.iter().zip(&mut self.column) {
            column[..n].copy_from_slice(&half[kx * n..(kx + 1) * n]);
            column[n..].fill(Complex::default());
            (plans.columns_forward).process_with_scratch(column, &mut self.scratch);
        }
        let [x, y] = &mut self.column;
        multiply([x, y]);
        for (half, column) in halves.iter_mut().zip(&mut self.column) {
            (plans.columns_inverse).process_with_scratch(column, &mut self.scratch);
            half[kx * n..(kx + 1) * n].copy_from_slice(&column[..n]);
        }
    }

    /// The inverse row transforms of `half` (column-major, n values a column) into the n × n
    /// window `out`, scaled by 1/(2n)² (the transforms are unnormalised).
    fn rows_inverse(&mut self, plans: &Plans<T>, n: usize, half: &mut [Complex<T>], out: &mut [f64]) {
        let cols = n + 1;
        let scale = 1.0 / (4 * n * n) as f64;
        let zero = T::zero();
        for (block, out) in out.chunks_mut(ROW_BLOCK * n).enumerate() {
            transpose::<T, false>(&mut self.block, half, n, block * ROW_BLOCK, out.len() / n);
            for (r, out_row) in out.chunks_exact_mut(n).enumerate() {
                let row = &mut self.block[r * cols..(r + 1) * cols];
                // The zero and Nyquist frequencies of a real row are real: drop rounding residue.
                row[0].im = zero;
                row[n].im = zero;
                (plans.rows_inverse)
                    .process_with_scratch(row, &mut self.real_row, &mut self.scratch)
                    .expect("row lengths match the plan");
                for (o, &v) in out_row.iter_mut().zip(&self.real_row[..n]) {
                    let v: f64 = v.into();
                    *o = v * scale;
                }
            }
        }
    }
}

/// The transposition between `count` rows of n + 1 frequencies in `block` (rows `first..first +
/// count` of the window) and their places in the columns of `half` (n values a column): rows
/// into columns when `TO_COLUMNS`, else columns into rows.
fn transpose<T: Copy, const TO_COLUMNS: bool>(
    block: &mut [Complex<T>],
    half: &mut [Complex<T>],
    n: usize,
    first: usize,
    count: usize,
) {
    // A full block has a constant row count, so that the inner loop unrolls.
    if count == ROW_BLOCK {
        transpose_rows::<T, TO_COLUMNS, ROW_BLOCK>(block, half, n, first);
    } else {
        for r in 0..count {
            transpose_rows::<T, TO_COLUMNS, 1>(&mut block[r * (n + 1)..], half, n, first + r);
        }
    }
}

/// [`transpose`] of `R` rows.
#[inline(always)]
fn transpose_rows<T: Copy, const TO_COLUMNS: bool, const R: usize>(
    block: &mut [Complex<T>],
    half: &mut [Complex<T>],
    n: usize,
    first: usize,
) {
    let cols = n + 1;
    let mut rows = block[..R * cols].chunks_exact_mut(cols);
    let rows: [&mut [Complex<T>]; R] = std::array::from_fn(|_| rows.next().expect("R rows"));
    for (kx, column) in half.chunks_exact_mut(n).enumerate() {
        let column: &mut [Complex<T>; R] = (&mut column[first..first + R]).try_into().expect("R rows");
        for r in 0..R {
            if TO_COLUMNS {
                column[r] = rows[r][kx];
            } else {
                rows[r][kx] = column[r];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `kernel_of(dx, dy)` written in the circulant layout of a 2n × 2n kernel.
    fn circulant(n: usize, kernel_of: impl Fn(isize, isize) -> f64) -> Vec<f64> {
        let m = 2 * n;
        let wrap = |i: usize| {
            if i < n {
                i as isize
            } else {
                i as isize - m as isize
            }
        };
        let mut kernel = vec![0.0; m * m];
        for b in 0..m {
            for a in 0..m {
                if a != n && b != n {
                    kernel[b * m + a] = kernel_of(wrap(a), wrap(b));
                }
            }
        }
        kernel
    }

    /// Σ_j K(x_i − x_j) f_j by the direct sum.
    fn direct(n: usize, kernel_of: &impl Fn(isize, isize) -> f64, field: &[f64], i: usize) -> f64 {
        let (ix, iy) = ((i % n) as isize, (i / n) as isize);
        (0..n * n)
            .map(|j| kernel_of(ix - (j % n) as isize, iy - (j / n) as isize) * field[j])
            .sum()
    }

    #[test]
    fn fft_convolution_equals_the_direct_sum() {
        // Requirement: the FFT product equals the direct sum to round-off (1e-12 relative in f64)
        // for the kinds of kernel the BEM has: even in each offset (Boussinesq, Cerruti xx, yy),
        // odd in both (Cerruti xy); one component and a symmetric pair.
        let n = 7;
        let even = |dx: isize, dy: isize| 1.0 / (1.0 + (dx * dx + 3 * dy * dy) as f64);
        let odd = |dx: isize, dy: isize| (dx * dy) as f64 / (1.0 + (dx * dx + dy * dy) as f64).powf(1.5);
        let other = |dx: isize, dy: isize| 2.0 / (2.0 + (2 * dx * dx + dy * dy) as f64);
        let [a, b, c] =
            [circulant(n, even), circulant(n, odd), circulant(n, other)].map(|k| Symbol::of_kernel(n, &k));
        let x: Vec<f64> = (0..n * n).map(|k| ((k * 7) % 11) as f64 - 5.0).collect();
        let y: Vec<f64> = (0..n * n).map(|k| ((k * 5) % 13) as f64 - 6.0).collect();
        let mut conv = Convolver::<f64>::new(n);
        let close = |value: f64, expected: f64| (value - expected).abs() < 1e-12 * (1.0 + expected.abs());
        let mut u = vec![0.0; n * n];
        conv.convolve(&x, &a, &mut u);
        for (i, &ui) in u.iter().enumerate() {
            let expected = direct(n, &even, &x, i);
            assert!(close(ui, expected), "{i}: {ui} vs {expected}");
        }
        let mut v = vec![0.0; n * n];
        conv.convolve_pair([&x, &y], [&a, &b, &c], [&mut u, &mut v]);
        for i in 0..n * n {
            let eu = direct(n, &even, &x, i) + direct(n, &odd, &y, i);
            let ev = direct(n, &odd, &x, i) + direct(n, &other, &y, i);
            assert!(
                close(u[i], eu) && close(v[i], ev),
                "{i}: {} {} vs {eu} {ev}",
                u[i],
                v[i]
            );
        }
    }
}
