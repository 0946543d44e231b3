//! `fem-3d` with Coulomb friction: the hard cases of a path (μ = 0, gross sliding at once,
//! reversal at every increment, separation and re-contact while sliding, a pole element coarser
//! than the contact, bodies it does not model) on a coarse mesh (pole size c_max/4, a few
//! seconds each), and the paper's Figure 11–12 claim measured against the BEM at position 5 and
//! along Cattaneo's shift (heavy, ignored).
//!
//! The Q accuracy along the paper path and on Cattaneo's shift is checked by the shipped cases
//! (cases/paper-fig7.toml, cases/fem-3d-cattaneo.toml: `spherecontact verify`).

use crate::common;

use common::{identical_spheres, paper_scene_with_path};
use spherecontact::fem::FemSolid3d;
use spherecontact::history::History;
use spherecontact::map_measure;
use spherecontact::report::claims::measure::MapMeasures;
use spherecontact::report::claims::study;
use spherecontact::scene::Scene;
use spherecontact::solver::{self, SolveError, Solver};
use spherecontact::toolchain::{Tool, Toolchain};

fn gmsh_missing(test: &str) -> bool {
    let missing = Toolchain::default().require(Tool::Gmsh).is_err();
    if missing {
        eprintln!("{test}: gmsh is not installed, fem-3d is not available: nothing to run");
    }
    missing
}

/// fem-3d at pole size c_max/`divisions`.
fn fem3d(scene: &Scene, divisions: f64) -> History {
    let solver = FemSolid3d::with_pole_size(scene.max_contact_radius() / divisions);
    solver::run(&solver, scene).unwrap_or_else(|e| panic!("fem-3d: {e}"))
}

/// The coarse mesh of the light tests: the contact spans about four elements at its largest.
const COARSE: f64 = 4.0;
/// The mesh of the reversal test, whose Q is checked against the corrected reference: with the
/// multipliers at the corners, c_max/4 leaves 2.9 % of the peak, c_max/6 1.1 %, c_max/8 0.22 %.
///
/// Why c_max/4 is too coarse here and not for Cattaneo's shift: a reversal of ±0.5 µm slips only
/// a thin annulus. Cattaneo–Mindlin: the sliding shift is δ_s = 3μP/(16 G* c) = 4.15 µm at
/// δn = 17 µm (P = 808 N, c = 922 µm, G* = G/(2(2 − ν)) = 7.9 GPa), the first 0.5 µm leaves the
/// stick radius c_s/c = √(1 − δt/δ_s) = 0.938, and every later reversal of 1 µm, on Masing's
/// branch of twice the friction, √(1 − 1/(2 δ_s)) = 0.938 again: the slip annulus is 0.062 c =
/// 57 µm wide. c_max/4 puts the multiplier points 0.25 c = 230 µm apart, so the annulus is a
/// quarter of one spacing and lies between the last loaded ring and the edge, where no point
/// resolves it: Q, carried by μp over the annulus and by the stick zone's compliance inside, is
/// off by a share of the annulus's load. At c_max/8 the annulus is half a spacing. (Cattaneo's
/// shift to 5 µm slides the whole contact, its annuli are up to c wide: 0.52 % at c_max/4.)
const REVERSAL_MESH: f64 = 8.0;

#[test]
fn bodies_it_does_not_model_are_not_applicable_with_the_reason() {
    let mut scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 1.0)], 1);
    scene.pair.body2 = identical_spheres(0.1, 210e9, 0.29).body1;
    match FemSolid3d::default().solve(&scene) {
        Err(SolveError::NotApplicable(why)) => assert!(why.contains("dissimilar"), "{why}"),
        other => panic!("dissimilar bodies were answered: {other:?}"),
    }
    let mut axial = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 1.0)], 1);
    axial.domain.grip = spherecontact::domain::Grip::Axial;
    match FemSolid3d::default().solve(&axial) {
        Err(SolveError::NotApplicable(why)) => assert!(why.contains("axial grip"), "{why}"),
        other => panic!("a shifted axial grip was answered: {other:?}"),
    }
}

#[test]
fn zero_friction_gives_zero_tangential_force_exactly() {
    if gmsh_missing("zero_friction_gives_zero_tangential_force_exactly") {
        return;
    }
    let mut scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 2.0), (12.0, -1.0)], 2);
    scene.friction = 0.0;
    let history = fem3d(&scene, COARSE);
    assert!(history.steps.iter().all(|r| r.tangential_force == Some(0.0)));
    assert!(history.steps[2].normal_force.unwrap() > 0.0);
    // Every point in contact slips freely: the traction field is zero, no point sticks.
    let field = history.fields.last().expect("fields at the positions");
    assert!(field.traction.as_ref().unwrap().iter().all(|q| *q == [0.0, 0.0]));
    assert!(field.stick.as_ref().unwrap().iter().all(|&s| !s));
}

#[test]
fn gross_sliding_at_once_carries_mu_p() {
    if gmsh_missing("gross_sliding_at_once_carries_mu_p") {
        return;
    }
    // 6 µm in one increment at δn = 17 µm: past Cattaneo's sliding shift (4.1 µm).
    let scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 6.0)], 1);
    let history = fem3d(&scene, COARSE);
    let row = &history.steps[2];
    let (p, q) = (row.normal_force.unwrap(), row.tangential_force.unwrap());
    let ratio = q / (scene.friction * p);
    eprintln!(
        "gross sliding: Q/μP = {ratio:.6}, stick radius {:?}",
        row.stick_radius
    );
    // Every point slips with |q| = μp; q_x = μp cos θ with θ the slip's angle from x, which
    // the transverse compliance turns by a few per cent of a radian at most (cos ≥ 0.999);
    // measured Q/μP = 0.99987.
    assert!(ratio <= 1.0 + 1e-9 && ratio > 0.999, "Q/μP = {ratio}");
    assert_eq!(row.stick_radius, Some(0.0));
}

#[test]
#[ignore = "heavy: fem-3d along a path reversed at every increment, 6 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn reversal_at_every_increment_stays_on_the_masing_branches() {
    if gmsh_missing("reversal_at_every_increment_stays_on_the_masing_branches") {
        return;
    }
    // δt alternates ±0.5 µm at δn = 17 µm: every increment reverses the slip.
    let positions: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
        .chain(std::iter::once((17.0, 0.0)))
        .chain((0..8).map(|k| (17.0, if k % 2 == 0 { 0.5 } else { -0.5 })))
        .collect();
    let scene = paper_scene_with_path(&positions, 1);
    let history = fem3d(&scene, REVERSAL_MESH);
    let reference = common::solve("mdr-domain", &scene);
    let peak = reference.peak(spherecontact::history::Quantity::TangentialForce);
    let mut worst: f64 = 0.0;
    for (a, b) in history.steps.iter().zip(&reference.steps) {
        let (q, p) = (a.tangential_force.unwrap(), a.normal_force.unwrap());
        assert!(q.abs() <= scene.friction * p * (1.0 + 1e-9));
        worst = worst.max((q - b.tangential_force.unwrap()).abs() / peak);
    }
    eprintln!(
        "reversal every increment: worst |Q − Q_mdr-domain| = {:.3} % of the peak",
        100.0 * worst
    );
    // Each reversal after the first retraces the same branch (Masing): Q alternates between
    // two values, the same at every repetition to the engine's tolerance.
    let q: Vec<f64> = history
        .steps
        .iter()
        .map(|r| r.tangential_force.unwrap())
        .collect();
    for k in 4..q.len() {
        assert!(
            (q[k] - q[k - 2]).abs() < 1e-4 * peak,
            "step {k}: {} then {}",
            q[k - 2],
            q[k]
        );
    }
    // c_max/8 against the corrected reference: the mesh error of a contact eight elements wide,
    // measured 2.2e-3 of the peak; 1e-2 is the bound at the default mesh.
    assert!(worst < 1e-2, "{worst}");
}

#[test]
fn separation_and_recontact_while_sliding_start_from_rest() {
    if gmsh_missing("separation_and_recontact_while_sliding_start_from_rest") {
        return;
    }
    // Loaded and sheared, the gap opens while sliding, and closes again 2 µm further on.
    let path = [(0.0, 0.0), (17.0, 0.0), (17.0, 2.0), (-1.0, 3.0), (17.0, 5.0)];
    let scene = paper_scene_with_path(&path, 1);
    let history = fem3d(&scene, COARSE);
    let open = &history.steps[3];
    assert_eq!((open.normal_force, open.tangential_force), (Some(0.0), Some(0.0)));
    // The memory is cleared: the re-contact is the contact of a fresh pair loaded to 17 µm while
    // shifted by 2 µm in one increment.
    let fresh = fem3d(&paper_scene_with_path(&[(0.0, 0.0), (17.0, 2.0)], 1), COARSE);
    let (again, new) = (&history.steps[4], &fresh.steps[1]);
    let q = again.tangential_force.unwrap();
    assert!(q > 0.0);
    // The same mesh (gmsh is deterministic for one geometry) and the same increment.
    assert!(
        (q - new.tangential_force.unwrap()).abs() <= 1e-9 * q,
        "{q} against {:?}",
        new.tangential_force
    );
    assert!((again.normal_force.unwrap() - new.normal_force.unwrap()).abs() <= 1e-9 * q.abs().max(1.0));
}

#[test]
fn a_pole_element_coarser_than_the_contact_is_warned_about_with_friction() {
    if gmsh_missing("a_pole_element_coarser_than_the_contact_is_warned_about_with_friction") {
        return;
    }
    let scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 1.0)], 1);
    let history = fem3d(&scene, 1.0 / 0.7);
    let warnings = history.metadata.warnings.join("\n");
    assert!(warnings.contains("P, Q, c and p0 are unreliable"), "{warnings}");
    assert!(history.steps[2].tangential_force.is_some());
}

/// The paper's friction coefficient (cases/paper-fig7.toml).
const MU: f64 = 0.2;

/// What the Figure 11–12 tests read on a map at one path position: the map's measures (∫ q_y
/// over the quadrants), the transverse share max|q̄_y|/max|q̄_x| on the hat averages and the
/// stick zone's second-moment semi-axes (`map_measure`, what a case's checks read).
struct Map {
    measures: MapMeasures,
    ratio: f64,
    axes: [f64; 2],
}

/// The map of `history` at `position`, printed with `label`; the pointwise ratio of the reports
/// is printed, not asserted: a one-point spike at the stick edge, not a converged measure
/// (`fit::recovery`).
fn map_at(history: &History, position: usize, label: &str) -> Map {
    let (measures, c) = study::measure(history, position, MU, None).expect("a map");
    let field = history.field_at(position).expect("a map");
    let ratio = map_measure::transverse_ratio(field).expect("traction along x");
    let axes = map_measure::stick_semi_axes(field).expect("a stick zone");
    let q: Vec<f64> = measures.quadrants.iter().map(|s| s.total).collect();
    eprintln!(
        "{label}, position {position}: max|q̄_y|/max|q̄_x| (hat averages) {ratio:.4}, pointwise \
         {:.4}; ∫q_y over the quadrants {:+.3e} {:+.3e} {:+.3e} {:+.3e} N; stick semi-axes x/y \
         {:.1}/{:.1} µm; c {:.1} µm, spacing c/{:.0}",
        measures.qy_max / measures.qx_max,
        q[0],
        q[1],
        q[2],
        q[3],
        1e6 * axes[0],
        1e6 * axes[1],
        1e6 * c,
        c / measures.spacing
    );
    Map {
        measures,
        ratio,
        axes,
    }
}

/// A fem-3d run of the Figure 11–12 tests: pole size c_max/N and increments a segment.
type Run = (f64, usize);

/// The maps along one path at some of its positions: the BEM's (64², its default; 10 and 20
/// increments a segment) and fem-3d's (its runs), each indexed by run, then position.
struct Ladder {
    runs: Vec<Run>,
    bem: [Vec<Map>; 2],
    solid: Vec<Vec<Map>>,
}

impl Ladder {
    /// Every run along `path` (µm, the paper's spheres), measured at `positions`.
    fn along(path: &[(f64, f64)], positions: &[usize], runs: &[Run]) -> Self {
        let maps = |h: &History, label: &str| -> Vec<Map> {
            positions.iter().map(|&k| map_at(h, k, label)).collect()
        };
        let scene = |s| paper_scene_with_path(path, s);
        let bem = [10, 20].map(|s| {
            maps(
                &common::solve("bem", &scene(s)),
                &format!("bem, {s} increments a segment"),
            )
        });
        let solid = runs
            .iter()
            .map(|&(divisions, s)| {
                let label = format!("fem-3d c_max/{divisions}, {s} increments a segment");
                maps(&fem3d(&scene(s), divisions), &label)
            })
            .collect();
        Self {
            runs: runs.to_vec(),
            bem,
            solid,
        }
    }

    /// fem-3d's maps at the `k`-th measured position on its default mesh c_max/10 and finer,
    /// each with the BEM's at the same increments.
    fn judged(&self, k: usize) -> impl Iterator<Item = (&Map, &Map)> {
        self.runs
            .iter()
            .zip(&self.solid)
            .filter(|((divisions, _), _)| *divisions >= 10.0)
            .map(move |((_, s), run)| (&run[k], &self.bem[usize::from(*s == 20)][k]))
    }

    /// The sign pattern at the `k`-th measured position in both BEM runs and the judged fem-3d
    /// runs: q_y odd in x and in y (neighbouring quadrants opposite, equal within `tolerance` of
    /// the largest: the BEM's grid and fem-3d's mesh are not symmetric in x), the same sign in
    /// the first quadrant.
    fn assert_sign_pattern(&self, k: usize, tolerance: f64) {
        let reference = self.bem[0][k].measures.quadrants[0].total;
        let bem = self.bem.iter().map(|run| &run[k]);
        for map in bem.chain(self.judged(k).map(|(m, _)| m)) {
            let q = map.measures.quadrants;
            assert!(map.measures.is_odd_in_x_and_y(tolerance), "position {k}: {q:?}");
            assert!(q[0].total * reference > 0.0, "position {k}: {q:?}");
        }
    }

    /// The transverse share at the `k`-th measured position in every fem-3d run, in order.
    fn ratios(&self, k: usize) -> Vec<f64> {
        self.solid.iter().map(|run| run[k].ratio).collect()
    }

    /// The BEM's transverse share at the `k`-th measured position, at 10 and 20 increments.
    fn bem_ratios(&self, k: usize) -> [f64; 2] {
        self.bem.each_ref().map(|run| run[k].ratio)
    }

    /// The judged fem-3d runs' transverse share within `tolerance` (relative) of the BEM's at
    /// the same increments, at the `k`-th measured position.
    fn assert_ratio_near_the_bem(&self, k: usize, tolerance: f64) {
        for (mine, theirs) in self.judged(k) {
            let (r, rb) = (mine.ratio, theirs.ratio);
            assert!(
                (r / rb - 1.0).abs() < tolerance,
                "position {k}: fem-3d {r}, bem {rb}"
            );
        }
    }

    /// The judged fem-3d runs' stick semi-axes within `tolerance` [m] of the BEM's at the same
    /// increments, at the `k`-th measured position.
    fn assert_semi_axes_near_the_bem(&self, k: usize, tolerance: f64) {
        for (mine, theirs) in self.judged(k) {
            let (a, b) = (mine.axes, theirs.axes);
            assert!(
                (0..2).all(|i| (a[i] - b[i]).abs() < tolerance),
                "position {k}: {a:?} against {b:?}"
            );
        }
    }
}

/// The fem-3d runs that show convergence and the increments' effect: c_max/8, /10 and /14 at 10
/// increments a segment, c_max/10 at 20.
const RUNS_TO_C14: [Run; 4] = [(8.0, 10), (10.0, 10), (14.0, 10), (10.0, 20)];

/// A quarter of a c_max/10 element at δn = 17 µm (c = 922 µm): 23 µm, the resolution of the stick
/// zone's edge on fem-3d's default mesh (its corner multipliers are h ≈ c/10 apart).
const QUARTER_ELEMENT: f64 = 0.25 * 9.2e-5;

/// The paper's Figure 11–12 claim at position 5 (δn = 17 µm after the shifts 1, 2, 3 µm):
/// q_y against q_x, its sign over the quadrants and the stick semi-axes, fem-3d against the BEM,
/// each converged under refinement of the mesh (c_max/8, /10, /14) and of the increments (10, 20
/// a segment). Heavy (fem-3d along five segments four times, c_max/14 among them, about 3 min):
/// `cargo test --release --test suite fem3d_friction:: -- --ignored --nocapture`.
#[test]
#[ignore]
fn transverse_traction_and_stick_zone_at_position_five_converge_and_match_the_bem() {
    if gmsh_missing("transverse_traction_and_stick_zone_at_position_five_converge_and_match_the_bem") {
        return;
    }
    let path = [
        (0.0, 0.0),
        (10.0, 0.0),
        (14.0, 1.0),
        (17.0, 1.0),
        (17.0, 2.0),
        (17.0, 3.0),
    ];
    let ladder = Ladder::along(&path, &[5], &RUNS_TO_C14);
    ladder.assert_sign_pattern(0, 0.1);
    // ∫ q_y dA over the first quadrant within 6 % of the BEM's (64², its default) at the same
    // increments: measured −3.5 %, −2.9 % (c_max/10, /14) and −4.7 % (20 increments): the finite
    // body's softer shear (Q at position 5 is 1.6 % below MD's) beside the half-space's BEM.
    for (m, b) in ladder.judged(0) {
        let (qs, qb) = (m.measures.quadrants[0].total, b.measures.quadrants[0].total);
        assert!((qs / qb - 1.0).abs() < 0.06, "fem-3d {qs} N, bem {qb} N");
    }
    let (r, [rb10, rb20]) = (ladder.ratios(0), ladder.bem_ratios(0));
    let (r8, r10, r14, r10_20) = (r[0], r[1], r[2], r[3]);
    // The transverse share on the hat averages converges in the mesh: 0.0488, 0.0498, 0.0504 at
    // c_max/8, /10, /14, successive changes falling, the last 1.2 %.
    assert!((r14 - r10).abs() < (r10 - r8).abs(), "{r8} {r10} {r14}");
    assert!((r14 / r10 - 1.0).abs() < 0.02, "{r10} {r14}");
    // In the increments (q_y depends on the increment size, the forces hardly do): 10 → 20 a
    // segment moves fem-3d by +0.8 % (0.0498 → 0.0502) and the BEM alike (0.0495 → 0.0497 on
    // 64², 0.0492 → 0.0496 on 128²).
    assert!((r10_20 / r10 - 1.0).abs() < 0.02, "{r10} {r10_20}");
    assert!((rb20 / rb10 - 1.0).abs() < 0.02, "{rb10} {rb20}");
    // Against the BEM at the same increments, within 5 %: measured +0.6 % (c_max/10), +1.8 %
    // (c_max/14) and +1.0 % (20 increments). The BEM's is converged in its panels (0.0495,
    // 0.0492, 0.0492 on 64², 128², 256²); fem-3d's limit (≈ 0.051 by its falling changes) is
    // the finite body's, whose q_y integral differs by −3 to −5 % (above); both put the largest
    // |q̄_y| in the slip annulus at (±0.57, ±0.55) c (`examples/fem3d_transverse.rs`).
    ladder.assert_ratio_near_the_bem(0, 0.05);
    // The stick semi-axes converge to a quarter of a c_max/10 element: c_max/10 → /14 moves them
    // by 5.3 and 11.1 µm (489.2/492.5 → 494.5/481.4 µm); and they sit within a quarter element of
    // the BEM's (486.4/486.4 µm on 64²; at most 8.1 µm apart): no departure from a disc is
    // resolved.
    let axes: Vec<[f64; 2]> = ladder.solid.iter().map(|run| run[0].axes).collect();
    for a in 0..2 {
        assert!((axes[2][a] - axes[1][a]).abs() < QUARTER_ELEMENT, "{axes:?}");
    }
    ladder.assert_semi_axes_near_the_bem(0, QUARTER_ELEMENT);
}

/// The same claim along Cattaneo's shift: δn = 17 µm, then δt = 1, 2, 3, 4 µm at constant δn
/// (positions 2–5), fem-3d at c_max/10, /14, /18 and the BEM (64²), 10 and 20 increments a
/// segment. The panel study (64², 128², 256²: the BEM's share moves by at most 1.2 % a rung at δt ≥ 2 µm)
/// and c_max/8 are in `cargo run --release --example fem3d_transverse -- shift`. Heavy
/// (c_max/18 needs 6 GB; 137 s in all measured alone):
/// `cargo test --release --test suite fem3d_friction:: -- --ignored --nocapture`.
#[test]
#[ignore]
fn transverse_traction_and_stick_zone_along_the_cattaneo_shift_converge_and_match_the_bem() {
    if gmsh_missing("transverse_traction_and_stick_zone_along_the_cattaneo_shift_converge_and_match_the_bem")
    {
        return;
    }
    let path = [
        (0.0, 0.0),
        (17.0, 0.0),
        (17.0, 1.0),
        (17.0, 2.0),
        (17.0, 3.0),
        (17.0, 4.0),
    ];
    let runs = [(10.0, 10), (14.0, 10), (18.0, 10), (10.0, 20)];
    let ladder = Ladder::along(&path, &[2, 3, 4, 5], &runs);
    // The sign pattern −, +, −, + (counter-clockwise from x, y > 0) at every δt in both, the
    // quadrants' integrals equal within 10 % of the largest at δt ≥ 2 µm; at δt = 1 µm fem-3d's
    // mesh, not symmetric in x, splits them by 10.6 % (c_max/10: −0.0819, +0.0732 N; the BEM's
    // ±0.0722 N) where the slip annulus is about one element wide (below), so 15 % there.
    ladder.assert_sign_pattern(0, 0.15);
    for k in 1..4 {
        ladder.assert_sign_pattern(k, 0.1);
    }
    // δt = 2 and 3 µm (k = 1, 2): the share converges in the mesh, measured 0.0575, 0.0588,
    // 0.0598 and 0.0529, 0.0542, 0.0545 at c_max/10, /14, /18 (successive changes falling; the
    // last 1.7 % and 0.6 %), and hardly moves with the increments (10 → 20 a segment: fem-3d
    // +0.5 %, +0.8 %; the BEM +0.7 %, +0.8 %).
    for k in [1, 2] {
        let (r, [rb10, rb20]) = (ladder.ratios(k), ladder.bem_ratios(k));
        assert!((r[2] - r[1]).abs() < (r[1] - r[0]).abs(), "δt = {k} µm: {r:?}");
        assert!((r[2] / r[1] - 1.0).abs() < 0.025, "δt = {k} µm: {r:?}");
        assert!((r[3] / r[0] - 1.0).abs() < 0.02, "δt = {k} µm: {r:?}");
        assert!((rb20 / rb10 - 1.0).abs() < 0.02, "δt = {k} µm: {rb10} {rb20}");
        // Against the BEM at the same increments, within 6 %: measured −1.9 %, +0.3 %, +2.0 %
        // (δt = 2 µm) and +0.6 %, +3.0 %, +3.6 % (3 µm) at c_max/10, /14, /18; −2.0 % and +0.6 %
        // at 20 increments. fem-3d's limit lies about 3.5 % above the BEM's converged share
        // (0.0578 and 0.0526 on 256²): the finite body's softer shear, as its Q (cases/
        // fem-3d-cattaneo.toml: 3.5 % below Cattaneo–Mindlin's); 6 % is that plus the 2 % its
        // c_max/10 still moves.
        ladder.assert_ratio_near_the_bem(k, 0.06);
    }
    // δt = 1 µm is not asserted: fem-3d's share is not converged (0.0610, 0.0524, 0.0738 at
    // c_max/10, /14, /18 against the BEM's 0.0600, 0.0614, 0.0608 on 64², 128², 256²): the slip
    // annulus c − c_s ≈ 118 µm is 1.3 elements of c_max/10 and 2.3 of c_max/18 wide, too thin
    // for the stick edge's spike to average out over a hat.
    // The stick semi-axes within a quarter of a c_max/10 element of the BEM's at δt = 1, 2, 3 µm:
    // measured at most 16, 14 and 10 µm apart (c_max/18 at 3 µm: 495.9/493.4 against 486.4/486.4
    // µm). At δt = 4 µm (printed, not asserted) fem-3d's zone is about 50 µm larger (209/199 to
    // 209/214 µm against 165/151): b = c √(1 − δt/δ_s) near gross sliding magnifies the finite
    // body's softer shear (its δ_s about 2.4 % above the BEM's), not a mesh effect.
    for k in 0..3 {
        ladder.assert_semi_axes_near_the_bem(k, QUARTER_ELEMENT);
    }
}

/// Q on Cattaneo's shift (δn = 17 µm, δt 0 → 5 µm, 10 increments) against mdr-domain under
/// refinement of the pole size, c_max/4, /6, /10, /14. Heavy (c/14: 2.5 GB, about a minute):
/// `cargo test --release --test suite fem3d_friction:: -- --ignored --nocapture`.
#[test]
#[ignore]
fn tangential_force_converges_under_refinement() {
    if gmsh_missing("tangential_force_converges_under_refinement") {
        return;
    }
    let mut scene = paper_scene_with_path(&[(0.0, 0.0), (17.0, 0.0), (17.0, 5.0)], 10);
    scene.path =
        spherecontact::path::LoadingPath::try_new(scene.path.positions().to_vec(), vec![2, 10]).unwrap();
    let reference = common::solve("mdr-domain", &scene);
    let peak = reference.peak(spherecontact::history::Quantity::TangentialForce);
    let errors: Vec<f64> = [4.0, 6.0, 10.0, 14.0]
        .into_iter()
        .map(|divisions| {
            let history = fem3d(&scene, divisions);
            let worst = history
                .steps
                .iter()
                .zip(&reference.steps)
                .map(|(a, b)| (a.tangential_force.unwrap() - b.tangential_force.unwrap()).abs() / peak)
                .fold(0.0, f64::max);
            eprintln!(
                "c/{divisions}: worst |Q − Q_mdr-domain| = {:.4} % of the peak",
                100.0 * worst
            );
            worst
        })
        .collect();
    // The error falls at every refinement, towards the reference's own first-order remainder
    // (about 1.1e-3 of the peak, which fem-axisym also leaves at c_max/40): measured 0.52 %,
    // 0.19 %, 0.10 %, 0.096 % at c_max/4, /6, /10, /14 with the corner multipliers.
    assert!(errors.windows(2).all(|e| e[1] < e[0]), "{errors:?}");
    assert!(errors[2] < 3e-3, "{errors:?}");
}
