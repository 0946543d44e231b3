//! The axisymmetric normal-contact run shared by the external decks: check that the scene fits
//! the model, mesh it, fill and run the deck once for all the path's approaches, read back, and
//! give one `History` row per path step.
//!
//! Model: two identical spheres are symmetric about their contact plane, which stays flat and
//! frictionless under a normal load; so one sphere pressed by d = δn/2 against a rigid
//! frictionless plane is exact (Johnson 1985, §4.2). Different spheres, or a sphere on a flat,
//! are not modelled yet (`NotApplicable`). Linear elastic frictionless normal contact is path
//! independent, so the deck solves only the distinct positive δn of the path positions, in one
//! process; rows between positions are left empty (never interpolated), and an open contact
//! (δn ≤ 0) gives P = c = p0 = 0 exactly without a solve.

use std::time::{Duration, Instant};

use serde_json::json;

use super::deck::{self, Deck, DeckInput, RunDir};
use super::geo::{self, MeshFiles};
use super::readback::{self, DeckRow, Profile};
use super::toolchain::{Tool, Toolchain};
use crate::history::{History, Metadata, StepResult, SurfaceField};
use crate::scene::Scene;
use crate::solver::{SolveError, Solver};

/// Penalty factor: k = KFAC · E / h. Reason (docs/toolchain.md): at 1e3 the penetration at the pole
/// is below 1e-3 h and P moves by less than 0.01 % when kfac doubles.
pub const KFAC: f64 = 1e3;

/// Cap on contact iterations per approach (active set or Newton); a row that hits it fails.
pub const MAX_ITERATIONS: u32 = 30;

/// Time allowed per solved approach (≈ 2–3 s each at the default mesh) and for start-up
/// (imports, dolfinx's form compilation on a first run).
const TIME_PER_APPROACH: Duration = Duration::from_secs(60);
const TIME_TO_START: Duration = Duration::from_secs(120);

/// Pressure profiles are kept out to this multiple of the largest contact radius.
const PROFILE_WINDOW: f64 = 1.5;

/// How a deck is run.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// The executables.
    pub toolchain: Toolchain,
    /// Pole element size [m]; default [`geo::default_resolution`].
    pub resolution: Option<f64>,
    /// Time limit for the deck; default 120 s + 60 s per solved approach.
    pub timeout: Option<Duration>,
    /// A replacement deck text (already filled), for fault tests and experiments.
    pub deck_text: Option<String>,
}

/// Wall time of the three parts of an external run [s].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timing {
    /// gmsh.
    pub meshing_s: f64,
    /// The deck.
    pub solving_s: f64,
    /// steps.csv and the field files through meshio.
    pub reading_s: f64,
}

/// An external deck as a [`Solver`].
pub struct AxisymSolver<D: Deck> {
    /// The deck.
    pub deck: D,
    /// How it is run.
    pub options: Options,
}

/// Pole element sizes of the external ladder, as fractions of the path's largest contact radius.
pub const LADDER: [f64; 4] = [1.0 / 10.0, 1.0 / 20.0, 1.0 / 40.0, 1.0 / 80.0];

impl<D: Deck + 'static> Solver for AxisymSolver<D> {
    fn name(&self) -> &'static str {
        self.deck.name()
    }

    fn resolution_ladder(&self, scene: &Scene) -> Vec<Box<dyn Solver>> {
        LADDER
            .iter()
            .map(|fraction| {
                let mut options = self.options.clone();
                options.resolution = Some(fraction * scene.max_contact_radius());
                Box::new(AxisymSolver {
                    deck: self.deck.clone(),
                    options,
                }) as Box<dyn Solver>
            })
            .collect()
    }

    fn description(&self) -> &'static str {
        self.deck.description()
    }

    fn solve(&self, scene: &Scene) -> Result<History, SolveError> {
        applicable(scene)?;
        let toolchain = &self.options.toolchain;
        let version = toolchain
            .require(self.deck.tool())
            .map_err(SolveError::Unavailable)?;
        toolchain.require(Tool::Meshio).map_err(SolveError::Unavailable)?;
        let resolution = self
            .options
            .resolution
            .unwrap_or_else(|| geo::default_resolution(scene));
        let approaches = distinct_approaches(scene);
        let mut dir = RunDir::new(&format!("spherecontact-{}-", self.deck.name()))
            .map_err(|e| SolveError::Failed(format!("no temporary directory: {e}")))?;
        match self.run_in(scene, resolution, &approaches, &dir) {
            Ok((rows, profiles, mesh, timing)) => {
                Ok(self.history(scene, &version, &approaches, &rows, &profiles, &mesh, timing))
            }
            Err(SolveError::Failed(message)) => Err(SolveError::Failed(format!(
                "{message} (deck, mesh, stdout and stderr kept in {})",
                dir.keep().display()
            ))),
            Err(other) => Err(other),
        }
    }
}

type RunOutput = (Vec<DeckRow>, Vec<Profile>, MeshFiles, Timing);

impl<D: Deck> AxisymSolver<D> {
    /// A deck with default options.
    pub fn new(deck: D) -> Self {
        Self {
            deck,
            options: Options::default(),
        }
    }

    /// Meshes, runs the deck and reads back, in `dir`.
    fn run_in(
        &self,
        scene: &Scene,
        resolution: f64,
        approaches: &[f64],
        dir: &RunDir,
    ) -> Result<RunOutput, SolveError> {
        let toolchain = &self.options.toolchain;
        let mesh = geo::mesh(scene, resolution, dir.path(), toolchain)?;
        let mut timing = Timing {
            meshing_s: mesh.wall_s,
            ..Timing::default()
        };
        if approaches.is_empty() {
            return Ok((Vec::new(), Vec::new(), mesh, timing));
        }
        let input = self.input(scene, resolution, approaches, &mesh);
        let text = self
            .options
            .deck_text
            .clone()
            .unwrap_or_else(|| deck::fill(self.deck.template(), &input));
        let deck_file = dir.path().join(self.deck.file_name());
        std::fs::write(&deck_file, text).map_err(|e| SolveError::Failed(format!("writing the deck: {e}")))?;
        let timeout = self.options.timeout.unwrap_or(
            TIME_TO_START + TIME_PER_APPROACH * u32::try_from(approaches.len()).unwrap_or(u32::MAX),
        );
        let job = self.deck.job(toolchain, &deck_file, timeout);
        let run = super::process::run(&job, dir.path(), "deck")
            .map_err(|e| SolveError::Failed(format!("{} could not start: {e}", self.deck.tool().name())))?;
        timing.solving_s = run.wall_s;
        if let Some(why) = deck::failure(&self.deck, &run.ending, timeout) {
            return Err(SolveError::Failed(format!(
                "{why}; last output:\n{}",
                run.tail(12)
            )));
        }
        let start = Instant::now();
        let d: Vec<f64> = approaches.iter().map(|dn| dn / 2.0).collect();
        let rows = readback::read_steps(dir.path(), &d).map_err(SolveError::Failed)?;
        if let Some(row) = rows.iter().find(|r| !r.converged) {
            return Err(SolveError::Failed(format!(
                "contact iteration did not converge in {} iterations at δn = {:e} m",
                row.iterations,
                2.0 * row.d
            )));
        }
        let files: Vec<String> = rows.iter().map(|r| r.field_file.clone()).collect();
        let window_mm = PROFILE_WINDOW * scene.max_contact_radius() * 1e3;
        let profiles = readback::read_profiles(
            dir.path(),
            &files,
            input.radius_mm,
            window_mm,
            toolchain,
            TIME_TO_START,
        )
        .map_err(SolveError::Failed)?;
        timing.reading_s = start.elapsed().as_secs_f64();
        Ok((rows, profiles, mesh, timing))
    }

    /// The template's numbers, converted to mm, N, MPa.
    fn input(&self, scene: &Scene, resolution: f64, approaches: &[f64], mesh: &MeshFiles) -> DeckInput {
        let body = scene.pair.body1;
        let mesh_file = self.deck.mesh_file(mesh);
        DeckInput {
            scene: scene.name.clone(),
            mesh: mesh_file
                .file_name()
                .map_or_else(String::new, |f| f.to_string_lossy().into_owned()),
            radius_mm: body.radius * 1e3,
            young_mpa: body.material.young * 1e-6,
            poisson: body.material.poisson,
            h_mm: resolution * 1e3,
            kfac: KFAC,
            d_mm: approaches.iter().map(|dn| dn / 2.0 * 1e3).collect(),
            max_iterations: MAX_ITERATIONS,
        }
    }

    /// One row per path step: deck rows at positions, exact zeros where the contact is open,
    /// `None` between positions.
    #[allow(clippy::too_many_arguments)]
    fn history(
        &self,
        scene: &Scene,
        version: &str,
        approaches: &[f64],
        rows: &[DeckRow],
        profiles: &[Profile],
        mesh: &MeshFiles,
        timing: Timing,
    ) -> History {
        let index_of = |dn: f64| approaches.iter().position(|&a| a == dn);
        let mut steps = Vec::new();
        let mut fields = Vec::new();
        let mut reaction = Vec::new();
        let mut iterations = Vec::new();
        let mut crossing = Vec::new();
        for step in scene.steps() {
            let mut row = StepResult::at(&step);
            if let Some(position) = step.position {
                match index_of(step.delta_n) {
                    Some(i) => {
                        let deck_row = &rows[i];
                        row.normal_force = Some(deck_row.force_contact);
                        row.contact_radius =
                            Some(readback::contact_radius(&profiles[i]).unwrap_or(deck_row.contact_radius));
                        crossing.push(json!([position, deck_row.contact_radius]));
                        row.peak_pressure = Some(deck_row.p0);
                        reaction.push(json!([position, deck_row.force_reaction]));
                        iterations.push(json!([position, deck_row.iterations]));
                        if scene.records_fields_at(position) {
                            fields.push(SurfaceField {
                                position,
                                points: profiles[i].iter().map(|s| [s.r, 0.0]).collect(),
                                pressure: profiles[i].iter().map(|s| s.pressure).collect(),
                                traction: None,
                                stick: None,
                            });
                        }
                    }
                    None => {
                        // δn ≤ 0: the spheres do not touch.
                        row.normal_force = Some(0.0);
                        row.contact_radius = Some(0.0);
                        row.peak_pressure = Some(0.0);
                    }
                }
            }
            steps.push(row);
        }
        let triangles = mesh.triangles;
        let mut metadata = Metadata {
            version: format!("{} {version}", self.deck.tool().name()),
            model: format!(
                "axisymmetric, one sphere ({}) pressed by δn/2 against its rigid frictionless symmetry plane; \
                 P from the contact traction",
                scene.domain.describe()
            ),
            resolution: format!(
                "pole element {:.3} µm (c_max/{:.0}), {triangles} triangles",
                mesh.resolution * 1e6,
                scene.max_contact_radius() / mesh.resolution
            ),
            warnings: vec![
                "a finite body, not a half-space: its offset from Hertz is the domain's (reference: mdr-domain)".into(),
                "rows between path positions are not computed (empty): the deck solves the distinct δn of the positions".into(),
            ],
            ..Metadata::default()
        };
        if !scene.path.is_normal_only() {
            metadata
                .warnings
                .push("normal contact only: tangential force and stick radius are not computed".into());
        }
        let extra = &mut metadata.extra;
        extra.insert("domain".into(), json!(scene.domain));
        extra.insert("p0_method".into(), json!(self.deck.p0_method()));
        extra.insert("normal_force_from_reaction_by_position".into(), json!(reaction));
        extra.insert("iterations_by_position".into(), json!(iterations));
        extra.insert(
            "contact_radius_method".into(),
            json!("edge fit of the gap g ~ (r - c)^(3/2) to the first two surface nodes outside the contact"),
        );
        extra.insert(
            "contact_radius_deck_linear_crossing_by_position".into(),
            json!(crossing),
        );
        extra.insert("solved_delta_n_m".into(), json!(approaches));
        extra.insert("penalty_factor".into(), json!(KFAC));
        extra.insert("meshing_s".into(), json!(timing.meshing_s));
        extra.insert("solving_s".into(), json!(timing.solving_s));
        extra.insert("reading_back_s".into(), json!(timing.reading_s));
        extra.insert("outcome".into(), json!("exited with code 0, output read back"));
        History {
            metadata,
            steps,
            fields,
        }
    }
}

/// `NotApplicable` unless the scene is two identical finite spheres (the symmetric model).
fn applicable(scene: &Scene) -> Result<(), SolveError> {
    if !scene.pair.is_symmetric() {
        return Err(SolveError::NotApplicable(
            "the external decks model two identical spheres through their symmetry plane; \
             different spheres or a sphere on a flat are not modelled yet"
                .into(),
        ));
    }
    if !scene.pair.body1.radius.is_finite() {
        return Err(SolveError::NotApplicable(
            "two flats have no contact to model".into(),
        ));
    }
    Ok(())
}

/// The distinct positive δn of the path positions, ascending [m].
pub fn distinct_approaches(scene: &Scene) -> Vec<f64> {
    let mut approaches: Vec<f64> = scene
        .path
        .positions()
        .iter()
        .map(|p| p.delta_n)
        .filter(|&dn| dn > 0.0)
        .collect();
    approaches.sort_by(f64::total_cmp);
    approaches.dedup();
    approaches
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::external::freefem::FreeFem;

    #[test]
    fn approaches_are_the_distinct_positive_positions() {
        let scene = crate::external::test_scene(&[0.0, 10.0, 17.0, 17.0, 20.0, 15.0, 0.0]);
        let a = distinct_approaches(&scene);
        let um: Vec<f64> = a.iter().map(|x| (x * 1e6).round()).collect();
        assert_eq!(um, vec![10.0, 15.0, 17.0, 20.0]);
    }

    #[test]
    fn different_spheres_are_not_applicable() {
        let mut scene = crate::external::test_scene(&[0.0, 17.0]);
        scene.pair.body2.radius = 0.05;
        let e = AxisymSolver::new(FreeFem).solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::NotApplicable(_)), "{e}");
    }

    #[test]
    fn a_missing_tool_is_unavailable_not_a_failure() {
        let scene = crate::external::test_scene(&[0.0, 17.0]);
        let mut solver = AxisymSolver::new(FreeFem);
        solver.options.toolchain.freefem = "/nonexistent/FreeFem++".into();
        let e = solver.solve(&scene).unwrap_err();
        assert!(matches!(e, SolveError::Unavailable(_)), "{e}");
        assert!(e.to_string().contains("scripts/setup.sh"), "{e}");
    }
}
