//! The compliance operator: what the contact engine knows of the bodies.
//!
//! A compliance C maps multipliers λ at m contact points (pressures or nodal forces, `k`
//! components a point) to the displacements they cause there, u = C λ. Vectors are stored
//! component-major: entry `c·m + i` is component c at point i.
//!
//! Each point carries a weight a_i: the resultant of the multipliers is Σ a_i λ_i (a_i = h² for
//! panel pressures, 1 for nodal forces, h² times the multiplicity of a point in a symmetric
//! reduction), and C is self-adjoint and positive definite in the work product
//! ⟨x, y⟩ = Σ_i a_i x_i·y_i. Every algorithm of the engine works in that product, so a reduced
//! operator (a quarter grid with multiplicities) gives the same iterates as the full one.

use faer::MatRef;

/// A linear, self-adjoint, positive definite compliance on m contact points.
pub trait Compliance {
    /// The number of contact points m.
    fn points(&self) -> usize;

    /// Components a point (1: normal, or a 1D tangential model; 2: a tangential plane).
    fn components(&self) -> usize;

    /// The point weights a_i (see the module doc).
    fn weights(&self) -> &[f64];

    /// `out = C load` (component-major, length m·k each).
    fn apply(&mut self, load: &[f64], out: &mut [f64]);

    /// `out = C load` as a correction: a product the solver scales by a step and adds to an exact
    /// displacement, so that only its error relative to the correction matters, not relative to
    /// the displacement. The default is [`Compliance::apply`]; an operator may run it in a lower
    /// precision and say so with [`Compliance::rough_corrections`].
    fn apply_correction(&mut self, load: &[f64], out: &mut [f64]) {
        self.apply(load, out);
    }

    /// True when [`Compliance::apply_correction`] is less precise than [`Compliance::apply`]: a
    /// solver that used it checks its answer with an exact product before it stops.
    fn rough_corrections(&self) -> bool {
        false
    }

    /// An upper bound of the largest eigenvalue of C (in the work product): scales the
    /// tangential tolerance.
    fn largest_eigenvalue(&self) -> f64;

    /// How many columns [`Compliance::add_columns`] may add before one [`Compliance::apply`] is
    /// cheaper (0: never; the default).
    fn column_budget(&self) -> usize {
        0
    }

    /// `out += Σ_j C e_j δ_j` for the changes `(j, δ_j)` (j indexes the component-major vector).
    /// The default applies C to the sparse vector.
    fn add_columns(&mut self, changes: &[(usize, f64)], out: &mut [f64]) {
        let mut load = vec![0.0; out.len()];
        for &(j, delta) in changes {
            load[j] += delta;
        }
        let mut extra = vec![0.0; out.len()];
        self.apply(&load, &mut extra);
        out.iter_mut().zip(&extra).for_each(|(o, e)| *o += e);
    }

    /// The matrix of C, when the operator holds one (the direct solvers factor its blocks).
    fn matrix(&self) -> Option<MatRef<'_, f64>> {
        None
    }
}

/// ⟨x, y⟩ = Σ a_i x_i y_i over component-major vectors with point weights `a`.
pub fn work(a: &[f64], x: &[f64], y: &[f64]) -> f64 {
    let m = a.len();
    x.chunks(m)
        .zip(y.chunks(m))
        .map(|(x, y)| a.iter().zip(x).zip(y).map(|((a, x), y)| a * x * y).sum::<f64>())
        .sum()
}

/// Σ_i a_i v_{c,i}: the resultant of component `c` of a component-major field.
pub fn resultant(a: &[f64], field: &[f64], component: usize) -> f64 {
    let m = a.len();
    a.iter()
        .zip(&field[component * m..(component + 1) * m])
        .map(|(a, v)| a * v)
        .sum()
}

/// Brings `out = C load` up to date after the caller changed `load` at `changes` (index and
/// change), by adding columns when few changed and by a full product otherwise; true when a full
/// product was spent.
pub fn update_after_changes(
    op: &mut dyn Compliance,
    changes: &[(usize, f64)],
    load: &[f64],
    out: &mut [f64],
) -> bool {
    if changes.is_empty() {
        false
    } else if changes.len() <= op.column_budget() {
        op.add_columns(changes, out);
        false
    } else {
        op.apply(load, out);
        true
    }
}
