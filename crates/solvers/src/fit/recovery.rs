//! The consistent recovery of a contact field from its multipliers: hat averages rather than
//! nodal values, and the transverse traction's share measured on them.
//!
//! A mesh solver's contact multipliers (fem-3d's corner rule, the 3D deck's sub-triangles) are
//! not samples of the traction: a point's unknown stands for its hat's share of the traction,
//! and the field v_h = Σ_j v_j φ_j they define reproduces the traction's averages over the hats,
//! ∫ φ_i v_h dA ≈ ∫ φ_i v dA. Its nodal values overshoot where v is not smooth on the scale of a
//! hat: by O(h²) at a concave extremum (the peak pressure, [`super::surface::peak_by_moments`]),
//! and by an amount that does not fall with h at the stick zone's edge, where Cattaneo's stick
//! deficit μp − |q| opens like √(c_s − r) (Johnson 1985, eq. 7.38). There fem-3d puts a one-point
//! spike into q_y, the component that |q| ≤ μp leaves room for: at the paper's position 5 its
//! largest |q_y| is a single point at r ≈ c_s, 6–25 times its neighbours' mean, whose value
//! wanders with the mesh and the increments (max|q_y|/max|q_x| 0.056–0.12 from c_max/6 to
//! c_max/14) while the BEM's pointwise ratio is converged (0.0495, 0.0492, 0.0492 on 64², 128²,
//! 256² panels) with its largest |q_y| in the slip annulus at r ≈ 0.78 c
//! (`examples/fem3d_transverse.rs`). The hat averages v̄_i = ∫ φ_i v_h dA / ∫ φ_i dA are the
//! quantities the rule determines; their maximum converges (see [`transverse_ratio`]).

/// The hat averages v̄_i = ∫ φ_i v_h dA / ∫ φ_i dA of the field v_h = Σ_j v_j φ_j, linear on
/// `triangles` (indices into `points`, (x, y) [m]). On a triangle T, ∫_T φ_i φ_k dA =
/// |T| (1 + δ_ik)/12 and ∫_T φ_i dA = |T|/3, so v̄_i = Σ_T |T| (v_i + Σ_{k∈T} v_k)/12 / Σ_T |T|/3;
/// points in no triangle keep their value.
pub fn hat_averages(points: &[[f64; 2]], triangles: &[[usize; 3]], values: &[f64]) -> Vec<f64> {
    let (mut sum, mut weight) = (vec![0.0; values.len()], vec![0.0; values.len()]);
    for t in triangles {
        let area = spherecontact_model::history::triangle_area(t.map(|i| points[i]));
        let total: f64 = t.iter().map(|&k| values[k]).sum();
        for &i in t {
            sum[i] += area / 12.0 * (values[i] + total);
            weight[i] += area / 3.0;
        }
    }
    (0..values.len())
        .map(|i| {
            if weight[i] > 0.0 {
                sum[i] / weight[i]
            } else {
                values[i]
            }
        })
        .collect()
}

/// max|q̄_y| / max|q̄_x| over the contact (p > 0): the transverse traction's share, on the hat
/// averages of a map linear on `triangles`, or on the values themselves for a grid of panels
/// (`triangles` `None`: a panel's value is already its average). Outside the contact the
/// traction counts as zero. `None` without traction along x.
///
/// Converged where the pointwise ratio is not (`examples/fem3d_transverse.rs`, position 5,
/// 10 increments a segment unless said): fem-3d 0.0488, 0.0498, 0.0504 at c_max/8, /10, /14
/// (0.0490, 0.0498, 0.0502 at c_max/10 with 5, 10, 20 increments; the BEM moves alike, 0.0487,
/// 0.0492, 0.0496); the BEM 0.0495, 0.0492, 0.0492 on 64², 128², 256² panels.
pub fn transverse_ratio(
    points: &[[f64; 2]],
    triangles: Option<&[[usize; 3]]>,
    traction: &[[f64; 2]],
    pressure: &[f64],
) -> Option<f64> {
    let component = |a: usize| -> Vec<f64> {
        let v: Vec<f64> = traction
            .iter()
            .zip(pressure)
            .map(|(q, &p)| if p > 0.0 { q[a] } else { 0.0 })
            .collect();
        match triangles {
            Some(t) => hat_averages(points, t, &v),
            None => v,
        }
    };
    let largest = |v: Vec<f64>| {
        v.iter()
            .zip(pressure)
            .filter(|(_, &p)| p > 0.0)
            .fold(0.0, |m: f64, (x, _)| m.max(x.abs()))
    };
    let (x, y) = (largest(component(0)), largest(component(1)));
    (x > 0.0).then(|| y / x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles on the unit square.
    fn square() -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
        (
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![[0, 1, 2], [0, 2, 3]],
        )
    }

    #[test]
    fn hat_averages_keep_linear_fields_where_the_hats_are_whole_and_average_a_spike() {
        let (points, triangles) = square();
        // A constant is kept everywhere (rows of the mass matrix over its lumped diagonal sum
        // to one).
        let constant = hat_averages(&points, &triangles, &[2.0; 4]);
        assert!(constant.iter().all(|v| (v - 2.0).abs() < 1e-15), "{constant:?}");
        // A one-point spike v = δ_i0: point 0 lies in both triangles (area ½ each), so
        // v̄_0 = 2 (½ · 2/12) / (2 · ½/3) = ½; point 1 shares one triangle with it:
        // (½ · 1/12) / (½/3) = ¼.
        let spike = hat_averages(&points, &triangles, &[1.0, 0.0, 0.0, 0.0]);
        assert!(
            (spike[0] - 0.5).abs() < 1e-15 && (spike[1] - 0.25).abs() < 1e-15,
            "{spike:?}"
        );
    }

    #[test]
    fn the_transverse_ratio_reads_averages_on_a_mesh_and_values_on_a_grid() {
        let (points, triangles) = square();
        // q_x = 1 everywhere, q_y a spike of 0.2 at point 0: on the mesh the spike is averaged
        // (0.2 · ½ = 0.1), on a grid it is read as it is; no contact, no ratio.
        let traction = [[1.0, 0.2], [1.0, 0.0], [1.0, 0.0], [1.0, 0.0]];
        let pressure = [1.0; 4];
        let mesh = transverse_ratio(&points, Some(&triangles), &traction, &pressure).unwrap();
        assert!((mesh - 0.1).abs() < 1e-15, "{mesh}");
        let grid = transverse_ratio(&points, None, &traction, &pressure).unwrap();
        assert!((grid - 0.2).abs() < 1e-15, "{grid}");
        assert_eq!(transverse_ratio(&points, None, &traction, &[0.0; 4]), None);
    }
}
