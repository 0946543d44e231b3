//! The paper's discretisation in the `reproduce-paper` report: how far the paper's kind of model
//! — 20-node bricks with face-to-face penalty contact and Coulomb friction, `ccx-3d` with
//! `[calculix] element = "hex20r"` — is from the corrected reference (mdr-domain) and from fem-3d
//! at the path positions it ran, from the run of its own case ([`DEFAULT_CASE`], which
//! `reproduce-paper` runs beside the paper's case when CalculiX is installed, or another given to
//! `--discretisation`). Without that run the section says why and how to get it.

use std::path::{Path, PathBuf};

use super::document::{Cell, Section, Table};
use spherecontact_model::history::{History, StepResult};
use spherecontact_system::toolchain::{Tool, Toolchain};
use spherecontact_verify::CaseRun;

/// The solver that runs the paper's discretisation.
pub const SOLVER: &str = "ccx-3d";
/// The corrected reference.
pub const REFERENCE: &str = "mdr-domain";
/// The in-crate 3D FEM beside it.
pub const FEM: &str = "fem-3d";

/// The case `reproduce-paper` runs by default, relative to the folder that holds the paper case's
/// folder (`cases/paper-fig7.toml` → `cases-heavy/ccx-3d-hex20.toml`).
pub const DEFAULT_CASE: &str = "cases-heavy/ccx-3d-hex20.toml";

/// The default case of the paper's discretisation beside the paper case `paper` ([`DEFAULT_CASE`]
/// under the folder that holds `paper`'s folder), when `toolchain` has CalculiX and gmsh (each
/// asked for its version once); otherwise why it is not run.
pub fn default_case(paper: &Path, toolchain: &Toolchain) -> Result<PathBuf, String> {
    let missing: Vec<String> = [Tool::Ccx, Tool::Gmsh]
        .map(|tool| toolchain.probe(tool))
        .into_iter()
        .filter_map(|p| p.version.err().map(|why| format!("{}: {why}", p.tool.name())))
        .collect();
    if !missing.is_empty() {
        return Err(format!("CalculiX and gmsh are needed ({})", missing.join("; ")));
    }
    let file = paper
        .parent()
        .and_then(Path::parent)
        .unwrap_or(Path::new(""))
        .join(DEFAULT_CASE);
    match file.is_file() {
        true => Ok(file),
        false => Err(format!(
            "no case of it at {} (beside the paper case's folder)",
            file.display()
        )),
    }
}

/// The paper's discretisation as the report has it.
pub enum Discretisation<'a> {
    /// The run of its case.
    Run(&'a CaseRun),
    /// Not run, and why (e.g. CalculiX is not installed; `--no-discretisation`).
    NotRun(&'a str),
}

/// The section's title.
const TITLE: &str = "The paper's discretisation: 20-node bricks, face-to-face penalty contact";

/// The section: a sentence and a table of P and Q at every position of the run, or, without a
/// run, why and the command that makes one.
pub fn section(discretisation: &Discretisation) -> Section {
    let run = match discretisation {
        Discretisation::Run(run) => *run,
        Discretisation::NotRun(why) => {
            return note(format!(
                "Not run: {why}. The paper's kind of model (CalculiX C3D20R bricks, face-to-face \
                 penalty contact, both spheres meshed: about 140 s of CPU) is run beside the paper's \
                 case by `spherecontact reproduce-paper` when CalculiX is installed ({DEFAULT_CASE}; \
                 `--discretisation CASE` for another case)."
            ))
        }
    };
    let history = |name: &str| run.histories.get(name).and_then(|r| r.as_ref().ok());
    let (Some(bricks), Some(reference), Some(fem)) = (history(SOLVER), history(REFERENCE), history(FEM))
    else {
        let why: Vec<String> = [SOLVER, REFERENCE, FEM]
            .iter()
            .filter_map(|name| match run.histories.get(*name) {
                Some(Ok(_)) => None,
                Some(Err(e)) => Some(format!("{name}: {e}")),
                None => Some(format!("{name}: not in the case")),
            })
            .collect();
        return note(format!("{}: not compared ({}).", run.case.name(), why.join("; ")));
    };
    let rows = rows(bricks, reference, fem);
    let worst = |k: usize| rows.iter().map(|r| r.errors[k].abs()).fold(0.0, f64::max);
    // fem-3d with the bricks' regularised stick (`[fem-3d] stick_slope`): then their Q
    // difference is the contact discretisation's, the stick slope's softening in both.
    let regularised = fem
        .metadata
        .extra
        .get("stick_slope_pa_per_m")
        .and_then(|v| v.as_f64())
        .map_or_else(String::new, |lambda| {
            format!(" (fem-3d with the same stick slope, λ = {lambda:.3e} Pa/m: the elastic slip before sliding in both)")
        });
    Section {
        title: TITLE.into(),
        paragraphs: vec![
            format!(
                "The paper's kind of model — {} bricks with face-to-face penalty contact and Coulomb \
                 friction ({}: {}) — is, at path positions 1–{}, within {:.2} % of the corrected \
                 reference mdr-domain in P and {:.2} % of its peak in Q; from fem-3d, {:.2} % in P \
                 and {:.2} % in Q{regularised}.",
                bricks
                    .metadata
                    .extra
                    .get("element")
                    .and_then(|e| e.as_str())
                    .unwrap_or("20-node"),
                run.case.name(),
                bricks.metadata.resolution,
                rows.len(),
                100.0 * worst(0),
                100.0 * worst(2),
                100.0 * worst(1),
                100.0 * worst(3),
            ),
            "The bricks' errors in P relative to the other solver's P; in Q relative to mdr-domain's \
             largest |Q| over the positions."
                .into(),
        ],
        tables: tables(&rows),
        figures: vec![],
        folded: false,
    }
}

/// A section of one paragraph.
fn note(text: String) -> Section {
    Section {
        title: TITLE.into(),
        paragraphs: vec![text],
        tables: vec![],
        figures: vec![],
        folded: true,
    }
}

/// One path position: the three solvers' P and Q, and the bricks' errors (P against mdr-domain,
/// P against fem-3d, Q against mdr-domain, Q against fem-3d).
struct Row {
    at: StepResult,
    forces: [[f64; 2]; 3],
    errors: [f64; 4],
}

/// The positions (after the first) where all three solvers have P and Q.
fn rows(bricks: &History, reference: &History, fem: &History) -> Vec<Row> {
    let forces = |h: &History, k: usize| {
        let s = h.at_position(k)?;
        Some([s.normal_force?, s.tangential_force?])
    };
    let positions: Vec<usize> = bricks
        .at_positions()
        .filter_map(|s| s.position)
        .filter(|&k| k > 0)
        .collect();
    let peak_q = positions
        .iter()
        .filter_map(|&k| forces(reference, k))
        .map(|f| f[1].abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    positions
        .into_iter()
        .filter_map(|k| {
            let (b, r, f) = (forces(bricks, k)?, forces(reference, k)?, forces(fem, k)?);
            Some(Row {
                at: bricks.at_position(k)?.clone(),
                forces: [b, f, r],
                errors: [
                    b[0] / r[0] - 1.0,
                    b[0] / f[0] - 1.0,
                    (b[1] - r[1]) / peak_q,
                    (b[1] - f[1]) / peak_q,
                ],
            })
        })
        .collect()
}

/// The tables, one of P and one of Q (one of thirteen columns was 1 500 px wide: the page
/// scrolled sideways on a laptop): position, δn, δt, the force of each solver, the bricks' errors.
fn tables(rows: &[Row]) -> Vec<Table> {
    [("P", 0), ("Q", 1)]
        .into_iter()
        .map(|(force, k)| table(rows, force, k))
        .collect()
}

/// The table of force `force` (`k`: 0 for P, 1 for Q).
fn table(rows: &[Row], force: &str, k: usize) -> Table {
    let header = [
        "position".to_owned(),
        "δn [µm]".to_owned(),
        "δt [µm]".to_owned(),
        format!("{force} bricks [N]"),
        format!("{force} {FEM} [N]"),
        format!("{force} {REFERENCE} [N]"),
        format!("bricks − {REFERENCE}"),
        format!("bricks − {FEM}"),
    ];
    let percent = |e: f64| Cell::plain(format!("{:+.2} %", 100.0 * e));
    Table {
        header: header.to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                let mut row = vec![
                    Cell::plain(r.at.position.map_or(String::new(), |k| k.to_string())),
                    Cell::plain(format!("{:.2}", r.at.delta_n * 1e6)),
                    Cell::plain(format!("{:.2}", r.at.delta_t * 1e6)),
                ];
                row.extend(r.forces.iter().map(|f| Cell::plain(format!("{:.2}", f[k]))));
                row.extend(r.errors[2 * k..2 * k + 2].iter().map(|&e| percent(e)));
                row
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use spherecontact_case::Case;

    /// A history with (P, Q) at positions 0, 1, 2.
    fn history(forces: [[f64; 2]; 3]) -> History {
        History {
            steps: forces
                .iter()
                .enumerate()
                .map(|(k, f)| StepResult {
                    step: k,
                    position: Some(k),
                    delta_n: 1e-5 * k as f64,
                    delta_t: 1e-6 * k as f64,
                    normal_force: Some(f[0]),
                    tangential_force: Some(f[1]),
                    ..StepResult::default()
                })
                .collect(),
            ..History::default()
        }
    }

    fn run(bricks: Option<History>) -> CaseRun {
        let case = Case::parse(
            std::path::Path::new("hex.toml"),
            "friction = 0.2\nsolvers = [\"hertz\"]\n[body1]\nradius = 0.1\nyoung = 70e9\npoisson = 0.3\n\
             [path]\nunit = \"um\"\ndelta_n = [0, 10, 20]\ndelta_t = [0, 1, 2]\nsubsteps = 1\n",
        )
        .unwrap();
        let mut histories = spherecontact_check::Histories::new();
        histories.insert(
            REFERENCE.into(),
            Ok(history([[0.0; 2], [100.0, 10.0], [200.0, 20.0]])),
        );
        histories.insert(FEM.into(), Ok(history([[0.0; 2], [101.0, 11.0], [202.0, 19.0]])));
        let bricks =
            bricks.ok_or_else(|| spherecontact_model::solver::SolveError::Unavailable("no ccx".into()));
        histories.insert(SOLVER.into(), bricks);
        CaseRun {
            case,
            warnings: vec![],
            histories,
            outcomes: vec![],
        }
    }

    #[test]
    fn the_table_gives_the_bricks_errors_against_both_references() {
        let run = run(Some(history([[0.0; 2], [99.0, 10.5], [204.0, 19.0]])));
        let section = section(&Discretisation::Run(&run));
        // Positions 1 and 2; P against each reference's P, Q against mdr-domain's peak (20 N).
        let text = |k: usize| -> Vec<&str> {
            assert_eq!(section.tables[k].rows.len(), 2);
            section.tables[k].rows[1]
                .iter()
                .map(|c| c.text.as_str())
                .collect()
        };
        assert_eq!(
            text(0),
            ["2", "20.00", "2.00", "204.00", "202.00", "200.00", "+2.00 %", "+0.99 %"]
        );
        assert_eq!(
            text(1),
            ["2", "20.00", "2.00", "19.00", "19.00", "20.00", "-5.00 %", "+0.00 %"]
        );
        assert_eq!(section.tables[1].header[3], "Q bricks [N]");
        // The sentence quotes the worst over the positions.
        assert!(
            section.paragraphs[0].contains(
                "within 2.00 % of the corrected reference mdr-domain in P and 5.00 % of its peak in Q; \
                 from fem-3d, 1.98 % in P and 2.50 % in Q"
            ),
            "{}",
            section.paragraphs[0]
        );
        assert!(
            !section.paragraphs[0].contains("stick slope"),
            "exact fem-3d says nothing of one"
        );
    }

    #[test]
    fn a_fem_3d_with_the_bricks_stick_slope_is_named_so() {
        let mut regularised = run(Some(history([[0.0; 2], [99.0, 10.5], [204.0, 19.0]])));
        if let Some(Ok(fem)) = regularised.histories.get_mut(FEM) {
            fem.metadata
                .extra
                .insert("stick_slope_pa_per_m".into(), serde_json::json!(3.8e15));
        }
        let section = section(&Discretisation::Run(&regularised));
        assert!(
            section.paragraphs[0]
                .contains("2.50 % in Q (fem-3d with the same stick slope, λ = 3.800e15 Pa/m"),
            "{}",
            section.paragraphs[0]
        );
    }

    #[test]
    fn without_a_run_or_without_ccx_the_section_says_why() {
        let not_run = section(&Discretisation::NotRun("not asked for (--no-discretisation)"));
        assert!(
            not_run.paragraphs[0].starts_with("Not run: not asked for (--no-discretisation).")
                && not_run.paragraphs[0].contains("(cases-heavy/ccx-3d-hex20.toml; `--discretisation CASE`"),
            "{}",
            not_run.paragraphs[0]
        );
        let missing = section(&Discretisation::Run(&run(None)));
        assert!(missing.tables.is_empty());
        assert!(missing.paragraphs[0].contains("ccx-3d") && missing.paragraphs[0].contains("no ccx"));
    }

    /// A toolchain whose ccx is a script answering `-v` as CalculiX 2.20 does, and the machine's
    /// gmsh (the probe asks each for its version).
    fn toolchain_with_ccx(dir: &Path, gmsh: &str) -> Toolchain {
        let ccx = dir.join("ccx");
        std::fs::write(&ccx, "#!/bin/sh\necho\necho This is Version 2.20\n").unwrap();
        std::fs::set_permissions(&ccx, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
        Toolchain {
            ccx,
            gmsh: gmsh.into(),
            ..Toolchain::default()
        }
    }

    #[test]
    fn the_default_case_is_beside_the_paper_cases_folder_when_calculix_and_gmsh_answer() {
        let root = spherecontact_model::fixtures::repository();
        let paper = root.join("cases/paper-fig7.toml");
        // Missing tools: not run, naming each.
        let none = Toolchain {
            ccx: "/nonexistent/ccx".into(),
            gmsh: "/nonexistent/gmsh".into(),
            ..Toolchain::default()
        };
        let why = default_case(&paper, &none).unwrap_err();
        assert!(
            why.starts_with("CalculiX and gmsh are needed (CalculiX: /nonexistent/ccx")
                && why.contains("; gmsh: /nonexistent/gmsh"),
            "{why}"
        );
        // gmsh is a dependency of the whole crate's 3D path; where it is missing, only the
        // refusal above can be checked.
        if !Toolchain::default().probe(Tool::Gmsh).available() {
            return;
        }
        let dir = tempfile::tempdir().unwrap();
        let tools = toolchain_with_ccx(dir.path(), "gmsh");
        assert_eq!(default_case(&paper, &tools), Ok(root.join(DEFAULT_CASE)));
        // A paper case elsewhere has no discretisation case beside it: not run, and where it was looked for.
        let elsewhere = dir.path().join("cases/paper.toml");
        let why = default_case(&elsewhere, &tools).unwrap_err();
        assert!(
            why.contains(&dir.path().join(DEFAULT_CASE).display().to_string()),
            "{why}"
        );
    }
}
