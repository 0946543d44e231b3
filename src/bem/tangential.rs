//! The incremental tangential problem with Coulomb friction (Kalker 1990, *Three-Dimensional
//! Elastic Bodies in Rolling Contact*, ch. 2: the "shift" formulation), at a known pressure.
//!
//! Over one increment the bodies' far points shift tangentially by Δδt (along x). At panel i the
//! slip increment (relative tangential displacement of the surface particles) is
//!
//! ```text
//! Δs_i = Δδt e_x − (K Δq)_i,      Δq = q − q_prev,
//! ```
//! with K the two-body Cerruti influence matrix and q the traction on body 1 (so that Σ q_x h² is
//! Q, of the sign of δt). Coulomb: |q_i| ≤ g_i = μ p_i; stick (|q_i| < g_i) takes the shift up
//! elastically, Δs_i = 0; slip (|q_i| = g_i) has q_i aligned with Δs_i. These are the optimality
//! conditions of the convex programme
//!
//! ```text
//! min ½ Δqᵀ K Δq − Δδt Σ_i Δq_{x,i}   subject to |q_i| ≤ g_i,
//! ```
//! whose gradient is −Δs (K is symmetric positive definite). It is solved by the accelerated
//! projected gradient method (Nesterov 1983; Beck & Teboulle 2009, FISTA) with the adaptive
//! restart of O'Donoghue & Candès (2015), step 1/L with L the largest eigenvalue of K (bounded by
//! the largest eigenvalue of the 2 × 2 symbol of the padded circulant). Panels out of contact have
//! g = 0 and so carry no traction; a panel entering contact starts at q = 0 and sticks with the
//! relative displacement it arrives with.

use super::convolution::{Convolver, Spectrum};

/// A tangential traction or displacement field: x and y components per panel.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Vector2Field {
    /// x components.
    pub x: Vec<f64>,
    /// y components.
    pub y: Vec<f64>,
}

impl Vector2Field {
    /// A zero field of `len` panels.
    pub fn zeros(len: usize) -> Self {
        Self {
            x: vec![0.0; len],
            y: vec![0.0; len],
        }
    }

    /// |v_i| (by the plain square root: hypot's overflow guard costs and is not needed here).
    pub fn magnitude(&self, i: usize) -> f64 {
        (self.x[i] * self.x[i] + self.y[i] * self.y[i]).sqrt()
    }

    /// Scales each panel's vector into the disc of radius `bound[i]`.
    fn project(&mut self, bound: &[f64]) {
        for (i, &g) in bound.iter().enumerate() {
            let norm = self.magnitude(i);
            if norm > g {
                let scale = if norm > 0.0 { g / norm } else { 0.0 };
                self.x[i] *= scale;
                self.y[i] *= scale;
            }
        }
    }
}

/// The tangential operator q ↦ K q on one grid.
pub struct TangentialOperator {
    convolver: Convolver,
    xx: Spectrum,
    xy: Spectrum,
    yy: Spectrum,
    /// The largest eigenvalue of K (an upper bound) [m/Pa].
    lipschitz: f64,
}

impl TangentialOperator {
    /// The operator with the Cerruti kernels (circulant layout).
    pub fn new(mut convolver: Convolver, xx: &[f64], xy: &[f64], yy: &[f64]) -> Self {
        let xx = convolver.kernel_spectrum(xx);
        let xy = convolver.kernel_spectrum(xy);
        let yy = convolver.kernel_spectrum(yy);
        // The kernels are even, so their spectra are real: the symbol at each frequency is the
        // symmetric matrix [[a, b], [b, c]] with largest eigenvalue (a+c)/2 + √(((a−c)/2)² + b²).
        let lipschitz = xx
            .values()
            .iter()
            .zip(xy.values())
            .zip(yy.values())
            .map(|((a, b), c)| {
                let (a, b, c) = (a.re, b.re, c.re);
                0.5 * (a + c) + (0.25 * (a - c).powi(2) + b * b).sqrt()
            })
            .fold(0.0, f64::max);
        Self {
            convolver,
            xx,
            xy,
            yy,
            lipschitz,
        }
    }

    /// u = K q.
    pub fn apply(&mut self, q: &Vector2Field) -> Vector2Field {
        let qx = self.convolver.field_spectrum(&q.x);
        let qy = self.convolver.field_spectrum(&q.y);
        let ux = Spectrum::combination(&[(&self.xx, &qx), (&self.xy, &qy)]);
        let uy = Spectrum::combination(&[(&self.xy, &qx), (&self.yy, &qy)]);
        Vector2Field {
            x: self.convolver.field(ux),
            y: self.convolver.field(uy),
        }
    }
}

/// One increment of the tangential problem.
///
/// A good `guess` matters: along a path, the previous increment's traction change scaled to this
/// increment's shift starts the iteration close to the answer.
pub struct TangentialProblem<'a> {
    /// The traction bound g_i = μ p_i at the end of the increment [Pa].
    pub bound: &'a [f64],
    /// The traction at the start of the increment [Pa].
    pub previous: &'a Vector2Field,
    /// Where the iteration starts (projected onto the bounds first) [Pa].
    pub guess: Vector2Field,
    /// The increment of rigid tangential shift Δδt along x [m].
    pub shift: f64,
    /// Convergence: the projected-gradient step below `tolerance · max g` on every panel.
    pub tolerance: f64,
    /// Iteration cap.
    pub max_iterations: usize,
}

/// The solution of one increment.
#[derive(Debug)]
pub struct TangentialSolution {
    /// The traction q at the end of the increment [Pa].
    pub traction: Vector2Field,
    /// The slip increment Δs [m].
    pub slip: Vector2Field,
    /// Iterations spent.
    pub iterations: usize,
}

/// The increment did not converge within the iteration cap.
#[derive(Debug, PartialEq)]
pub struct NotConverged {
    /// Iterations spent.
    pub iterations: usize,
    /// The last projected-gradient step over max g.
    pub residual: f64,
}

impl TangentialProblem<'_> {
    /// −Δs = K(q − q_prev) − Δδt e_x: the gradient of the programme at `q`.
    fn gradient(&self, op: &mut TangentialOperator, q: &Vector2Field) -> Vector2Field {
        let change = Vector2Field {
            x: q.x.iter().zip(&self.previous.x).map(|(a, b)| a - b).collect(),
            y: q.y.iter().zip(&self.previous.y).map(|(a, b)| a - b).collect(),
        };
        let mut gradient = op.apply(&change);
        gradient.x.iter_mut().for_each(|u| *u -= self.shift);
        gradient
    }

    /// Solves the increment.
    pub fn solve(&self, op: &mut TangentialOperator) -> Result<TangentialSolution, NotConverged> {
        let scale = self.bound.iter().copied().fold(0.0, f64::max);
        let mut x = self.guess.clone();
        x.project(self.bound);
        let mut y = x.clone();
        let mut momentum = 1.0_f64;
        let step = 1.0 / op.lipschitz;
        let mut residual = f64::INFINITY;
        for iteration in 0..self.max_iterations {
            let gradient = self.gradient(op, &y);
            let mut next = Vector2Field {
                x: y.x.iter().zip(&gradient.x).map(|(y, g)| y - step * g).collect(),
                y: y.y.iter().zip(&gradient.y).map(|(y, g)| y - step * g).collect(),
            };
            next.project(self.bound);
            let moved = (0..next.x.len())
                .map(|i| (next.x[i] - y.x[i]).powi(2) + (next.y[i] - y.y[i]).powi(2))
                .fold(0.0, f64::max)
                .sqrt();
            residual = if scale > 0.0 { moved / scale } else { 0.0 };
            if residual <= self.tolerance {
                let slip = self.gradient(op, &next);
                return Ok(TangentialSolution {
                    slip: Vector2Field {
                        x: slip.x.iter().map(|g| -g).collect(),
                        y: slip.y.iter().map(|g| -g).collect(),
                    },
                    traction: next,
                    iterations: iteration + 1,
                });
            }
            // Restart when the step works against the momentum (O'Donoghue & Candès, eq. 12).
            let against: f64 = (0..next.x.len())
                .map(|i| {
                    (y.x[i] - next.x[i]) * (next.x[i] - x.x[i]) + (y.y[i] - next.y[i]) * (next.y[i] - x.y[i])
                })
                .sum();
            let weight = if against > 0.0 {
                momentum = 1.0;
                0.0
            } else {
                let following = 0.5 * (1.0 + (1.0 + 4.0 * momentum * momentum).sqrt());
                let w = (momentum - 1.0) / following;
                momentum = following;
                w
            };
            for i in 0..next.x.len() {
                y.x[i] = next.x[i] + weight * (next.x[i] - x.x[i]);
                y.y[i] = next.y[i] + weight * (next.y[i] - x.y[i]);
            }
            x = next;
        }
        Err(NotConverged {
            iterations: self.max_iterations,
            residual,
        })
    }
}
