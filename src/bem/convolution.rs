//! The discrete convolution u_i = Σ_j K(x_i − x_j) t_j of an n × n field with an influence
//! kernel, by FFT on the zero-padded 2n × 2n grid (non-periodic: the padding keeps the
//! circular wrap-around off the n × n window; Liu, Wang & Liu 2000, "DC-FFT").
//!
//! A 2D real transform is a real-to-complex transform of each row (realfft, n + 1 frequencies)
//! followed by complex transforms of each of those n + 1 columns (rustfft). Spectra are stored
//! column by column: entry (kx, ky) at kx · 2n + ky. Only the n rows that carry data are
//! transformed forward (a row of zeros, out of contact, is a row of zeros: not transformed), and
//! only the n rows of the window backward.
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

/// Rows transformed and transposed together.
const ROW_BLOCK: usize = 8;

/// A 2D spectrum on the padded grid, column-major in the half-spectrum layout.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum<T = f64>(Vec<Complex<T>>);

/// FFT plans and work buffers for one grid size, in precision `T`.
pub struct Convolver<T: Precision = f64> {
    n: usize,
    rows_forward: Arc<dyn RealToComplex<T>>,
    rows_inverse: Arc<dyn ComplexToReal<T>>,
    columns_forward: Arc<dyn Fft<T>>,
    columns_inverse: Arc<dyn Fft<T>>,
    real_row: Vec<T>,
    /// `ROW_BLOCK` rows of n + 1 frequencies.
    block: Vec<Complex<T>>,
    scratch: Vec<Complex<T>>,
}

impl<T: Precision> Convolver<T> {
    /// Plans for an n × n field (padded to 2n × 2n).
    pub fn new(n: usize) -> Self {
        let m = 2 * n;
        let mut real = RealFftPlanner::<T>::new();
        let mut complex = FftPlanner::<T>::new();
        let rows_forward = real.plan_fft_forward(m);
        let rows_inverse = real.plan_fft_inverse(m);
        let columns_forward = complex.plan_fft_forward(m);
        let columns_inverse = complex.plan_fft_inverse(m);
        let scratch_len = [
            rows_forward.get_scratch_len(),
            rows_inverse.get_scratch_len(),
            columns_forward.get_inplace_scratch_len(),
            columns_inverse.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        Self {
            n,
            rows_forward,
            rows_inverse,
            columns_forward,
            columns_inverse,
            real_row: vec![T::zero(); m],
            block: vec![Complex::default(); ROW_BLOCK * (n + 1)],
            scratch: vec![Complex::default(); scratch_len],
        }
    }

    /// The spectrum of a 2n × 2n kernel in the circulant layout of [`super::influence::Kernels`].
    pub fn kernel_spectrum(&mut self, kernel: &[f64]) -> Spectrum<T> {
        let mut spectrum = self.spectrum();
        self.forward(kernel, 2 * self.n, &mut spectrum);
        spectrum
    }

    /// A zero spectrum of this grid: the work space of [`Convolver::field_spectrum_into`].
    pub fn spectrum(&self) -> Spectrum<T> {
        Spectrum(vec![Complex::default(); (self.n + 1) * 2 * self.n])
    }

    /// The spectrum of an n × n field, zero-padded, into `out` (no allocation).
    pub fn field_spectrum_into(&mut self, field: &[f64], out: &mut Spectrum<T>) {
        self.forward(field, self.n, out);
    }

    /// Forward transform of the rows of `data` (each `width` long, n or 2n), zero-padded to 2n
    /// columns and (for n rows) 2n rows.
    fn forward(&mut self, data: &[f64], width: usize, out: &mut Spectrum<T>) {
        let (n, m) = (self.n, 2 * self.n);
        let half = n + 1;
        let spectrum = &mut out.0;
        if width < m {
            // The padding rows: zero in every column.
            for kx in 0..half {
                spectrum[kx * m + n..(kx + 1) * m].fill(Complex::default());
            }
        }
        // Rows are transformed in blocks and written out column by column, `ROW_BLOCK` values at a
        // time: the transposition then touches each memory page once per block, not once per row.
        for (block, rows) in data.chunks(ROW_BLOCK * width).enumerate() {
            let count = rows.len() / width;
            for (r, row) in rows.chunks_exact(width).enumerate() {
                let spectrum_row = &mut self.block[r * half..(r + 1) * half];
                if row.iter().all(|&v| v == 0.0) {
                    spectrum_row.fill(Complex::default());
                    continue;
                }
                for (t, &v) in self.real_row.iter_mut().zip(row) {
                    *t = T::of(v);
                }
                self.real_row[width..].fill(T::zero());
                self.rows_forward
                    .process_with_scratch(&mut self.real_row, spectrum_row, &mut self.scratch)
                    .expect("row lengths match the plan");
            }
            let first = block * ROW_BLOCK;
            for kx in 0..half {
                let column = &mut spectrum[kx * m + first..kx * m + first + count];
                for (r, value) in column.iter_mut().enumerate() {
                    *value = self.block[r * half + kx];
                }
            }
        }
        self.columns_forward
            .process_with_scratch(spectrum, &mut self.scratch);
    }

    /// The n × n window of the inverse transform of `spectrum` (consumed as work space), into
    /// `out` (no allocation).
    pub fn field_into(&mut self, spectrum: &mut Spectrum<T>, out: &mut [f64]) {
        let (n, m) = (self.n, 2 * self.n);
        let half = n + 1;
        self.columns_inverse
            .process_with_scratch(&mut spectrum.0, &mut self.scratch);
        let scale = 1.0 / (m * m) as f64;
        let zero = T::zero();
        for (block, out) in out.chunks_mut(ROW_BLOCK * n).enumerate() {
            let (first, count) = (block * ROW_BLOCK, out.len() / n);
            for kx in 0..half {
                let column = &spectrum.0[kx * m + first..kx * m + first + count];
                for (r, value) in column.iter().enumerate() {
                    self.block[r * half + kx] = *value;
                }
            }
            for (r, out_row) in out.chunks_exact_mut(n).enumerate() {
                let row = &mut self.block[r * half..(r + 1) * half];
                // The zero and Nyquist frequencies of a real row are real: drop rounding residue.
                row[0].im = zero;
                row[n].im = zero;
                self.rows_inverse
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

impl<T: Precision> Spectrum<T> {
    /// Multiplies this spectrum by a real symbol (the spectrum of an even kernel), in place: one
    /// convolution without a new buffer.
    pub fn times_real(&mut self, symbol: &[T]) {
        self.0.iter_mut().zip(symbol).for_each(|(f, &k)| *f = *f * k);
    }

    /// The real part of each value: the symbol of a kernel even in each offset (or odd in both),
    /// whose spectrum is real up to round-off.
    pub fn real_part(&self) -> Vec<T> {
        self.0.iter().map(|v| v.re).collect()
    }

    /// `(x, y) ← (a x + b y, b x + c y)` at every frequency, in place: the two components of a
    /// symmetric 2 × 2 convolution with real symbols a, b, c, in one pass.
    pub fn mix_in_place(x: &mut Spectrum<T>, y: &mut Spectrum<T>, [a, b, c]: [&[T]; 3]) {
        for ((((x, y), &a), &b), &c) in x.0.iter_mut().zip(y.0.iter_mut()).zip(a).zip(b).zip(c) {
            let (xv, yv) = (*x, *y);
            *x = xv * a + yv * b;
            *y = xv * b + yv * c;
        }
    }

    /// The values, in the half-spectrum layout.
    pub fn values(&self) -> &[Complex<T>] {
        &self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fft_convolution_equals_the_direct_sum() {
        let n = 6;
        let m = 2 * n;
        // An arbitrary kernel of the offsets, written in the circulant layout.
        let kernel_of = |dx: isize, dy: isize| 1.0 / (1.0 + (dx * dx + 3 * dy * dy) as f64) + 0.1 * dx as f64;
        let mut kernel = vec![0.0; m * m];
        for b in 0..m {
            for a in 0..m {
                let wrap = |i: usize| {
                    if i < n {
                        i as isize
                    } else {
                        i as isize - m as isize
                    }
                };
                if a != n && b != n {
                    kernel[b * m + a] = kernel_of(wrap(a), wrap(b));
                }
            }
        }
        let field: Vec<f64> = (0..n * n).map(|k| ((k * 7) % 11) as f64 - 5.0).collect();
        let mut conv = Convolver::<f64>::new(n);
        // The kernel is not even (its 0.1 dx part): its spectrum is complex, multiplied in full.
        let ks = conv.kernel_spectrum(&kernel);
        let mut fs = conv.spectrum();
        conv.field_spectrum_into(&field, &mut fs);
        fs.0.iter_mut().zip(&ks.0).for_each(|(f, k)| *f *= k);
        let mut u = vec![0.0; n * n];
        conv.field_into(&mut fs, &mut u);
        for (i, &ui) in u.iter().enumerate() {
            let (ix, iy) = ((i % n) as isize, (i / n) as isize);
            let direct: f64 = (0..n * n)
                .map(|j| {
                    let (jx, jy) = ((j % n) as isize, (j / n) as isize);
                    kernel_of(ix - jx, iy - jy) * field[j]
                })
                .sum();
            assert!(
                (ui - direct).abs() < 1e-12 * (1.0 + direct.abs()),
                "{i}: {ui} vs {direct}"
            );
        }
    }
}
