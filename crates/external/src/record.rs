//! What a deck run becomes: one `History` row per path step from the deck's rows and the contact
//! line's nodal state, the surface fields at path positions, and the metadata that says how they
//! were obtained (model, grip, modes, iterations, flagged steps, timings).

use serde_json::json;

use super::deck::Deck;
use super::field_files::Profile;
use super::plan::{Plan, KFAC};
use super::readback::{DeckRow, Outcome};
use super::surface::Surface;
use spherecontact_model::history::{History, Metadata, StepResult};
use spherecontact_model::scene::Scene;
use spherecontact_solvers::fem::mesh::geo::MeshFiles;

/// Wall time of the three parts of an external run [s].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timing {
    /// gmsh.
    pub meshing_s: f64,
    /// The deck.
    pub solving_s: f64,
    /// steps.csv, surface.csv and the field files through meshio.
    pub reading_s: f64,
}

/// What a finished deck run left, read back.
pub struct Run {
    /// One row per computed step.
    pub rows: Vec<DeckRow>,
    /// The contact line at each computed step.
    pub surfaces: Vec<Surface>,
    /// The mesh.
    pub mesh: MeshFiles,
    /// Wall times of meshing, solving, reading back.
    pub timing: Timing,
    /// The deck's own clock of its set-up and of the path [s] (`timing.csv`).
    pub deck_clock: (Option<f64>, Option<f64>),
}

/// Largest disagreement between a field file's pressure and the nodal pressure of `surface.csv`,
/// relative to the largest pressure: both hold the same numbers; VTU and XDMF keep at least
/// single precision (1e-7), so 1e-6 separates round-off from a different field.
const FIELD_FILE_AGREEMENT: f64 = 1e-6;

/// Checks that a field file's surface pressure (read through meshio) is the nodal pressure of
/// `surface.csv` at the same radii (within [`FIELD_FILE_AGREEMENT`]).
pub fn check_field_file(file: &str, profile: &Profile, surface: &Surface) -> Result<(), String> {
    let scale = surface
        .nodes
        .iter()
        .fold(0.0_f64, |m, n| m.max(n.pressure))
        .max(1.0);
    let tolerance_r = 1e-9 * surface.nodes.last().map_or(1.0, |n| n.r);
    let mut matched = 0;
    for point in profile {
        let Some(node) = surface
            .nodes
            .iter()
            .find(|n| (n.r - point.r).abs() <= tolerance_r)
        else {
            continue;
        };
        matched += 1;
        if (node.pressure - point.pressure).abs() > FIELD_FILE_AGREEMENT * scale {
            return Err(format!(
                "{file}: its pressure departs from surface.csv's at a node by {:.1e} of the peak \
                 (allowed: {FIELD_FILE_AGREEMENT:e}: the same numbers, written twice)",
                (node.pressure - point.pressure).abs() / scale
            ));
        }
    }
    if matched < 2 {
        return Err(format!("{file}: no surface point at the radii of surface.csv"));
    }
    Ok(())
}

/// The history of a run: one row per path step, fields at path positions, metadata.
pub fn history(deck: &impl Deck, scene: &Scene, version: &str, plan: &Plan, run: &Run) -> History {
    let mut steps = Vec::with_capacity(run.rows.len());
    let mut fields = Vec::new();
    let mut reaction = Vec::new();
    for ((step, row), surface) in scene.steps().iter().zip(&run.rows).zip(&run.surfaces) {
        let measures = surface.measures();
        let in_contact = row.force_contact > 0.0;
        let contact_radius = measures.contact_radius;
        if let (Some(position), Some(p)) = (step.position, row.force_reaction) {
            reaction.push(json!([position, p]));
        }
        if let Some(position) = step.position.filter(|&p| scene.records_fields_at(p)) {
            fields.push(surface.field(position, measures.pressure.clone(), plan.tangential));
        }
        steps.push(StepResult {
            normal_force: Some(row.force_contact),
            tangential_force: plan.tangential.then_some(row.tangential_force),
            contact_radius,
            peak_pressure: measures.peak_pressure,
            stick_radius: (plan.tangential && in_contact)
                .then(|| contact_radius.map(|c| surface.stick_radius(c)))
                .flatten(),
            ..StepResult::at(step)
        });
    }
    History {
        metadata: metadata(deck, scene, version, plan, run, reaction),
        steps,
        fields,
    }
}

/// How the history was obtained.
/// The warning every deck's history carries: a finite body, not Hertz's half-space.
pub const FINITE_BODY: &str = "finite body, not a half-space: P, c, p0 and Q differ from Hertz and \
     Mindlin–Deresiewicz by the domain's compliance, which mdr-domain computes (docs/finite-body.md)";

fn metadata(
    deck: &impl Deck,
    scene: &Scene,
    version: &str,
    plan: &Plan,
    run: &Run,
    reaction: Vec<serde_json::Value>,
) -> Metadata {
    let mesh = &run.mesh;
    let modes = if plan.tangential {
        "Fourier modes n = 0 (normal) and n = 1 (tangential: far face shifted by δt/2, Coulomb with \
         history per contact node, traction along x as Mindlin assumes)"
    } else {
        "Fourier mode n = 0 (normal; the path has no tangential motion)"
    };
    let mut metadata = Metadata {
        version: format!("{} {version}", deck.tool().name()),
        model: format!(
            "axisymmetric, one sphere ({}) against its symmetry plane, exact for identical spheres; \
             {modes}; penalty k = {KFAC:e} E/h with nodal contact quadrature, condensed onto the \
             contact-line nodes",
            scene.domain.describe()
        ),
        resolution: format!(
            "pole element {:.3} µm (c_max/{:.0}), {} triangles; every path step computed",
            mesh.resolution * 1e6,
            scene.max_contact_radius() / mesh.resolution,
            mesh.triangles
        ),
        warnings: vec![FINITE_BODY.into()],
        ..Metadata::default()
    };
    if plan.tangential {
        metadata
            .warnings
            .push("q_y and non-circular stick zones are outside this model (Fourier modes 0 and 1)".into());
    }
    let flagged: Vec<usize> = steps_with(run, Outcome::Capped);
    let timing = &run.timing;
    let run_facts = RunFacts {
        candidate_nodes: run.surfaces.first().map_or(0, |s| s.nodes.len()),
        capped: &flagged,
        wall_s: [timing.meshing_s, timing.solving_s, timing.reading_s],
    };
    record_run(&mut metadata, plan, &run_facts);
    let extra = &mut metadata.extra;
    extra.insert(
        "fourier_modes".into(),
        json!(if plan.tangential { vec![0, 1] } else { vec![0] }),
    );
    extra.insert(
        "contact_measures".into(),
        json!("as fem-axisym, from the nodal ring forces: c from a quadratic fit of p² at the edge, p0 from an even fit of p on 0 < r ≤ c/2, stick radius c √(stick area / contact area) of the nodal rings (fit::stick)"),
    );
    extra.insert("normal_force_from_reaction_by_position".into(), json!(reaction));
    let total = |f: fn(&DeckRow) -> u32| run.rows.iter().map(|r| u64::from(f(r))).sum::<u64>();
    extra.insert(
        "iterations_normal_total".into(),
        json!(total(|r| r.iterations_normal)),
    );
    extra.insert(
        "iterations_tangential_total".into(),
        json!(total(|r| r.iterations_tangential)),
    );
    extra.insert(
        "stick_edge_cycles_at_steps".into(),
        json!(steps_with(run, Outcome::Cycle)),
    );
    if let (Some(setup), Some(path)) = run.deck_clock {
        extra.insert("deck_setup_s".into(), json!(setup));
        extra.insert("deck_path_s".into(), json!(path));
    }
    metadata
}

/// What every deck run (axisymmetric or 3D) records the same way.
pub struct RunFacts<'a> {
    /// Contact candidate nodes.
    pub candidate_nodes: usize,
    /// The steps whose contact iteration hit its cap.
    pub capped: &'a [usize],
    /// Wall time of meshing, solving and reading back [s].
    pub wall_s: [f64; 3],
}

/// Records in `metadata` what every deck run states: the grip, the steps computed, the candidate
/// zone, the penalty, the capped steps (with a warning when there are any), the wall times and
/// the outcome.
pub fn record_run(metadata: &mut Metadata, plan: &Plan, facts: &RunFacts) {
    if !facts.capped.is_empty() {
        metadata.warnings.push(format!(
            "the contact iteration hit its cap at steps {:?}: their values are the last iterate's",
            facts.capped
        ));
    }
    let [meshing, solving, reading] = facts.wall_s;
    let extra = &mut metadata.extra;
    extra.insert("grip".into(), json!(plan.grip.name()));
    extra.insert("computed_steps".into(), json!("every step of the path"));
    extra.insert("candidate_radius_m".into(), json!(plan.candidate_radius));
    extra.insert("candidate_nodes".into(), json!(facts.candidate_nodes));
    extra.insert("penalty_factor".into(), json!(KFAC));
    extra.insert("capped_steps".into(), json!(facts.capped));
    extra.insert("meshing_s".into(), json!(meshing));
    extra.insert("solving_s".into(), json!(solving));
    extra.insert("reading_back_s".into(), json!(reading));
    extra.insert("outcome".into(), json!("exited with code 0, output read back"));
}

/// The path steps whose iteration ended with `outcome`.
fn steps_with(run: &Run, outcome: Outcome) -> Vec<usize> {
    run.rows
        .iter()
        .filter(|r| r.outcome == outcome)
        .map(|r| r.step)
        .collect()
}
