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
