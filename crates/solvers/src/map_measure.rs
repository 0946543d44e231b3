//! The measures of a surface map that checks and reports share: the transverse traction's share
//! max|q̄_y| / max|q̄_x| and the stick zone's semi-axes, on the areas the field's
//! [`Layout`] gives its samples. A case's checks (`transverse_ratio`,
//! `stick_semi_axis_x`, `stick_semi_axis_y`, `spherecontact-check`) and the report's map measures
//! (`report::claims::measure`) read them here, so each is computed once.

use spherecontact_model::history::{Layout, Quantity, SurfaceField, TangentialComponents};

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
    if field.layout == Layout::Profile || field.components != TangentialComponents::InPlane {
        return None;
    }
    crate::fit::recovery::transverse_ratio(&field.points, field.layout.triangles(), traction, &field.pressure)
}

/// The stick zone's semi-axes along x and y [m] from its area-weighted second moments
/// ([`crate::fit::stick::semi_axes`]); `None` for a profile, a field without stick status or
/// with no point sticking.
pub fn stick_semi_axes(field: &SurfaceField) -> Option<[f64; 2]> {
    let stick = field.stick.as_ref()?;
    let areas = field.layout.areas(&field.points)?;
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
            layout: Layout::Grid { spacing: 1.0 },
            ..SurfaceField::default()
        }
    }

    #[test]
    fn a_grid_gives_its_ratio_and_semi_axes_and_a_profile_none() {
        let field = grid();
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
