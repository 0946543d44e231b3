//! The impact report: "How far is your DEM code from exact Mindlin–Deresiewicz in impact?" —
//! Chung & Ooi's figures redrawn (each outcome against the swept variable, every solver beside
//! the exact reference, MDR in the same integrator), each law's worst distance from it, and the
//! checks. Written by `spherecontact impact` (docs/impact.md).

use anyhow::Result;

use crate::document::{Cell, Document, Section, Table};
use crate::figures::figure;
use crate::plot::{Axes, LinePlot, Series, Style};
use spherecontact_impact::case::{Quantity, SweepVariable, Variant};
use spherecontact_impact::code_rule::{is_reference, Rule};
use spherecontact_impact::judge::values;
use spherecontact_impact::solver_run::SolverRun;
use spherecontact_impact::ImpactRun;
use spherecontact_model::number::format_value;

/// The title of the report (and its first section).
pub const TITLE: &str = "How far is your DEM code from exact Mindlin–Deresiewicz in impact?";

/// The swept value as plotted: degrees for angles, SI otherwise; and the axis label.
fn axis(variable: Option<SweepVariable>) -> (f64, String) {
    match variable {
        Some(SweepVariable::IncidentAngle) => (180.0 / std::f64::consts::PI, "incident angle [deg]".into()),
        Some(SweepVariable::TangentialVelocity) => (1.0, "tangential velocity [m/s]".into()),
        Some(SweepVariable::Spin) => (1.0, "spin of body 1 [rad/s]".into()),
        Some(SweepVariable::Restitution) => (1.0, "prescribed restitution [-]".into()),
        None => (1.0, "impact".into()),
    }
}

/// The worst distance of `run` from the reference run over the sweep, per quantity: relative
/// for durations, forces, overlaps and spins, absolute for restitutions and angles.
pub fn worst_distance(
    run: &SolverRun,
    reference: &SolverRun,
    quantity: Quantity,
) -> Option<(f64, Option<f64>)> {
    let relative = matches!(
        quantity,
        Quantity::ContactDuration | Quantity::MaxNormalForce | Quantity::MaxOverlap
    );
    values(run, quantity)
        .into_iter()
        .zip(values(reference, quantity))
        .filter_map(|((at, v), (_, r))| {
            let (v, r) = (v?, r?);
            let d = if relative {
                spherecontact_check::relative_error(v, r, r, spherecontact_check::ABS_ZERO)
            } else {
                (v - r).abs()
            };
            d.is_finite().then_some((d, at))
        })
        .max_by(|a, b| a.0.total_cmp(&b.0))
}

/// The distance table of one case: a row per DEM law and variant, a column per quantity.
fn distance_table(run: &ImpactRun) -> Table {
    let mut header = vec!["solver".to_owned(), "kind".to_owned(), "variant".to_owned()];
    header.extend(Quantity::ALL.iter().map(|q| {
        let kind = if matches!(
            q,
            Quantity::ContactDuration | Quantity::MaxNormalForce | Quantity::MaxOverlap
        ) {
            "relative"
        } else {
            "absolute"
        };
        format!(
            "{} ({kind}{})",
            q.name(),
            if *q == Quantity::ReboundAngularVelocity {
                ", rad/s"
            } else {
                ""
            }
        )
    }));
    let rows = run
        .runs
        .iter()
        .filter(|r| !is_reference(&r.solver))
        .filter_map(|r| {
            // Each code against the reference under its own damping rule (code_rule).
            let reference = run
                .runs
                .iter()
                .find(|x| x.solver == Rule::of(&r.solver).reference() && x.variant == r.variant)?;
            let mut row = vec![
                Cell::plain(&r.solver),
                Cell::plain(spherecontact_case::impact_kind_in_words(&run.case, &r.solver)),
                Cell::plain(r.variant.name()),
            ];
            row.extend(Quantity::ALL.iter().map(|&q| {
                Cell::plain(match worst_distance(r, reference, q) {
                    Some((d, at)) => format!("{} (at {})", format_value(Some(d)), format_value(at)),
                    None => "—".to_owned(),
                })
            }));
            Some(row)
        })
        .collect();
    Table { header, rows }
}

/// The checks of one case as a table.
fn check_table(run: &ImpactRun) -> Table {
    Table {
        header: [
            "verdict",
            "solver",
            "quantity",
            "variant",
            "worst error",
            "tolerance",
            "reason",
        ]
        .map(String::from)
        .to_vec(),
        rows: run
            .outcomes
            .iter()
            .map(|o| {
                let class = match o.verdict.label() {
                    "OK" => "ok",
                    "NOOK" => "nook",
                    _ => "info",
                };
                vec![
                    Cell::with_class(o.verdict.label(), class),
                    Cell::plain(&o.check.solver),
                    Cell::plain(o.check.quantity.name()),
                    Cell::plain(o.check.variant.name()),
                    Cell::plain(format_value(o.worst.map(|w| w.error))),
                    Cell::plain(format_value(o.check.tolerance)),
                    Cell::plain(&o.check.reason),
                ]
            })
            .collect(),
    }
}

/// A figure of one series per run, the reference dashed and drawn last; none when no run has a
/// point.
fn runs_figure(
    id: String,
    plot: [String; 4],
    caption: String,
    series: Vec<(&SolverRun, Vec<(f64, f64)>)>,
) -> Result<Option<crate::document::Figure>> {
    let mut series: Vec<Series> = series
        .into_iter()
        .filter(|(_, points)| !points.is_empty())
        .map(|(r, points)| {
            let style = if is_reference(&r.solver) {
                Style::Reference
            } else {
                Style::Line
            };
            Series::joined(&r.solver, points, style)
        })
        .collect();
    if series.is_empty() {
        return Ok(None);
    }
    series.sort_by_key(|s| s.style == Style::Reference);
    // Title, axis labels, and the name of the y column of the figure's data file.
    let [title, x_label, y_label, y_name] = plot;
    let plot = LinePlot {
        title,
        x_label: x_label.clone(),
        y_label,
        series,
        axes: Axes::Linear,
    };
    figure(&id, plot, caption, &x_label, &y_name).map(Some)
}

/// One figure: `quantity` against the sweep, every solver of `variant`, the reference dashed.
fn sweep_figure(
    run: &ImpactRun,
    quantity: Quantity,
    variant: Variant,
) -> Result<Option<crate::document::Figure>> {
    let variable = run.case.sweep.as_ref().map(|s| s.variable);
    let (scale, x_label) = axis(variable);
    let series = run
        .runs
        .iter()
        .filter(|r| r.variant == variant)
        .map(|r| {
            let points = values(r, quantity)
                .into_iter()
                .filter_map(|(at, v)| Some((at? * scale, v?)))
                .collect();
            (r, points)
        })
        .collect();
    let id = format!(
        "{}-{}-{}",
        run.case.name,
        quantity.name().replace('_', "-"),
        variant.name()
    );
    let title = format!("{}: {} ({})", run.case.name, quantity.name(), variant.name());
    let y_label = format!("{} [{}]", quantity.name(), quantity.unit());
    let caption = format!(
        "{} of the {} run against the swept variable: the exact reference (mdr: MDR's springs in \
         the same rigid-body integrator) dashed, each DEM law beside it.",
        quantity.name(),
        variant.name()
    );
    runs_figure(
        id,
        [title, x_label, y_label, quantity.name().into()],
        caption,
        series,
    )
}

/// The first sweep point's normal force or overlap against time (Chung & Ooi's figures of tests
/// 1 and 2), every solver of the prescribed run; none without traces (a run read back from a
/// run file carries none).
fn trace_figure(run: &ImpactRun, force: bool) -> Result<Option<crate::document::Figure>> {
    let (name, unit, scale) = if force {
        ("normal force", "N", 1.0)
    } else {
        ("overlap", "µm", 1e6)
    };
    let series = run
        .runs
        .iter()
        .filter(|r| r.variant == Variant::Prescribed)
        .map(|r| {
            let points = r
                .trace
                .iter()
                .map(|s| {
                    (
                        s.time * 1e6,
                        if force { s.normal_force } else { s.overlap } * scale,
                    )
                })
                .collect();
            (r, points)
        })
        .collect();
    let id = format!("{}-{}-time", run.case.name, name.replace(' ', "-"));
    let title = format!("{}: {name} against time", run.case.name);
    let caption = format!(
        "{name} against time from first touch, first sweep point, prescribed run: the exact reference \
         (mdr) dashed, each DEM law beside it (in normal impact they coincide with it to the bed's \
         discretisation)."
    );
    runs_figure(
        id,
        [
            title,
            "time [µs]".into(),
            format!("{name} [{unit}]"),
            name.replace(' ', "_"),
        ],
        caption,
        series,
    )
}

/// The section of one case (with the first point's force and overlap against time when
/// `traces`).
fn case_section(run: &ImpactRun, traces: bool) -> Result<Section> {
    let case = &run.case;
    let mut figures = Vec::new();
    if traces {
        for force in [true, false] {
            figures.extend(trace_figure(run, force)?);
        }
    }
    if case.sweep.is_some() {
        let quantities: &[Quantity] = if case.friction > 0.0
            && case
                .sweep
                .as_ref()
                .is_some_and(|s| s.variable != SweepVariable::Restitution)
        {
            &[
                Quantity::TangentialRestitution,
                Quantity::ReboundAngularVelocity,
                Quantity::ReboundAngle,
            ]
        } else {
            &[
                Quantity::NormalRestitution,
                Quantity::MaxNormalForce,
                Quantity::ContactDuration,
            ]
        };
        for variant in case.variants() {
            for &q in quantities {
                figures.extend(sweep_figure(run, q, variant)?);
            }
        }
    }
    Ok(Section {
        title: format!("{} — {}", case.name, case.file.display()),
        paragraphs: vec![
            case.description.clone(),
            "Worst distance of each DEM law from the exact reference over the sweep (the sweep value \
             where it is worst in brackets, SI: rad, m/s, rad/s):"
                .into(),
        ],
        tables: vec![distance_table(run), check_table(run)],
        figures,
        folded: false,
    })
}

/// The report of `runs`; `traces`: with the force and overlap against time of each case's first
/// sweep point (`spherecontact impact`; a verification's report has none, as a run file carries
/// no trace, so that `verify --out` and `merge` write the same report).
pub fn document<'a>(runs: impl IntoIterator<Item = &'a ImpactRun>, traces: bool) -> Result<Document> {
    let mut sections = vec![Section {
        title: TITLE.into(),
        paragraphs: vec![
            "Chung & Ooi's (2011, Granular Matter 13:643–656) impact benchmarks, each DEM law as the \
             contact law of the same rigid-body integrator (velocity Verlet, both bodies' translation \
             and rotation) beside the exact quasi-static reference: MDR's spring bed, exact \
             Mindlin–Deresiewicz for any oblique history. Where a test prescribes a restitution, \
             every law gets the same Tsuji damping and friction bounded by the elastic normal force \
             (each DEM code, LAMMPS, YADE and LIGGGHTS run dynamically, its own: mdr-lammps, \
             mdr-yade, mdr-liggghts), and \
             the elastic variant (e = 1) runs beside: there the reference is exact without \
             assumption. Conventions, damping and convergence: docs/impact.md."
                .into(),
        ],
        tables: Vec::new(),
        figures: Vec::new(),
        folded: false,
    }];
    for run in runs {
        sections.push(case_section(run, traces)?);
    }
    Ok(Document {
        title: TITLE.into(),
        sections,
    })
}
