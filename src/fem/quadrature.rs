//! Gauss rules on the reference triangle {ξ ≥ 0, η ≥ 0, ξ + η ≤ 1} (area ½) and on [0, 1].
//!
//! The points are interior, so no quadrature point ever lies on the symmetry axis r = 0, where the
//! hoop strain u_r / r of the axisymmetric element is 0/0 (docs/toolchain.md, pitfall 5).

/// A quadrature point: reference coordinates and weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Reference coordinates (ξ, η) on the triangle, (ξ, 0) on the line.
    pub at: [f64; 2],
    /// Weight (they sum to the reference measure: ½ on the triangle, 1 on the line).
    pub weight: f64,
}

/// Strang & Fix's 3-point rule, exact for polynomials of degree 2 (Strang & Fix 1973, Table 4.1).
pub fn triangle_degree2() -> Vec<Point> {
    let (a, b) = (1.0 / 6.0, 2.0 / 3.0);
    [[a, a], [b, a], [a, b]]
        .into_iter()
        .map(|at| Point {
            at,
            weight: 1.0 / 6.0,
        })
        .collect()
}

/// Dunavant's 6-point rule, exact for polynomials of degree 4 (Dunavant 1985, Table 4).
pub fn triangle_degree4() -> Vec<Point> {
    let orbit = |a: f64, w: f64| {
        let b = 1.0 - 2.0 * a;
        [[a, a], [b, a], [a, b]].map(|at| Point { at, weight: w / 2.0 })
    };
    let mut points = orbit(0.445_948_490_915_965, 0.223_381_589_678_011).to_vec();
    points.extend(orbit(0.091_576_213_509_771, 0.109_951_743_655_322));
    points
}

/// 3-point Gauss–Legendre on [0, 1], exact for polynomials of degree 5.
pub fn line_gauss3() -> Vec<Point> {
    let d = 0.5 * (0.6f64).sqrt();
    [(0.5 - d, 5.0 / 18.0), (0.5, 8.0 / 18.0), (0.5 + d, 5.0 / 18.0)]
        .into_iter()
        .map(|(x, weight)| Point { at: [x, 0.0], weight })
        .collect()
}

/// n-point Gauss–Legendre on [0, 1], exact for polynomials of degree 2n − 1: the roots of the
/// Legendre polynomial P_n by Newton's method from Tricomi's estimate cos(π(k − ¼)/(n + ½)),
/// weights 2/((1 − x²) P_n'(x)²) on [−1, 1] (Abramowitz & Stegun 25.4.29), mapped to [0, 1].
pub fn line_gauss_legendre(n: usize) -> Vec<Point> {
    let legendre = |x: f64| {
        // P_n(x) and P_n'(x) by the three-term recurrence.
        let (mut p0, mut p1) = (1.0, x);
        for k in 2..=n {
            let k = k as f64;
            (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
        }
        let derivative = n as f64 * (x * p1 - p0) / (x * x - 1.0);
        (p1, derivative)
    };
    (1..=n)
        .map(|k| {
            let mut x = (std::f64::consts::PI * (k as f64 - 0.25) / (n as f64 + 0.5)).cos();
            for _ in 0..100 {
                let (p, dp) = legendre(x);
                let step = p / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let (_, dp) = legendre(x);
            Point {
                at: [0.5 * (1.0 - x), 0.0],
                weight: 1.0 / ((1.0 - x * x) * dp * dp),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ ξ^i η^j over the reference triangle = i! j! / (i + j + 2)!.
    fn exact(i: i32, j: i32) -> f64 {
        let f = |n: i32| (1..=n).map(f64::from).product::<f64>();
        f(i) * f(j) / f(i + j + 2)
    }

    fn integrate(rule: &[Point], i: i32, j: i32) -> f64 {
        rule.iter()
            .map(|p| p.weight * p.at[0].powi(i) * p.at[1].powi(j))
            .sum()
    }

    #[test]
    fn triangle_rules_are_exact_to_their_degree() {
        for (rule, degree) in [(triangle_degree2(), 2), (triangle_degree4(), 4)] {
            for i in 0..=degree {
                for j in 0..=degree - i {
                    let err = (integrate(&rule, i, j) - exact(i, j)).abs();
                    assert!(err < 1e-14, "degree {degree}: ξ^{i} η^{j} off by {err}");
                }
            }
        }
    }

    #[test]
    fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
        for n in [1, 2, 5, 8, 12] {
            let rule = line_gauss_legendre(n);
            for k in 0..2 * n {
                let sum: f64 = rule.iter().map(|p| p.weight * p.at[0].powi(k as i32)).sum();
                assert!(
                    (sum - 1.0 / (k + 1) as f64).abs() < 1e-14,
                    "n = {n}, degree {k}: {sum}"
                );
            }
        }
    }

    #[test]
    fn line_rule_is_exact_to_degree_five() {
        for k in 0..=5 {
            let sum: f64 = line_gauss3().iter().map(|p| p.weight * p.at[0].powi(k)).sum();
            assert!((sum - 1.0 / f64::from(k + 1)).abs() < 1e-15);
        }
    }
}
