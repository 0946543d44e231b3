//! Least-squares fits shared by the solvers' post-processing (contact edges) and the
//! convergence tests (observed rates).

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_line_and_its_zero() {
        let line = Line::fit(&[(1.0, -1.0), (2.0, 1.0), (3.0, 3.0)]).unwrap();
        assert!((line.slope - 2.0).abs() < 1e-15);
        assert!((line.zero().unwrap() - 1.5).abs() < 1e-15);
        assert!(Line::fit(&[(1.0, 1.0)]).is_none());
        assert!(Line::fit(&[(1.0, 1.0), (1.0, 2.0)]).is_none());
    }
}
