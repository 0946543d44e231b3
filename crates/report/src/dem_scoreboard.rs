//! "How far is your DEM code from Mindlin–Deresiewicz?": every DEM law of a case run, built into
//! the crate or a real DEM code, with its distance from MDR (exact Mindlin–Deresiewicz) along the
//! path: the worst over every step and the distance at each path position, both as
//! |Q − Q_MDR| / max |Q_MDR| (the measure of the cases' informational checks).

use super::document::{Cell, Section, Table};
use spherecontact_model::history::History;
use spherecontact_model::solver::{Kind, SolveError};
use spherecontact_verify::CaseRun;

/// The section's title.
pub const TITLE: &str = "How far is your DEM code from Mindlin–Deresiewicz?";

/// The exact reference.
const REFERENCE: &str = "mdr";

/// One law's distance from MDR, or why it has none.
#[derive(Clone, Debug, PartialEq)]
pub struct Score {
    /// The solver.
    pub solver: String,
    /// Where it comes from: "built-in law", "real code", or the case's own ("your law (a
    /// program)", "your code (stored results)", …).
    pub kind: String,
    /// Worst distance over every step and the distance at each path position; or why missing.
    pub distances: Result<(f64, Vec<f64>), String>,
}

/// Where a DEM solver of the run stands in the scoreboard: built-in laws, then real codes, then
/// the case's own laws and codes; `None` for a solver that is not a DEM law or code.
fn placement(run: &CaseRun, solver: &str) -> Option<(u8, String)> {
    let kind = run.case.solver_kind(solver).filter(|k| k.is_dem())?;
    let law = kind == Kind::DemLaw;
    Some(match run.case.own_solver(solver) {
        None if law => (0, "built-in law".to_owned()),
        None => (1, "real code".to_owned()),
        Some(own) => {
            let what = if law { "law" } else { "code" };
            (2 + u8::from(!law), format!("your {what} ({})", own.origin()))
        }
    })
}

/// The scores of every DEM law and code the run has — built into the crate, a real DEM code, or
/// the case's own (`kind = "dem-law"` or `"dem-code"`) — in that order, each group in the case's
/// order; empty without an MDR history.
pub fn scores(run: &CaseRun) -> Vec<Score> {
    let Some(Ok(reference)) = run.histories.get(REFERENCE) else {
        return Vec::new();
    };
    let mut placed: Vec<(u8, String, String)> = run
        .case
        .required_solvers()
        .into_iter()
        .filter_map(|solver| placement(run, &solver).map(|(group, kind)| (group, kind, solver)))
        .collect();
    placed.sort_by_key(|(group, ..)| *group);
    placed
        .into_iter()
        .filter_map(|(_, kind, solver)| {
            let distances = match run.histories.get(&solver)? {
                Ok(history) => distances(history, reference),
                Err(SolveError::Unavailable(_)) => Err("not available".into()),
                Err(SolveError::NotApplicable(why)) => Err(format!("not applicable: {why}")),
                Err(SolveError::Failed(_)) => Err("failed".into()),
            };
            Some(Score {
                solver,
                kind,
                distances,
            })
        })
        .collect()
}

/// |Q − Q_MDR| / max |Q_MDR|: the worst over every step, and at each path position.
fn distances(history: &History, reference: &History) -> Result<(f64, Vec<f64>), String> {
    let peak = reference.peak(spherecontact_model::history::Quantity::TangentialForce);
    if peak == 0.0 {
        return Err("MDR gives no tangential force on this path".into());
    }
    let mut worst: f64 = 0.0;
    let mut at_positions = Vec::new();
    for (row, exact) in history.steps.iter().zip(&reference.steps) {
        let (Some(q), Some(q_exact)) = (row.tangential_force, exact.tangential_force) else {
            return Err(format!("no tangential force at step {}", row.step));
        };
        let distance = (q - q_exact).abs() / peak;
        worst = worst.max(distance);
        if row.position.is_some() {
            at_positions.push(distance);
        }
    }
    Ok((worst, at_positions))
}

/// A distance for people, in per cent: two decimals from 0.01 % up, else scientific.
fn format(distance: f64) -> String {
    if distance == 0.0 {
        "0".to_owned()
    } else if distance >= 1e-4 {
        format!("{:.2} %", distance * 100.0)
    } else {
        format!("{:.1e} %", distance * 100.0)
    }
}

/// The scoreboard as a table: law, kind, worst, then one column per path position.
pub fn table(run: &CaseRun) -> Table {
    let positions = run.case.scene.path.positions().len();
    let mut header = vec![
        "law".to_owned(),
        "kind".to_owned(),
        "worst (every step)".to_owned(),
    ];
    header.extend((0..positions).map(|k| format!("P{k}")));
    let rows = scores(run)
        .into_iter()
        .map(|score| {
            let mut row = vec![Cell::plain(&score.solver), Cell::plain(&score.kind)];
            match score.distances {
                Ok((worst, at)) => {
                    row.push(Cell::with_class(format(worst), "info"));
                    row.extend(at.into_iter().map(|d| Cell::plain(format(d))));
                }
                Err(why) => {
                    let class = if why == "not available" { "na" } else { "nook" };
                    row.push(Cell::with_class(why, class));
                    row.extend((0..positions).map(|_| Cell::plain("—")));
                }
            }
            row
        })
        .collect();
    Table { header, rows }
}

/// The report section (no table when the run has no MDR or no DEM law).
pub fn section(run: &CaseRun) -> Section {
    let table = table(run);
    Section {
        title: TITLE.into(),
        paragraphs: vec![
            "Every DEM tangential law of this case — built into the crate, run in a real DEM code \
             (LAMMPS pair_style granular, YADE), or the case's own (a program or stored results the \
             case marks `kind = \"dem-law\"` or `\"dem-code\"`) — against MDR, the exact Mindlin–Deresiewicz \
             solution along the same path: |Q − Q_MDR| / max |Q_MDR|, the worst over every step \
             and at each path position. Measured and published, never judged; a code that is not \
             installed is named, never drawn as zero."
                .into(),
        ],
        tables: if table.rows.is_empty() {
            vec![]
        } else {
            vec![table]
        },
        figures: vec![],
        folded: false,
    }
}

/// The scoreboard as aligned text, for the terminal.
pub fn text(run: &CaseRun) -> String {
    let table = table(run);
    let widths: Vec<usize> = (0..table.header.len())
        .map(|k| {
            table
                .rows
                .iter()
                .map(|r| r[k].text.chars().count())
                .chain([table.header[k].chars().count()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: Vec<&str>| {
        cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:<w$}"))
            .collect::<Vec<_>>()
            .join("  ")
            .trim_end()
            .to_owned()
    };
    let mut out = format!("{}: {TITLE}\n", run.case.name());
    out.push_str(&line(table.header.iter().map(String::as_str).collect()));
    out.push('\n');
    for row in &table.rows {
        out.push_str(&line(row.iter().map(|c| c.text.as_str()).collect()));
        out.push('\n');
    }
    out
}
