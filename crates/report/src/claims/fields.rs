//! The claims about the surface fields at the focus position (the paper's Figures 10–12): the
//! pressure and the stick zone are axisymmetric, the frictional stress is not, Cattaneo–Mindlin's
//! neglect of q_y and the paper's "mismatch", and where the largest frictional stress lies. Each
//! is measured on the paper's own kind of model, a finite element solver that maps the contact
//! plane (fem-3d), when it ran, else on the first map solver; at the finest resolution of the
//! study, with the coarser rung and the run itself beside it, and the other map solvers (the
//! BEM's half-space) measured alike beside them.

mod transverse;

use super::measure::{MapMeasures, RadialProfile, AXIS_READ};
use super::study::{self, Study};
use crate::figures::{history, TANGENTIAL_REFERENCE};
use crate::{claims::is_finite_element, claims::Claim, claims::Verdict};
use spherecontact_reference::cattaneo_mindlin::virgin_stick_radius;
use spherecontact_verify::CaseRun;

/// |q| "is axisymmetric" when it differs along x and along y by at most 1 % of its peak: a
/// contour plot of ten levels steps by 10 %, so 1 % is a tenth of one level.
const MAGNITUDE_AXISYMMETRY: f64 = 0.01;

/// The mesh size for which the report quantifies how a coarse mesh lowers the cusp of |q|
/// [fraction of c]: ten elements across the contact radius.
const COARSE_MESH: f64 = 0.1;

/// One solve's measures at the focus position, and how it was resolved.
struct Measured {
    /// "at h = c/58" for a study rung, "in this run (h = c/26, 100 increments a segment)".
    label: String,
    /// "c/58" for a study rung, the label for the run.
    short: String,
    measures: MapMeasures,
    /// The contact radius [m].
    c: f64,
}

/// A map solver's measures: the study's rungs (coarse to fine), then the run itself.
struct Evidence {
    solver: String,
    /// The solver's Q at the focus position in this run [N].
    force: Option<f64>,
    cases: Vec<Measured>,
    /// How many of `cases` come from the study.
    rungs: usize,
}

impl Evidence {
    /// The finest study rung, or the run itself without a study.
    fn best(&self) -> &Measured {
        &self.cases[self.rungs.saturating_sub(1)]
    }

    /// The others, for the parentheses.
    fn others(&self) -> impl Iterator<Item = &Measured> {
        let best = self.rungs.saturating_sub(1);
        self.cases
            .iter()
            .enumerate()
            .filter(move |(k, _)| *k != best)
            .map(|(_, m)| m)
    }

    /// `value` at the best case, the others in parentheses: "0.52 c at h = c/58 (c/29: 0.53 c; …)".
    fn across(&self, value: impl Fn(&Measured) -> Option<String>) -> String {
        let best = self.best();
        let others: Vec<String> = self
            .others()
            .filter_map(|m| Some(format!("{}: {}", m.short, value(m)?)))
            .collect();
        let mut text = format!("{} {}", value(best).unwrap_or_else(|| "—".into()), best.label);
        if !others.is_empty() {
            text.push_str(&format!(" ({})", others.join("; ")));
        }
        text
    }

    /// The largest change of `value` between the two finest study rungs, if there are two.
    fn change(&self, value: impl Fn(&Measured) -> Option<f64>) -> Option<f64> {
        (self.rungs >= 2).then(|| {
            let (a, b) = (&self.cases[self.rungs - 2], &self.cases[self.rungs - 1]);
            Some((value(a)? - value(b)?).abs())
        })?
    }
}

/// What the field claims compare with: MD's (MDR's) stick radius and traction, and Hertz at the
/// focus position.
struct References {
    /// μ p0 of Hertz at the focus position [Pa].
    mu_p0: f64,
    /// MDR's stick radius [m] and contact radius [m], if it ran.
    md_stick: Option<(f64, f64)>,
    /// MDR's traction profile.
    md: Option<RadialProfile>,
    /// Cattaneo–Mindlin's stick radius for Hertz's P and MDR's Q [m].
    cm_stick: Option<f64>,
}

fn references(run: &CaseRun) -> References {
    let scene = &run.case.scene;
    let focus = run.case.focus;
    let delta_n = scene
        .steps()
        .into_iter()
        .find(|s| s.position == Some(focus))
        .map_or(0.0, |s| s.delta_n);
    let hertz = scene.hertz();
    let mdr = history(run, TANGENTIAL_REFERENCE).and_then(|h| h.at_position(focus));
    References {
        mu_p0: scene.friction * hertz.peak_pressure(delta_n),
        md_stick: mdr
            .and_then(|row| Some((row.stick_radius?, row.contact_radius?)))
            .filter(|&(_, c)| c > 0.0),
        md: study::md_profile(run),
        cm_stick: mdr
            .and_then(|row| row.tangential_force)
            .map(|q| virgin_stick_radius(&hertz, scene.friction, delta_n, q)),
    }
}

/// The evidence of every map solver of the run.
fn evidence(run: &CaseRun, study: &Study) -> Vec<Evidence> {
    let size = |m: &MapMeasures, c: f64| format!("c/{:.0}", c / m.spacing);
    let case_increments = run.case.scene.path.substeps().first().copied().unwrap_or(0);
    study::map_solvers(run)
        .into_iter()
        .filter_map(|solver| {
            let (own, c) = study::measure_run(run, &solver)?;
            let mut cases: Vec<Measured> = study
                .of_solver(&solver)
                .map(|s| {
                    s.rungs
                        .iter()
                        .map(|r| Measured {
                            label: format!("at h = {}", size(&r.measures, r.contact_radius)),
                            short: size(&r.measures, r.contact_radius),
                            measures: r.measures.clone(),
                            c: r.contact_radius,
                        })
                        .collect()
                })
                .unwrap_or_default();
            let rungs = cases.len();
            let run_label = format!(
                "this run (h = {}, {case_increments} increments a segment)",
                size(&own, c)
            );
            cases.push(Measured {
                label: format!("in {run_label}"),
                short: run_label,
                measures: own,
                c,
            });
            let force = history(run, &solver)
                .and_then(|h| h.at_position(run.case.focus))
                .and_then(|row| row.tangential_force);
            Some(Evidence {
                solver,
                force,
                cases,
                rungs,
            })
        })
        .collect()
}

/// How far below the cusp of |q| at the stick edge a sample up to h/2 inside it can lie,
/// relative to the peak of `m`, for samples `h` [m] apart: on the stick side
/// μp − |q| = μp0 √(c_s² − r²)/c grows as √(2 c_s (c_s − r)), so μp0 √(c_s h)/c (Cattaneo's
/// stick radius c_s for the run's P and Q).
fn cusp_sampling(r: &References, m: &Measured, h: f64) -> Option<f64> {
    let cs = r.cm_stick?;
    Some(fraction(
        r.mu_p0 * (cs * h).sqrt(),
        m.c * m.measures.peak.map_or(0.0, |p| p.value),
    ))
}

/// a / b, or 0 where b is not positive (no traction: nothing to compare with), never NaN.
fn fraction(a: f64, b: f64) -> f64 {
    if b > 0.0 {
        a / b
    } else {
        0.0
    }
}

/// What a row found on one solver.
struct Found {
    /// What was measured.
    measured: String,
    /// The verdict.
    verdict: Verdict,
    /// The verdict in a sentence.
    reading: String,
    /// The one number that decides it, against what.
    decides: String,
}

impl Found {
    fn new(measured: String, verdict: Verdict, reading: impl Into<String>, decides: String) -> Self {
        Self {
            measured,
            verdict,
            reading: reading.into(),
            decides,
        }
    }
}

/// A row's measurement from the evidence of the solver it is judged on and of the other map
/// solvers (to compare with).
type Finding = fn(&Evidence, &References, &[&Evidence]) -> Found;

/// The claims about the surface fields.
pub fn claims(run: &CaseRun, study: &Study) -> Vec<Claim> {
    let evidence = evidence(run, study);
    let references = references(run);
    let fe_note = if evidence.iter().any(|e| is_finite_element(&e.solver)) {
        String::new()
    } else {
        ". The paper's FE model: not measured (needs fem-3d)".to_owned()
    };
    let focus = run.case.focus;
    let rows: [(&str, &str, Judge, Finding); 5] = [
        (
            "The contact pressure is axisymmetric, as Hertz's (Figure 10)",
            "pressure-map",
            Judge::FiniteElement,
            pressure_axisymmetry,
        ),
        (
            "The contact status (stick zone) is axisymmetric (Figure 12)",
            "status-map",
            Judge::FiniteElement,
            stick_zone,
        ),
        (
            "The frictional stress is non-axisymmetric, unlike MD's (Figure 11)",
            "traction-y-map",
            Judge::FiniteElement,
            transverse::claim,
        ),
        (
            "There is a mismatch in the tangential stress distribution against MD, left for further investigation \
             (Conclusion): is it Cattaneo–Mindlin's neglect of q_y?",
            "traction-profile",
            Judge::HalfSpace,
            mismatch,
        ),
        (
            "The maximum frictional stress is not at the stick/slip boundary, contrary to MD (Results)",
            "traction-magnitude-map",
            Judge::FiniteElement,
            peak_location,
        ),
    ];
    rows.into_iter()
        .map(|(claim, figure, judge, row)| {
            let Some(judged) = judge.pick(&evidence) else {
                return Claim::not_measured(
                    claim,
                    "a solver that maps the contact plane with friction (bem, fem-3d)",
                    "—",
                );
            };
            let e = &evidence[judged];
            let others: Vec<&Evidence> = evidence
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != judged)
                .map(|(_, o)| o)
                .collect();
            let found = row(e, &references, &others);
            let beside: String = others
                .iter()
                .map(|o| format!(". Beside it, {}: {}", o.solver, row(o, &references, &[]).measured))
                .collect();
            Claim {
                claim: claim.into(),
                measured: format!("{}: {}{beside}{fe_note}", e.solver, found.measured),
                verdict: found.verdict,
                reading: found.reading,
                decides: format!("{}: {}", e.solver, found.decides),
                evidence: format!("figure {figure}-{focus}"),
            }
        })
        .collect()
}

/// Which map solver a row is judged on.
#[derive(Clone, Copy)]
enum Judge {
    /// The paper's own kind of model: the first finite element map solver (fem-3d), else the
    /// first map solver. For what the paper saw in its FE maps.
    FiniteElement,
    /// The first half-space map solver (the BEM), else the first map solver. For a question
    /// about Mindlin–Deresiewicz's assumptions, which hold for half-spaces: a finite body's
    /// traction departs from MD's by its own compliance too.
    HalfSpace,
}

impl Judge {
    /// The index of the judged solver in `evidence`, if any solver mapped the plane.
    fn pick(self, evidence: &[Evidence]) -> Option<usize> {
        let wanted = |e: &Evidence| is_finite_element(&e.solver) == matches!(self, Judge::FiniteElement);
        evidence
            .iter()
            .position(wanted)
            .or((!evidence.is_empty()).then_some(0))
    }
}

/// p read along x and along y, against the peak.
fn pressure_axisymmetry(e: &Evidence, _: &References, _: &[&Evidence]) -> Found {
    let departure = |m: &Measured| fraction(m.measures.pressure_axis_difference, m.measures.pressure_max);
    let measured = format!(
        "p read along x and along y (r ≤ {AXIS_READ} c) differs, relative to its peak, by ≤ {}",
        e.across(|m| Some(format!("{:.2} %", departure(m) * 100.0)))
    );
    let d = departure(e.best());
    let moves = match e.change(|m| Some(departure(m))) {
        Some(c) if c > d => format!(
            "; the coarser rung departs by {:.2} %: the departure falls under refinement (the mesh's, not the field's)",
            (d + c) * 100.0
        ),
        Some(c) => format!("; it moves by {:.2} % of the peak under refinement", c * 100.0),
        None => String::new(),
    };
    let decides = format!(
        "p along x against along y: {}",
        super::against_limit(d, MAGNITUDE_AXISYMMETRY)
    );
    if d <= MAGNITUDE_AXISYMMETRY {
        Found::new(
            measured,
            Verdict::Confirmed,
            format!(
                "axisymmetric to {:.2} % of its peak, within a tenth of a contour level{moves}",
                d * 100.0
            ),
            decides,
        )
    } else {
        Found::new(
            measured,
            Verdict::NotConfirmed,
            format!(
                "p departs from axisymmetry by {:.2} % of its peak, more than a tenth of a contour level{moves}",
                d * 100.0
            ),
            decides,
        )
    }
}

/// Stick semi-axes along x and y against each other and against MD: judged on the second
/// moments (integrals over the stick samples, which converge), the edge fit beside them (where
/// the discrete edge falls between a mesh's nodes moves it by up to a sample).
fn stick_zone(e: &Evidence, r: &References, _: &[&Evidence]) -> Found {
    let relative = |axes: Option<[f64; 2]>, c: f64| axes.map(|[x, y]| [fraction(x, c), fraction(y, c)]);
    let moments = |m: &Measured| relative(m.measures.stick_moments, m.c);
    let edges = |m: &Measured| relative(m.measures.stick_axes, m.c);
    let text = |[x, y]: [f64; 2]| format!("{x:.4} c, {y:.4} c ((a_y − a_x)/c = {:+.1e})", y - x);
    let mut measured = format!(
        "stick semi-axes a_x, a_y from the stick zone's second moments = {}; from the edge fit along the axes {}",
        e.across(|m| moments(m).map(text)),
        e.across(|m| edges(m).map(text))
    );
    if let Some((cs, c)) = r.md_stick {
        measured.push_str(&format!("; MD (mdr) c_s = {:.4} c", cs / c));
    }
    let Some([x, y]) = moments(e.best()) else {
        return Found::new(
            measured,
            Verdict::NotMeasured,
            "no stick zone to measure",
            "no stick zone".into(),
        );
    };
    // What refinement still moves the semi-axes; without two rungs, half a sample (where the
    // discrete edge falls).
    let (resolution, how) = match e
        .change(|m| Some(moments(m)?[0]))
        .zip(e.change(|m| Some(moments(m)?[1])))
    {
        Some((dx, dy)) => (dx.max(dy), "their change under refinement"),
        None => (0.5 * e.best().measures.spacing / e.best().c, "half a sample"),
    };
    let departure = (y - x).abs();
    let decides = format!("|a_y − a_x| = {departure:.1e} c against {resolution:.1e} c ({how})");
    if departure <= resolution {
        Found::new(
            measured,
            Verdict::Confirmed,
            format!(
                "no departure from a disc is resolved: the second moments' |a_y − a_x| = {departure:.1e} c, within {how} \
                 ({resolution:.1e} c)"
            ),
            decides,
        )
    } else {
        Found::new(
            measured,
            Verdict::NotConfirmed,
            format!(
                "the stick zone is elongated: the second moments' |a_y − a_x| = {departure:.1e} c beyond {how} \
                 ({resolution:.1e} c)"
            ),
            decides,
        )
    }
}

/// The departure from MD's traction, split into its transverse and parallel parts.
fn mismatch(e: &Evidence, r: &References, _: &[&Evidence]) -> Found {
    let part = |m: &Measured, k: usize| m.measures.departure.map(|d| fraction(d[k], r.mu_p0));
    let measured = format!(
        "RMS over the contact of the departure from MD's traction (mdr's q(r) along x), relative to μp0: transverse \
         q_y {}; parallel q_x − q_MD {}",
        e.across(|m| part(m, 0).map(|v| format!("{:.2} %", v * 100.0))),
        e.across(|m| part(m, 1).map(|v| format!("{:.2} %", v * 100.0)))
    );
    let best = e.best();
    let (Some(transverse), Some(parallel)) = (part(best, 0), part(best, 1)) else {
        return Found::new(
            measured,
            Verdict::NotMeasured,
            format!("needs {TANGENTIAL_REFERENCE}'s traction"),
            format!("needs {TANGENTIAL_REFERENCE}'s traction"),
        );
    };
    let peak = best.measures.peak.map_or(0.0, |p| p.value);
    let share = fraction(best.measures.transverse_share, peak);
    let decides = format!(
        "RMS transverse q_y {:.2} % against parallel q_x − q_MD {:.2} % of μp0",
        transverse * 100.0,
        parallel * 100.0
    );
    if transverse > parallel {
        Found::new(
            measured,
            Verdict::Partly,
            format!(
                "q_y is the larger part of the exact solution's departure from MD, so Cattaneo–Mindlin's neglect of q_y \
                 explains a non-axisymmetric traction vector; it cannot explain visibly non-axisymmetric contours of |q|, \
                 which q_y changes by ≤ {:.2} % of the peak",
                share * 100.0
            ),
            decides,
        )
    } else {
        Found::new(
            measured,
            Verdict::NotConfirmed,
            "the parallel part q_x − q_MD is the larger: the neglect of q_y is not the main departure from MD",
            decides,
        )
    }
}

/// Where the largest |q| lies against the stick edge, and what a coarse mesh does to it.
fn peak_location(e: &Evidence, r: &References, _: &[&Evidence]) -> Found {
    let offset = |m: &Measured| {
        let p = m.measures.peak?;
        Some((p.radius() - p.edge?) / m.measures.spacing)
    };
    let mut measured = format!(
        "max |q| = {}; its distance from the stick edge in its direction (the ellipse through a_x, a_y): {}",
        e.across(|m| m.measures.peak.map(|p| {
            format!(
                "{:.2} MPa at r = {:.4} c, θ = {:.0}°",
                p.value * 1e-6,
                fraction(p.radius(), m.c),
                p.point[1].atan2(p.point[0]).to_degrees()
            )
        })),
        e.across(|m| offset(m).map(|o| format!("{o:+.2} h")))
    );
    if let Some(md) = &r.md {
        let (rm, qm) = md.peak();
        if let Some((_, c)) = r.md_stick {
            measured.push_str(&format!(
                "; MD (mdr): {:.2} MPa at r = {:.4} c",
                qm * 1e-6,
                rm / c
            ));
        }
    }
    let best = e.best();
    let Some(o) = offset(best) else {
        return Found::new(
            measured,
            Verdict::NotMeasured,
            "no stick zone to locate the maximum against",
            "no stick zone".into(),
        );
    };
    // Why a coarse mesh smears it: on the stick side μp − |q| = μp0 √(c_s² − r²)/c grows as
    // √(2 c_s (c_s − r)), so a node h/2 inside the edge is lower than the cusp by μp0 √(c_s h)/c.
    let smear = cusp_sampling(r, best, COARSE_MESH * best.c);
    let why = smear.map_or_else(String::new, |s| {
        format!(
            ". |q| has a cusp there (on the stick side μp − |q| grows as √(c_s − r)): a mesh of h = c/{:.0} samples it \
             up to h/2 inside, {:.0} % below the peak, and nodal averaging spreads the maximum over an element — a \
             coarse FE mesh smears and displaces it",
            1.0 / COARSE_MESH,
            s * 100.0
        )
    });
    let decides = format!("max |q| {o:+.1} samples h from the stick edge against ±1 h");
    if o.abs() <= 1.0 {
        Found::new(
            measured,
            Verdict::NotConfirmed,
            format!("the maximum lies on the stick/slip boundary, within one sample (as MD says){why}"),
            decides,
        )
    } else {
        Found::new(
            measured,
            Verdict::Confirmed,
            format!("the maximum lies {o:+.1} samples from the stick/slip boundary{why}"),
            decides,
        )
    }
}
