//! The condensed compliance of a factored body at its contact degrees of freedom.
//!
//! With the stiffness K factored once, the compliance of m contact DOFs,
//! C_ij = e_i · K⁻¹ e_j (displacement of DOF i under a unit force at DOF j), takes m solves,
//! done as blocked multi-column solves. The result is a dense faer matrix that the contact
//! engine ([`spherecontact_contact::DenseCompliance`]) solves on.

use faer::Mat;

use crate::fem::factor::Factor;

/// The condensed response of one body at its contact DOFs.
#[derive(Clone, Debug)]
pub struct Condensed {
    /// Compliance C (m × m) [m/N].
    pub compliance: Mat<f64>,
    /// Far-boundary reaction per unit force at each contact DOF: R = ρ · λ.
    pub reaction: Vec<f64>,
}

/// Contact columns solved at once (a blocked multi-right-hand-side solve).
pub const BLOCK: usize = 64;

/// Condenses a factored system of `n` free DOFs onto the free DOFs `dofs`; `reaction` lists the
/// (DOF, coefficient) pairs whose sum is the far-boundary reaction.
pub fn condense(factor: &Factor, n: usize, dofs: &[usize], reaction: &[(usize, f64)]) -> Condensed {
    let m = dofs.len();
    let mut compliance = Mat::<f64>::zeros(m, m);
    let mut rho = vec![0.0; m];
    for start in (0..m).step_by(BLOCK) {
        let cols = BLOCK.min(m - start);
        let mut x = Mat::<f64>::zeros(n, cols);
        for c in 0..cols {
            x[(dofs[start + c], c)] = 1.0;
        }
        factor.solve_in_place(x.as_mut());
        for c in 0..cols {
            let j = start + c;
            for (i, &dof) in dofs.iter().enumerate() {
                compliance[(i, j)] = x[(dof, c)];
            }
            rho[j] = reaction.iter().map(|&(d, v)| v * x[(d, c)]).sum();
        }
    }
    Condensed {
        compliance,
        reaction: rho,
    }
}
