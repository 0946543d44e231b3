//! A small writer of VTK unstructured grids (ASCII XML `.vtu`) for ParaView: points, cells of
//! one VTK cell type, and named point-data arrays of one to three components.
//!
//! Format: VTK File Formats, "XML File Formats: UnstructuredGrid" (Kitware, VTK User's Guide,
//! 11th ed., ch. 19). Written atomically through [`spherecontact_system::io::write_atomically`].

use spherecontact_model::history::{History, Layout, SurfaceField};
use spherecontact_model::scene::Scene;
use spherecontact_model::solver::{Kind, SolveError, Solver};
use std::fmt::Write as _;
use std::path::Path;

/// VTK cell type codes used in this crate (vtkCellType.h).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellType {
    /// 3-node triangle (VTK_TRIANGLE = 5).
    Triangle,
    /// 4-node quadrilateral (VTK_QUAD = 9).
    Quad,
    /// 6-node triangle (VTK_QUADRATIC_TRIANGLE = 22): corners, then midsides 0–1, 1–2, 2–0.
    QuadraticTriangle,
    /// 8-node quadrilateral (VTK_QUADRATIC_QUAD = 23).
    QuadraticQuad,
    /// 10-node tetrahedron (VTK_QUADRATIC_TETRA = 24): corners, then midsides 0–1, 1–2, 2–0,
    /// 0–3, 1–3, 2–3.
    QuadraticTetra,
}

impl CellType {
    /// The VTK code.
    pub fn code(self) -> u8 {
        match self {
            Self::Triangle => 5,
            Self::Quad => 9,
            Self::QuadraticTriangle => 22,
            Self::QuadraticQuad => 23,
            Self::QuadraticTetra => 24,
        }
    }

    /// Nodes per cell.
    pub fn nodes(self) -> usize {
        match self {
            Self::Triangle => 3,
            Self::Quad => 4,
            Self::QuadraticTriangle => 6,
            Self::QuadraticQuad => 8,
            Self::QuadraticTetra => 10,
        }
    }
}

/// A named point-data array: `components` values per point, point-major.
#[derive(Clone, Debug, PartialEq)]
pub struct PointData {
    /// The array's name in ParaView.
    pub name: String,
    /// Components per point (1 to 3).
    pub components: usize,
    /// The values, `components` per point.
    pub values: Vec<f64>,
}

/// An unstructured grid of one cell type.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Point coordinates.
    pub points: Vec<[f64; 3]>,
    /// The cell type of every cell.
    pub cell_type: CellType,
    /// Cells as point indices, `cell_type.nodes()` each.
    pub cells: Vec<Vec<usize>>,
    /// Point data arrays.
    pub point_data: Vec<PointData>,
}

/// Why a grid cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum VtuError {
    /// The grid is inconsistent.
    #[error("invalid grid: {0}")]
    Invalid(String),
    /// Writing failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

impl Grid {
    fn validate(&self) -> Result<(), VtuError> {
        let n = self.points.len();
        let k = self.cell_type.nodes();
        if let Some(c) = self
            .cells
            .iter()
            .position(|c| c.len() != k || c.iter().any(|&p| p >= n))
        {
            return Err(VtuError::Invalid(format!(
                "cell {c}: needs {k} point indices below {n}"
            )));
        }
        for d in &self.point_data {
            if !(1..=3).contains(&d.components) || d.values.len() != d.components * n {
                return Err(VtuError::Invalid(format!(
                    "point data '{}': {} values for {n} points of {} components (1–3)",
                    d.name,
                    d.values.len(),
                    d.components
                )));
            }
            if d.values.iter().any(|v| !v.is_finite()) {
                return Err(VtuError::Invalid(format!(
                    "point data '{}' is not finite",
                    d.name
                )));
            }
        }
        Ok(())
    }

    /// The grid as VTU XML text.
    pub fn to_xml(&self) -> Result<String, VtuError> {
        self.validate()?;
        let mut s = String::new();
        let join = |it: &mut dyn Iterator<Item = String>| it.collect::<Vec<_>>().join(" ");
        let _ = writeln!(s, r#"<?xml version="1.0"?>"#);
        let _ = writeln!(
            s,
            r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">"#
        );
        let _ = writeln!(s, "<UnstructuredGrid>");
        let _ = writeln!(
            s,
            r#"<Piece NumberOfPoints="{}" NumberOfCells="{}">"#,
            self.points.len(),
            self.cells.len()
        );
        let _ = writeln!(s, "<PointData>");
        for d in &self.point_data {
            let _ = writeln!(
                s,
                r#"<DataArray type="Float64" Name="{}" NumberOfComponents="{}" format="ascii">"#,
                escape(&d.name),
                d.components
            );
            let _ = writeln!(s, "{}", join(&mut d.values.iter().map(|v| format!("{v:e}"))));
            let _ = writeln!(s, "</DataArray>");
        }
        let _ = writeln!(s, "</PointData>");
        let _ = writeln!(s, "<Points>");
        let _ = writeln!(
            s,
            r#"<DataArray type="Float64" NumberOfComponents="3" format="ascii">"#
        );
        let _ = writeln!(
            s,
            "{}",
            join(&mut self.points.iter().flatten().map(|v| format!("{v:e}")))
        );
        let _ = writeln!(s, "</DataArray>\n</Points>\n<Cells>");
        let _ = writeln!(
            s,
            r#"<DataArray type="Int64" Name="connectivity" format="ascii">"#
        );
        let _ = writeln!(
            s,
            "{}",
            join(&mut self.cells.iter().flatten().map(|v| v.to_string()))
        );
        let _ = writeln!(s, "</DataArray>");
        let _ = writeln!(s, r#"<DataArray type="Int64" Name="offsets" format="ascii">"#);
        let k = self.cell_type.nodes();
        let _ = writeln!(
            s,
            "{}",
            join(&mut (1..=self.cells.len()).map(|i| (i * k).to_string()))
        );
        let _ = writeln!(s, "</DataArray>");
        let _ = writeln!(s, r#"<DataArray type="UInt8" Name="types" format="ascii">"#);
        let code = self.cell_type.code().to_string();
        let _ = writeln!(s, "{}", vec![code; self.cells.len()].join(" "));
        let _ = writeln!(
            s,
            "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>"
        );
        Ok(s)
    }

    /// Writes the grid to `path` atomically.
    pub fn write(&self, path: &Path) -> Result<(), VtuError> {
        let xml = self.to_xml()?;
        spherecontact_system::io::write_atomically(path, xml.as_bytes())?;
        Ok(())
    }
}

/// Escapes the XML attribute characters of a name.
fn escape(name: &str) -> String {
    name.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl Grid {
    /// A surface field sampled on a full rectangular grid, as quads joining neighbouring samples
    /// on the plane z = 0, with point data `pressure`, `traction` (q_x, q_y, 0) and `stick`
    /// (1 stick, 0 slip, −1 out of contact); `None` when the field's layout is not a grid (a
    /// profile along the axis, triangles) or its samples do not fill the rectangle.
    pub fn of_surface_field(field: &SurfaceField) -> Option<Grid> {
        if !matches!(field.layout, Layout::Grid { .. }) {
            return None;
        }
        let axis = |k: usize| {
            let mut values: Vec<f64> = field.points.iter().map(|p| p[k]).collect();
            values.sort_by(f64::total_cmp);
            values.dedup();
            values
        };
        let (xs, ys) = (axis(0), axis(1));
        if xs.len() < 2 || ys.len() < 2 || xs.len() * ys.len() != field.points.len() {
            return None;
        }
        let mut index = vec![usize::MAX; field.points.len()];
        for (k, p) in field.points.iter().enumerate() {
            let i = xs.binary_search_by(|x| x.total_cmp(&p[0])).ok()?;
            let j = ys.binary_search_by(|y| y.total_cmp(&p[1])).ok()?;
            index[j * xs.len() + i] = k;
        }
        if index.contains(&usize::MAX) {
            return None;
        }
        let at = |i: usize, j: usize| index[j * xs.len() + i];
        let cells = (0..ys.len() - 1)
            .flat_map(|j| (0..xs.len() - 1).map(move |i| (i, j)))
            .map(|(i, j)| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            .collect();
        let mut point_data = vec![PointData {
            name: "pressure".into(),
            components: 1,
            values: field.pressure.clone(),
        }];
        if let Some(traction) = &field.traction {
            point_data.push(PointData {
                name: "traction".into(),
                components: 3,
                values: traction.iter().flat_map(|q| [q[0], q[1], 0.0]).collect(),
            });
        }
        if let Some(stick) = &field.stick {
            let status = |k: usize| match (field.pressure[k] > 0.0, stick[k]) {
                (false, _) => -1.0,
                (true, true) => 1.0,
                (true, false) => 0.0,
            };
            point_data.push(PointData {
                name: "stick".into(),
                components: 1,
                values: (0..stick.len()).map(status).collect(),
            });
        }
        Some(Grid {
            points: field.points.iter().map(|p| [p[0], p[1], 0.0]).collect(),
            cell_type: CellType::Quad,
            cells,
            point_data,
        })
    }
}

/// A solver whose surface fields on a grid are also written as VTU files, one per path position
/// (`<dir>/<case>-<solver>-<position>.vtu`).
pub struct SurfaceVtu {
    /// The solver.
    pub inner: Box<dyn Solver>,
    /// Where the files go.
    pub dir: std::path::PathBuf,
}

impl Solver for SurfaceVtu {
    fn name(&self) -> &str {
        self.inner.name()
    }

    fn kind(&self) -> Kind {
        self.inner.kind()
    }

    fn cores(&self) -> usize {
        self.inner.cores()
    }

    fn description(&self) -> &str {
        self.inner.description()
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        let history = self.inner.solve(scene)?;
        for field in &history.fields {
            let Some(grid) = Grid::of_surface_field(field) else {
                continue;
            };
            let path = self
                .dir
                .join(format!("{}-{}-{}.vtu", scene.name, self.name(), field.position));
            spherecontact_system::io::create_folder(&self.dir)
                .and_then(|()| grid.write(&path).map_err(std::io::Error::other))
                .map_err(|e| SolveError::Failed(format!("writing {}: {e}", path.display())))?;
        }
        Ok(history)
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        self.inner.estimated_seconds(scene)
    }
}

#[cfg(test)]
mod tests {
    use spherecontact_model::history::{Layout, SurfaceField, TangentialComponents};

    #[test]
    fn a_profile_is_not_a_grid_and_a_grid_becomes_quads() {
        let profile = SurfaceField {
            position: 1,
            points: (0..5).map(|k| [k as f64, 0.0]).collect(),
            pressure: vec![1.0; 5],
            traction: None,
            stick: None,
            slip: None,
            components: TangentialComponents::InPlane,
            layout: Layout::Profile,
        };
        assert!(Grid::of_surface_field(&profile).is_none());
        let points: Vec<[f64; 2]> = (0..12).map(|k| [(k % 4) as f64, (k / 4) as f64]).collect();
        let field = SurfaceField {
            position: 1,
            pressure: points
                .iter()
                .map(|p| if p[0] > 0.0 { 1.0 } else { 0.0 })
                .collect(),
            traction: Some(points.iter().map(|p| [p[1], 0.0]).collect()),
            stick: Some(points.iter().map(|p| p[1] > 0.0).collect()),
            slip: None,
            components: TangentialComponents::InPlane,
            points,
            layout: Layout::Grid { spacing: 1.0 },
        };
        let grid = Grid::of_surface_field(&field).unwrap();
        assert_eq!(grid.cells.len(), 3 * 2, "4 × 3 samples make 3 × 2 quads");
        let stick = &grid.point_data.iter().find(|d| d.name == "stick").unwrap().values;
        assert_eq!(
            (stick[0], stick[1], stick[5]),
            (-1.0, 0.0, 1.0),
            "out of contact, slip, stick"
        );
    }

    use super::*;

    fn two_triangles() -> Grid {
        Grid {
            points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
            cell_type: CellType::Triangle,
            cells: vec![vec![0, 1, 2], vec![1, 3, 2]],
            point_data: vec![PointData {
                name: "u".into(),
                components: 2,
                values: vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0],
            }],
        }
    }

    #[test]
    fn writes_offsets_types_and_arrays() {
        let xml = two_triangles().to_xml().unwrap();
        assert!(xml.contains(r#"NumberOfPoints="4" NumberOfCells="2""#));
        assert!(xml.contains("\n3 6\n"), "offsets");
        assert!(xml.contains("\n5 5\n"), "types");
        assert!(xml.contains(r#"Name="u" NumberOfComponents="2""#));
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("g.vtu");
        two_triangles().write(&path).unwrap();
        assert_eq!(std::fs::read_to_string(path).unwrap(), xml);
    }

    #[test]
    fn rejects_bad_cells_and_data() {
        let mut g = two_triangles();
        g.cells[1][0] = 9;
        assert!(g.to_xml().is_err());
        let mut g = two_triangles();
        g.point_data[0].values.pop();
        assert!(g.to_xml().is_err());
        let mut g = two_triangles();
        g.point_data[0].values[0] = f64::NAN;
        assert!(g.to_xml().is_err());
    }
}
