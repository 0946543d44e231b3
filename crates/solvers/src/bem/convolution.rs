//! The discrete convolution u_i = Σ_j K(x_i − x_j) t_j of an n × n field with an influence
//! kernel, by FFT on the zero-padded 2n × 2n grid (non-periodic: the padding keeps the
//! circular wrap-around off the n × n window; Liu, Wang & Liu 2000, "DC-FFT").
//!
//! A 2D real transform is a real-to-complex transform of each row (realfft, n + 1 frequencies)
//! followed by complex transforms of each of those n + 1 columns (rustfft). Only the n rows that
//! carry data are transformed forward (a row of zeros, out of contact, is a row of zeros: not
//! transformed), and only the n rows of the window backward. A column's forward transform, its
//! product with the kernel's symbol and its inverse run one after the other while the column
//! sits in the cache, so the spectrum of the whole grid is never stored: only the row transforms
//! of the n data rows are, and the n window rows of each transformed column (n + 1 columns of n
//! values each).
//!
//! The columns are transformed at their full length 2n although their rows n..2n are zero. With
//! w_j = exp(−iπ j/n), X_{2k} = FFT_n(x)[k] and X_{2k+1} = FFT_n(x_j w_j)[k] (j < n) would save
//! the zero fill and one radix-2 pass, but the twiddled second half costs more than both: one f32
//! convolution at 128² measured 115 µs that way against 107 µs at full length.
//!
//! **Threads.** Each pass splits into independent parts (blocks of rows, ranges of columns) run
//! by the process's team ([`spherecontact_model::team`]: the caller and, on a machine of two cores or more, one
//! worker that spins between passes). The row transforms are kept block by block, kx major within
//! a block, so that a part writes one contiguous piece; the column pass writes its columns apart
//! from them. A row or column is transformed by the same code whichever thread takes it, so a
//! product is the same, bit for bit, on any team. Measured on the paper path at 128² (two cores,
//! `examples/bem_timing.rs`, medians of 5 side by side): 1.66 s wall on two threads (3.19 s CPU,
//! the worker's spinning included) against 2.14 s on one.
//!
//! The plans are rustfft's and realfft's, built by the workspace crate `fft-plans`
//! (`crates/fft-plans`): their planners are monomorphised there once, not in this library.
//!
//! The transforms run in a chosen [`Precision`] (f64 or f32); fields and kernels are f64 on both
//! sides. In f32 a transform is about twice as fast (twice the SIMD lanes, half the memory) and
//! a product carries a relative error of about 1e-7 · log₂(2n) of its largest value.

use std::ops::Range;

use fft_plans::{Complex, Planned, Plans};

use spherecontact_model::team::{self, Team};

/// The floating-point type the transforms run in: f64 or f32.
pub trait Precision: Planned + Default + Into<f64> {
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

/// Rows transformed and transposed together, and the unit of the row passes' parts: each column
/// takes 16 consecutive values (two cache lines in f32) from a block. Measured, one f32
/// convolution (medians of 7, thread CPU) at 128² (256²), in the layout before columns were
/// multiplied one by one: blocks of 8 rows in a loop of variable length 111 µs (507 µs), of 16
/// rows unrolled 104 µs (494 µs), of 32 rows unrolled 102 µs (499 µs); 16 rows of 257 f32
/// frequencies (33 kB) still fit a level-1 cache.
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
        let plans = f64::plans(m);
        let (rows, columns) = (plans.real_forward, plans.forward);
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
    /// Per component, the row transforms of the n data rows, block by block: block b holds rows
    /// `ROW_BLOCK`·b onwards as n + 1 columns of `ROW_BLOCK` values (kx major).
    rows: [Vec<Complex<T>>; 2],
    /// Per component, the columns after the column pass: n + 1 columns of the n window rows
    /// (column-major).
    columns: [Vec<Complex<T>>; 2],
    /// Work buffers, one set a thread of the team.
    buffers: Vec<Buffers<T>>,
}

impl<T: Precision> Convolver<T> {
    /// Plans for an n × n field (padded to 2n × 2n).
    pub fn new(n: usize) -> Self {
        let m = 2 * n;
        // Rows and columns of the padded grid are both of length 2n: one set of plans.
        let plans = T::plans(m);
        let blocks = n.div_ceil(ROW_BLOCK);
        Self {
            n,
            rows: [0, 1].map(|_| vec![Complex::default(); blocks * ROW_BLOCK * (n + 1)]),
            columns: [0, 1].map(|_| vec![Complex::default(); (n + 1) * n]),
            buffers: vec![Buffers::new(&plans, n)],
            plans,
        }
    }

    /// `out = K * load` for a kernel of symbol `symbol` (n × n fields).
    pub fn convolve(&mut self, load: &[f64], symbol: &Symbol<T>, out: &mut [f64]) {
        team::with_team(|team| self.convolve_on(team, load, symbol, out));
    }

    /// `(u, v) = (A * x + B * y, B * x + C * y)` for kernels of symbols [A, B, C]: the two
    /// components of a symmetric 2 × 2 convolution, in one pass over the columns.
    pub fn convolve_pair(&mut self, loads: [&[f64]; 2], symbols: [&Symbol<T>; 3], outs: [&mut [f64]; 2]) {
        team::with_team(|team| self.convolve_pair_on(team, loads, symbols, outs));
    }

    /// [`Convolver::convolve`] on `team`.
    fn convolve_on(&mut self, team: &Team, load: &[f64], symbol: &Symbol<T>, out: &mut [f64]) {
        let m = 2 * self.n;
        self.run(team, [load], [out], |kx, [x, _]| {
            let s = &symbol.0[kx * m..(kx + 1) * m];
            x.iter_mut().zip(s).for_each(|(v, &k)| *v = *v * k);
        });
    }

    /// [`Convolver::convolve_pair`] on `team`.
    fn convolve_pair_on(
        &mut self,
        team: &Team,
        [x, y]: [&[f64]; 2],
        [a, b, c]: [&Symbol<T>; 3],
        [u, v]: [&mut [f64]; 2],
    ) {
        let m = 2 * self.n;
        self.run(team, [x, y], [u, v], |kx, [x, y]| {
            let range = kx * m..(kx + 1) * m;
            let (a, b, c) = (&a.0[range.clone()], &b.0[range.clone()], &c.0[range]);
            for i in 0..m {
                let (xv, yv) = (x[i], y[i]);
                x[i] = xv * a[i] + yv * b[i];
                y[i] = xv * b[i] + yv * c[i];
            }
        });
    }

    /// The three passes for K components (1 or 2), each spread over `team`: rows forward (blocks
    /// of rows), columns (ranges of kx: forward, `multiply(kx, spectra of column kx)` in place,
    /// inverse), rows inverse into `outs` (blocks of rows). The parts of a pass are independent,
    /// and each row and column is transformed by the same code on any thread: the product is the
    /// same, bit for bit, on any team.
    fn run<const K: usize>(
        &mut self,
        team: &Team,
        loads: [&[f64]; K],
        outs: [&mut [f64]; K],
        multiply: impl Fn(usize, [&mut [Complex<T>]; 2]) + Sync,
    ) {
        let (n, plans) = (self.n, &self.plans);
        let blocks = n.div_ceil(ROW_BLOCK);
        let threads = team.threads();
        while self.buffers.len() < threads {
            self.buffers.push(Buffers::new(plans, n));
        }
        let cut: Vec<_> = team::ranges(blocks, threads).collect();
        let rows = self.rows[..K].iter_mut().map(|r| &mut r[..]);
        let mut pieces = split(&mut self.buffers, rows, ROW_BLOCK * (n + 1), &cut);
        team.run(&mut pieces, |i, (buffers, rows)| {
            for (rows, load) in rows.iter_mut().zip(loads) {
                buffers.rows_forward(plans, n, load, rows, cut[i].start);
            }
        });
        let rows = &self.rows[..K];
        let cut: Vec<_> = team::ranges(n + 1, threads).collect();
        let columns = self.columns[..K].iter_mut().map(|c| &mut c[..]);
        let mut pieces = split(&mut self.buffers, columns, n, &cut);
        team.run(&mut pieces, |i, (buffers, columns)| {
            for kx in cut[i].clone() {
                let local = kx - cut[i].start;
                buffers.column_product(plans, n, [kx, local], rows, columns, |s| multiply(kx, s));
            }
        });
        let columns = &self.columns[..K];
        let cut: Vec<_> = team::ranges(blocks, threads).collect();
        let mut pieces = split(&mut self.buffers, outs, ROW_BLOCK * n, &cut);
        team.run(&mut pieces, |i, (buffers, outs)| {
            for (out, columns) in outs.iter_mut().zip(columns) {
                buffers.rows_inverse(plans, n, columns, out, cut[i].start * ROW_BLOCK);
            }
        });
    }
}

/// The parts of a pass: part i has a set of `buffers` and, of each of `slices`, the values of the
/// units `cut[i]` (`unit` values a unit; the last piece ends with its slice).
fn split<'a, B, X>(
    buffers: &'a mut [B],
    slices: impl IntoIterator<Item = &'a mut [X]>,
    unit: usize,
    cut: &[Range<usize>],
) -> Vec<(&'a mut B, Vec<&'a mut [X]>)> {
    let mut parts: Vec<_> = buffers
        .iter_mut()
        .zip(cut)
        .map(|(b, _)| (b, Vec::new()))
        .collect();
    for mut rest in slices {
        let (total, mut done) = (rest.len(), 0);
        for ((_, pieces), range) in parts.iter_mut().zip(cut) {
            let end = (range.end * unit).min(total);
            let (piece, tail) = std::mem::take(&mut rest).split_at_mut(end - done);
            pieces.push(piece);
            (rest, done) = (tail, end);
        }
    }
    parts
}

impl<T: Precision> Buffers<T> {
    fn new(plans: &Plans<T>, n: usize) -> Self {
        let scratch_len = [
            plans.real_forward.get_scratch_len(),
            plans.real_inverse.get_scratch_len(),
            plans.forward.get_inplace_scratch_len(),
            plans.inverse.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        Self {
            real_row: vec![T::zero(); 2 * n],
            block: vec![Complex::default(); ROW_BLOCK * (n + 1)],
            scratch: vec![Complex::default(); scratch_len],
            column: [0, 1].map(|_| vec![Complex::default(); 2 * n]),
        }
    }

    /// Row transforms of the n × n `field` (zero-padded to 2n) into the row blocks `rows`, the
    /// first of them block `first_block`: rows are transformed into `block` and written out kx
    /// major, `ROW_BLOCK` values a column, so that the column pass reads runs of them.
    fn rows_forward(
        &mut self,
        plans: &Plans<T>,
        n: usize,
        field: &[f64],
        rows: &mut [Complex<T>],
        first_block: usize,
    ) {
        let cols = n + 1;
        for (b, out) in rows.chunks_exact_mut(ROW_BLOCK * cols).enumerate() {
            let first = (first_block + b) * ROW_BLOCK;
            let count = ROW_BLOCK.min(n - first);
            for (r, row) in field[first * n..(first + count) * n].chunks_exact(n).enumerate() {
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
                (plans.real_forward)
                    .process_with_scratch(&mut self.real_row, spectrum_row, &mut self.scratch)
                    .expect("row lengths match the plan");
            }
            to_columns(&self.block, out, cols, count);
        }
    }

    /// Column kx (`local` within `columns`, the pieces of the columns of a range of kx, one a
    /// component) from the row blocks `rows` of each component: zero-padded to 2n, transformed,
    /// `multiply`, transformed back, and its first n values (the window) put in `columns`.
    fn column_product(
        &mut self,
        plans: &Plans<T>,
        n: usize,
        [kx, local]: [usize; 2],
        rows: &[Vec<Complex<T>>],
        columns: &mut [&mut [Complex<T>]],
        multiply: impl FnOnce([&mut [Complex<T>]; 2]),
    ) {
        for (rows, column) in rows.iter().zip(&mut self.column) {
            for (b, block) in rows.chunks_exact(ROW_BLOCK * (n + 1)).enumerate() {
                let first = b * ROW_BLOCK;
                let count = ROW_BLOCK.min(n - first);
                column[first..first + count].copy_from_slice(&block[kx * ROW_BLOCK..][..count]);
            }
            column[n..].fill(Complex::default());
            (plans.forward).process_with_scratch(column, &mut self.scratch);
        }
        let [x, y] = &mut self.column;
        multiply([x, y]);
        for (out, column) in columns.iter_mut().zip(&mut self.column) {
            (plans.inverse).process_with_scratch(column, &mut self.scratch);
            out[local * n..(local + 1) * n].copy_from_slice(&column[..n]);
        }
    }

    /// The inverse row transforms of `columns` (column-major, n values a column) into the rows
    /// of the window from `first` on (`out`), scaled by 1/(2n)² (the transforms are unnormalised).
    fn rows_inverse(
        &mut self,
        plans: &Plans<T>,
        n: usize,
        columns: &[Complex<T>],
        out: &mut [f64],
        first: usize,
    ) {
        let cols = n + 1;
        let scale = 1.0 / (4 * n * n) as f64;
        let zero = T::zero();
        for (b, out) in out.chunks_mut(ROW_BLOCK * n).enumerate() {
            from_columns(columns, &mut self.block, n, first + b * ROW_BLOCK, out.len() / n);
            for (r, out_row) in out.chunks_exact_mut(n).enumerate() {
                let row = &mut self.block[r * cols..(r + 1) * cols];
                // The zero and Nyquist frequencies of a real row are real: drop rounding residue.
                row[0].im = zero;
                row[n].im = zero;
                (plans.real_inverse)
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

/// `count` rows of `cols` frequencies in `block` written kx major into a row block: `out[kx ·
/// ROW_BLOCK + r] = block[r · cols + kx]`.
fn to_columns<T: Copy>(block: &[Complex<T>], out: &mut [Complex<T>], cols: usize, count: usize) {
    // A full block has a constant row count, so that the inner loop unrolls.
    if count == ROW_BLOCK {
        let mut rows = block.chunks_exact(cols);
        let rows: [&[Complex<T>]; ROW_BLOCK] = std::array::from_fn(|_| rows.next().expect("full block"));
        for (kx, column) in out.chunks_exact_mut(ROW_BLOCK).enumerate() {
            for r in 0..ROW_BLOCK {
                column[r] = rows[r][kx];
            }
        }
    } else {
        for (kx, column) in out.chunks_exact_mut(ROW_BLOCK).enumerate() {
            for (r, value) in column[..count].iter_mut().enumerate() {
                *value = block[r * cols + kx];
            }
        }
    }
}

/// Rows `first..first + count` of the window gathered from `columns` (column-major, n values a
/// column) into `block` (rows of n + 1 frequencies).
fn from_columns<T: Copy>(
    columns: &[Complex<T>],
    block: &mut [Complex<T>],
    n: usize,
    first: usize,
    count: usize,
) {
    let cols = n + 1;
    if count == ROW_BLOCK {
        let mut rows = block.chunks_exact_mut(cols);
        let rows: [&mut [Complex<T>]; ROW_BLOCK] = std::array::from_fn(|_| rows.next().expect("full block"));
        for (kx, column) in columns.chunks_exact(n).enumerate() {
            let column: &[Complex<T>; ROW_BLOCK] =
                column[first..first + ROW_BLOCK].try_into().expect("full block");
            for r in 0..ROW_BLOCK {
                rows[r][kx] = column[r];
            }
        }
    } else {
        for (kx, column) in columns.chunks_exact(n).enumerate() {
            for r in 0..count {
                block[r * cols + kx] = column[first + r];
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
    fn a_product_is_the_same_bit_for_bit_on_any_team() {
        // Requirement: the parts of a pass are independent and each row and column is transformed
        // by the same code, so teams of 1, 2 and 3 threads give identical bits (n = 40: blocks of
        // 16, 16 and 8 rows, uneven parts), for one component and a pair.
        let n = 40;
        let kernel = |dx: isize, dy: isize| 1.0 / (1.0 + (dx * dx + 2 * dy * dy) as f64);
        let symbol: Symbol<f32> = Symbol::<f64>::of_kernel(n, &circulant(n, kernel)).to();
        let x: Vec<f64> = (0..n * n).map(|k| ((k * 7) % 11) as f64 - 5.0).collect();
        let y: Vec<f64> = (0..n * n).map(|k| ((k * 5) % 13) as f64 - 6.0).collect();
        let products = |threads: usize| {
            let team = Team::new(threads);
            let mut conv = Convolver::<f32>::new(n);
            let mut u = vec![0.0; n * n];
            conv.convolve_on(&team, &x, &symbol, &mut u);
            let (mut p, mut q) = (vec![0.0; n * n], vec![0.0; n * n]);
            let symbols = [&symbol, &symbol, &symbol];
            conv.convolve_pair_on(&team, [&x, &y], symbols, [&mut p, &mut q]);
            [u, p, q].map(|v| v.iter().map(|v| v.to_bits()).collect::<Vec<_>>())
        };
        let alone = products(1);
        assert!(
            alone[0].iter().any(|&b| b != 0),
            "a product of zeros tests nothing"
        );
        for threads in [2, 3] {
            assert_eq!(products(threads), alone, "{threads} threads");
        }
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
