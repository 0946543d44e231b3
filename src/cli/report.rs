//! `compare`, `reproduce-paper` and `bench`: a case's solvers run into a report.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use spherecontact::case::Case;
use spherecontact::case::ReadRoots;
use spherecontact::external::permission::CommandPermission;
use spherecontact::report::discretisation;
use spherecontact::report::{history_files, summary};
use spherecontact::schedule::Judged;
use spherecontact::toolchain::Toolchain;
use spherecontact::verify::CaseRun;
use spherecontact::{baseline, merge, progress, schedule, solver};

use super::Jobs;
use crate::{claim, load_case, planned_solvers, resolution_options, CommandOptions, Force, InputError};

pub(crate) fn bench(
    case: &Path,
    solvers: &[String],
    repeat: usize,
    out: Option<PathBuf>,
    force: bool,
    roots: &ReadRoots,
    permission: &CommandPermission,
) -> Result<ExitCode, InputError> {
    let case = load_shown(case, &[], roots, permission)?;
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
        outln!("{line}");
    }
    outln!(
        "{}: {increments} increments, {repeat} timed runs per rung, interleaved; medians",
        case.name()
    );
    let table = &document.sections[0].tables[0];
    outln!(
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
        outln!(
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
    outln!("report: {}", out.join("report.html").display());
    let failed = rungs
        .iter()
        .any(|r| matches!(r, Err((_, e)) if !matches!(e, solver::SolveError::Unavailable(_))));
    Ok(if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}

/// The case of `file` ([`load_case`]), every command it would run printed on stderr before
/// anything runs (docs/security.md, "What a case would run is shown before it runs").
fn load_shown(
    file: &Path,
    resolutions: &[(String, String)],
    roots: &ReadRoots,
    permission: &CommandPermission,
) -> Result<Case, InputError> {
    let case = load_case(file, None, resolutions, roots, permission)?;
    case.command_lines().iter().for_each(|line| eprintln!("{line}"));
    Ok(case)
}

/// How the progress lines reach the user beside `bar`: above it (a hidden bar prints nothing:
/// stderr then).
fn printer(bar: &indicatif::ProgressBar) -> Box<dyn Fn(&str)> {
    let lines = bar.clone();
    match bar.is_hidden() {
        true => Box::new(|line| eprintln!("{line}")),
        false => Box::new(move |line| lines.println(line)),
    }
}

/// Runs the cases' solvers concurrently within the cores, all in one schedule (verify's, costed
/// by each case's baseline where there is one: the costs only order the runs), a bar counting
/// the runs done; one judged run a case, in order.
fn run_solvers(cases: Vec<Case>, jobs: Jobs) -> Vec<CaseRun> {
    let total: usize = cases.iter().map(|c| c.required_solvers().len()).sum();
    let bar = indicatif::ProgressBar::new(total as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {msg}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    let names: Vec<&str> = cases.iter().map(Case::name).collect();
    bar.set_prefix(names.join(" + "));
    let recorded: Vec<(String, baseline::Baseline)> = cases
        .iter()
        .filter_map(|case| {
            let shape = baseline::Shape::of_path(case);
            let found = baseline::Baseline::load(Path::new(baseline::DIR), &shape)
                .ok()
                .flatten()?;
            Some((case.name().to_owned(), found))
        })
        .collect();
    let runs = schedule::run_cases(
        cases,
        jobs.cores(),
        |case, solver| {
            let (_, found) = recorded.iter().find(|(name, _)| name == case.name())?;
            found.wall_s(solver)
        },
        &|run, solve| {
            bar.set_message(run.solver.clone());
            let output = progress::printing_through(printer(&bar), solve);
            bar.inc(1);
            output
        },
    );
    bar.finish_and_clear();
    runs
}

/// The case's run read from the run files of `verify --out` folders ([`merge::merge`]) and
/// judged; its solvers are not run again, and the run says so among its warnings.
fn stored_run(dirs: &[PathBuf], case: &Case, roots: &ReadRoots) -> Result<CaseRun, InputError> {
    let merged = merge::merge(dirs, roots).map_err(|e| InputError(format!("--from: {e}")))?;
    // The case was just read from its file, so the file has a canonical path.
    let wanted =
        std::fs::canonicalize(&case.file).map_err(|e| InputError(format!("{}: {e}", case.file.display())))?;
    let mut run = schedule::judge(merged.plan, merged.finished)
        .into_iter()
        .find_map(|judged| match judged {
            Judged::Path(run) if std::fs::canonicalize(&run.case.file).is_ok_and(|f| f == wanted) => {
                Some(run)
            }
            _ => None,
        })
        .ok_or_else(|| {
            InputError(format!(
                "--from {}: no run of case {} there (allowed: folders of `verify --out DIR` that ran it)",
                dirs[0].display(),
                case.file.display()
            ))
        })?;
    let folders: Vec<String> = dirs.iter().map(|d| d.display().to_string()).collect();
    run.warnings.insert(
        0,
        format!(
            "the solvers' runs were read from the `verify --out` run file(s) of {}, not run again by this command",
            folders.join(", ")
        ),
    );
    Ok(run)
}

/// Which report to write.
pub(crate) enum Report {
    Compare,
    /// The paper's, with the case of its discretisation run beside.
    Paper {
        discretisation: DiscretisationChoice,
    },
}

/// Which case of the paper's discretisation `reproduce-paper` runs beside the paper's.
pub(crate) enum DiscretisationChoice {
    /// [`discretisation::DEFAULT_CASE`] when CalculiX and gmsh are installed, none (the report
    /// says why) when not.
    Default,
    /// This case (`--discretisation CASE`).
    Case(PathBuf),
    /// None (`--no-discretisation`).
    Skip,
}

impl DiscretisationChoice {
    /// The case file to run beside the paper's case `paper`, or why none is run. The default is
    /// looked for beside the paper case's folder (`cases/` → `cases-heavy/`).
    fn file(self, paper: &Path) -> Result<PathBuf, String> {
        match self {
            DiscretisationChoice::Case(file) => Ok(file),
            DiscretisationChoice::Skip => Err("not asked for (--no-discretisation)".into()),
            DiscretisationChoice::Default => discretisation::default_case(paper, &Toolchain::default()),
        }
    }
}

/// The options `compare` and `reproduce-paper` share.
#[derive(clap::Args)]
pub(crate) struct ReportOptions {
    /// A solver's resolution, over the case's `[resolution]` (repeatable), e.g. bem=128,
    /// fem-axisym=c/80, fem-axisym=10um, mdr=16000.
    #[arg(long = "resolution", value_name = "SOLVER=VALUE")]
    resolution: Vec<String>,
    /// The cores the solvers (and the paper's resolution study) run within.
    #[command(flatten)]
    jobs: Jobs,
    /// Read the case's solver runs from this folder of `verify --out DIR` (repeatable: the
    /// folders of its shards) instead of running them again; not with --resolution.
    #[arg(long = "from", value_name = "DIR")]
    from: Vec<PathBuf>,
    #[command(flatten)]
    commands: CommandOptions,
    #[command(flatten)]
    force: Force,
}

pub(crate) fn report(
    case: &Path,
    out: Option<PathBuf>,
    kind: Report,
    options: ReportOptions,
    roots: &ReadRoots,
) -> Result<ExitCode, InputError> {
    let ReportOptions {
        resolution,
        jobs,
        from,
        commands,
        force,
    } = options;
    if !from.is_empty() && !resolution.is_empty() {
        return Err(InputError(
            "--resolution: not with --from (the runs read are at the resolutions their `verify` recorded)"
                .into(),
        ));
    }
    let (permission, force) = (&commands.permission()?, force.force);
    let resolution = &resolution;
    let case = load_shown(case, &resolution_options(resolution)?, roots, permission)?;
    let out = out.unwrap_or_else(|| PathBuf::from("out").join(format!("compare-{}", case.name())));
    // The paper's quoted values are read before anything is written or run: a missing file is
    // bad input.
    let paper_references = match &kind {
        Report::Paper { .. } => Some(
            spherecontact::report::paper_numbers::Quoted::for_case(&case)
                .map_err(|e| InputError(format!("{}: {e}", case.file.display())))?
                .0,
        ),
        Report::Compare => None,
    };
    // The discretisation case, or why none runs, is read before anything is written or run: bad
    // input exits 2. (`compare` has no such section: its reason is never shown.)
    let discretisation: Result<Case, String> = match kind {
        Report::Paper { discretisation } => match discretisation.file(&case.file) {
            Ok(file) => Ok(load_shown(&file, &[], roots, permission)?),
            Err(why) => Err(why),
        },
        Report::Compare => Err("not a paper report".into()),
    };
    // Stored runs are read and checked before anything is written.
    let stored = match from.is_empty() {
        true => None,
        false => Some(stored_run(&from, &case, roots)?),
    };
    let folder = claim(&out, force)?;
    // The case's solvers (unless read) and the discretisation's, in one schedule: the
    // discretisation's CalculiX run takes one core while the paper's solvers share the other.
    let mut to_run: Vec<Case> = Vec::new();
    if stored.is_none() {
        to_run.push(case);
    }
    let not_run = match discretisation {
        Ok(case) => {
            eprintln!("{}: the paper's discretisation, beside", case.name());
            to_run.push(case);
            None
        }
        Err(why) => Some(why),
    };
    let mut runs = run_solvers(to_run, jobs).into_iter();
    let run = stored.unwrap_or_else(|| runs.next().expect("the case was run"));
    let discretisation: Result<CaseRun, String> = match not_run {
        None => Ok(runs.next().expect("the discretisation was run")),
        Some(why) => Err(why),
    };
    let document = match paper_references {
        None => spherecontact::report::compare::document(&run),
        Some(reference_dir) => {
            // The surface-field claims at the finest rungs of each map solver's ladder.
            let study = spherecontact::report::claims::Study::of_ladders(&run, jobs.cores());
            let section = match &discretisation {
                Ok(run) => discretisation::Discretisation::Run(run),
                Err(why) => discretisation::Discretisation::NotRun(why),
            };
            spherecontact::report::paper::document(&run, &study, &reference_dir, &section)
        }
    }
    .map_err(|e| InputError(format!("building the report: {e}")))?;
    history_files::write_all(&folder.path().join("solvers"), &run)
        .and_then(|()| match &discretisation {
            Ok(d) => history_files::write_all(&folder.path().join("discretisation"), d),
            Err(_) => Ok(()),
        })
        .and_then(|()| document.write(folder.path()))
        .map_err(|e| InputError(format!("--out {}: {e}", out.display())))?;
    out!("{}", summary::screen(&run));
    if let Ok(d) = &discretisation {
        out!("{}", summary::screen(d));
    }
    outln!("report: {}", out.join("report.html").display());
    Ok(
        if run.passed() && discretisation.as_ref().map_or(true, CaseRun::passed) {
            ExitCode::SUCCESS
        } else {
            ExitCode::FAILURE
        },
    )
}
