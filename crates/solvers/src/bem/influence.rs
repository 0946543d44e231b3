//! Influence coefficients of uniformly loaded square panels on two elastic half-spaces:
//! Boussinesq (normal) and Cerruti (tangential), in closed form.
//!
//! A point force on the surface of a half-space (shear modulus G, Poisson ratio ν) displaces the
//! surface point at distance ρ = √(X² + Y²) by (Johnson 1985, eqs. 3.19 and 3.86 at z = 0):
//!
//! ```text
//! normal force P:       u_z = (1 − ν) P / (2πG ρ)               (Boussinesq)
//! tangential force Q_x: u_x = Q_x / (2πG) [(1 − ν)/ρ + ν X²/ρ³]  (Cerruti)
//!                       u_y = Q_x / (2πG) ν X Y / ρ³
//! ```
//! (plus the cross terms u_z ∝ (1 − 2ν) Q_x X/ρ² and u_x ∝ (1 − 2ν) P X/ρ², which cancel between
//! two bodies with equal (1 − 2ν)/G, i.e. Dundurs β = 0; see `solver`).
//!
//! Equal and opposite tractions on the two bodies displace them relative to each other by the sum
//! of their compliances: normally (1 − ν)/(2πG) = (1 − ν²)/(πE) sums to 1/(πE*); tangentially
//! (1 − ν)/G and ν/G sum to Σ (1 − νᵢ)/Gᵢ and Σ νᵢ/Gᵢ.
//!
//! A uniform traction over the square panel [−a, a]² (a = h/2) integrates the kernels; with the
//! corner sum 𝒞[F](x, y) = F(x+a, y+a) − F(x−a, y+a) − F(x+a, y−a) + F(x−a, y−a) of a primitive F
//! with ∂²F/∂X∂Y equal to the kernel (Love 1929 for the normal case; Johnson 1985, eq. 3.25):
//!
//! ```text
//! ∫∫ X²/ρ³  dX dY = 𝒞[A(X, Y)],   A(X, Y) = Y asinh(X/|Y|)      (A = 0 on Y = 0)
//! ∫∫ 1/ρ    dX dY = 𝒞[A(X, Y) + A(Y, X)]                        (Love's X asinh(Y/X) + Y asinh(X/Y))
//! ∫∫ XY/ρ³  dX dY = 𝒞[−ρ]
//! ```
//! A is odd in X and in Y, which makes the corner sum valid in every quadrant and free of the
//! logarithms of zero that the usual ln form meets on the axes.

use spherecontact_model::pair::{ContactPair, Material};

use super::grid::Grid;

/// A(X, Y) = Y asinh(X/|Y|), the primitive of X²/ρ³.
fn primitive_x2(x: f64, y: f64) -> f64 {
    if y == 0.0 {
        0.0
    } else {
        y * (x / y.abs()).asinh()
    }
}

/// The primitive −ρ of XY/ρ³.
fn primitive_xy(x: f64, y: f64) -> f64 {
    -x.hypot(y)
}

/// The compliances of the pair that scale the kernels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairCompliance {
    /// 1/E* = Σ (1 − νᵢ²)/Eᵢ [1/Pa].
    pub normal: f64,
    /// Σ (1 − νᵢ)/Gᵢ [1/Pa].
    pub shear: f64,
    /// Σ νᵢ/Gᵢ [1/Pa].
    pub poisson_shear: f64,
}

impl PairCompliance {
    /// The compliances of `pair`.
    pub fn of(pair: &ContactPair) -> Self {
        let sum = |f: fn(&Material) -> f64| f(&pair.body1.material) + f(&pair.body2.material);
        Self {
            normal: 1.0 / pair.effective_modulus(),
            shear: sum(|m| (1.0 - m.poisson) / m.shear_modulus()),
            poisson_shear: sum(|m| m.poisson / m.shear_modulus()),
        }
    }
}

/// The kernels on the 2n × 2n circulant layout of the zero-padded convolution: entry (a, b)
/// holds the relative displacement at a collocation point per unit traction on the panel at
/// offset (dx, dy) = (a, b) panels for a, b < n and (a − 2n, b − 2n) beyond n; row and column n
/// (offset ±n, never needed) are zero.
///
/// ```text
/// zz = 𝒞[1/ρ] / (π E*)
/// xx = [Σ(1−ν)/G 𝒞[1/ρ] + Σν/G 𝒞[X²/ρ³]] / 2π,   yy the same with Y²/ρ³
/// xy = Σν/G 𝒞[XY/ρ³] / 2π   (also y from x: the matrix is symmetric)
/// ```
pub struct Kernels;

/// The three tangential kernels (Cerruti), in the circulant layout of [`Kernels`].
#[derive(Clone, Debug, PartialEq)]
pub struct TangentialKernels {
    /// x–x.
    pub xx: Vec<f64>,
    /// x–y (= y–x).
    pub xy: Vec<f64>,
    /// y–y.
    pub yy: Vec<f64>,
}

/// A primitive tabulated at the panel vertices: the 2n × 2n points ((i − n + ½) h, (j − n + ½) h),
/// so that the corner sum of the panel at offset (dx, dy) reads four neighbouring entries.
struct VertexTable {
    values: Vec<f64>,
    side: usize,
}

impl VertexTable {
    /// F tabulated, for F odd in each argument (`odd`) or even in each. The vertices are
    /// symmetric, w(2n − 1 − i) = −w(i): F is evaluated on the quadrant i, j ≥ n and mirrored
    /// with the sign of its parity (exact: the primitives here flip sign, or not, bit for bit).
    fn of(f: impl Fn(f64, f64) -> f64, odd: bool, n: usize, h: f64) -> Self {
        let side = 2 * n;
        let w = |i: usize| (i as f64 - n as f64 + 0.5) * h;
        let sign = if odd { -1.0 } else { 1.0 };
        let mut values = vec![0.0; side * side];
        for j in n..side {
            for i in n..side {
                let v = f(w(i), w(j));
                let (mi, mj) = (side - 1 - i, side - 1 - j);
                values[j * side + i] = v;
                values[j * side + mi] = sign * v;
                values[mj * side + i] = sign * v;
                values[mj * side + mi] = v;
            }
        }
        Self { values, side }
    }

    /// 𝒞[F] for the panel at offset (dx, dy) panels, |dx|, |dy| < n.
    fn corner_sum(&self, dx: isize, dy: isize) -> f64 {
        let n = (self.side / 2) as isize;
        let (i, j) = ((dx + n - 1) as usize, (dy + n - 1) as usize);
        let at = |i: usize, j: usize| self.values[j * self.side + i];
        at(i + 1, j + 1) - at(i, j + 1) - at(i + 1, j) + at(i, j)
    }
}

impl Kernels {
    /// Calls `fill(k, 𝒞[X²/ρ³], 𝒞[Y²/ρ³], offset)` for every used entry k of the layout.
    fn for_each_offset(grid: &Grid, mut fill: impl FnMut(usize, f64, f64, (isize, isize))) {
        let (n, m) = (grid.n, 2 * grid.n);
        // ∫∫ Y²/ρ³ at offset (dx, dy) is ∫∫ X²/ρ³ at (dy, dx): one table serves both.
        let x2 = VertexTable::of(primitive_x2, true, n, grid.h);
        let offset = |a: usize| match a.cmp(&n) {
            std::cmp::Ordering::Less => Some(a as isize),
            std::cmp::Ordering::Greater => Some(a as isize - m as isize),
            std::cmp::Ordering::Equal => None,
        };
        for b in 0..m {
            for a in 0..m {
                if let (Some(dx), Some(dy)) = (offset(a), offset(b)) {
                    fill(b * m + a, x2.corner_sum(dx, dy), x2.corner_sum(dy, dx), (dx, dy));
                }
            }
        }
    }

    /// The Boussinesq kernel zz of `grid`.
    pub fn normal(grid: &Grid, compliance: &PairCompliance) -> Vec<f64> {
        let mut zz = vec![0.0; 4 * grid.len()];
        Self::for_each_offset(grid, |k, cx2, cy2, _| {
            // ∫∫ 1/ρ = ∫∫ (X² + Y²)/ρ³
            zz[k] = compliance.normal * (cx2 + cy2) / std::f64::consts::PI;
        });
        zz
    }

    /// The Cerruti kernels xx, xy, yy of `grid`.
    pub fn tangential(grid: &Grid, compliance: &PairCompliance) -> TangentialKernels {
        let len = 4 * grid.len();
        let mut kernels = TangentialKernels {
            xx: vec![0.0; len],
            xy: vec![0.0; len],
            yy: vec![0.0; len],
        };
        let xy = VertexTable::of(primitive_xy, false, grid.n, grid.h);
        let tau = 2.0 * std::f64::consts::PI;
        Self::for_each_offset(grid, |k, cx2, cy2, (dx, dy)| {
            let inverse = cx2 + cy2;
            kernels.xx[k] = (compliance.shear * inverse + compliance.poisson_shear * cx2) / tau;
            kernels.yy[k] = (compliance.shear * inverse + compliance.poisson_shear * cy2) / tau;
            kernels.xy[k] = compliance.poisson_shear * xy.corner_sum(dx, dy) / tau;
        });
        kernels
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn unit() -> PairCompliance {
        PairCompliance {
            normal: 1.0,
            shear: 1.0,
            poisson_shear: 0.5,
        }
    }

    #[test]
    fn self_influence_is_loves_closed_form() {
        // Love (1929): the centre of a uniformly loaded square of side h sinks by
        // (1 − ν²)/E · p · (4h/π) asinh(1); here 1/E* = 1, h = 2.
        let grid = Grid { n: 4, h: 2.0 };
        let (zz, k) = (
            Kernels::normal(&grid, &unit()),
            Kernels::tangential(&grid, &unit()),
        );
        let love = 4.0 * 2.0 * 1.0_f64.asinh() / std::f64::consts::PI;
        assert_relative_eq!(zz[0], love, max_relative = 1e-14);
        // By symmetry ∫∫X²/ρ³ = ∫∫Y²/ρ³ = ½∫∫1/ρ at the centre, and XY/ρ³ integrates to zero.
        assert_relative_eq!(k.xx[0], k.yy[0], max_relative = 1e-14);
        assert!(k.xy[0].abs() < 1e-14);
    }

    #[test]
    fn far_panels_act_as_point_forces() {
        // At distance ρ ≫ h the panel is a point force h² p: Boussinesq and Cerruti directly.
        let (n, h) = (64, 1e-3);
        let grid = Grid { n, h };
        let (zz, k) = (
            Kernels::normal(&grid, &unit()),
            Kernels::tangential(&grid, &unit()),
        );
        let (dx, dy) = (30, -40);
        let index = (2 * n as isize + dy) as usize * 2 * n + dx as usize;
        let (x, y) = (dx as f64 * h, dy as f64 * h);
        let rho = x.hypot(y);
        let area = h * h;
        let tau = 2.0 * std::f64::consts::PI;
        // Tolerance: the next term of the multipole expansion is O((h/ρ)²) = 4e-4 at 50 panels.
        assert_relative_eq!(
            zz[index],
            area / (std::f64::consts::PI * rho),
            max_relative = 1e-4
        );
        let xx = area * (1.0 / rho + 0.5 * x * x / rho.powi(3)) / tau;
        assert_relative_eq!(k.xx[index], xx, max_relative = 1e-4);
        let xy = area * 0.5 * x * y / rho.powi(3) / tau;
        assert_relative_eq!(k.xy[index], xy, max_relative = 1e-4);
    }

    #[test]
    fn kernels_are_even_in_each_offset_and_xy_odd() {
        let grid = Grid { n: 4, h: 1.0 };
        let (zz, k) = (
            Kernels::normal(&grid, &unit()),
            Kernels::tangential(&grid, &unit()),
        );
        let m = 8;
        // Offset (1, 2) at (1, 2); offset (−1, 2) at (7, 2); (1, −2) at (1, 6).
        assert_relative_eq!(zz[2 * m + 1], zz[2 * m + 7], max_relative = 1e-14);
        assert_relative_eq!(k.xx[2 * m + 1], k.xx[6 * m + 1], max_relative = 1e-14);
        assert_relative_eq!(k.xy[2 * m + 1], -k.xy[2 * m + 7], max_relative = 1e-14);
        assert_relative_eq!(k.xy[2 * m + 1], -k.xy[6 * m + 1], max_relative = 1e-14);
        assert_eq!(zz[4 * m + 1], 0.0);
    }
}
