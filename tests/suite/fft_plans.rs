//! The FFT plans the BEM's convolution uses (crates/fft-plans), tested through their trait objects
//! here: a unit test of that crate would compile rustfft's planner a second time (its test
//! binary), 24 s of the test command's compile.

use fft_plans::{Complex, Planned};

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
