//! `compare`, `reproduce-paper` and `bench`: a case's solvers run into a report.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use spherecontact::case::ReadRoots;
use spherecontact::external::permission::CommandPermission;
use spherecontact::report::{history_files, summary};
use spherecontact::verify::CaseRun;
use spherecontact::{progress, solver, verify};

use crate::{claim, load_case, planned_solvers, resolution_options, InputError};

pub(crate) fn bench(
    case: &Path,
    solvers: &[String],
    repeat: usize,
    out: Option<PathBuf>,
    force: bool,
    roots: &ReadRoots,
    permission: &CommandPermission,
) -> Result<ExitCode, InputError> {
    let case = load_case(case, None, &[], roots, permission)?;
    case.command_lines().iter().for_each(|line| eprintln!("{line}"));
    let (plan, left_out) =
        spherecontact::bench::sweepable(&case, planned_solvers(&case, solvers)?, !solvers.is_empty())?;
    for name in left_out {
        eprintln!("note: {name} is defined by the case (stored results or a command): not swept");
    }
    let out = out.unwrap_or_else(|| PathBuf::from("out").join(format!("bench-{}", case.name())));
    let folder = claim(&out, force)?;
    if cfg!(debug_assertions) {
        eprintln!("warning: built without optimisation; run `cargo run --release -- bench …` for representative timings");
    }
    let increments = case.scene.steps().len() - 1;
    let rungs = spherecontact::bench::sweep(&plan, &case.scene, repeat)
        .map_err(|e| InputError(format!("{}: the references failed: {e}", case.name())))?;
    let document = spherecontact::report::bench::document(case.name(), increments, repeat, &rungs)
        .map_err(|e| InputError(format!("building the bench report: {e}")))?;
    document
        .write(folder.path())
        .map_err(|e| InputError(format!("--out {}: {e}", out.display())))?;
    for line in spherecontact::report::bench::machine() {
        println!("{line}");
    }
    println!(
        "{}: {increments} increments, {repeat} timed runs per rung, interleaved; medians",
        case.name()
    );
    let table = &document.sections[0].tables[0];
    println!(
        "  {:<22} {:<40} {:>12} {:>12} {:>12} {:>12} {:>12} {:>14} {:>12}",
        "solver",
        "resolution",
        "CPU [ms]",
        "wall [ms]",
        "P error",
        "Q error",
        "reference",
        "P raw/Hertz",
        "Q raw/MDR"
    );
    for row in &table.rows {
        let cell = |k: usize| row.get(k).map_or("", |c| c.text.as_str());
        println!(
            "  {:<22} {:<40} {:>12} {:>12} {:>12} {:>12} {:>12} {:>14} {:>12}",
            cell(0),
            cell(1),
            cell(2),
            cell(3),
            cell(4),
            cell(5),
            cell(6),
            cell(7),
            cell(8)
        );
    }
    println!("report: {}", out.join("report.html").display());
    let failed = rungs
        .iter()
        .any(|r| matches!(r, Err((_, e)) if !matches!(e, solver::SolveError::Unavailable(_))));
    Ok(if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}

/// Which report to write.
pub(crate) enum Report {
    Compare,
    /// The paper's, with the case of its discretisation (`--discretisation`) run beside.
    Paper {
        discretisation: Option<PathBuf>,
    },
}

pub(crate) fn report(
    case: &Path,
    out: Option<PathBuf>,
    force: bool,
    resolution: &[String],
    kind: Report,
    roots: &ReadRoots,
    permission: &CommandPermission,
) -> Result<ExitCode, InputError> {
    let case = load_case(case, None, &resolution_options(resolution)?, roots, permission)?;
    case.command_lines().iter().for_each(|line| eprintln!("{line}"));
    let out = out.unwrap_or_else(|| PathBuf::from("out").join(format!("compare-{}", case.name())));
    // The paper's quoted values are read before anything is written or run: a missing file is
    // bad input.
    let paper_references = match &kind {
        Report::Paper { .. } => Some(
            spherecontact::report::paper::Quoted::for_case(&case)
                .map_err(|e| InputError(format!("{}: {e}", case.file.display())))?
                .0,
        ),
        Report::Compare => None,
    };
    // The discretisation case is read before anything is written or run: bad input exits 2.
    let discretisation = match kind {
        Report::Paper {
            discretisation: Some(file),
        } => Some(load_case(&file, None, &[], roots, permission)?),
        _ => None,
    };
    let folder = claim(&out, force)?;
    let bar = indicatif::ProgressBar::new(case.required_solvers().len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {msg}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix(case.name().to_owned());
    // The progress lines go above the bar (a hidden bar prints nothing: stderr then).
    let lines = bar.clone();
    let printer: Box<dyn Fn(&str)> = match bar.is_hidden() {
        true => Box::new(|line| eprintln!("{line}")),
        false => Box::new(move |line| lines.println(line)),
    };
    let run = progress::printing_through(printer, || {
        verify::run_case_with_progress(case, &mut |name, index, _| {
            bar.set_position(index as u64);
            bar.set_message(name.to_owned());
        })
    });
    bar.finish_and_clear();
    let discretisation = discretisation.map(|case| {
        eprintln!("{}: the paper's discretisation", case.name());
        progress::printing_through(Box::new(|line: &str| eprintln!("{line}")), || {
            verify::run_case_with_progress(case, &mut |_, _, _| {})
        })
    });
    let document = match paper_references {
        None => spherecontact::report::compare::document(&run),
        Some(reference_dir) => {
            // The surface-field claims at the finest rungs of each map solver's ladder.
            let study = spherecontact::report::claims::Study::of_ladders(&run);
            spherecontact::report::paper::document(&run, &study, &reference_dir, discretisation.as_ref())
        }
    }
    .map_err(|e| InputError(format!("building the report: {e}")))?;
    history_files::write_all(&folder.path().join("solvers"), &run)
        .and_then(|()| match &discretisation {
            Some(d) => history_files::write_all(&folder.path().join("discretisation"), d),
            None => Ok(()),
        })
        .and_then(|()| document.write(folder.path()))
        .map_err(|e| InputError(format!("--out {}: {e}", out.display())))?;
    print!("{}", summary::screen(&run));
    if let Some(d) = &discretisation {
        print!("{}", summary::screen(d));
    }
    println!("report: {}", out.join("report.html").display());
    Ok(
        if run.passed() && discretisation.as_ref().is_none_or(CaseRun::passed) {
            ExitCode::SUCCESS
        } else {
            ExitCode::FAILURE
        },
    )
}
