//! Gauss rules on the reference triangle {ξ ≥ 0, η ≥ 0, ξ + η ≤ 1} (area ½), on [0, 1], and on
//! the reference tetrahedron {ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1} (volume ⅙).
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

/// A quadrature point of the reference tetrahedron.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point3 {
    /// Reference coordinates (ξ, η, ζ).
    pub at: [f64; 3],
    /// Weight (they sum to ⅙, the reference volume).
    pub weight: f64,
}

/// The points of the tetrahedron with barycentric coordinates every distinct permutation of
/// `barycentric`, each with weight `weight`.
fn tetrahedron_orbit(barycentric: [f64; 4], weight: f64) -> Vec<Point3> {
    let mut points: Vec<Point3> = Vec::new();
    for p in PERMUTATIONS_OF_4 {
        let at = [barycentric[p[1]], barycentric[p[2]], barycentric[p[3]]];
        let seen = points
            .iter()
            .any(|q| q.at.iter().zip(&at).all(|(a, b)| (a - b).abs() < 1e-15));
        if !seen {
            points.push(Point3 { at, weight });
        }
    }
    points
}

/// The 24 permutations of (0, 1, 2, 3).
const PERMUTATIONS_OF_4: [[usize; 4]; 24] = {
    let mut all = [[0; 4]; 24];
    let mut k = 0;
    let mut a = 0;
    while a < 4 {
        let mut b = 0;
        while b < 4 {
            let mut c = 0;
            while c < 4 {
                if a != b && b != c && a != c {
                    all[k] = [a, b, c, 6 - a - b - c];
                    k += 1;
                }
                c += 1;
            }
            b += 1;
        }
        a += 1;
    }
    all
};

/// The 4-point rule exact for polynomials of degree 2 (Hammer, Marlowe & Stroud 1956): enough
/// for the stiffness of a straight-sided 10-node tetrahedron, whose integrand ∇N·∇N is
/// quadratic.
pub fn tetrahedron_degree2() -> Vec<Point3> {
    let a = 0.138_196_601_125_010_5; // (5 − √5)/20
    tetrahedron_orbit([1.0 - 3.0 * a, a, a, a], 1.0 / 24.0)
}

/// The 14-point rule exact for polynomials of degree 5, all weights positive (Walkington 2000):
/// for curved (isoparametric) tetrahedra, whose integrand is rational, and for errors against
/// a smooth exact solution. Exactness is checked by the test below.
pub fn tetrahedron_degree5() -> Vec<Point3> {
    let (a, wa) = (0.092_735_250_310_891_2, 0.012_248_840_519_393_66);
    let (b, wb) = (0.310_885_919_263_300_6, 0.018_781_320_953_002_64);
    let (c, wc) = (0.454_496_295_874_350_4, 0.007_091_003_462_846_911);
    let mut points = tetrahedron_orbit([1.0 - 3.0 * a, a, a, a], wa);
    points.extend(tetrahedron_orbit([1.0 - 3.0 * b, b, b, b], wb));
    points.extend(tetrahedron_orbit([c, c, 0.5 - c, 0.5 - c], wc));
    points
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

    /// ∫ ξ^i η^j ζ^k over the reference tetrahedron = i! j! k! / (i + j + k + 3)!.
    fn exact3(i: i32, j: i32, k: i32) -> f64 {
        let f = |n: i32| (1..=n).map(f64::from).product::<f64>();
        f(i) * f(j) * f(k) / f(i + j + k + 3)
    }

    #[test]
    fn tetrahedron_rules_are_exact_to_their_degree() {
        for (rule, degree, count) in [(tetrahedron_degree2(), 2, 4), (tetrahedron_degree5(), 5, 14)] {
            assert_eq!(rule.len(), count);
            assert!(rule
                .iter()
                .all(|p| p.weight > 0.0 && p.at.iter().sum::<f64>() < 1.0));
            for i in 0..=degree {
                for j in 0..=degree - i {
                    for k in 0..=degree - i - j {
                        let sum: f64 = rule
                            .iter()
                            .map(|p| p.weight * p.at[0].powi(i) * p.at[1].powi(j) * p.at[2].powi(k))
                            .sum();
                        let err = (sum - exact3(i, j, k)).abs();
                        assert!(err < 1e-15, "degree {degree}: ξ^{i} η^{j} ζ^{k} off by {err}");
                    }
                }
            }
        }
    }
}
