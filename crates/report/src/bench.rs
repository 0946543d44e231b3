//! The `bench` report: each solver's resolution ladder as error against CPU time, all solvers on
//! one log-log front, with the machine and versions it was measured on.

use anyhow::Result;

use super::document::{Cell, Document, Figure, Section, Table};
use super::plot::{Axes, LinePlot, Series, Style};
use spherecontact_verify::bench::{median, Rung, RungResult, CORRECTED_REFERENCE, REFERENCE_SPRINGS};

/// Facts about the machine that make timings comparable: CPU, cores, load, versions.
pub fn machine() -> Vec<String> {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|text| {
            text.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let load = std::fs::read_to_string("/proc/loadavg").map_or_else(
        |_| "unknown".into(),
        |l| l.split_whitespace().take(3).collect::<Vec<_>>().join(" "),
    );
    let rustc = std::process::Command::new("rustc")
        .arg("--version")
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "rustc not on PATH".into());
    vec![
        format!("CPU: {cpu}; {cores} cores available; load average at the start {load}."),
        format!(
            "spherecontact {} ({} build); {rustc}.",
            env!("CARGO_PKG_VERSION"),
            if cfg!(debug_assertions) {
                "debug"
            } else {
                "release"
            }
        ),
    ]
}

/// The half-space references of P and Q.
const RAW: [&str; 2] = ["hertz", "mdr"];

/// The reference rung `rung`'s P (k = 0) or Q (k = 1) error was measured against.
fn reference_of(rung: &Rung, k: usize) -> &'static str {
    if rung.raw.is_some() {
        CORRECTED_REFERENCE
    } else {
        RAW[k]
    }
}

/// An error to four figures, "—" without one.
fn format_error(e: Option<f64>) -> String {
    e.map_or_else(|| "—".to_owned(), |e| format!("{e:.3e}"))
}

/// The bench report of a sweep.
pub fn document(case: &str, increments: usize, repeat: usize, rungs: &[RungResult]) -> Result<Document> {
    let raw = |r: &Rung, k: usize| r.raw.map(|raw| if k == 0 { raw.0 } else { raw.1 });
    let table = Table {
        header: [
            "solver",
            "resolution",
            "median CPU [ms]",
            "median wall [ms]",
            "P error",
            "Q error",
            "reference",
            "P raw vs Hertz",
            "Q raw vs MDR",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows: rungs
            .iter()
            .map(|r| match r {
                Ok(r) => vec![
                    Cell::plain(&r.timing.solver),
                    Cell::plain(&r.timing.history.metadata.resolution),
                    Cell::with_class(format!("{:.3}", median(&r.timing.cpu_seconds) * 1e3), "timing"),
                    Cell::with_class(format!("{:.3}", median(&r.timing.seconds) * 1e3), "timing"),
                    Cell::plain(format_error(r.normal_error)),
                    Cell::plain(format_error(r.tangential_error)),
                    Cell::plain(r.reference),
                    Cell::plain(raw(r, 0).map_or_else(|| "—".to_owned(), format_error)),
                    Cell::plain(raw(r, 1).map_or_else(|| "—".to_owned(), format_error)),
                ],
                Err((name, e)) => {
                    let mut row = vec![Cell::plain(name), Cell::with_class(format!("missing: {e}"), "na")];
                    row.extend((0..7).map(|_| Cell::plain("—")));
                    row
                }
            })
            .collect(),
    };
    let mut figures = Vec::new();
    for (id, what, k) in [("normal-front", "P error", 0), ("tangential-front", "Q error", 1)] {
        let error = |r: &Rung| {
            if k == 0 {
                r.normal_error
            } else {
                r.tangential_error
            }
        };
        let mut series: Vec<Series> = Vec::new();
        let mut add = |name: String, point: (f64, f64)| {
            // A solver's rungs form one run: the line joins consecutive resolutions.
            match series.iter_mut().find(|s| s.name == name) {
                Some(s) => s.runs[0].push(point),
                None => series.push(Series::joined(name, vec![point], Style::Markers)),
            }
        };
        for rung in rungs.iter().flatten() {
            let cpu = median(&rung.timing.cpu_seconds) * 1e3;
            if let Some(e) = error(rung).filter(|e| *e > 0.0) {
                add(
                    format!("{} vs {}", rung.timing.solver, reference_of(rung, k)),
                    (cpu, e),
                );
            }
            // The raw offset of a finite body from the half-space, beside its corrected error.
            if let Some(e) = raw(rung, k).flatten().filter(|e| *e > 0.0) {
                add(format!("{} raw vs {}", rung.timing.solver, RAW[k]), (cpu, e));
            }
        }
        if series.is_empty() {
            continue;
        }
        let plot = LinePlot {
            title: format!("{case}: {what} against CPU time"),
            x_label: "median CPU time [ms]".into(),
            y_label: "worst error along the path".into(),
            series,
            axes: Axes::LogLog,
        };
        let data = Table {
            header: vec!["series".into(), "median CPU [ms]".into(), "error".into()],
            rows: plot
                .series
                .iter()
                .flat_map(|s| {
                    s.points().map(|p| {
                        vec![
                            Cell::plain(&s.name),
                            Cell::plain(format!("{:.6e}", p.0)),
                            Cell::plain(format!("{:.6e}", p.1)),
                        ]
                    })
                })
                .collect(),
        };
        let caption = format!(
            "{what} (P: relative at every step in contact; Q: relative to the reference's peak) against median CPU time; \
             one point per rung of each solver's resolution ladder, zero errors (exact by construction) not drawn. \
             A finite-body solver (FEM, deck) is scored against {CORRECTED_REFERENCE}, Mindlin–Deresiewicz in series \
             with the case's domain (docs/finite-body.md): that series is its discretisation error. Its \"raw\" series \
             is the same rungs against the half-space ({}), which adds the domain effect and levels off at it.",
            RAW[k]
        );
        figures.push(Figure {
            id: id.into(),
            svg: plot.to_svg()?,
            caption,
            data,
        });
    }
    let mut paragraphs = machine();
    paragraphs.push(format!(
        "{increments} increments; each rung ran once untimed, then {repeat} times interleaved with all the others; medians. \
         The half-space references are Hertz (P) and MDR on {REFERENCE_SPRINGS} springs (Q); finite bodies are scored \
         against {CORRECTED_REFERENCE}, with their raw offsets from the half-space in the last two columns."
    ));
    Ok(Document {
        title: format!("spherecontact bench: {case}"),
        sections: vec![
            glance(rungs),
            Section {
                title: "Speed against error".into(),
                figures,
                ..Section::default()
            },
            Section {
                title: "Every rung".into(),
                paragraphs,
                tables: vec![table],
                folded: true,
                ..Section::default()
            },
        ],
    })
}

/// The first screen: one line per solver, its finest rung (the last of its ladder) with its
/// time and errors, and the rungs that did not run.
fn glance(rungs: &[RungResult]) -> Section {
    let mut solvers: Vec<&str> = Vec::new();
    for rung in rungs {
        let name = match rung {
            Ok(r) => r.timing.solver.as_str(),
            Err((name, _)) => name.as_str(),
        };
        if !solvers.contains(&name) {
            solvers.push(name);
        }
    }
    let rows = solvers
        .iter()
        .map(|&name| {
            let ok = rungs.iter().flatten().filter(|r| r.timing.solver == name);
            let failed = rungs
                .iter()
                .filter(|r| matches!(r, Err((n, _)) if n == name))
                .count();
            let status = match failed {
                0 => Cell::with_class("ran", "ok"),
                n => Cell::with_class(format!("{n} rung(s) missing"), "na"),
            };
            match ok.last() {
                Some(r) => vec![
                    Cell::plain(name),
                    status,
                    Cell::plain(&r.timing.history.metadata.resolution),
                    Cell::with_class(format!("{:.3}", median(&r.timing.cpu_seconds) * 1e3), "timing"),
                    Cell::plain(format_error(r.normal_error)),
                    Cell::plain(format_error(r.tangential_error)),
                    Cell::plain(r.reference),
                ],
                None => std::iter::once(Cell::plain(name))
                    .chain(std::iter::once(status))
                    .chain((0..5).map(|_| Cell::plain("—")))
                    .collect(),
            }
        })
        .collect();
    Section {
        title: "At a glance".into(),
        paragraphs: vec![format!(
            "{} solvers, {} rungs measured, {} missing. Each solver at the finest rung of its ladder; every rung in \
             the figures and in the folded table at the end.",
            solvers.len(),
            rungs.iter().flatten().count(),
            rungs.iter().filter(|r| r.is_err()).count()
        )],
        tables: vec![Table {
            header: [
                "solver",
                "status",
                "finest resolution",
                "median CPU [ms]",
                "P error",
                "Q error",
                "reference",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect(),
            rows,
        }],
        ..Section::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_model::history::History;
    use spherecontact_verify::bench::Timing;

    fn rung(solver: &str, errors: (f64, f64), raw: Option<(Option<f64>, Option<f64>)>) -> RungResult {
        Ok(Rung {
            timing: Timing {
                solver: solver.into(),
                seconds: vec![0.2],
                cpu_seconds: vec![0.1],
                history: History::default(),
            },
            reference: if raw.is_some() {
                CORRECTED_REFERENCE
            } else {
                "hertz, mdr"
            },
            normal_error: Some(errors.0),
            tangential_error: Some(errors.1),
            raw,
        })
    }

    #[test]
    fn a_finite_body_is_scored_against_the_corrected_reference_with_its_raw_offset_beside() {
        let rungs = [
            rung("fem-axisym", (2e-4, 1e-3), Some((Some(5e-3), Some(3e-2)))),
            rung("mdr", (1e-6, 1e-7), None),
        ];
        let document = document("case", 10, 1, &rungs).unwrap();
        let section = |title: &str| document.sections.iter().find(|s| s.title == title).unwrap();
        let row = |k: usize| -> Vec<&str> {
            section("Every rung").tables[0].rows[k]
                .iter()
                .map(|c| c.text.as_str())
                .collect()
        };
        assert_eq!(
            row(0)[4..],
            [
                "2.000e-4",
                "1.000e-3",
                CORRECTED_REFERENCE,
                "5.000e-3",
                "3.000e-2"
            ]
        );
        assert_eq!(row(1)[6..], ["hertz, mdr", "—", "—"]);
        let series = |id: &str| -> Vec<String> {
            let figure = section("Speed against error")
                .figures
                .iter()
                .find(|f| f.id == id)
                .unwrap();
            figure.data.rows.iter().map(|r| r[0].text.clone()).collect()
        };
        assert_eq!(
            series("normal-front"),
            [
                "fem-axisym vs mdr-domain",
                "fem-axisym raw vs hertz",
                "mdr vs hertz"
            ]
        );
        assert_eq!(
            series("tangential-front"),
            ["fem-axisym vs mdr-domain", "fem-axisym raw vs mdr", "mdr vs mdr"]
        );
        // The first screen: one line per solver, at its finest rung.
        let glance = &document.sections[0];
        assert_eq!(glance.title, "At a glance");
        let first: Vec<&str> = glance.tables[0].rows[0].iter().map(|c| c.text.as_str()).collect();
        assert_eq!(first[0], "fem-axisym");
        assert_eq!(first[4..], ["2.000e-4", "1.000e-3", CORRECTED_REFERENCE]);
        assert!(document.sections[2].folded, "every rung: folded at the end");
    }
}
