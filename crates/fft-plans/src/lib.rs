//! The FFT plans of one transform length, in f64 and f32: a real-to-complex pair (realfft) and
//! a complex pair (rustfft), planned here and handed out as trait objects.
//!
//! **Why a crate of its own.** rustfft's planner is generic over the float type and chooses its
//! algorithm at run time (scalar, SSE or AVX butterflies of every prime size, mixed radix,
//! Rader, Bluestein), so every algorithm it might choose is monomorphised wherever the planner
//! is called. Called from spherecontact it was a third of the library's LLVM IR (773 k of
//! 2.34 M lines, `cargo llvm-lines --release --lib`), compiled twice by the README's test
//! command: once in the library and once in its unit-test binary. Here the planner is
//! instantiated in two non-generic functions ([`Planned::plans`] for f64 and f32), compiled
//! once as a dependency; the library calls the plans through `dyn`, which instantiates nothing.
//! The plans and their results are the same as before, bit for bit: the same planner builds
//! them.

use std::sync::Arc;

pub use realfft::num_complex::Complex;
pub use realfft::{ComplexToReal, RealToComplex};
pub use rustfft::{Fft, FftNum};

/// The four plans of one length: forward and inverse, real (rows) and complex (columns).
pub struct Plans<T> {
    /// Real to complex, `len` reals to `len / 2 + 1` frequencies.
    pub real_forward: Arc<dyn RealToComplex<T>>,
    /// Complex to real, the inverse of `real_forward` (unnormalised).
    pub real_inverse: Arc<dyn ComplexToReal<T>>,
    /// Complex forward transform of length `len`.
    pub forward: Arc<dyn Fft<T>>,
    /// Complex inverse transform of length `len` (unnormalised).
    pub inverse: Arc<dyn Fft<T>>,
}

/// A float type whose plans this crate builds: f64 and f32.
pub trait Planned: FftNum {
    /// The plans of transforms of length `len`.
    fn plans(len: usize) -> Plans<Self>;
}

impl Planned for f64 {
    fn plans(len: usize) -> Plans<f64> {
        plan(len)
    }
}

impl Planned for f32 {
    fn plans(len: usize) -> Plans<f32> {
        plan(len)
    }
}

/// The plans of length `len`, by realfft's and rustfft's planners.
fn plan<T: FftNum>(len: usize) -> Plans<T> {
    let mut real = realfft::RealFftPlanner::<T>::new();
    let mut complex = rustfft::FftPlanner::<T>::new();
    Plans {
        real_forward: real.plan_fft_forward(len),
        real_inverse: real.plan_fft_inverse(len),
        forward: complex.plan_fft_forward(len),
        inverse: complex.plan_fft_inverse(len),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requirement: each pair inverts to `len` times its input (both unnormalised). Reference:
    /// the input. Tolerance: 1e-12 relative in f64, 1e-5 in f32 (round-off of log₂ len passes).
    #[test]
    fn the_pairs_invert_each_other_up_to_the_length() {
        fn check<T: Planned + Into<f64> + From<f32>>(len: usize, tolerance: f64) {
            let plans = T::plans(len);
            let input: Vec<T> = (0..len).map(|i| T::from((i as f32 * 0.37).sin())).collect();
            let mut real = input.clone();
            let mut spectrum = vec![Complex::new(T::zero(), T::zero()); len / 2 + 1];
            plans.real_forward.process(&mut real, &mut spectrum).unwrap();
            let mut back = vec![T::zero(); len];
            plans.real_inverse.process(&mut spectrum, &mut back).unwrap();
            let mut complex: Vec<Complex<T>> = input.iter().map(|&x| Complex::new(x, T::zero())).collect();
            plans.forward.process(&mut complex);
            plans.inverse.process(&mut complex);
            for (i, &x) in input.iter().enumerate() {
                let x: f64 = x.into();
                for y in [back[i].into(), complex[i].re.into()] {
                    let y: f64 = y;
                    assert!(
                        (y / len as f64 - x).abs() <= tolerance,
                        "{len}: {i}: {y} against {x}"
                    );
                }
            }
        }
        for len in [2, 30, 256] {
            check::<f64>(len, 1e-12);
            check::<f32>(len, 1e-5);
        }
    }
}
