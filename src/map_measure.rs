//! The measures of a surface map that checks and reports share: how a field's samples cover the
//! contact plane ([`Layout`]), the area each stands for, the transverse traction's share
//! max|q̄_y| / max|q̄_x| and the stick zone's semi-axes. A case's checks (`transverse_ratio`,
//! `stick_semi_axis_x`, `stick_semi_axis_y`, [`crate::check`]) and the report's map measures
//! (`report::claims::measure`) read them here, so each is computed once.

use crate::history::{Quantity, SurfaceField, TangentialComponents};

/// How a field's samples cover the contact plane.
#[derive(Clone, Debug, PartialEq)]
pub enum Layout {
    /// Samples along the x axis of an axisymmetric (or 1D) solution: the same on every radius.
    Profile,
    /// The centres of square panels of side `spacing` [m].
    Grid {
        /// The panel side [m].
        spacing: f64,
    },
    /// The vertices of a triangulated contact surface, values at the vertices.
    Triangles(Vec<[usize; 3]>),
}

impl Layout {
    /// The layout of `field`: its own triangles when it has them (a surface mesh), else samples
    /// all on y = 0 are a profile and anything else a grid of square panels (the BEM's).
    pub fn of(field: &SurfaceField) -> Self {
        if let Some(triangles) = &field.triangles {
            Layout::Triangles(triangles.clone())
        } else if field.points.iter().all(|p| p[1] == 0.0) {
            Layout::Profile
        } else {
            Layout::Grid {
                spacing: smallest_spacing(field.points.iter().map(|p| p[0])),
            }
        }
    }

    /// The area each of `points` stands for [m²] (a panel's, or a third of the triangles around
    /// a vertex); `None` for a profile.
    pub fn areas(&self, points: &[[f64; 2]]) -> Option<Vec<f64>> {
        match self {
            Layout::Profile => None,
            Layout::Grid { spacing } => Some(vec![spacing * spacing; points.len()]),
            Layout::Triangles(triangles) => {
                let mut areas = vec![0.0; points.len()];
                for t in triangles {
                    let [a, b, c] = t.map(|i| points[i]);
                    let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
                    for &i in t {
                        areas[i] += area / 3.0;
                    }
                }
                Some(areas)
            }
        }
    }

    /// The triangles, for a mesh.
    pub fn triangles(&self) -> Option<&[[usize; 3]]> {
        match self {
            Layout::Triangles(t) => Some(t),
            _ => None,
        }
    }
}

/// The smallest positive spacing between coordinates [m] (0 with fewer than two).
pub fn smallest_spacing(coordinates: impl Iterator<Item = f64>) -> f64 {
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

/// `quantity` measured on `field`; `None` for a quantity that is not a map measure, or a field
/// that does not show it (a profile, no traction or stick status, no traction along x, no
/// point sticking).
pub fn measure(quantity: Quantity, field: &SurfaceField) -> Option<f64> {
    match quantity {
        Quantity::TransverseRatio => transverse_ratio(field),
        Quantity::StickSemiAxisX => stick_semi_axes(field).map(|a| a[0]),
        Quantity::StickSemiAxisY => stick_semi_axes(field).map(|a| a[1]),
        _ => None,
    }
}

/// max|q̄_y| / max|q̄_x| over the contact on the values the contact rule determines: hat averages
/// on a mesh, a grid's panel values ([`crate::fit::recovery::transverse_ratio`]); `None` for a
/// profile, a field without traction, one whose model takes the traction along x (its q_y = 0
/// is assumed, not measured) or without traction along x.
pub fn transverse_ratio(field: &SurfaceField) -> Option<f64> {
    let traction = field.traction.as_ref()?;
    let layout = Layout::of(field);
    if layout == Layout::Profile || field.components != TangentialComponents::InPlane {
        return None;
    }
    crate::fit::recovery::transverse_ratio(&field.points, layout.triangles(), traction, &field.pressure)
}

/// The stick zone's semi-axes along x and y [m] from its area-weighted second moments
/// ([`crate::fit::stick::semi_axes`]); `None` for a profile, a field without stick status or
/// with no point sticking.
pub fn stick_semi_axes(field: &SurfaceField) -> Option<[f64; 2]> {
    let stick = field.stick.as_ref()?;
    let areas = Layout::of(field).areas(&field.points)?;
    crate::fit::stick::semi_axes(&field.points, &areas, &field.pressure, stick)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four panels of side 1 around the centre, q = (1, ±0.1), sticking inside.
    fn grid() -> SurfaceField {
        SurfaceField {
            position: 2,
            points: vec![[-0.5, -0.5], [0.5, -0.5], [-0.5, 0.5], [0.5, 0.5]],
            pressure: vec![1.0; 4],
            traction: Some(vec![[1.0, 0.1], [1.0, -0.1], [1.0, -0.1], [1.0, 0.1]]),
            stick: Some(vec![true; 4]),
            ..SurfaceField::default()
        }
    }

    #[test]
    fn a_grid_gives_its_ratio_and_semi_axes_and_a_profile_none() {
        let field = grid();
        assert_eq!(Layout::of(&field), Layout::Grid { spacing: 1.0 });
        assert!((measure(Quantity::TransverseRatio, &field).unwrap() - 0.1).abs() < 1e-15);
        // The panels' centres at ±0.5: ⟨x²⟩ = ¼, a = 2 √¼ = 1 on both axes.
        assert_eq!(measure(Quantity::StickSemiAxisX, &field), Some(1.0));
        assert_eq!(measure(Quantity::StickSemiAxisY, &field), Some(1.0));
        assert_eq!(measure(Quantity::NormalForce, &field), None);
        let along_x = SurfaceField {
            components: TangentialComponents::AlongX,
            ..grid()
        };
        assert_eq!(transverse_ratio(&along_x), None, "q_y assumed, not measured");
        let profile = SurfaceField {
            points: vec![[0.0, 0.0], [1.0, 0.0]],
            pressure: vec![1.0; 2],
            traction: Some(vec![[1.0, 0.0]; 2]),
            stick: Some(vec![true; 2]),
            ..SurfaceField::default()
        };
        assert_eq!(transverse_ratio(&profile), None);
        assert_eq!(stick_semi_axes(&profile), None);
    }
}
