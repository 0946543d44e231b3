//! The contact surface's nodal state that the 3D deck writes at every computed step
//! (`surface.csv`: the candidate nodes of the half surface y ≥ 0, P2 vertices and midside nodes),
//! and what is measured from it.
//!
//! The deck applies contact by nodal quadrature: node i carries the force ω_i p_i (ω_i its lumped
//! area, see docs/external-decks.md), and the half model's forces are doubled for the whole sphere.
//! Measures, all from the nodes in contact (p > 0):
//! - contact radius c and peak pressure p0 from a least-squares fit of the Hertz form
//!   p² = p0² (1 − r²/c²), linear in r² (the form the axisymmetric decks fit at the edge);
//! - the stick radius: midway between the innermost slipping node and the farthest sticking node
//!   inside it (c when none slips, 0 when the innermost node in contact slips): the radius of
//!   the largest centred disc that sticks, within half a node spacing.
//!
//! Units: the file is in mm, MPa; [`Node3`] is SI.

use super::readback;
use crate::history::{SurfaceField, TangentialComponents};

/// The columns of the 3D `surface.csv`, in order.
pub const SURFACE3_COLUMNS: [&str; 11] = [
    "step",
    "x_mm",
    "y_mm",
    "weight_mm2",
    "gap_mm",
    "p_MPa",
    "qx_MPa",
    "qy_MPa",
    "stick",
    "slip_x_mm",
    "slip_y_mm",
];

/// One candidate contact node at one step, SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node3 {
    /// Position (x, y) on the contact plane [m], y ≥ 0.
    pub point: [f64; 2],
    /// Nodal quadrature weight (lumped area) [m²].
    pub weight: f64,
    /// Height of the deformed surface above the contact plane [m] (negative: penetration).
    pub gap: f64,
    /// Contact pressure [Pa].
    pub pressure: f64,
    /// Tangential traction (q_x, q_y) on body 1 [Pa], signed so that ∫ q_x dA = Q.
    pub traction: [f64; 2],
    /// In contact and sticking.
    pub stick: bool,
    /// Relative displacement of the two surfaces (body 1 − body 2) [m].
    pub slip: [f64; 2],
}

impl Node3 {
    /// Distance from the pole [m].
    pub fn r(&self) -> f64 {
        self.point[0].hypot(self.point[1])
    }
}

/// The candidate nodes of one computed step.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface3 {
    /// The path step.
    pub step: usize,
    /// The nodes, in the deck's order (the same at every step).
    pub nodes: Vec<Node3>,
}

/// Contact radius and peak pressure of one step (see the module doc).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Measures3 {
    /// Contact radius [m].
    pub contact_radius: Option<f64>,
    /// Peak pressure p0 [Pa].
    pub peak_pressure: Option<f64>,
}

impl Surface3 {
    /// c and p0 from the least-squares fit of p² = a − b r² over the nodes in contact.
    pub fn measures(&self) -> Measures3 {
        let points: Vec<(f64, f64)> = self
            .nodes
            .iter()
            .filter(|n| n.pressure > 0.0)
            .map(|n| (n.r() * n.r(), n.pressure * n.pressure))
            .collect();
        if points.len() < 3 {
            return Measures3::default();
        }
        // p² = a − b r²: the shared least-squares line of p² against r² ([`crate::fit::Line`]).
        let Some(line) = crate::fit::Line::fit(&points) else {
            return Measures3::default();
        };
        let (slope, a) = (line.slope, line.mean_y - line.slope * line.mean_x);
        if !(slope < 0.0 && a > 0.0) {
            return Measures3::default();
        }
        Measures3 {
            contact_radius: Some((a / -slope).sqrt()),
            peak_pressure: Some(a.sqrt()),
        }
    }

    /// The stick radius (see the module doc), for a step in contact of radius `contact_radius`.
    pub fn stick_radius(&self, contact_radius: f64) -> f64 {
        let in_contact = self.nodes.iter().filter(|n| n.pressure > 0.0);
        let Some(r_slip) = in_contact
            .clone()
            .filter(|n| !n.stick)
            .map(Node3::r)
            .min_by(f64::total_cmp)
        else {
            return contact_radius;
        };
        in_contact
            .filter(|n| n.stick && n.r() < r_slip)
            .map(Node3::r)
            .max_by(f64::total_cmp)
            .map_or(0.0, |r_stick| 0.5 * (r_stick + r_slip))
    }

    /// P by the nodal rule, 2 Σ ω p over the half surface [N].
    pub fn normal_force(&self) -> f64 {
        2.0 * self.nodes.iter().map(|n| n.weight * n.pressure).sum::<f64>()
    }

    /// Whether a node within `band` of the outermost candidate carries pressure: the contact may
    /// reach beyond the candidate zone.
    pub fn edge_loaded(&self, band: f64) -> bool {
        let outer = self.nodes.iter().map(Node3::r).fold(0.0, f64::max);
        self.nodes
            .iter()
            .any(|n| n.pressure > 0.0 && n.r() >= outer - band)
    }

    /// The surface field at path position `position` on the whole contact plane: the half
    /// surface and its mirror image in y = 0 (p, q_x and slip_x even, q_y and slip_y odd in y);
    /// traction, status and slip when the tangential problem was solved.
    pub fn field(&self, position: usize, tangential: bool) -> SurfaceField {
        let mirrored: Vec<(Node3, f64)> = self
            .nodes
            .iter()
            .flat_map(|n| {
                let image = (n.point[1] > 0.0).then_some((*n, -1.0));
                std::iter::once((*n, 1.0)).chain(image)
            })
            .collect();
        SurfaceField {
            position,
            points: mirrored
                .iter()
                .map(|(n, s)| [n.point[0], s * n.point[1]])
                .collect(),
            pressure: mirrored.iter().map(|(n, _)| n.pressure).collect(),
            traction: tangential.then(|| {
                mirrored
                    .iter()
                    .map(|(n, s)| [n.traction[0], s * n.traction[1]])
                    .collect()
            }),
            stick: tangential.then(|| mirrored.iter().map(|(n, _)| n.stick).collect()),
            slip: tangential.then(|| mirrored.iter().map(|(n, s)| [n.slip[0], s * n.slip[1]]).collect()),
            components: TangentialComponents::InPlane,
            triangles: None,
        }
    }
}

/// Reads the 3D `surface.csv` from `text`: one block of candidate nodes per computed step, the
/// steps `steps` in order, every block with the same nodes.
///
/// Fails, naming the row and column, on a wrong header, a value that is not a finite number, a
/// step that is not the one expected, blocks of different sizes, or missing blocks.
pub fn parse_surface3(text: &str, steps: &[usize]) -> Result<Vec<Surface3>, String> {
    let records = readback::records(text, "surface.csv", &SURFACE3_COLUMNS)?;
    let mut surfaces: Vec<Surface3> = Vec::with_capacity(steps.len());
    for (k, record) in records.iter().enumerate() {
        let at = |e: String| format!("surface.csv row {}: {e}", k + 1);
        let number = |i: usize, scale: f64| readback::finite(record, &SURFACE3_COLUMNS, i, scale).map_err(at);
        let step: usize = record[0]
            .parse()
            .map_err(|_| at(format!("step = `{}` is not a step index", &record[0])))?;
        let stick = match &record[8] {
            "0" => false,
            "1" => true,
            other => return Err(at(format!("stick = `{other}` is not 0 or 1"))),
        };
        let node = Node3 {
            point: [number(1, 1e-3)?, number(2, 1e-3)?],
            weight: number(3, 1e-6)?,
            gap: number(4, 1e-3)?,
            pressure: number(5, 1e6)?,
            traction: [number(6, 1e6)?, number(7, 1e6)?],
            stick,
            slip: [number(9, 1e-3)?, number(10, 1e-3)?],
        };
        match surfaces.last_mut() {
            Some(s) if s.step == step => s.nodes.push(node),
            _ => {
                let expected = steps.get(surfaces.len()).copied();
                if expected != Some(step) {
                    return Err(at(format!("step {step}, expected {expected:?}")));
                }
                if let Some(previous) = surfaces.last() {
                    let size = surfaces[0].nodes.len();
                    if previous.nodes.len() != size {
                        return Err(at(format!(
                            "step {} has {} nodes, the first step {size}",
                            previous.step,
                            previous.nodes.len()
                        )));
                    }
                }
                surfaces.push(Surface3 {
                    step,
                    nodes: vec![node],
                });
            }
        }
    }
    let size = surfaces.first().map_or(0, |s| s.nodes.len());
    if surfaces.len() != steps.len() || surfaces.iter().any(|s| s.nodes.len() != size) {
        return Err(format!(
            "surface.csv has {} complete step blocks, expected {} (truncated output)",
            surfaces.len(),
            steps.len()
        ));
    }
    Ok(surfaces)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Hertz pressure p0 √(1 − r²/c²) on a polar grid, sticking inside r = c/2.
    fn hertz_surface(c: f64, p0: f64) -> Surface3 {
        let mut nodes = Vec::new();
        for i in 0..=12 {
            let r = 1.3 * c * f64::from(i) / 12.0;
            for j in 0..=4 {
                let theta = std::f64::consts::PI * f64::from(j) / 4.0;
                let p = p0 * (1.0 - (r / c).powi(2)).max(0.0).sqrt();
                nodes.push(Node3 {
                    point: [r * theta.cos(), r * theta.sin()],
                    weight: 1e-8,
                    gap: 0.0,
                    pressure: p,
                    traction: [0.2 * p, 0.01 * p * theta.sin()],
                    stick: p > 0.0 && r < 0.5 * c,
                    slip: [0.0, 0.0],
                });
                if i == 0 {
                    break;
                }
            }
        }
        Surface3 { step: 3, nodes }
    }

    #[test]
    fn the_fit_recovers_a_hertz_profile_and_the_stick_radius_lies_between_rings() {
        let (c, p0) = (1e-3, 4.5e8);
        let s = hertz_surface(c, p0);
        let m = s.measures();
        // p² is exactly linear in r² on the nodes in contact: the fit is exact to round-off.
        assert!((m.contact_radius.unwrap() - c).abs() < 1e-9 * c, "{m:?}");
        assert!((m.peak_pressure.unwrap() - p0).abs() < 1e-6 * p0, "{m:?}");
        // rings every 0.1083 c: the last sticking ring is at 0.433 c, the first slipping at 0.542 c
        let ring = 1.3 * c / 12.0;
        assert!((s.stick_radius(c) - 4.5 * ring).abs() < 1e-12);
    }

    #[test]
    fn the_field_mirrors_the_half_surface_with_odd_transverse_components() {
        let s = hertz_surface(1e-3, 4.5e8);
        let f = s.field(5, true);
        let off_plane = s.nodes.iter().filter(|n| n.point[1] > 0.0).count();
        assert_eq!(f.points.len(), s.nodes.len() + off_plane);
        let q = f.traction.unwrap();
        let sum_qy: f64 = q.iter().map(|t| t[1]).sum();
        assert!(sum_qy.abs() < 1e-6, "q_y is odd in y: {sum_qy}");
        assert!(f.points.iter().any(|p| p[1] < 0.0));
    }

    #[test]
    fn a_truncated_or_garbled_surface_file_is_refused_with_its_row() {
        let header = SURFACE3_COLUMNS.join(",");
        let row = |step: usize| format!("{step},0.0,0.0,1e-3,0.0,10.0,1.0,0.0,1,0.0,0.0\n");
        let good = format!("{header}\n{}{}", row(0), row(1));
        assert_eq!(parse_surface3(&good, &[0, 1]).unwrap().len(), 2);
        let truncated = format!("{header}\n{}", row(0));
        assert!(parse_surface3(&truncated, &[0, 1])
            .unwrap_err()
            .contains("truncated"));
        let garbled = format!("{header}\n{}", row(0).replace("10.0", "nan"));
        let e = parse_surface3(&garbled, &[0]).unwrap_err();
        assert!(e.contains("row 1") && e.contains("p_MPa"), "{e}");
    }
}
