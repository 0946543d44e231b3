//! Sums and maxima over a vector in interleaved accumulators.
//!
//! A float sum in one accumulator waits for each addition before the next (about four cycles):
//! a loop `s += f(i)` runs at one term per four cycles, whatever the core could do beside. With
//! [`LANES`] accumulators, term i going to accumulator i mod [`LANES`], the additions overlap (and
//! the compiler may put the lanes in one SIMD register). The order of the additions changes, so
//! the sum changes by round-off only (a relative 1e-16 per term).

/// Interleaved accumulators.
pub const LANES: usize = 4;

/// Σ_{i < len} term(i), in [`LANES`] accumulators.
#[inline(always)]
pub fn sum(len: usize, mut term: impl FnMut(usize) -> f64) -> f64 {
    let mut lanes = [0.0; LANES];
    let whole = len - len % LANES;
    for start in (0..whole).step_by(LANES) {
        for (l, lane) in lanes.iter_mut().enumerate() {
            *lane += term(start + l);
        }
    }
    let tail: f64 = (whole..len).map(term).sum();
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
}

/// max(start, term(i) for i < len), in [`LANES`] accumulators (exact: the maximum does not
/// depend on the order).
#[inline(always)]
pub fn max(len: usize, start: f64, mut term: impl FnMut(usize) -> f64) -> f64 {
    let mut lanes = [start; LANES];
    let whole = len - len % LANES;
    for first in (0..whole).step_by(LANES) {
        for (l, lane) in lanes.iter_mut().enumerate() {
            *lane = lane.max(term(first + l));
        }
    }
    let tail = (whole..len).map(term).fold(start, f64::max);
    lanes.iter().copied().fold(tail, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interleaved_sums_and_maxima_equal_the_plain_ones() {
        for len in [0, 1, 3, 4, 5, 17] {
            let values: Vec<f64> = (0..len).map(|i| ((i * 7) % 5) as f64 - 1.5).collect();
            // Small integers and halves: every partial sum is exact, in any order.
            assert_eq!(sum(len, |i| values[i]), values.iter().sum::<f64>());
            assert_eq!(
                max(len, -9.0, |i| values[i]),
                values.iter().copied().fold(-9.0, f64::max)
            );
        }
    }
}
