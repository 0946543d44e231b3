//! The contact surface's state that the 3D deck writes at every computed step (`surface.csv`:
//! the contact points of the half surface y ≥ 0, the corners of the candidate faces), and what is
//! measured from it.
//!
//! The deck applies fem-3d's default contact rule (`Rule::Corners`): point j's multiplier
//! ω_j p_j (ω_j = ∫ L_j dA, L_j its linear hat on the faces, see docs/external-decks.md), and the
//! half model's forces are doubled for the whole sphere. The measures (c, p0, the stick zone) are
//! fem-3d's ([`spherecontact_solvers::fit::surface`]) on the same weights; the fields read back in fem-3d's layout
//! (the half's points, their mirror images, the faces: [`Mirror`]).
//!
//! Units: the file is in mm, MPa; [`Node3`] is SI.

use super::readback;
use spherecontact_model::history::{Layout, StepResult, SurfaceField, TangentialComponents};
use spherecontact_model::mirror::Mirror;
use spherecontact_model::scene::Scene;
use spherecontact_solvers::fit::stick::{self, StickZone};
use spherecontact_solvers::fit::surface::{self, Measures};

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

/// One contact point (a face corner) at one step, SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node3 {
    /// Position (x, y) on the contact plane [m], y ≥ 0.
    pub point: [f64; 2],
    /// The point's weight ω = ∫ L dA, L its linear hat on the faces [m²].
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

/// The contact points of one computed step.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface3 {
    /// The path step.
    pub step: usize,
    /// The points, in the deck's order (the same at every step).
    pub nodes: Vec<Node3>,
}

impl Surface3 {
    /// The points' positions on the contact plane (z = 0).
    fn positions(&self) -> Vec<[f64; 3]> {
        self.nodes.iter().map(|n| [n.point[0], n.point[1], 0.0]).collect()
    }

    /// The points' pressures [Pa].
    fn pressures(&self) -> Vec<f64> {
        self.nodes.iter().map(|n| n.pressure).collect()
    }

    /// c and p0 by fem-3d's measures ([`surface::measure`]: c from the pressure's second moment,
    /// integrated over `triangles`, on which the contact rule interpolates p linearly; p0 from the
    /// smooth even fit near the pole).
    pub fn measures(&self, triangles: &[[usize; 3]]) -> Measures {
        surface::measure(&self.positions(), triangles, &self.pressures())
    }

    /// The stick zone of contact radius `contact_radius` by the measure of every solver
    /// ([`stick::stick_zone`]: c √(stick area / contact area) and the semi-axes of the zone's
    /// second moments); `None` when no loaded node sticks.
    pub fn stick_zone(&self, contact_radius: f64) -> Option<StickZone> {
        let points: Vec<[f64; 2]> = self.nodes.iter().map(|n| n.point).collect();
        let weights: Vec<f64> = self.nodes.iter().map(|n| n.weight).collect();
        let flags: Vec<bool> = self.nodes.iter().map(|n| n.stick).collect();
        stick::stick_zone(contact_radius, &points, &weights, &self.pressures(), &flags)
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

    /// Whether each node lies on the symmetry plane y = 0 (within 1e-9 of the surface's extent:
    /// the deck's own test, on coordinates written with 17 digits).
    pub fn on_plane(&self) -> Vec<bool> {
        let extent = self.nodes.iter().map(Node3::r).fold(0.0, f64::max);
        self.nodes
            .iter()
            .map(|n| n.point[1].abs() <= 1e-9 * extent)
            .collect()
    }

    /// The surface field at path position `position` on the whole contact plane, in fem-3d's
    /// layout ([`Mirror`]): the half surface, then the mirror images of its nodes off the plane
    /// (p, q_x and slip_x even, q_y and slip_y odd in y), on the faces `triangles` (indices of
    /// the half's points) and their images; traction, status and slip
    /// when the tangential problem was solved.
    pub fn field(&self, position: usize, tangential: bool, triangles: &[[usize; 3]]) -> SurfaceField {
        let mirror = Mirror::new(&self.on_plane());
        let nodes = &self.nodes;
        let pairs = |f: fn(&Node3) -> [f64; 2]| mirror.odd_y(&nodes.iter().map(f).collect::<Vec<_>>());
        SurfaceField {
            position,
            points: pairs(|n| n.point),
            pressure: mirror.even(&nodes.iter().map(|n| n.pressure).collect::<Vec<_>>()),
            traction: tangential.then(|| pairs(|n| n.traction)),
            stick: tangential.then(|| mirror.even(&nodes.iter().map(|n| n.stick).collect::<Vec<_>>())),
            slip: tangential.then(|| pairs(|n| n.slip)),
            components: TangentialComponents::InPlane,
            layout: Layout::Triangles(mirror.triangles(triangles)),
        }
    }
}

/// One row per step of `scene` (every step computed) from each step's forces (P, Q) [N] and
/// contact surface, and the fields at the positions the case records: c and p0 by
/// [`Surface3::measures`], the stick radius by [`Surface3::stick_zone`] (when `tangential`).
pub fn step_results(
    scene: &Scene,
    tangential: bool,
    forces: &[[f64; 2]],
    surfaces: &[Surface3],
    triangles: &[[usize; 3]],
) -> (Vec<StepResult>, Vec<SurfaceField>) {
    let mut steps = Vec::with_capacity(forces.len());
    let mut fields = Vec::new();
    for ((step, &[normal, shear]), surface) in scene.steps().iter().zip(forces).zip(surfaces) {
        let measures = surface.measures(triangles);
        if let Some(position) = step.position.filter(|&p| scene.records_fields_at(p)) {
            fields.push(surface.field(position, tangential, triangles));
        }
        steps.push(StepResult {
            normal_force: Some(normal),
            tangential_force: tangential.then_some(shear),
            contact_radius: measures.radius,
            peak_pressure: measures.peak,
            stick_radius: (tangential && normal > 0.0).then(|| {
                let c = measures.radius.unwrap_or(0.0);
                surface.stick_zone(c).map_or(0.0, |z| z.radius)
            }),
            ..StepResult::at(step)
        });
    }
    (steps, fields)
}

/// The columns of the 3D deck's `triangles.csv`: the candidate faces, as indices of the contact
/// points of one step's block of `surface.csv`.
pub const TRIANGLE_COLUMNS: [&str; 3] = ["a", "b", "c"];

/// Reads `triangles.csv` from `text` for a surface of `nodes` nodes.
///
/// Fails, naming the line and column, on a wrong header, an index that is not a node of the
/// surface, or a file without triangles.
pub fn parse_triangles(text: &str, nodes: usize) -> Result<Vec<[usize; 3]>, String> {
    let rows = readback::records(text, "triangles.csv", &TRIANGLE_COLUMNS)?;
    let triangles = rows
        .iter()
        .map(|row| {
            let index = |i: usize| {
                row.whole::<usize>(i, "a node index")
                    .and_then(|j| match j < nodes {
                        true => Ok(j),
                        false => Err(row.cell_error(
                            i,
                            format!(
                                "not a node of the surface (allowed: 0 to {})",
                                nodes.saturating_sub(1)
                            ),
                        )),
                    })
            };
            Ok([index(0)?, index(1)?, index(2)?])
        })
        .collect::<Result<Vec<_>, String>>()?;
    if triangles.is_empty() {
        return Err("triangles.csv has no triangles".into());
    }
    Ok(triangles)
}

/// Reads the 3D `surface.csv` from `text`: one block of candidate nodes per computed step, the
/// steps `steps` in order, every block with the same nodes.
///
/// Fails, naming the line and column, on a wrong header, a value that is not a finite number, a
/// step that is not the one expected, blocks of different sizes, or missing blocks.
pub fn parse_surface3(text: &str, steps: &[usize]) -> Result<Vec<Surface3>, String> {
    let rows = readback::records(text, "surface.csv", &SURFACE3_COLUMNS)?;
    let mut surfaces: Vec<Surface3> = Vec::with_capacity(steps.len());
    for row in &rows {
        let (step, node) = parse_node3(row)?;
        match surfaces.last_mut() {
            Some(s) if s.step == step => s.nodes.push(node),
            _ => {
                let expected = steps.get(surfaces.len()).copied();
                if expected != Some(step) {
                    return Err(row.cell_error(0, super::surface::not_the_next_step(expected)));
                }
                if let Some(previous) = surfaces.last() {
                    let size = surfaces[0].nodes.len();
                    if previous.nodes.len() != size {
                        return Err(row.error(format!(
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

/// The step and the node of one row of the 3D `surface.csv`, SI.
fn parse_node3(row: &readback::Row) -> Result<(usize, Node3), String> {
    let number = |i: usize, scale: f64| row.finite(i, scale);
    Ok((
        row.whole(0, "a step index")?,
        Node3 {
            point: [number(1, 1e-3)?, number(2, 1e-3)?],
            weight: number(3, 1e-6)?,
            gap: number(4, 1e-3)?,
            pressure: number(5, 1e6)?,
            traction: [number(6, 1e6)?, number(7, 1e6)?],
            stick: row.choice(8, &[("0", false), ("1", true)])?,
            slip: [number(9, 1e-3)?, number(10, 1e-3)?],
        },
    ))
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
    fn the_field_mirrors_the_half_surface_with_odd_transverse_components() {
        let s = hertz_surface(1e-3, 4.5e8);
        let f = s.field(5, true, &[[0, 1, 2]]);
        // the nodes at θ = π have y = r sin π ≈ 1e-16 r: on the plane within the tolerance
        let off_plane = s.on_plane().iter().filter(|&&on| !on).count();
        assert_eq!(off_plane, s.nodes.iter().filter(|n| n.point[1] > 1e-12).count());
        assert_eq!(f.points.len(), s.nodes.len() + off_plane);
        let q = f.traction.unwrap();
        let sum_qy: f64 = q.iter().map(|t| t[1]).sum();
        assert!(sum_qy.abs() < 1e-6, "q_y is odd in y: {sum_qy}");
        assert!(f.points.iter().any(|p| p[1] < 0.0));
        assert_eq!(f.layout.triangles().map(<[_]>::len), Some(2));
        assert_eq!(parse_triangles("a,b,c\n0,1,2\n", 3).unwrap(), [[0, 1, 2]]);
        let e = parse_triangles("a,b,c\n0,1,3\n", 3).unwrap_err();
        assert_eq!(
            e,
            "triangles.csv:2: column `c`: not a node of the surface (allowed: 0 to 2)"
        );
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
        assert!(
            e.starts_with("surface.csv:2: column `p_MPa`: not a finite number"),
            "{e}"
        );
    }
}
