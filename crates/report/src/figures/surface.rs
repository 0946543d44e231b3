//! The one adapter between the solvers' surface fields ([`SurfaceField`]) and the report: every
//! figure and every claim reads a field through [`FieldView`], by its layout (a profile along x,
//! grid panels, or the triangles of a surface mesh: the field's [`Layout`]), so a change of `SurfaceField` is an edit of this file and that one.
//!
//! Frame (as in `SurfaceField`): origin at the contact centre, x along δt, y across it; the
//! traction is the one on body 1, signed so that ∫ q_x dA = Q.

pub use spherecontact_model::history::Layout;
use spherecontact_model::history::{History, SurfaceField, TangentialComponents};

/// A half-axis of the contact plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HalfAxis {
    /// x ≥ 0, y = 0 (along the shift).
    X,
    /// x = 0, y ≥ 0 (across it).
    Y,
    /// x ≤ 0, y = 0.
    MinusX,
    /// x = 0, y ≤ 0.
    MinusY,
}

impl HalfAxis {
    /// (distance along the half-axis, distance from its line) of a point.
    fn coordinates(self, p: [f64; 2]) -> (f64, f64) {
        match self {
            HalfAxis::X => (p[0], p[1]),
            HalfAxis::Y => (p[1], p[0]),
            HalfAxis::MinusX => (-p[0], p[1]),
            HalfAxis::MinusY => (-p[1], p[0]),
        }
    }

    /// The point at distance `r` along the half-axis.
    fn point(self, r: f64) -> [f64; 2] {
        match self {
            HalfAxis::X => [r, 0.0],
            HalfAxis::Y => [0.0, r],
            HalfAxis::MinusX => [-r, 0.0],
            HalfAxis::MinusY => [0.0, -r],
        }
    }
}

/// A point of a field: a weighted combination of samples (one sample on a grid or a profile,
/// a triangle's three corners on a mesh), at distance `r` [m] from the centre.
#[derive(Clone, Debug, PartialEq)]
pub struct Probe {
    /// The distance from the contact centre [m].
    pub r: f64,
    /// (sample, weight) pairs, weights summing to 1.
    weights: Vec<(usize, f64)>,
}

/// One solver's surface field at one path position, read by layout.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldView<'a> {
    field: &'a SurfaceField,
}

impl<'a> FieldView<'a> {
    /// The view of `field`.
    pub fn of(field: &'a SurfaceField) -> Self {
        Self { field }
    }

    /// How the samples cover the plane.
    pub fn layout(&self) -> &'a Layout {
        &self.field.layout
    }

    /// The views of every field of `history`, in its order.
    pub fn all(history: &'a History) -> impl Iterator<Item = FieldView<'a>> {
        history.fields.iter().map(Self::of)
    }

    /// The path position.
    pub fn position(&self) -> usize {
        self.field.position
    }

    /// The view of `history`'s field at path position `position`, if it has one.
    pub fn at_position(history: &'a History, position: usize) -> Option<Self> {
        history.field_at(position).map(Self::of)
    }

    /// True when the field covers the plane (a grid or triangles), not only the x axis.
    pub fn is_map(&self) -> bool {
        *self.layout() != Layout::Profile
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.field.points.len()
    }

    /// True without samples.
    pub fn is_empty(&self) -> bool {
        self.field.points.is_empty()
    }

    /// Sample `i`'s position (x, y) [m].
    pub fn point(&self, i: usize) -> [f64; 2] {
        self.field.points[i]
    }

    /// The contact pressure p [Pa] at sample `i`.
    pub fn pressure(&self, i: usize) -> f64 {
        self.field.pressure[i]
    }

    /// True where sample `i` is in contact (p > 0).
    pub fn in_contact(&self, i: usize) -> bool {
        self.field.pressure[i] > 0.0
    }

    /// True when the solver resolves the frictional traction.
    pub fn has_traction(&self) -> bool {
        self.field.traction.is_some()
    }

    /// The traction (q_x, q_y) [Pa] at sample `i`, if resolved.
    pub fn traction(&self, i: usize) -> Option<[f64; 2]> {
        self.field.traction.as_ref().map(|q| q[i])
    }

    /// The slip (relative tangential displacement of the surfaces) [m] at sample `i`, if resolved.
    pub fn slip(&self, i: usize) -> Option<[f64; 2]> {
        self.field.slip.as_ref().map(|s| s[i])
    }

    /// True when the solver resolves the transverse components (q_y, slip_y); false when its
    /// model takes the traction along x, so that their zeros are an assumption, not a result.
    pub fn resolves_transverse(&self) -> bool {
        self.field.components == TangentialComponents::InPlane
    }

    /// The transverse traction q_y [Pa] at sample `i`, if the solver resolves it.
    pub fn traction_y(&self, i: usize) -> Option<f64> {
        self.traction(i)
            .filter(|_| self.resolves_transverse())
            .map(|q| q[1])
    }

    /// The transverse slip [m] at sample `i`, if the solver resolves it.
    pub fn slip_y(&self, i: usize) -> Option<f64> {
        self.slip(i).filter(|_| self.resolves_transverse()).map(|s| s[1])
    }

    /// Stick (true) or slip at sample `i`, if resolved.
    pub fn stick(&self, i: usize) -> Option<bool> {
        self.field.stick.as_ref().map(|s| s[i])
    }

    /// The sample spacing [m]: the panel side, the mean edge of the mesh, or the profile's step:
    /// the resolution of any position read from the field.
    pub fn spacing(&self) -> f64 {
        match self.layout() {
            Layout::Grid { spacing } => *spacing,
            Layout::Profile => smallest_spacing(self.field.points.iter().map(|p| p[0])),
            Layout::Triangles(triangles) => {
                let edges: Vec<f64> = triangles
                    .iter()
                    .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
                    .map(|(a, b)| distance(self.point(a), self.point(b)))
                    .collect();
                edges.iter().sum::<f64>() / edges.len().max(1) as f64
            }
        }
    }

    /// Probes along a half-axis, from the centre out: the samples on the axis for a grid (the row
    /// or column through the centre) and a profile (the same on y as on x: axisymmetric);
    /// interpolation in the triangles the axis crosses, every half mesh size, for a mesh.
    pub fn along(&self, axis: HalfAxis) -> Vec<Probe> {
        match self.layout() {
            Layout::Profile => self.row(|p| HalfAxis::X.coordinates(p)),
            Layout::Grid { .. } => self.row(|p| axis.coordinates(p)),
            Layout::Triangles(triangles) => {
                // Probes every half mesh size, and one at the mesh's edge.
                let step = 0.5 * self.spacing();
                let reach = (0..self.len())
                    .map(|i| axis.coordinates(self.point(i)).0)
                    .fold(0.0, f64::max);
                let steps = (reach / step).floor() as usize;
                (0..=steps)
                    .map(|k| k as f64 * step)
                    .chain((reach > steps as f64 * step).then_some(reach))
                    .filter_map(|r| {
                        let weights = self.locate(triangles, axis.point(r))?;
                        Some(Probe { r, weights })
                    })
                    .collect()
            }
        }
    }

    /// The area each sample stands for [m²] (a panel's, or a third of the triangles around a
    /// vertex); `None` for a profile.
    pub fn areas(&self) -> Option<Vec<f64>> {
        self.layout().areas(&self.field.points)
    }

    /// The field viewed.
    pub fn field(&self) -> &'a SurfaceField {
        self.field
    }

    /// The samples nearest the line t = 0 with s ≥ 0, where (s, t) = `coordinates(point)`,
    /// sorted by s.
    fn row(&self, coordinates: impl Fn([f64; 2]) -> (f64, f64)) -> Vec<Probe> {
        let nearest = (0..self.len())
            .map(|i| coordinates(self.point(i)).1.abs())
            .fold(f64::INFINITY, f64::min);
        let mut probes: Vec<Probe> = (0..self.len())
            .filter_map(|i| {
                let (s, t) = coordinates(self.point(i));
                (t.abs() == nearest && s >= 0.0).then(|| Probe {
                    r: s,
                    weights: vec![(i, 1.0)],
                })
            })
            .collect();
        probes.sort_by(|a, b| a.r.total_cmp(&b.r));
        probes
    }

    /// Barycentric weights of `at` in the triangle containing it, if any.
    fn locate(&self, triangles: &[[usize; 3]], at: [f64; 2]) -> Option<Vec<(usize, f64)>> {
        triangles.iter().find_map(|t| {
            let [a, b, c] = t.map(|i| self.point(i));
            let det = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]);
            if det == 0.0 {
                return None;
            }
            let l0 = ((b[1] - c[1]) * (at[0] - c[0]) + (c[0] - b[0]) * (at[1] - c[1])) / det;
            let l1 = ((c[1] - a[1]) * (at[0] - c[0]) + (a[0] - c[0]) * (at[1] - c[1])) / det;
            let l2 = 1.0 - l0 - l1;
            let eps = -1e-9;
            (l0 >= eps && l1 >= eps && l2 >= eps).then(|| vec![(t[0], l0), (t[1], l1), (t[2], l2)])
        })
    }

    /// A sample quantity at a probe, interpolated with the probe's weights.
    pub fn at(&self, probe: &Probe, value: impl Fn(usize) -> Option<f64>) -> Option<f64> {
        probe.weights.iter().map(|&(i, w)| value(i).map(|v| w * v)).sum()
    }

    /// The probe's nearest sample (largest weight): where a category (stick/slip) is read.
    pub fn nearest(&self, probe: &Probe) -> usize {
        probe
            .weights
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(0, |&(i, _)| i)
    }

    /// The triangles, for a mesh.
    pub fn triangles(&self) -> Option<&[[usize; 3]]> {
        self.layout().triangles()
    }
}

/// The distance between two points [m].
fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The smallest positive spacing between coordinates [m] (0 with fewer than two).
fn smallest_spacing(coordinates: impl Iterator<Item = f64>) -> f64 {
    let mut xs: Vec<f64> = coordinates.collect();
    xs.sort_by(f64::total_cmp);
    let smallest = xs
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    if smallest.is_finite() {
        smallest
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> SurfaceField {
        let points: Vec<[f64; 2]> = (0..16)
            .map(|k| [((k % 4) as f64 - 2.0) * 0.5, ((k / 4) as f64 - 2.0) * 0.5])
            .collect();
        SurfaceField {
            position: 1,
            pressure: points.iter().map(|p| 1.0 - p[0] * p[0] - p[1] * p[1]).collect(),
            traction: Some(points.iter().map(|p| [p[0], p[1]]).collect()),
            stick: None,
            slip: None,
            components: TangentialComponents::InPlane,
            points,
            layout: Layout::Grid { spacing: 0.5 },
        }
    }

    #[test]
    fn a_grid_is_read_along_its_centre_row_and_column() {
        let field = grid();
        let view = FieldView::of(&field);
        let x: Vec<f64> = view.along(HalfAxis::X).iter().map(|p| p.r).collect();
        assert_eq!(x, vec![0.0, 0.5]);
        let y = view.along(HalfAxis::Y);
        let q_y: Vec<f64> = y
            .iter()
            .map(|p| view.at(p, |i| view.traction(i).map(|q| q[1])).unwrap())
            .collect();
        assert_eq!(q_y, vec![0.0, 0.5], "the column x = 0 read along y");
    }

    #[test]
    fn a_profile_is_the_same_along_x_and_y() {
        let field = SurfaceField {
            position: 0,
            points: vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]],
            pressure: vec![2.0, 1.0, 0.0],
            traction: None,
            stick: None,
            slip: None,
            components: TangentialComponents::InPlane,
            layout: Layout::Profile,
        };
        let view = FieldView::of(&field);
        assert_eq!(view.along(HalfAxis::X), view.along(HalfAxis::Y));
        assert_eq!(view.spacing(), 1.0);
    }

    #[test]
    fn triangles_are_interpolated_along_the_axes() {
        // Two triangles over the unit square, p = 1 + x + 2y (linear: interpolation is exact).
        let field = SurfaceField {
            position: 0,
            points: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
            pressure: vec![1.0, 2.0, 3.0, 4.0],
            traction: None,
            stick: None,
            slip: None,
            components: TangentialComponents::InPlane,
            layout: Layout::Triangles(vec![[0, 1, 2], [1, 3, 2]]),
        };
        let view = FieldView::of(&field);
        let along_y = view.along(HalfAxis::Y);
        let p: Vec<f64> = along_y
            .iter()
            .map(|probe| view.at(probe, |i| Some(view.pressure(i))).unwrap())
            .collect();
        let expected: Vec<f64> = along_y.iter().map(|probe| 1.0 + 2.0 * probe.r).collect();
        for (a, b) in p.iter().zip(&expected) {
            assert!((a - b).abs() < 1e-12, "{p:?} vs {expected:?}");
        }
        assert!(along_y.len() >= 2);
    }
}
