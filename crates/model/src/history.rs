//! What a solver returns: one row of contact quantities per path step, and how it was obtained.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;

use crate::path::Step;

/// The contact quantities of one path step, in SI units. A quantity the solver does not produce
/// is `None` (an empty CSV cell), never NaN or zero.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepResult {
    /// Step index, 0 for the start.
    pub step: usize,
    /// The path position this step reaches; `None` between positions.
    pub position: Option<usize>,
    /// Relative normal approach δn [m].
    pub delta_n: f64,
    /// Relative tangential displacement δt [m].
    pub delta_t: f64,
    /// Normal force P [N].
    pub normal_force: Option<f64>,
    /// Tangential force Q along δt [N].
    pub tangential_force: Option<f64>,
    /// Contact radius c [m].
    pub contact_radius: Option<f64>,
    /// Peak contact pressure p0 [Pa].
    pub peak_pressure: Option<f64>,
    /// Radius of the stick zone [m]: equal to c in full stick, 0 in gross sliding.
    pub stick_radius: Option<f64>,
}

impl StepResult {
    /// A row for `step` with every quantity still absent.
    pub fn at(step: &Step) -> Self {
        Self {
            step: step.index,
            position: step.position,
            delta_n: step.delta_n,
            delta_t: step.delta_t,
            ..Self::default()
        }
    }
}

/// A contact quantity that checks and reports can name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Normal force P [N].
    NormalForce,
    /// Tangential force Q [N].
    TangentialForce,
    /// Contact radius c [m].
    ContactRadius,
    /// Peak pressure p0 [Pa].
    PeakPressure,
    /// Stick radius [m].
    StickRadius,
    /// The pressure profile p(r) at one path position (checks only: its RMS difference from a
    /// reference solver's, `profile` (spherecontact-solvers)).
    PressureProfile,
    /// The traction profile q_x(r) at one path position (checks only, as the pressure's).
    TractionProfile,
    /// max|q̄_y| / max|q̄_x| on a map at a path position (checks only, `map_measure` (spherecontact-solvers)).
    TransverseRatio,
    /// The stick zone's semi-axis along x [m] on a map at a path position (checks only).
    StickSemiAxisX,
    /// The stick zone's semi-axis along y [m] on a map at a path position (checks only).
    StickSemiAxisY,
}

impl Quantity {
    /// Every quantity, in CSV column order.
    pub const ALL: [Quantity; 5] = [
        Quantity::NormalForce,
        Quantity::TangentialForce,
        Quantity::ContactRadius,
        Quantity::PeakPressure,
        Quantity::StickRadius,
    ];

    /// The profiles a check can compare (not step values: no CSV column).
    pub const PROFILES: [Quantity; 2] = [Quantity::PressureProfile, Quantity::TractionProfile];

    /// The measures a check reads from a map at path positions (not step values: no CSV column).
    pub const MAP_MEASURES: [Quantity; 3] = [
        Quantity::TransverseRatio,
        Quantity::StickSemiAxisX,
        Quantity::StickSemiAxisY,
    ];

    /// The name used in case files and CSV headers.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::NormalForce => "normal_force",
            Quantity::TangentialForce => "tangential_force",
            Quantity::ContactRadius => "contact_radius",
            Quantity::PeakPressure => "peak_pressure",
            Quantity::StickRadius => "stick_radius",
            Quantity::PressureProfile => "pressure_profile",
            Quantity::TractionProfile => "traction_profile",
            Quantity::TransverseRatio => "transverse_ratio",
            Quantity::StickSemiAxisX => "stick_semi_axis_x",
            Quantity::StickSemiAxisY => "stick_semi_axis_y",
        }
    }

    /// The SI unit.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::NormalForce | Quantity::TangentialForce => "N",
            Quantity::ContactRadius
            | Quantity::StickRadius
            | Quantity::StickSemiAxisX
            | Quantity::StickSemiAxisY => "m",
            Quantity::TransverseRatio => "1",
            Quantity::PeakPressure | Quantity::PressureProfile | Quantity::TractionProfile => "Pa",
        }
    }

    /// The step quantity (a CSV column) named `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|q| q.name() == name)
    }

    /// The quantity a check may name `name`: a step quantity, a profile or a map measure.
    pub fn checkable(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .chain(Self::PROFILES)
            .chain(Self::MAP_MEASURES)
            .find(|q| q.name() == name)
    }

    /// True for a measure read from a map at a path position ([`Self::MAP_MEASURES`]).
    pub fn is_map_measure(self) -> bool {
        Self::MAP_MEASURES.contains(&self)
    }

    /// This quantity's value in a step row.
    pub fn of(self, row: &StepResult) -> Option<f64> {
        match self {
            Quantity::NormalForce => row.normal_force,
            Quantity::TangentialForce => row.tangential_force,
            Quantity::ContactRadius => row.contact_radius,
            Quantity::PeakPressure => row.peak_pressure,
            Quantity::StickRadius => row.stick_radius,
            Quantity::PressureProfile
            | Quantity::TractionProfile
            | Quantity::TransverseRatio
            | Quantity::StickSemiAxisX
            | Quantity::StickSemiAxisY => None,
        }
    }
}

impl Metadata {
    /// The resolution in words, with the user's choice where there is one (what reports show).
    pub fn resolution_shown(&self) -> String {
        match &self.chosen_resolution {
            Some(value) => format!("{} (chosen: {value})", self.resolution),
            None => self.resolution.clone(),
        }
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How a history was obtained.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Metadata {
    /// The solver's command-line name.
    pub solver: String,
    /// The solver's version (the crate's for in-crate solvers, the tool's for external ones).
    pub version: String,
    /// The model actually solved (e.g. "half-space, 1D springs" or "axisymmetric, one sphere").
    pub model: String,
    /// The resolution (springs, mesh size, grid), in words.
    pub resolution: String,
    /// The resolution the user chose (a case's `[resolution]` entry or `--resolution`), as
    /// given; `None`: the solver's default.
    pub chosen_resolution: Option<String>,
    /// Wall time of the solve [s].
    pub wall_time_s: f64,
    /// Warnings a reader must see (validity limits, assumptions that do not hold).
    pub warnings: Vec<String>,
    /// Solver-specific facts (DOFs, iterations, ...).
    pub extra: BTreeMap<String, serde_json::Value>,
    /// Why a quantity is missing from the rows of a history read from a results file (a stored
    /// file, a program's output): the column is not in its header, or a cell of it is not a
    /// number (the file, line and column). That quantity's alone: its checks are NOOK with the
    /// reason, the other quantities are read and judged.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub unread: BTreeMap<Quantity, String>,
}

/// Which in-plane components of the tangential traction and slip a solver resolves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TangentialComponents {
    /// Both q_x and q_y (and both slip components): the BEM grid, the 3D meshes.
    #[default]
    InPlane,
    /// q_x only: the model takes the traction along the shift (Mindlin–Deresiewicz's
    /// assumption; the axisymmetric Fourier n = 1 solvers and decks, MDR, Cattaneo–Mindlin).
    /// The second component of `traction` and `slip` is 0 by that assumption, not by a solve:
    /// readers treat q_y and slip_y as not produced.
    AlongX,
}

/// Surface fields on the contact plane at one path position.
///
/// Frame: origin at the contact centre, x along δt, y across it, both on the contact plane.
/// Axisymmetric and 1D solvers sample the x axis (y = 0).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SurfaceField {
    /// The path position.
    pub position: usize,
    /// Sample points (x, y) [m].
    pub points: Vec<[f64; 2]>,
    /// Contact pressure p [Pa], compressive positive.
    pub pressure: Vec<f64>,
    /// Tangential traction (q_x, q_y) [Pa] on body 1, signed so that ∫ q_x dA = Q; `None` for
    /// frictionless solvers; q_y only where `components` says it is resolved.
    pub traction: Option<Vec<[f64; 2]>>,
    /// Stick (true) or slip (false) at each point in contact (p > 0); `None` where not resolved.
    pub stick: Option<Vec<bool>>,
    /// Relative tangential displacement of the surfaces (body 1 − body 2) [m] at each point,
    /// accumulated along the path; `None` for solvers that do not resolve it.
    pub slip: Option<Vec<[f64; 2]>>,
    /// Which components of `traction` and `slip` the solver resolved.
    pub components: TangentialComponents,
    /// How the samples cover the contact plane: what reports draw them on, what areas the map
    /// measures (`map_measure` (spherecontact-solvers)) give them.
    pub layout: Layout,
}

/// How a surface field's samples cover the contact plane.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Layout {
    /// Samples along the x axis of an axisymmetric (or 1D) solution: the same on every radius.
    #[default]
    Profile,
    /// The centres of square panels of side `spacing` [m].
    Grid {
        /// The panel side [m].
        spacing: f64,
    },
    /// The vertices of a triangulated contact surface (indices into the field's points), values
    /// at the vertices.
    Triangles(Vec<[usize; 3]>),
}

impl Layout {
    /// The area each of `points` stands for [m²] (a panel's, or a third of the triangles around
    /// a vertex); `None` for a profile.
    pub fn areas(&self, points: &[[f64; 2]]) -> Option<Vec<f64>> {
        match self {
            Layout::Profile => None,
            Layout::Grid { spacing } => Some(vec![spacing * spacing; points.len()]),
            Layout::Triangles(triangles) => {
                let mut areas = vec![0.0; points.len()];
                for t in triangles {
                    let area = triangle_area(t.map(|i| points[i]));
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

/// A solver's result along a whole path.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct History {
    /// How it was obtained.
    pub metadata: Metadata,
    /// One row per path step, step 0 first.
    pub steps: Vec<StepResult>,
    /// Surface fields at path positions, for solvers that resolve them.
    pub fields: Vec<SurfaceField>,
}

impl History {
    /// The rows that reach path positions, in order.
    pub fn at_positions(&self) -> impl Iterator<Item = &StepResult> {
        self.steps.iter().filter(|r| r.position.is_some())
    }

    /// The largest |value| of `quantity` over the steps (0 where the solver gives none).
    pub fn peak(&self, quantity: Quantity) -> f64 {
        self.steps
            .iter()
            .filter_map(|r| quantity.of(r))
            .fold(0.0, |m, v| m.max(v.abs()))
    }

    /// The surface field at path position `position`, if the solver wrote one.
    pub fn field_at(&self, position: usize) -> Option<&SurfaceField> {
        self.fields.iter().find(|f| f.position == position)
    }

    /// The row reaching path position `position`, if the path has it.
    pub fn at_position(&self, position: usize) -> Option<&StepResult> {
        self.steps.iter().find(|r| r.position == Some(position))
    }
}

/// The area of the triangle with vertices `a`, `b`, `c` (x, y) [m²]: half the magnitude of the
/// cross product of two edges.
pub fn triangle_area([a, b, c]: [[f64; 2]; 3]) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_layout_gives_areas_and_names_itself_in_json() {
        // The unit square as two triangles: each corner of the diagonal carries a third of both.
        let points = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
        let mesh = Layout::Triangles(vec![[0, 1, 2], [1, 3, 2]]);
        assert_eq!(
            mesh.areas(&points),
            Some(vec![1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0])
        );
        assert_eq!(Layout::Grid { spacing: 0.5 }.areas(&points), Some(vec![0.25; 4]));
        assert_eq!(Layout::Profile.areas(&points), None);
        let json = |layout: &Layout| serde_json::to_string(layout).unwrap();
        assert_eq!(json(&Layout::Profile), r#""profile""#);
        assert_eq!(
            json(&Layout::Grid { spacing: 0.5 }),
            r#"{"grid":{"spacing":0.5}}"#
        );
        assert_eq!(json(&mesh), r#"{"triangles":[[0,1,2],[1,3,2]]}"#);
    }
}
