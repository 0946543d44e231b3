//! The few operations on 3-vectors that the first-order body's geometry needs.

/// a − b.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a × b.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// a · b.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The mean of `points`.
pub fn centroid(points: impl ExactSizeIterator<Item = [f64; 3]>) -> [f64; 3] {
    let n = points.len().max(1) as f64;
    let sum = points.fold([0.0; 3], |s, p| [s[0] + p[0], s[1] + p[1], s[2] + p[2]]);
    sum.map(|x| x / n)
}

/// A polygon's area vector by Newell's rule (its normal by the right-hand rule of its order,
/// its length the area for a planar polygon).
pub fn area_vector(points: &[[f64; 3]]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for (k, &p) in points.iter().enumerate() {
        let c = cross(p, points[(k + 1) % points.len()]);
        n = [n[0] + 0.5 * c[0], n[1] + 0.5 * c[1], n[2] + 0.5 * c[2]];
    }
    n
}
