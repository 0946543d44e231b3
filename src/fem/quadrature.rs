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
    fn line_rule_is_exact_to_degree_five() {
        for k in 0..=5 {
            let sum: f64 = line_gauss3().iter().map(|p| p.weight * p.at[0].powi(k)).sum();
            assert!((sum - 1.0 / f64::from(k + 1)).abs() < 1e-15);
        }
    }
}
