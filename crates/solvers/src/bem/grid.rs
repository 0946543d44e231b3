//! The square grid of constant-traction panels on the contact plane.
//!
//! `n × n` square panels of side `h`. Panel (ix, iy) has its centre (collocation point) at
//! x = (ix − n/2) h, y = (iy − n/2) h, so the contact centre (the origin) is the centre of panel
//! (n/2, n/2) and the peak pressure is sampled where it occurs; for even `n` the window reaches
//! one panel further on the negative side than on the positive. Fields are stored row-major in y:
//! index k = iy · n + ix.

/// A square grid of `n × n` panels of side `h`, centred on the contact centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// Panels along each side.
    pub n: usize,
    /// Panel side h [m].
    pub h: f64,
}

impl Grid {
    /// A grid of `n × n` panels covering at least `half_width` [m] on each side of the centre.
    pub fn covering(n: usize, half_width: f64) -> Self {
        // The positive side reaches (n/2 − 1/2) h: make that the half-width.
        let reach = (n / 2) as f64 - 0.5;
        Self {
            n,
            h: half_width / reach,
        }
    }

    /// The number of panels, n².
    pub fn len(&self) -> usize {
        self.n * self.n
    }

    /// True for a grid without panels.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// The panel area h² [m²].
    pub fn panel_area(&self) -> f64 {
        self.h * self.h
    }

    /// The centre coordinate of panel index `i` along one axis [m].
    pub fn coordinate(&self, i: usize) -> f64 {
        (i as f64 - (self.n / 2) as f64) * self.h
    }

    /// The centre (x, y) of panel `k` [m].
    pub fn centre(&self, k: usize) -> [f64; 2] {
        [self.coordinate(k % self.n), self.coordinate(k / self.n)]
    }

    /// Every panel centre, in field order.
    pub fn centres(&self) -> Vec<[f64; 2]> {
        (0..self.len()).map(|k| self.centre(k)).collect()
    }

    /// True for a panel on the outermost ring of the window.
    pub fn is_on_edge(&self, k: usize) -> bool {
        let (ix, iy) = (k % self.n, k / self.n);
        ix == 0 || iy == 0 || ix + 1 == self.n || iy + 1 == self.n
    }

    /// The index of the centre panel (the contact centre).
    pub fn centre_index(&self) -> usize {
        (self.n / 2) * self.n + self.n / 2
    }

    /// The radius of a disc with the area of `panels` panels [m]: how contact and stick zones,
    /// counted in panels, are reported as radii.
    pub fn equivalent_radius(&self, panels: usize) -> f64 {
        (panels as f64 * self.panel_area() / std::f64::consts::PI).sqrt()
    }

    /// The bilinear interpolant at `point` [m] of `field` (one value a panel centre), zero beyond
    /// the outermost centres (a contact field vanishes at the window's edge).
    pub fn interpolate(&self, field: &[f64], [x, y]: [f64; 2]) -> f64 {
        let half = (self.n / 2) as f64;
        // Position in panel-index units; the four centres around it and the weights.
        let (u, v) = (x / self.h + half, y / self.h + half);
        let (iu, iv) = (u.floor(), v.floor());
        let (fu, fv) = (u - iu, v - iv);
        let value = |i: f64, j: f64| {
            let inside = (0.0..self.n as f64).contains(&i) && (0.0..self.n as f64).contains(&j);
            if inside {
                field[j as usize * self.n + i as usize]
            } else {
                0.0
            }
        };
        (1.0 - fv) * ((1.0 - fu) * value(iu, iv) + fu * value(iu + 1.0, iv))
            + fv * ((1.0 - fu) * value(iu, iv + 1.0) + fu * value(iu + 1.0, iv + 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_origin_is_a_panel_centre_and_the_window_covers_the_half_width() {
        let grid = Grid::covering(8, 1.0);
        assert_eq!(grid.centre(grid.centre_index()), [0.0, 0.0]);
        let last = grid.coordinate(7) + 0.5 * grid.h;
        let first = grid.coordinate(0) - 0.5 * grid.h;
        assert!((last - 1.0).abs() < 1e-12 && first < -1.0);
        assert!(grid.is_on_edge(0) && grid.is_on_edge(63) && !grid.is_on_edge(9));
    }

    #[test]
    fn interpolation_is_exact_for_a_linear_field_inside_and_zero_beyond_the_centres() {
        let grid = Grid::covering(8, 1.0);
        let linear = |[x, y]: [f64; 2]| 2.0 + 3.0 * x - 0.5 * y;
        let field: Vec<f64> = grid.centres().into_iter().map(linear).collect();
        let (first, last) = (grid.coordinate(0), grid.coordinate(7));
        for point in [[0.1, -0.2], [first, last], [0.5 * (first + last), 0.33]] {
            let value = grid.interpolate(&field, point);
            assert!((value - linear(point)).abs() < 1e-12, "{point:?}: {value}");
        }
        assert_eq!(grid.interpolate(&field, [last + grid.h, 0.0]), 0.0);
        assert_eq!(grid.interpolate(&field, [0.0, first - grid.h]), 0.0);
    }
}
