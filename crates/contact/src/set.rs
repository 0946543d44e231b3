//! Friction sets: where Coulomb's law allows the tangential multiplier of a point to lie,
//! |q_i| ≤ g_i with g_i = μ p_i, in the shape the tangential model needs.

/// The admissible set of one point's tangential multiplier, scaled by its bound g.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrictionSet {
    /// −g ≤ q ≤ g: one tangential component (a 1D model, the Fourier n = 1 contact line, a bed of
    /// springs).
    Interval,
    /// |(q_x, q_y)| ≤ g: two tangential components (the BEM grid, a 3D contact surface).
    Disc,
}

impl FrictionSet {
    /// The components a point has in this set.
    pub fn components(self) -> usize {
        match self {
            FrictionSet::Interval => 1,
            FrictionSet::Disc => 2,
        }
    }
}

/// The Euclidean norm of point `i` of a component-major field of `m` points.
pub(crate) fn norm_at(field: &[f64], m: usize, i: usize) -> f64 {
    field.iter().skip(i).step_by(m).map(|v| v * v).sum::<f64>().sqrt()
}

/// Scales point `i` of `field` by `s`.
pub(crate) fn scale_at(field: &mut [f64], m: usize, i: usize, s: f64) {
    field.iter_mut().skip(i).step_by(m).for_each(|v| *v *= s);
}

/// The dot product of point `i` of two component-major fields.
pub(crate) fn dot_at(a: &[f64], b: &[f64], m: usize, i: usize) -> f64 {
    a.iter()
        .skip(i)
        .step_by(m)
        .zip(b.iter().skip(i).step_by(m))
        .map(|(x, y)| x * y)
        .sum()
}
