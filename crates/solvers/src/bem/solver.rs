//! The `bem` solver: the contact followed increment by increment along the path on one grid,
//! with the History quantities per step and the surface fields at every path position.

use serde_json::json;

use spherecontact_model::driver::{self, PathIncrement, PathModel};
use spherecontact_model::history::{
    History, Layout, Metadata, StepResult, SurfaceField, TangentialComponents,
};
use spherecontact_model::limits::MAX_BEM_GRID;
use spherecontact_model::path::Step;
use spherecontact_model::resolution::{self, ResolutionError};
use spherecontact_model::scene::{Scene, DISSIMILARITY_BETA};
use spherecontact_model::solver::{Kind, SolveError, Solver};

use super::grid::Grid;
use super::state::{ContactState, IncrementCost, IncrementError, Snapshot, Tolerances};

/// Fewer panels than this across the largest contact diameter earn a warning.
pub const MIN_PANELS_ACROSS: f64 = 8.0;

/// Half-space boundary elements on an n × n grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bem {
    /// Panels along each side of the window.
    pub grid: usize,
    /// The window's half-width over the path's largest Hertz contact radius.
    pub window: f64,
    /// Convergence tolerances and iteration cap.
    pub tolerances: Tolerances,
}

impl Default for Bem {
    /// 64² panels: the paper path's tangential force within 2 % of MDR at every position and
    /// Hertz's force within 0.3 % (see the case files); the window is 1.1 c_max.
    fn default() -> Self {
        Self::with_grid(64)
    }
}

/// A path position's fields, kept for output.
#[derive(Clone, Debug, PartialEq)]
pub struct PositionFields {
    /// The path position.
    pub position: usize,
    /// The fields there.
    pub snapshot: Snapshot,
}

impl Bem {
    /// The solver on an `n × n` grid with the default window and tolerances.
    pub fn with_grid(n: usize) -> Self {
        Self {
            grid: n,
            window: 1.1,
            // Tolerances: the tangential one is matched to the tightest check on Q, Cattaneo at
            // ν = 0 (exact, Q error 5.8e-5 at 64², bound 1e-4) and 5e-4 at 128² (4.2e-4
            // measured): from 1e-5 to 3e-5 the paper path's Ft at 128² moves by < 6e-5 of its
            // peak and Cattaneo's Q at 128²–256² by < 1e-5, for 2× fewer iterations
            // (examples/bem_timing.rs). Tightening the normal one tenfold moves Hertz P and p0 at
            // 128² by < 3e-6. Discretisation errors are above 1e-5 at 128², 1e-4 at 64², and fall
            // as h²: beyond 128² the normal tolerance falls with them.
            tolerances: Tolerances {
                normal: 1e-6 * (128.0 / n.max(1) as f64).powi(2).min(1.0),
                tangential: 3e-5,
                max_iterations: 5000,
            },
        }
    }

    /// Solves `scene`, returning the history and the full grid fields at every path position
    /// (pressure, traction, stick and accumulated slip: what a VTU writer needs).
    pub fn solve_with_fields(&self, scene: &Scene) -> Result<(History, Vec<PositionFields>), SolveError> {
        if self.grid < 4 || !self.grid.is_multiple_of(2) || self.grid > MAX_BEM_GRID {
            return Err(SolveError::Failed(format!(
                "bem needs an even grid of 4 to {MAX_BEM_GRID} panels a side (got {})",
                self.grid
            )));
        }
        let c_max = scene.max_contact_radius();
        if let Some(history) = driver::never_closed_history(scene, self.metadata(scene)) {
            // Nothing to discretise.
            return Ok((history, Vec::new()));
        }
        let mut metadata = self.metadata(scene);
        let grid = Grid::covering(self.grid, self.window * c_max);
        let mut walker = Walker {
            scene,
            state: ContactState::new(scene, grid, self.tolerances),
            fields: Vec::new(),
            total: IncrementCost::default(),
        };
        let rows = driver::walk(scene, &mut walker)?;
        let (fields, total) = (walker.fields, walker.total);
        metadata.resolution = format!(
            "{n}×{n} panels of {h:.3e} m ({across:.1} across the largest Hertz contact), window ±{w:.3e} m",
            n = grid.n,
            h = grid.h,
            across = 2.0 * c_max / grid.h,
            w = self.window * c_max
        );
        if 2.0 * c_max / grid.h < MIN_PANELS_ACROSS {
            metadata.warnings.push(format!(
                "grid too coarse: the largest contact spans {:.1} panels across (< {MIN_PANELS_ACROSS})",
                2.0 * c_max / grid.h
            ));
        }
        metadata.extra.insert("panels".into(), json!(grid.len()));
        metadata
            .extra
            .insert("dundurs_beta".into(), json!(scene.pair.dundurs_beta()));
        metadata.extra.insert("panel_size_m".into(), json!(grid.h));
        metadata
            .extra
            .insert("normal_cg_iterations".into(), json!(total.normal_iterations));
        metadata.extra.insert(
            "tangential_apg_iterations".into(),
            json!(total.tangential_iterations),
        );
        let history = History {
            metadata,
            steps: rows,
            fields: fields.iter().map(surface_field).collect(),
        };
        Ok((history, fields))
    }

    /// Model description and the warnings that do not depend on the grid.
    fn metadata(&self, scene: &Scene) -> Metadata {
        let mut warnings = Vec::new();
        let beta = scene.pair.dundurs_beta();
        if beta.abs() > DISSIMILARITY_BETA && scene.friction > 0.0 {
            warnings.push(format!(
                "bem neglects the normal–tangential coupling, exact only for Dundurs β = 0; this pair \
                 has β = {beta:.4}: pressure and traction are each solved as if uncoupled"
            ));
        }
        Metadata {
            model: "two elastic half-spaces, constant-traction square panels, Boussinesq–Cerruti \
                    (decoupled, β = 0), exact non-penetration, incremental Coulomb friction"
                .into(),
            warnings,
            ..Metadata::default()
        }
    }
}

/// The BEM contact as the path walker drives it, keeping the fields of every path position.
struct Walker<'a> {
    scene: &'a Scene,
    state: ContactState,
    fields: Vec<PositionFields>,
    total: IncrementCost,
}

impl Walker<'_> {
    /// Keeps the fields at `step` if it is a position the scene records.
    fn keep(&mut self, step: &Step) {
        if let Some(position) = step.position.filter(|&p| self.scene.records_fields_at(p)) {
            self.fields.push(PositionFields {
                position,
                snapshot: self.state.snapshot().clone(),
            });
        }
    }
}

impl PathModel for Walker<'_> {
    fn advance(&mut self, increment: &PathIncrement) -> Result<StepResult, SolveError> {
        let step = increment.step;
        let cost = self
            .state
            .advance(step.delta_n, increment.shift())
            .map_err(|e| increment_failure(e, step.index))?;
        self.total.normal_iterations += cost.normal_iterations;
        self.total.tangential_iterations += cost.tangential_iterations;
        self.keep(step);
        Ok(row(step, self.state.snapshot()))
    }

    fn release(&mut self, step: &Step) {
        self.state.release();
        self.keep(step);
    }
}

/// A path step's History row from the fields.
fn row(step: &Step, snapshot: &Snapshot) -> StepResult {
    let in_contact = snapshot.normal_force() > 0.0;
    StepResult {
        normal_force: Some(snapshot.normal_force()),
        tangential_force: Some(snapshot.tangential_force()),
        contact_radius: Some(snapshot.contact_radius()),
        peak_pressure: Some(snapshot.peak_pressure()),
        stick_radius: in_contact.then(|| snapshot.stick_radius()),
        ..StepResult::at(step)
    }
}

/// The History's surface field of a path position.
fn surface_field(fields: &PositionFields) -> SurfaceField {
    let s = &fields.snapshot;
    SurfaceField {
        position: fields.position,
        points: s.grid.centres(),
        pressure: s.pressure.clone(),
        traction: Some(s.traction.clone()),
        stick: Some(s.stick.clone()),
        // The engine's accumulated slip: the grid carries the pair's compliance and the relative
        // shift, so it is the relative slip (body 1 − body 2), as fem-axisym and fem-3d report it.
        slip: Some(s.slip.clone()),
        components: TangentialComponents::InPlane,
        layout: Layout::Grid { spacing: s.grid.h },
    }
}

/// A failed increment as the solver's error.
fn increment_failure(error: IncrementError, step: usize) -> SolveError {
    SolveError::Failed(match error {
        IncrementError::ContactAtEdge { radius, half_width } => format!(
            "at step {step} the contact (radius {radius:.3e} m) reached the edge of the window \
             (half-width {half_width:.3e} m): enlarge `window`"
        ),
        IncrementError::Engine(error) => format!("at step {step}: {error}"),
    })
}

impl Solver for Bem {
    fn name(&self) -> &'static str {
        "bem"
    }

    fn kind(&self) -> Kind {
        Kind::BoundaryElement
    }

    fn description(&self) -> &'static str {
        "half-space boundary elements: Boussinesq–Cerruti panels, FFT, the shared contact engine (Polonsky–Keer CG, incremental Coulomb by accelerated projected gradients)"
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        self.solve_with_fields(scene).map(|(history, _)| history)
    }

    fn estimated_seconds(&self, scene: &Scene) -> Option<f64> {
        Some(spherecontact_model::cost::bem(self.grid, scene.steps().len()))
    }

    /// The FFT products' team: two threads where two cores are free ([`spherecontact_model::team`]).
    fn cores(&self) -> usize {
        spherecontact_model::team::default_threads()
    }

    /// Grids of 16² … 128² panels over the same window.
    fn resolution_ladder(&self, _scene: &Scene) -> Vec<Box<dyn Solver>> {
        [16, 32, 64, 128]
            .into_iter()
            .map(|n| {
                Box::new(Bem {
                    window: self.window,
                    ..Bem::with_grid(n)
                }) as Box<dyn Solver>
            })
            .collect()
    }

    /// `n`: an even number of panels a side, 4 ≤ n ≤ [`MAX_BEM_GRID`], over the same window.
    fn at_resolution(&self, _scene: &Scene, value: &str) -> Result<Box<dyn Solver>, ResolutionError> {
        let n = resolution::count(self.name(), value, 4, MAX_BEM_GRID, true)?;
        Ok(Box::new(Bem {
            window: self.window,
            ..Bem::with_grid(n)
        }))
    }

    /// Pressure, traction and stick/slip of every path position as a grid of quads.
    fn writing_fields_to(&self, dir: &std::path::Path) -> Option<Box<dyn Solver>> {
        Some(Box::new(crate::vtu::SurfaceVtu {
            inner: Box::new(*self),
            dir: dir.to_path_buf(),
        }))
    }
}
