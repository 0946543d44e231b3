//! The condensed compliance of the contact surface, from the factorisation.
//!
//! A multiplier of component a at candidate j puts the nodal forces f_(k,a) = A_jk on the body
//! (a column b_(j,a) over the contact DOFs; [`super::surface`]) and is work-conjugate to the
//! averaged displacement (A u_a)_j. With C the block of K⁻¹ on the contact DOFs, the condensed
//! compliance of two sets of multipliers is Bᵀ C B. Two ways of computing it are offered and
//! measured (`examples/fem3d_timing.rs`):
//!
//! - [`Condensation::TrailingBlock`]: with the contact DOFs ordered last, C = (L₂₂ L₂₂ᵀ)⁻¹ with
//!   L₂₂ the factor's trailing block, so Bᵀ C B = Zᵀ Z with Z = L₂₂⁻¹ B: one dense triangular
//!   solve and a product, in the contact DOFs' dimension only.
//! - [`Condensation::BlockedSolves`]: X = K⁻¹ B (B embedded in the free DOFs), 64 columns per
//!   solve through the whole factor, then Bᵀ X.
//!
//! For identical spheres only the normal–normal and the tangential–tangential blocks enter (the
//! cross blocks cancel between the two mirror-image bodies), so only those are formed.

use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Accum, Mat, MatRef, Par};

use super::surface::Surface;
use super::system::System;
use crate::fem::factor::Factor;
use crate::fem::ordering::ContactLast;

/// How the condensed compliance is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Condensation {
    /// From the trailing block of the factor (contact DOFs ordered last).
    TrailingBlock,
    /// By solves through the whole factor, 64 right-hand sides at a time.
    BlockedSolves,
}

/// The condensed contact problem of one body.
#[derive(Clone, Debug)]
pub struct Condensed {
    /// Normal compliance: averaged u_z at j per unit normal multiplier at k [m/N] (m × m).
    pub normal: Mat<f64>,
    /// Tangential compliance over [`Condensed::tangential_unknowns`] [m/N].
    pub tangential: Mat<f64>,
    /// The tangential unknowns: (candidate, component 0 = x or 1 = y); u_y is fixed on the
    /// symmetry plane, where q_y = 0 by symmetry, so those candidates have no y unknown.
    pub tangential_unknowns: Vec<Unknown>,
    /// Far-face reaction per unit multiplier: [0] along x per tangential unknown (zero for y
    /// ones), [1] along z per normal unknown. Equilibrium makes ρ · λ the sum of the
    /// multipliers: a check of the assembly and the solves.
    pub reaction: [Vec<f64>; 2],
}

/// A multiplier: (candidate, component 0 = x, 1 = y, 2 = z).
pub type Unknown = (usize, usize);

/// The normal and the tangential multipliers to condense.
fn unknowns(surface: &Surface) -> (Vec<Unknown>, Vec<Unknown>) {
    let m = surface.len();
    let normal = (0..m).map(|j| (j, 2)).collect();
    let mut tangential: Vec<Unknown> = (0..m).map(|j| (j, 0)).collect();
    tangential.extend((0..m).filter(|&j| !surface.on_symmetry[j]).map(|j| (j, 1)));
    (normal, tangential)
}

/// The force columns B over the trailing (contact) DOFs for `columns`.
fn forces(surface: &Surface, order: &ContactLast, columns: &[Unknown]) -> Mat<f64> {
    let m = surface.nodes.len();
    let mut position = vec![usize::MAX; 3 * m];
    for (p, &(k, a)) in order.trailing.iter().enumerate() {
        position[3 * k + a] = p;
    }
    let mut b = Mat::<f64>::zeros(order.trailing.len(), columns.len());
    for (c, &(j, a)) in columns.iter().enumerate() {
        for &(k, v) in &surface.average[j] {
            if let Some(&p) = position.get(3 * k + a).filter(|&&p| p != usize::MAX) {
                b[(p, c)] += v;
            }
        }
    }
    b
}

/// Zᵀ Z.
fn gram(z: MatRef<'_, f64>) -> Mat<f64> {
    let mut c = Mat::<f64>::zeros(z.ncols(), z.ncols());
    matmul(c.as_mut(), Accum::Replace, z.transpose(), z, 1.0, Par::Seq);
    c
}

/// Condenses the body onto its candidate surface. [`Condensation::TrailingBlock`] needs a
/// factor whose order ends with `order.trailing_dofs`; the blocked solves take any order.
pub fn condense(
    system: &System,
    factor: &Factor,
    order: &ContactLast,
    surface: &Surface,
    how: Condensation,
) -> Condensed {
    let (normal_unknowns, tangential_unknowns) = unknowns(surface);
    let b_normal = forces(surface, order, &normal_unknowns);
    let b_tangential = forces(surface, order, &tangential_unknowns);
    let (normal, tangential) = match how {
        Condensation::TrailingBlock => {
            let l22 = factor.trailing_block(order.trailing.len());
            let solve = |mut b: Mat<f64>| {
                solve_lower_triangular_in_place(l22.as_ref(), b.as_mut(), Par::Seq);
                gram(b.as_ref())
            };
            (solve(b_normal), solve(b_tangential))
        }
        Condensation::BlockedSolves => (
            blocked(system, factor, order, b_normal.as_ref()),
            blocked(system, factor, order, b_tangential.as_ref()),
        ),
    };
    let reaction = reactions(system, factor, order, surface, &tangential_unknowns);
    Condensed {
        normal,
        tangential,
        tangential_unknowns,
        reaction,
    }
}

/// Columns solved at once through the whole factor.
pub const BLOCK: usize = 64;

/// Bᵀ K⁻¹ B by solves of 64 columns at a time.
fn blocked(system: &System, factor: &Factor, order: &ContactLast, b: MatRef<'_, f64>) -> Mat<f64> {
    let (n, md, cols) = (system.dofs.count(), order.trailing.len(), b.ncols());
    let dof = |p: usize| order.trailing_dofs[p];
    let mut c = Mat::<f64>::zeros(cols, cols);
    for start in (0..cols).step_by(BLOCK) {
        let width = BLOCK.min(cols - start);
        let mut x = Mat::<f64>::zeros(n, width);
        for q in 0..width {
            for p in 0..md {
                x[(dof(p), q)] = b[(p, start + q)];
            }
        }
        factor.solve_in_place(x.as_mut());
        let contact = Mat::<f64>::from_fn(md, width, |p, q| x[(dof(p), q)]);
        let block = c.as_mut().subcols_mut(start, width);
        matmul(
            block,
            Accum::Replace,
            b.transpose(),
            contact.as_ref(),
            1.0,
            Par::Seq,
        );
    }
    c
}

/// Far-face reactions per unit multiplier: ρ_a = K⁻¹ r_a (two solves), averaged like the
/// displacements.
fn reactions(
    system: &System,
    factor: &Factor,
    order: &ContactLast,
    surface: &Surface,
    tangential_unknowns: &[Unknown],
) -> [Vec<f64>; 2] {
    let n = system.dofs.count();
    let mut rho = Mat::<f64>::from_fn(n, 2, |i, a| system.reaction[a][i]);
    factor.solve_in_place(rho.as_mut());
    let m = surface.len();
    // ρ at each contact DOF, by (candidate node, component); fixed components stay zero.
    let mut at = vec![[0.0; 3]; surface.nodes.len()];
    for (&(k, a), &dof) in order.trailing.iter().zip(&order.trailing_dofs) {
        match a {
            0 => at[k][0] = rho[(dof, 0)],
            2 => at[k][2] = rho[(dof, 1)],
            _ => {}
        }
    }
    let averaged = |j: usize, a: usize| surface.average[j].iter().map(|&(k, v)| v * at[k][a]).sum::<f64>();
    let z = (0..m).map(|j| averaged(j, 2)).collect();
    let x = tangential_unknowns
        .iter()
        .map(|&(j, a)| if a == 0 { averaged(j, 0) } else { 0.0 })
        .collect();
    [x, z]
}
