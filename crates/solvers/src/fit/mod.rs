//! Least-squares fits shared by the solvers' post-processing (contact edges, the stick zone) and
//! the convergence tests (observed rates), and the consistent recovery of a mesh's contact fields
//! from their multipliers ([`recovery`]).
//!
//! | file | concept |
//! |---|---|
//! | this file | the least-squares line, the √-edge of a field along a ray, a triangle's area |
//! | [`profile`] | c and p0 of a radial profile from nodal ring forces |
//! | [`recovery`] | a mesh's contact fields recovered from their multipliers (hat averages) |
//! | [`surface`] | c and p0 of scattered nodes on triangles (second moment) |
//! | [`stick`] | the stick radius and the stick zone's semi-axes, for every layout |

pub mod profile;
pub mod recovery;
pub mod stick;
pub mod surface;

/// A straight line y = ȳ + slope (x − x̄) fitted by least squares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    /// Mean of the abscissae x̄.
    pub mean_x: f64,
    /// Mean of the ordinates ȳ.
    pub mean_y: f64,
    /// Slope Σ(x − x̄)(y − ȳ) / Σ(x − x̄)².
    pub slope: f64,
}

impl Line {
    /// The least-squares line through `points` (x, y); `None` with fewer than two distinct x.
    pub fn fit(points: &[(f64, f64)]) -> Option<Self> {
        let n = points.len() as f64;
        let mean_x = points.iter().map(|p| p.0).sum::<f64>() / n;
        let mean_y = points.iter().map(|p| p.1).sum::<f64>() / n;
        let sxy: f64 = points.iter().map(|(x, y)| (x - mean_x) * (y - mean_y)).sum();
        let sxx: f64 = points.iter().map(|(x, _)| (x - mean_x).powi(2)).sum();
        (points.len() >= 2 && sxx > 0.0).then(|| Line {
            mean_x,
            mean_y,
            slope: sxy / sxx,
        })
    }

    /// Where the line crosses y = 0; `None` if it is flat.
    pub fn zero(&self) -> Option<f64> {
        (self.slope != 0.0).then(|| self.mean_x - self.mean_y / self.slope)
    }
}

/// Where a field that vanishes like a square root at an edge reaches zero, from samples
/// (r, value) along a ray from the centre outward, every value positive.
///
/// Near the edge of a smooth non-conforming contact p ∝ √(c − r) (Johnson 1985, §5.1), and for
/// Hertz p² = p0² (1 − r²/c²) exactly; Cattaneo's stick-zone deficit μp − |q| is
/// μp0 (c_s/c) √(1 − r²/c_s²) (Johnson 1985, eq. 7.38). So a least-squares line of value²
/// against r² through the outer half of the samples meets zero at the edge: sub-sample
/// resolution, where counting whole samples is first order and noisy. `None` with fewer than
/// two samples in the outer half, or a line that does not fall.
pub fn square_root_edge(samples: &[(f64, f64)]) -> Option<f64> {
    let outer = &samples[samples.len() / 2..];
    if outer.len() < 2 {
        return None;
    }
    let points: Vec<(f64, f64)> = outer.iter().map(|&(r, v)| (r * r, v * v)).collect();
    Some(
        Line::fit(&points)
            .filter(|l| l.slope < 0.0)?
            .zero()?
            .max(0.0)
            .sqrt(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_root_edge_is_exact_on_a_hertz_profile() {
        // p = √(1 − r²/c²) sampled every 0.07 c: the fit returns c to rounding.
        let c = 0.9;
        let samples: Vec<(f64, f64)> = (0..13)
            .map(|k| k as f64 * 0.07 * c)
            .map(|r| (r, (1.0 - (r / c).powi(2)).sqrt()))
            .collect();
        assert!((square_root_edge(&samples).unwrap() - c).abs() < 1e-12);
        assert_eq!(square_root_edge(&samples[..2]), None, "too few samples");
    }

    #[test]
    fn recovers_a_line_and_its_zero() {
        let line = Line::fit(&[(1.0, -1.0), (2.0, 1.0), (3.0, 3.0)]).unwrap();
        assert!((line.slope - 2.0).abs() < 1e-15);
        assert!((line.zero().unwrap() - 1.5).abs() < 1e-15);
        assert!(Line::fit(&[(1.0, 1.0)]).is_none());
        assert!(Line::fit(&[(1.0, 1.0), (1.0, 2.0)]).is_none());
    }
}
