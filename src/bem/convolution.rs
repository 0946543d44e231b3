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
//! **Threads.** The rows are cut into bands and the columns into ranges, one a worker (rayon's
//! pool, as many workers as cores): the row passes run band by band, the column pass range by
//! range, each worker with its own buffers. Every row and column is transformed alike whatever
//! the worker, so the result does not depend on the number of threads.
//!
//! The transforms run in a chosen [`Precision`] (f64 or f32); fields and kernels are f64 on both
//! sides. In f32 a transform is about twice as fast (twice the SIMD lanes, half the memory) and
//! a product carries a relative error of about 1e-7 · log₂(2n) of its largest value.

use std::sync::Arc;

use rayon::prelude::*;
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

/// Rows transformed and transposed together.
const ROW_BLOCK: usize = 8;

/// The most workers a convolver uses (the machines this runs on have 2–8 cores).
const MAX_WORKERS: usize = 8;

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

/// The product of the spectra of column kx (one or two components) with the symbols, in place.
type Multiply<'a, T> = dyn Fn(usize, [&mut [Complex<T>]; 2]) + Sync + 'a;

/// The FFT plans of one grid size: rows and columns of the padded grid, both of length 2n.
struct Plans<T: Precision> {
    rows_forward: Arc<dyn RealToComplex<T>>,
    rows_inverse: Arc<dyn ComplexToReal<T>>,
    columns_forward: Arc<dyn Fft<T>>,
    columns_inverse: Arc<dyn Fft<T>>,
}

/// A band of rows [first, first + rows) of the n × n window: per component, the row transforms
/// as n + 1 columns of `rows` values (column-major).
struct Band<T: Precision> {
    first: usize,
    rows: usize,
    half: [Vec<Complex<T>>; 2],
}

/// One worker's buffers.
struct Worker<T: Precision> {
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
    bands: Vec<Band<T>>,
    workers: Vec<Worker<T>>,
}

impl<T: Precision> Convolver<T> {
    /// Plans for an n × n field (padded to 2n × 2n), with as many workers as rayon's pool has
    /// threads (at most [`MAX_WORKERS`], at most n).
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
        let count = rayon::current_num_threads().clamp(1, MAX_WORKERS).min(n.max(1));
        let bands = split(n, count)
            .into_iter()
            .map(|(first, end)| Band {
                first,
                rows: end - first,
                half: [0, 1].map(|_| vec![Complex::default(); (n + 1) * (end - first)]),
            })
            .collect();
        let workers = (0..count)
            .map(|_| Worker {
                real_row: vec![T::zero(); m],
                block: vec![Complex::default(); ROW_BLOCK * (n + 1)],
                scratch: vec![Complex::default(); scratch_len],
                column: [0, 1].map(|_| vec![Complex::default(); m]),
            })
            .collect();
        Self {
            n,
            plans,
            bands,
            workers,
        }
    }

    /// `out = K * load` for a kernel of symbol `symbol` (n × n fields).
    pub fn convolve(&mut self, load: &[f64], symbol: &Symbol<T>, out: &mut [f64]) {
        let m = 2 * self.n;
        self.run(&[load], [out], &|kx, [x, _]| {
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
        self.run(&[x, y], [u, v], &|kx, [x, y]| {
            let range = kx * m..(kx + 1) * m;
            let (a, b, c) = (&a.0[range.clone()], &b.0[range.clone()], &c.0[range]);
            for i in 0..m {
                let (xv, yv) = (x[i], y[i]);
                x[i] = xv * a[i] + yv * b[i];
                y[i] = xv * b[i] + yv * c[i];
            }
        });
    }

    /// The three passes for `loads.len()` components (1 or 2): rows forward, columns (forward,
    /// `multiply(kx, spectra of column kx)`, inverse), rows inverse into `outs`.
    fn run<const K: usize>(&mut self, loads: &[&[f64]], outs: [&mut [f64]; K], multiply: &Multiply<'_, T>) {
        let n = self.n;
        let k = loads.len();
        let plans = &self.plans;
        (self.bands.par_iter_mut())
            .zip(self.workers.par_iter_mut())
            .for_each(|(band, worker)| {
                for (c, load) in loads.iter().enumerate() {
                    let rows = &load[band.first * n..(band.first + band.rows) * n];
                    worker.rows_forward(plans, n, rows, &mut band.half[c]);
                }
            });
        self.columns(k, multiply);
        let plans = &self.plans;
        let mut outs: Vec<Vec<&mut [f64]>> = outs
            .into_iter()
            .map(|out| split_rows(out, &self.bands, n))
            .collect();
        let mut pieces: Vec<Vec<&mut [f64]>> = self.bands.iter().map(|_| Vec::new()).collect();
        for out in &mut outs {
            for (b, piece) in out.drain(..).enumerate() {
                pieces[b].push(piece);
            }
        }
        (self.bands.par_iter())
            .zip(self.workers.par_iter_mut())
            .zip(pieces)
            .for_each(|((band, worker), outs)| {
                for (c, out) in outs.into_iter().enumerate() {
                    worker.rows_inverse(plans, n, &band.half[c], out);
                }
            });
    }

    /// The column pass over the first `k` components, the columns cut into one range a worker.
    fn columns(&mut self, k: usize, multiply: &Multiply<'_, T>) {
        let (n, plans) = (self.n, &self.plans);
        let ranges = split(n + 1, self.workers.len());
        let rows: Vec<usize> = self.bands.iter().map(|b| b.rows).collect();
        // Per worker, the pieces of every band's halves in its range: [band · k + component].
        let mut pieces: Vec<Vec<&mut [Complex<T>]>> = ranges.iter().map(|_| Vec::new()).collect();
        for band in &mut self.bands {
            for half in band.half.iter_mut().take(k) {
                let mut rest: &mut [Complex<T>] = half;
                for (w, &(start, end)) in ranges.iter().enumerate() {
                    let (piece, tail) = rest.split_at_mut((end - start) * band.rows);
                    pieces[w].push(piece);
                    rest = tail;
                }
            }
        }
        (self.workers.par_iter_mut()).zip(pieces).zip(ranges).for_each(
            |((worker, mut pieces), (start, end))| {
                for kx in start..end {
                    worker.column_product(plans, n, kx - start, &rows, k, &mut pieces, |spectra| {
                        multiply(kx, spectra)
                    });
                }
            },
        );
    }
}

impl<T: Precision> Worker<T> {
    /// Row transforms of `rows` (whole rows of n values, zero-padded to 2n) into `half`
    /// (column-major, as many values a column as rows): rows are transformed in blocks and
    /// written out column by column, `ROW_BLOCK` values at a time, so the transposition touches
    /// each memory page once per block.
    fn rows_forward(&mut self, plans: &Plans<T>, n: usize, rows: &[f64], half: &mut [Complex<T>]) {
        let (cols, height) = (n + 1, rows.len() / n);
        for (block, rows) in rows.chunks(ROW_BLOCK * n).enumerate() {
            let count = rows.len() / n;
            for (r, row) in rows.chunks_exact(n).enumerate() {
                let spectrum_row = &mut self.block[r * cols..(r + 1) * cols];
                if row.iter().all(|&v| v == 0.0) {
                    spectrum_row.fill(Complex::default());
                    continue;
                }
                for (t, &v) in self.real_row.iter_mut().zip(row) {
                    *t = T::of(v);
                }
                self.real_row[n..].fill(T::zero());
                (plans.rows_forward)
                    .process_with_scratch(&mut self.real_row, spectrum_row, &mut self.scratch)
                    .expect("row lengths match the plan");
            }
            let first = block * ROW_BLOCK;
            for (kx, column) in half.chunks_exact_mut(height).enumerate() {
                for (r, value) in column[first..first + count].iter_mut().enumerate() {
                    *value = self.block[r * cols + kx];
                }
            }
        }
    }

    /// Column `j` of the pieces (`pieces[band · k + c]`, `rows[band]` values a column) for each
    /// of `k` components: gathered and zero-padded to 2n, transformed, `multiply`, transformed
    /// back, and its first n values (the window) scattered back.
    #[allow(clippy::too_many_arguments)]
    fn column_product(
        &mut self,
        plans: &Plans<T>,
        n: usize,
        j: usize,
        rows: &[usize],
        k: usize,
        pieces: &mut [&mut [Complex<T>]],
        multiply: impl FnOnce([&mut [Complex<T>]; 2]),
    ) {
        for c in 0..k {
            let column = &mut self.column[c];
            let mut at = 0;
            for (b, &height) in rows.iter().enumerate() {
                column[at..at + height].copy_from_slice(&pieces[b * k + c][j * height..(j + 1) * height]);
                at += height;
            }
            column[n..].fill(Complex::default());
            (plans.columns_forward).process_with_scratch(column, &mut self.scratch);
        }
        let [x, y] = &mut self.column;
        multiply([x, y]);
        for c in 0..k {
            let column = &mut self.column[c];
            (plans.columns_inverse).process_with_scratch(column, &mut self.scratch);
            let mut at = 0;
            for (b, &height) in rows.iter().enumerate() {
                pieces[b * k + c][j * height..(j + 1) * height].copy_from_slice(&column[at..at + height]);
                at += height;
            }
        }
    }

    /// The inverse row transforms of `half` (column-major, as many values a column as `out` has
    /// rows) into `out` (whole rows of n values), scaled by 1/(2n)² (the transforms are
    /// unnormalised).
    fn rows_inverse(&mut self, plans: &Plans<T>, n: usize, half: &[Complex<T>], out: &mut [f64]) {
        let (cols, height) = (n + 1, out.len() / n);
        let scale = 1.0 / (4 * n * n) as f64;
        let zero = T::zero();
        for (block, out) in out.chunks_mut(ROW_BLOCK * n).enumerate() {
            let (first, count) = (block * ROW_BLOCK, out.len() / n);
            for (kx, column) in half.chunks_exact(height).enumerate() {
                for (r, value) in column[first..first + count].iter().enumerate() {
                    self.block[r * cols + kx] = *value;
                }
            }
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

/// [0, len) cut into `parts` consecutive ranges of near-equal length.
fn split(len: usize, parts: usize) -> Vec<(usize, usize)> {
    (0..parts)
        .map(|p| (p * len / parts, (p + 1) * len / parts))
        .collect()
}

/// The rows of `field` (n values a row) cut as the bands cut the window.
fn split_rows<'a, T: Precision>(field: &'a mut [f64], bands: &[Band<T>], n: usize) -> Vec<&'a mut [f64]> {
    let mut rest = field;
    bands
        .iter()
        .map(|band| {
            let (piece, tail) = std::mem::take(&mut rest).split_at_mut(band.rows * n);
            rest = tail;
            piece
        })
        .collect()
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
        // odd in both (Cerruti xy); one component and a symmetric pair; on a grid whose rows
        // and columns do not divide evenly among the workers.
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

    #[test]
    fn the_product_does_not_depend_on_the_number_of_workers() {
        // Requirement: bands and ranges change which thread transforms a row or a column, never
        // how: one worker and three give the same bits.
        let n = 10;
        let kernel = circulant(n, |dx, dy| 1.0 / (1.0 + (dx * dx + dy * dy) as f64).sqrt());
        let symbol = Symbol::<f32>::of_kernel(n, &kernel);
        let load: Vec<f64> = (0..n * n).map(|k| ((k * 7) % 11) as f64).collect();
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a pool");
            pool.install(|| {
                let mut conv = Convolver::<f32>::new(n);
                let mut out = vec![0.0; n * n];
                conv.convolve(&load, &symbol, &mut out);
                (conv.workers.len(), out)
            })
        };
        let (one, three) = (run(1), run(3));
        assert_eq!((one.0, three.0), (1, 3));
        assert_eq!(one.1, three.1);
    }
}
