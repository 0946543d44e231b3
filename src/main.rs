//! The `spherecontact` command line: arguments are parsed raw (clap), validated into a plan
//! (cases read and checked, solver names resolved, nothing written yet), then executed.
//!
//! Exit codes: 0 success; 1 a check is NOOK or a solver failed; 2 bad input (arguments, case
//! files), in which case nothing is written.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use spherecontact::case::{limits, Case};
use spherecontact::conclusion::Conclusion;
use spherecontact::external::{geo, toolchain::Toolchain};
use spherecontact::report::{history_files, summary};
use spherecontact::runfile::RunFile;
use spherecontact::{baseline, io, merge, plan, registry, resolution, schedule, solver, verify};

#[derive(Parser)]
#[command(
    name = "spherecontact",
    version,
    about = "Verification harness for the contact of two elastic spheres"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a case's solvers and write DIR/<solver>.csv and DIR/<solver>.json.
    Run {
        /// The case file.
        case: PathBuf,
        /// A solver to run (repeatable); default: the case's own list.
        #[arg(long = "solver", value_name = "NAME")]
        solvers: Vec<String>,
        /// Output folder (created if missing).
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Also write VTU fields (ParaView) into DIR/<solver>-vtu/ for solvers that have them.
        #[arg(long)]
        vtu: bool,
        /// A solver's resolution, over the case's `[resolution]` (repeatable), e.g. bem=128,
        /// fem-axisym=c/80, fem-axisym=10um, mdr=16000.
        #[arg(long = "resolution", value_name = "SOLVER=VALUE")]
        resolution: Vec<String>,
        /// MPI ranks of the solvers that run under MPI (fenicsx-3d); default: the case's `ranks`.
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
        ranks: Option<u32>,
    },
    /// Run cases and judge their checks; exit 1 on any NOOK or DRIFT.
    Verify(VerifyArgs),
    /// Put the --out folders of `verify --shard` runs together: one summary and one JUnit,
    /// the same as the unsharded run's apart from timings; exit 1 on any NOOK.
    Merge {
        /// The folders written by `verify --out`.
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Write JUnit XML here.
        #[arg(long, value_name = "FILE")]
        junit: Option<PathBuf>,
        /// Write the merged summary (summary.txt) into this folder.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Count a check that is N/A (a solver not installed) as a failure, as CI does.
        #[arg(long)]
        require_external: bool,
        /// The non-regression baselines (<case>.toml) each value is compared with.
        #[arg(long, value_name = "DIR", default_value = baseline::DIR)]
        baselines: PathBuf,
    },
    /// Write Slurm batch scripts for a sharded verification: a job array of `verify --shard`,
    /// a merge job that depends on it, and submit.sh (nothing is submitted).
    Slurm(SlurmArgs),
    /// Non-regression baselines: `baseline update [CASE...]` runs the cases and rewrites their
    /// baselines (every check's value, each solver's version, resolution and wall time).
    Baseline {
        #[command(subcommand)]
        action: BaselineAction,
    },
    /// Write the gmsh geometry of a case's scene and mesh it (MSH 4.1 and FreeFEM's MSH 2.2).
    Mesh {
        /// The case file.
        case: PathBuf,
        /// Element size at the contact pole, e.g. c/80, 20um, 0.02mm, 2e-5 (m); default c_max/40.
        #[arg(long, value_name = "LENGTH")]
        resolution: Option<String>,
        /// Output folder (created if missing).
        #[arg(long, default_value = "out/mesh")]
        out: PathBuf,
    },
    /// Report each external tool: found or not, path, version, and how to install it.
    Doctor,
    /// List the solvers of this build and the cases under cases/.
    List,
    /// Run a case's solvers and write a comparison report (HTML, Markdown, SVG, CSV).
    Compare {
        /// The case file.
        case: PathBuf,
        /// Output folder; default: out/compare-<case name>.
        #[arg(long)]
        out: Option<PathBuf>,
        /// A solver's resolution, over the case's `[resolution]` (repeatable), e.g. bem=128,
        /// fem-axisym=c/80, fem-axisym=10um, mdr=16000.
        #[arg(long = "resolution", value_name = "SOLVER=VALUE")]
        resolution: Vec<String>,
    },
    /// Reproduce the paper: its case with every available solver, reported in its figures' order.
    ReproducePaper {
        /// Output folder.
        #[arg(long, default_value = "out/reproduce-paper")]
        out: PathBuf,
        /// The paper's case file.
        #[arg(long, default_value = "cases/paper-fig7.toml")]
        case: PathBuf,
        /// A solver's resolution, over the case's `[resolution]` (repeatable), e.g. bem=128,
        /// fem-axisym=c/80, fem-axisym=10um, mdr=16000.
        #[arg(long = "resolution", value_name = "SOLVER=VALUE")]
        resolution: Vec<String>,
    },
    /// Sweep each solver's resolution: error against CPU and wall time, side by side in one run
    /// (build with --release for representative numbers).
    Bench {
        /// The case file.
        case: PathBuf,
        /// A solver to sweep (repeatable); default: the case's own list.
        #[arg(long = "solver", value_name = "NAME")]
        solvers: Vec<String>,
        /// Timed runs per rung (the median is reported).
        #[arg(long, default_value_t = 11, value_parser = clap::value_parser!(u32).range(1..=10_000))]
        repeat: u32,
        /// Output folder; default: out/bench-<case name>.
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

/// The arguments of `verify`.
#[derive(clap::Args)]
struct VerifyArgs {
    /// Case files or folders (every .toml under them); default: cases/.
    cases: Vec<PathBuf>,
    /// Write JUnit XML here.
    #[arg(long, value_name = "FILE")]
    junit: Option<PathBuf>,
    /// Count a check that is N/A (a solver not installed) as a failure, as CI does.
    #[arg(long)]
    require_external: bool,
    /// A solver's resolution, over the case's `[resolution]` (repeatable), e.g. bem=128,
    /// fem-axisym=c/80, fem-axisym=10um, mdr=16000.
    #[arg(long = "resolution", value_name = "SOLVER=VALUE")]
    resolution: Vec<String>,
    /// MPI ranks of the solvers that run under MPI (fenicsx-3d); default: each case's `ranks`.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    ranks: Option<u32>,
    /// Run only the cases with this label (repeatable: any of them).
    #[arg(long = "label", value_name = "LABEL")]
    labels: Vec<String>,
    /// Leave out the cases with this label (repeatable).
    #[arg(long = "skip-label", value_name = "LABEL")]
    skip_labels: Vec<String>,
    /// Cores for concurrent runs (each solver takes the cores it declares); default: the
    /// machine's.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    jobs: Option<u32>,
    /// Run only the K-th of N parts of the runs, balanced by their recorded cost (e.g. 2/3);
    /// `merge` puts the parts' --out folders together.
    #[arg(long, value_name = "K/N")]
    shard: Option<String>,
    /// Write the run file (run.json: every run's history, for `merge`) and the printed
    /// summary (summary.txt) into this folder.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// The non-regression baselines (<case>.toml) each value is compared with.
    #[arg(long, value_name = "DIR", default_value = baseline::DIR)]
    baselines: PathBuf,
}

/// The arguments of `slurm`.
#[derive(clap::Args)]
struct SlurmArgs {
    /// Case files or folders; default: every .toml under cases/.
    cases: Vec<PathBuf>,
    /// How many shards (array tasks).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1000))]
    shards: u32,
    /// Where the scripts go, and the shards' and merged results when they run.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Run only the cases with this label (repeatable: any of them).
    #[arg(long = "label", value_name = "LABEL")]
    labels: Vec<String>,
    /// Leave out the cases with this label (repeatable).
    #[arg(long = "skip-label", value_name = "LABEL")]
    skip_labels: Vec<String>,
    /// Cores per shard (--cpus-per-task and verify --jobs).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=1024))]
    cores: u32,
    /// The Slurm partition.
    #[arg(long)]
    partition: Option<String>,
    /// Each job's time limit (Slurm's --time, e.g. 1:00:00).
    #[arg(long)]
    time: Option<String>,
    /// Count a check that is N/A as a failure.
    #[arg(long)]
    require_external: bool,
    /// The non-regression baselines.
    #[arg(long, value_name = "DIR", default_value = baseline::DIR)]
    baselines: PathBuf,
}

/// What `baseline` does.
#[derive(Subcommand)]
enum BaselineAction {
    /// Run cases and rewrite their baselines.
    Update {
        /// Case files or folders; default: every .toml under cases/.
        cases: Vec<PathBuf>,
        /// The baselines' folder.
        #[arg(long, value_name = "DIR", default_value = baseline::DIR)]
        baselines: PathBuf,
        /// Cores for concurrent runs; default: the machine's.
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
        jobs: Option<u32>,
    },
}

/// A bad-input error: printed, exit code 2, nothing written.
struct InputError(String);

/// Checks the output folder of a command before any work (nothing is written).
fn output_folder(option: &str, dir: &Path) -> Result<(), InputError> {
    io::check_output_folder(dir).map_err(|e| InputError(format!("{option} {}: {e}", dir.display())))
}

impl<E: std::fmt::Display> From<E> for InputError {
    fn from(e: E) -> Self {
        InputError(e.to_string())
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            case,
            solvers,
            out,
            vtu,
            resolution,
            ranks,
        } => run(&case, &solvers, &out, vtu, &resolution, ranks),
        Command::Verify(args) => verify_command(args),
        Command::Merge {
            dirs,
            junit,
            out,
            require_external,
            baselines,
        } => Outputs::checked(junit, out, require_external)
            .and_then(|outputs| merge_runs(&dirs, &baselines, &outputs)),
        Command::Baseline {
            action:
                BaselineAction::Update {
                    cases,
                    baselines,
                    jobs,
                },
        } => update_baselines(cases, &baselines, jobs),
        Command::Slurm(args) => slurm(args),
        Command::Mesh {
            case,
            resolution,
            out,
        } => mesh(&case, resolution.as_deref(), &out),
        Command::Doctor => Ok(doctor()),
        Command::List => list(),
        Command::Compare {
            case,
            out,
            resolution,
        } => report(&case, out, &resolution, Report::Compare),
        Command::ReproducePaper {
            out,
            case,
            resolution,
        } => report(&case, Some(out), &resolution, Report::Paper),
        Command::Bench {
            case,
            solvers,
            repeat,
            out,
        } => bench(&case, &solvers, repeat as usize, out),
    };
    match result {
        Ok(code) => code,
        Err(InputError(message)) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

/// The `--resolution SOLVER=VALUE` options, split, each solver named once.
fn resolution_options(options: &[String]) -> Result<Vec<(String, String)>, InputError> {
    let mut pairs: Vec<(String, String)> = Vec::new();
    for option in options {
        let (name, value) =
            resolution::split_option(option).map_err(|e| InputError(format!("--resolution: {e}")))?;
        if pairs.iter().any(|(n, _)| *n == name) {
            return Err(InputError(format!(
                "--resolution: `{name}` is given twice (allowed: each solver once)"
            )));
        }
        pairs.push((name, value));
    }
    Ok(pairs)
}

/// Loads the case at `file` with the command line's ranks and resolutions over its own.
fn load_case(file: &Path, ranks: Option<u32>, resolutions: &[(String, String)]) -> Result<Case, InputError> {
    let options = plan::CaseOptions {
        ranks,
        resolutions: resolutions.to_vec(),
    };
    Ok(options.load(file)?)
}

/// The solvers named on the command line (each once), or the case's own list.
fn planned_solvers(case: &Case, names: &[String]) -> Result<Vec<Box<dyn solver::Solver>>, InputError> {
    let names = if names.is_empty() {
        &case.solvers[..]
    } else {
        names
    };
    if let Some(twice) = names
        .iter()
        .enumerate()
        .find_map(|(i, n)| names[..i].contains(n).then_some(n))
    {
        return Err(InputError(format!(
            "--solver: `{twice}` is named twice (allowed: each solver once)"
        )));
    }
    names
        .iter()
        .map(|name| {
            case.solver(name).ok_or_else(|| {
                InputError(format!(
                    "--solver: unknown solver `{name}` (see `spherecontact list`)"
                ))
            })
        })
        .collect()
}

fn run(
    case: &Path,
    solvers: &[String],
    out: &Path,
    vtu: bool,
    resolution: &[String],
    ranks: Option<u32>,
) -> Result<ExitCode, InputError> {
    // Plan: the case and every solver named must be valid before anything is written.
    let case = load_case(case, ranks, &resolution_options(resolution)?)?;
    let mut plan = planned_solvers(&case, solvers)?;
    output_folder("--out", out)?;
    if vtu {
        plan = plan
            .into_iter()
            .map(|s| {
                let dir = out.join(format!("{}-vtu", s.name()));
                s.writing_fields_to(&dir).unwrap_or(s)
            })
            .collect();
    }
    std::fs::create_dir_all(out).map_err(|e| InputError(format!("--out {}: {e}", out.display())))?;
    let mut code = ExitCode::SUCCESS;
    for warning in case.scene.warnings() {
        eprintln!("warning: {}: {warning}", case.name());
    }
    for solver in plan {
        match solver::run(solver.as_ref(), &case.scene) {
            Ok(history) => {
                if let Err(e) = history_files::write(out, &history) {
                    eprintln!(
                        "error: {}: writing results to {}: {e}",
                        solver.name(),
                        out.display()
                    );
                    code = ExitCode::FAILURE;
                    continue;
                }
                for warning in &history.metadata.warnings {
                    eprintln!("warning: {}: {warning}", solver.name());
                }
                println!(
                    "{:<22} {:>9.3} ms  -> {}",
                    solver.name(),
                    history.metadata.wall_time_s * 1e3,
                    out.join(format!("{}.csv", solver.name())).display()
                );
            }
            Err(e) => {
                eprintln!("error: {}: {e}", solver.name());
                code = ExitCode::FAILURE;
            }
        }
    }
    Ok(code)
}

/// Where `verify` and `merge` write, checked before any work.
struct Outputs {
    junit: Option<PathBuf>,
    out: Option<PathBuf>,
    require_external: bool,
}

impl Outputs {
    fn checked(
        junit: Option<PathBuf>,
        out: Option<PathBuf>,
        require_external: bool,
    ) -> Result<Self, InputError> {
        if let Some(file) = &junit {
            io::check_output_file(file)
                .map_err(|e| InputError(format!("--junit {}: {e}", file.display())))?;
        }
        if let Some(dir) = &out {
            output_folder("--out", dir)?;
        }
        Ok(Outputs {
            junit,
            out,
            require_external,
        })
    }

    /// Prints the verdicts of `runs` and writes the JUnit and summary.
    fn write(&self, runs: &[verify::CaseRun]) -> Result<ExitCode, InputError> {
        let conclusion = Conclusion {
            runs,
            require_external: self.require_external,
        };
        let text = conclusion.text();
        print!("{text}");
        if let Some(file) = &self.junit {
            io::write_atomically(file, conclusion.junit().as_bytes())
                .map_err(|e| InputError(format!("--junit {}: {e}", file.display())))?;
        }
        if let Some(dir) = &self.out {
            std::fs::create_dir_all(dir)
                .and_then(|()| io::write_atomically(&dir.join("summary.txt"), text.as_bytes()))
                .map_err(|e| InputError(format!("--out {}: {e}", dir.display())))?;
        }
        Ok(if conclusion.passed() {
            ExitCode::SUCCESS
        } else {
            ExitCode::FAILURE
        })
    }
}

/// The cases of `verify`, read and selected, with their baselines; nothing run yet.
struct VerifyPlan {
    files: Vec<PathBuf>,
    options: plan::CaseOptions,
    plan: plan::Plan,
    baselines: std::collections::BTreeMap<String, baseline::Baseline>,
}

fn verify_plan(
    files: Vec<PathBuf>,
    selection: &plan::Selection,
    options: &plan::CaseOptions,
    baselines: &Path,
) -> Result<VerifyPlan, InputError> {
    let files = plan::case_files(&if files.is_empty() {
        vec![PathBuf::from("cases")]
    } else {
        files
    })?;
    let (mut selected, mut cases) = (Vec::new(), Vec::new());
    for file in files {
        let case = options.load(&file)?;
        if selection.selects(&case) {
            selected.push(file);
            cases.push(case);
        }
    }
    if cases.is_empty() {
        return Err(InputError(
            "no case files to verify (none given, or none selected by label)".into(),
        ));
    }
    let baselines = baseline::load_all(baselines, cases.iter().map(Case::name))?;
    let plan = plan::Plan::new(cases, |case, solver| baselines.get(case.name())?.wall_s(solver));
    Ok(VerifyPlan {
        files: selected,
        options: options.clone(),
        plan,
        baselines,
    })
}

/// `verify`: the plan checked and built (nothing written on bad input), then executed.
fn verify_command(args: VerifyArgs) -> Result<ExitCode, InputError> {
    let selection = plan::Selection::new(&args.labels, &args.skip_labels)?;
    let jobs = args.jobs.map_or_else(schedule::machine_cores, |n| n as usize);
    let shard = args.shard.map(|s| s.parse::<plan::Shard>()).transpose()?;
    let options = plan::CaseOptions {
        ranks: args.ranks,
        resolutions: resolution_options(&args.resolution)?,
    };
    let outputs = Outputs::checked(args.junit, args.out, args.require_external)?;
    let plan = verify_plan(args.cases, &selection, &options, &args.baselines)?;
    verify_cases(plan, shard, jobs, &outputs)
}

fn verify_cases(
    verify: VerifyPlan,
    shard: Option<plan::Shard>,
    jobs: usize,
    outputs: &Outputs,
) -> Result<ExitCode, InputError> {
    let plan = match shard {
        Some(shard) => verify.plan.shard(shard),
        None => verify.plan,
    };
    let finished = schedule::execute(&plan, jobs);
    if let Some(dir) = &outputs.out {
        RunFile::new(&plan, &finished, verify.files, verify.options, shard)
            .write(dir)
            .map_err(|e| InputError(format!("--out {}: {e}", dir.display())))?;
    }
    let mut runs = schedule::judge(plan, finished);
    baseline::compare_all(&verify.baselines, &mut runs);
    outputs.write(&runs)
}

fn merge_runs(dirs: &[PathBuf], baselines: &Path, outputs: &Outputs) -> Result<ExitCode, InputError> {
    let merged = merge::merge(dirs)?;
    let baselines = baseline::load_all(baselines, merged.plan.cases.iter().map(Case::name))?;
    for (dir, (shard, wall_s)) in dirs.iter().zip(&merged.shards) {
        let shard = shard.as_deref().unwrap_or("whole");
        eprintln!(
            "merge: {} (shard {shard}): runs {wall_s:.2} s wall in all",
            dir.display()
        );
    }
    let mut runs = schedule::judge(merged.plan, merged.finished);
    baseline::compare_all(&baselines, &mut runs);
    outputs.write(&runs)
}

fn update_baselines(cases: Vec<PathBuf>, dir: &Path, jobs: Option<u32>) -> Result<ExitCode, InputError> {
    let options = plan::CaseOptions::default();
    let verify = verify_plan(cases, &plan::Selection::default(), &options, dir)?;
    let jobs = jobs.map_or_else(schedule::machine_cores, |n| n as usize);
    let finished = schedule::execute(&verify.plan, jobs);
    std::fs::create_dir_all(dir).map_err(|e| InputError(format!("--baselines {}: {e}", dir.display())))?;
    for run in schedule::judge(verify.plan, finished) {
        let baseline = baseline::Baseline::of(&run);
        let file = baseline::file(dir, run.case.name());
        io::write_atomically(&file, baseline.to_toml().as_bytes())
            .map_err(|e| InputError(format!("--baselines {}: {e}", file.display())))?;
        println!(
            "baseline: {} ({} checks with a value, {} solvers ran)",
            file.display(),
            baseline.checks.len(),
            baseline.solvers.len()
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// Checks the cases and writes the Slurm scripts of `args` (nothing is submitted).
fn slurm(args: SlurmArgs) -> Result<ExitCode, InputError> {
    let selection = plan::Selection::new(&args.labels, &args.skip_labels)?;
    verify_plan(
        args.cases.clone(),
        &selection,
        &plan::CaseOptions::default(),
        &args.baselines,
    )?;
    output_folder("--out", &args.out)?;
    let root = std::env::current_dir()?;
    let mut merge_args = vec![
        "--baselines".to_owned(),
        root.join(&args.baselines).display().to_string(),
    ];
    if args.require_external {
        merge_args.push("--require-external".into());
    }
    let mut verify_args: Vec<String> = args.cases.iter().map(|c| c.display().to_string()).collect();
    for (option, list) in [("--label", &args.labels), ("--skip-label", &args.skip_labels)] {
        verify_args.extend(list.iter().flat_map(|l| [option.to_owned(), l.clone()]));
    }
    verify_args.extend(merge_args.iter().cloned());
    let job = spherecontact::slurm::SlurmJob {
        program: std::env::current_exe()?,
        out: root.join(&args.out),
        root,
        verify_args,
        merge_args,
        shards: args.shards as usize,
        cores: args.cores as usize,
        partition: args.partition,
        time: args.time,
    };
    job.write()
        .map_err(|e| InputError(format!("--out {}: {e}", args.out.display())))?;
    println!(
        "slurm: scripts in {}: run {}",
        args.out.display(),
        job.out.join("submit.sh").display()
    );
    Ok(ExitCode::SUCCESS)
}

fn mesh(case: &Path, resolution: Option<&str>, out: &Path) -> Result<ExitCode, InputError> {
    // Plan: the case and the resolution must be valid before anything is written.
    let case = Case::load(case)?;
    // The pole sizes of fem-axisym's and the decks' `[resolution]` (c/N or a length).
    let resolution = match resolution {
        Some(text) => resolution::pole_size("mesh", &case.scene, text, limits::MERIDIAN_POLE)
            .map_err(|e| InputError(format!("--resolution: {e}")))?,
        None => geo::default_resolution(&case.scene),
    };
    geo::geo_for_scene(&case.scene, resolution)?;
    output_folder("--out", out)?;
    std::fs::create_dir_all(out).map_err(|e| InputError(format!("--out {}: {e}", out.display())))?;
    match geo::mesh(&case.scene, resolution, out, &Toolchain::default()) {
        Ok(files) => {
            println!(
                "{}: pole element {:.3} µm, {} triangles, gmsh {:.2} s",
                case.name(),
                resolution * 1e6,
                files.triangles,
                files.wall_s
            );
            for file in [&files.geo, &files.msh41, &files.msh22_mm] {
                println!("  {}", file.display());
            }
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => {
            eprintln!("error: mesh: {e}");
            Ok(ExitCode::FAILURE)
        }
    }
}

fn doctor() -> ExitCode {
    let probes = Toolchain::default().doctor();
    for probe in &probes {
        println!("{}", probe.line());
    }
    if probes.iter().all(|p| p.available()) {
        ExitCode::SUCCESS
    } else {
        println!("some external tools are missing: run scripts/setup.sh");
        ExitCode::FAILURE
    }
}

fn bench(
    case: &Path,
    solvers: &[String],
    repeat: usize,
    out: Option<PathBuf>,
) -> Result<ExitCode, InputError> {
    let case = Case::load(case)?;
    let plan = planned_solvers(&case, solvers)?;
    let out = out.unwrap_or_else(|| PathBuf::from("out").join(format!("bench-{}", case.name())));
    output_folder("--out", &out)?;
    if cfg!(debug_assertions) {
        eprintln!("warning: built without optimisation; run `cargo run --release -- bench …` for representative timings");
    }
    let increments = case.scene.steps().len() - 1;
    let rungs = spherecontact::bench::sweep(&plan, &case.scene, repeat)
        .map_err(|e| InputError(format!("{}: the references failed: {e}", case.name())))?;
    let document = spherecontact::report::bench::document(case.name(), increments, repeat, &rungs)
        .map_err(|e| InputError(format!("building the bench report: {e}")))?;
    document
        .write(&out)
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
enum Report {
    Compare,
    Paper,
}

fn report(
    case: &Path,
    out: Option<PathBuf>,
    resolution: &[String],
    kind: Report,
) -> Result<ExitCode, InputError> {
    let case = load_case(case, None, &resolution_options(resolution)?)?;
    let out = out.unwrap_or_else(|| PathBuf::from("out").join(format!("compare-{}", case.name())));
    output_folder("--out", &out)?;
    let reference_dir = case.file.parent().unwrap_or(Path::new(".")).join("../reference");
    let bar = indicatif::ProgressBar::new(case.required_solvers().len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {msg}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix(case.name().to_owned());
    let run = verify::run_case_with_progress(case, &mut |name, index, _| {
        bar.set_position(index as u64);
        bar.set_message(name.to_owned());
    });
    bar.finish_and_clear();
    let document = match kind {
        Report::Compare => spherecontact::report::compare::document(&run),
        Report::Paper => {
            // The surface-field claims at the finest rungs of each map solver's ladder.
            let study = spherecontact::report::claims::Study::of_ladders(&run);
            spherecontact::report::paper::document(&run, &study, &reference_dir)
        }
    }
    .map_err(|e| InputError(format!("building the report: {e}")))?;
    history_files::write_all(&out.join("solvers"), &run)
        .and_then(|()| document.write(&out))
        .map_err(|e| InputError(format!("--out {}: {e}", out.display())))?;
    print!("{}", summary::screen(&run));
    println!("report: {}", out.join("report.html").display());
    Ok(if run.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn list() -> Result<ExitCode, InputError> {
    println!("solvers:");
    let solvers = registry::registry();
    let width = solvers
        .iter()
        .map(|s| s.name().chars().count())
        .max()
        .unwrap_or(0);
    for solver in solvers {
        println!("  {:<width$} {}", solver.name(), solver.description());
    }
    println!("cases:");
    for file in plan::case_files(&[PathBuf::from("cases")]).unwrap_or_default() {
        match Case::load(&file) {
            Ok(case) => println!(
                "  {:<22} {}  {}",
                case.name(),
                file.display(),
                case.description.lines().next().unwrap_or("")
            ),
            Err(e) => println!("  (invalid) {e}"),
        }
    }
    Ok(ExitCode::SUCCESS)
}
