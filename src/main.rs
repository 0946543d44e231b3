//! The `spherecontact` command line: arguments are parsed raw (clap), validated into a plan
//! (cases read and checked, solver names resolved, nothing written yet), then executed.
//!
//! Exit codes: 0 success; 1 a check is NOOK or a solver failed; 2 bad input (arguments, case
//! files), in which case nothing is written.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[macro_use]
mod stdout;
mod cli;

use clap::{Parser, Subcommand};
use cli::deck::{deck, DeckAction};
use cli::impact;
use cli::report::{bench, report, DiscretisationChoice, Report, ReportOptions};
use cli::verify::{
    merge_runs, slurm, update_baselines, verify_command, BaselineAction, Outputs, Require, SlurmArgs,
    VerifyArgs,
};
use spherecontact::case::{limits, Case, ReadRoots};
use spherecontact::external::permission::CommandPermission;
use spherecontact::fem::mesh::geo;
use spherecontact::report::history_files;
use spherecontact::toolchain::Toolchain;
use spherecontact::{baseline, io, plan, registry, resolution, solver, text};

#[derive(Parser)]
#[command(
    name = "spherecontact",
    version,
    about = "Verification harness for the contact of two elastic spheres"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// A folder whose files case files may also read (stored results, reference values), besides
    /// their own folder and the nearest `reference/` folder; repeatable (docs/security.md).
    #[arg(long = "allow-read", value_name = "DIR", global = true)]
    allow_read: Vec<PathBuf>,
}

/// Whether the programs cases name as solvers (`[[command_solvers]]`) may run.
#[derive(clap::Args)]
struct CommandOptions {
    /// Run the programs that cases name as solvers ([[command_solvers]]; `spherecontact list`
    /// shows them): without this (or SPHERECONTACT_ALLOW_COMMANDS=1) they are not run and the
    /// checks that need them are N/A.
    #[arg(long)]
    allow_commands: bool,
    /// Pass this environment variable to those programs too (repeatable); they get a minimal
    /// environment otherwise (docs/security.md).
    #[arg(long = "pass-env", value_name = "NAME")]
    pass_env: Vec<String>,
}

impl CommandOptions {
    /// The permission these options (and SPHERECONTACT_ALLOW_COMMANDS) give.
    fn permission(&self) -> Result<CommandPermission, InputError> {
        Ok(CommandPermission::from_options(
            self.allow_commands,
            &self.pass_env,
        )?)
    }
}

#[derive(Subcommand)]
enum Command {
    /// Run a case's solvers and write DIR/<solver>.csv and DIR/<solver>.json (an impact case:
    /// DIR/<solver>.csv per sweep point and DIR/<solver>-trace.csv, docs/impact.md).
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
        #[command(flatten)]
        commands: CommandOptions,
        #[command(flatten)]
        force: Force,
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
        #[command(flatten)]
        require: Require,
        /// Replace a --junit file that spherecontact did not write, or write --out into a folder
        /// that holds files it did not write.
        #[arg(long)]
        force: bool,
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
    /// An external deck run elsewhere (a cluster): `deck write` writes it into a folder,
    /// `deck read` reads its finished run back (docs/external-decks.md, "On a cluster").
    Deck {
        #[command(subcommand)]
        action: DeckAction,
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
        #[command(flatten)]
        force: Force,
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
        #[command(flatten)]
        options: ReportOptions,
    },
    /// Reproduce the paper: its case with every available solver, reported in its figures' order.
    ReproducePaper {
        /// Output folder.
        #[arg(long, default_value = "out/reproduce-paper")]
        out: PathBuf,
        /// The paper's case file.
        #[arg(long, default_value = "cases/paper-fig7.toml")]
        case: PathBuf,
        /// The case of the paper's discretisation (20-node bricks in CalculiX), run beside and
        /// reported against mdr-domain and fem-3d. Default: cases-heavy/ccx-3d-hex20.toml when
        /// CalculiX (ccx) and gmsh are installed (about 140 s of CPU on one core).
        #[arg(long, value_name = "CASE", conflicts_with = "no_discretisation")]
        discretisation: Option<PathBuf>,
        /// Do not run the paper's discretisation (the report says it was not asked for).
        #[arg(long)]
        no_discretisation: bool,
        #[command(flatten)]
        options: ReportOptions,
    },
    /// Run impact cases (default: every file under cases/impact/) with their checks and write
    /// the report "How far is your DEM code from exact Mindlin–Deresiewicz in impact?".
    Impact {
        /// Impact case files; default: every .toml under cases/impact/.
        cases: Vec<PathBuf>,
        /// Output folder: the report, and each case's solver files in <case>/.
        #[arg(long, default_value = "out/impact")]
        out: PathBuf,
        #[command(flatten)]
        force: Force,
        #[command(flatten)]
        commands: CommandOptions,
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
        #[command(flatten)]
        commands: CommandOptions,
        #[command(flatten)]
        force: Force,
    },
}

/// The `--force` of the commands that write an output folder.
#[derive(clap::Args)]
struct Force {
    /// Write into an existing folder that holds files spherecontact did not write (files with
    /// output names are replaced; the folder is marked as spherecontact's).
    #[arg(long)]
    force: bool,
}

/// A bad-input error: printed, exit code 2, nothing written.
struct InputError(String);

/// Claims the output folder of a command before any work: refused (nothing written) when it is
/// a system folder, holds files spherecontact did not write (without `--force`) or links, or is
/// in use by another run; held until the process ends.
fn claim(dir: &Path, force: bool) -> Result<io::OutputFolder, InputError> {
    io::OutputFolder::claim(dir, force).map_err(|e| InputError(format!("--out {}: {e}", dir.display())))
}

impl<E: std::fmt::Display> From<E> for InputError {
    fn from(e: E) -> Self {
        InputError(e.to_string())
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let roots = match ReadRoots::new(&cli.allow_read) {
        Ok(roots) => roots,
        Err(e) => return input_error(&e.to_string()),
    };
    let roots = &roots;
    let result = match cli.command {
        Command::Run {
            case,
            solvers,
            out,
            vtu,
            resolution,
            ranks,
            commands,
            force,
        } => commands.permission().and_then(|p| {
            run(
                &case,
                &solvers,
                &out,
                force.force,
                vtu,
                &resolution,
                ranks,
                roots,
                &p,
            )
        }),
        Command::Verify(args) => verify_command(args, roots),
        Command::Merge {
            dirs,
            junit,
            out,
            require,
            baselines,
            force,
        } => Outputs::checked(junit, out, require, force)
            .and_then(|outputs| merge_runs(&dirs, &baselines, &outputs, roots)),
        Command::Baseline {
            action:
                BaselineAction::Update {
                    cases,
                    baselines,
                    jobs,
                    commands,
                },
        } => update_baselines(cases, &baselines, jobs, roots, &commands),
        Command::Slurm(args) => slurm(args, roots),
        Command::Deck { action } => deck(action, roots),
        Command::Mesh {
            case,
            resolution,
            out,
            force,
        } => mesh(&case, resolution.as_deref(), &out, force.force, roots),
        Command::Doctor => Ok(doctor()),
        Command::List => list(roots),
        Command::Compare { case, out, options } => report(&case, out, Report::Compare, options, roots),
        Command::ReproducePaper {
            out,
            case,
            discretisation,
            no_discretisation,
            options,
        } => {
            let discretisation = match (discretisation, no_discretisation) {
                (Some(file), _) => DiscretisationChoice::Case(file),
                (None, true) => DiscretisationChoice::Skip,
                (None, false) => DiscretisationChoice::Default,
            };
            report(&case, Some(out), Report::Paper { discretisation }, options, roots)
        }
        Command::Bench {
            case,
            solvers,
            repeat,
            out,
            commands,
            force,
        } => commands
            .permission()
            .and_then(|p| bench(&case, &solvers, repeat as usize, out, force.force, roots, &p)),
        Command::Impact {
            cases,
            out,
            force,
            commands,
        } => commands.permission().and_then(|permission| {
            impact::report(&cases, &out, force.force, &permission)
                .map(|ok| if ok { ExitCode::SUCCESS } else { ExitCode::FAILURE })
                .map_err(InputError)
        }),
    };
    match result {
        Ok(code) => code,
        Err(InputError(message)) => input_error(&message),
    }
}

/// Prints a bad-input error (its control characters escaped) and gives exit code 2.
fn input_error(message: &str) -> ExitCode {
    eprintln!("error: {}", text::lines(message));
    ExitCode::from(2)
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

/// Loads the case at `file` (reading only under `roots`) with the command line's ranks and
/// resolutions over its own, its command solvers under `permission`.
fn load_case(
    file: &Path,
    ranks: Option<u32>,
    resolutions: &[(String, String)],
    roots: &ReadRoots,
    permission: &CommandPermission,
) -> Result<Case, InputError> {
    let options = plan::CaseOptions {
        ranks,
        resolutions: resolutions.to_vec(),
        roots: roots.clone(),
        permission: permission.clone(),
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
                let unknown = spherecontact::case::registry::unknown(name, &case.solver_names());
                InputError(format!("--solver: {unknown} (see `spherecontact list`)"))
            })
        })
        .collect()
}

fn run(
    case: &Path,
    solvers: &[String],
    out: &Path,
    force: bool,
    vtu: bool,
    resolution: &[String],
    ranks: Option<u32>,
    roots: &ReadRoots,
    permission: &CommandPermission,
) -> Result<ExitCode, InputError> {
    if impact::is_impact_file(case) {
        let plan = impact::plan(case, solvers, out, force, permission).map_err(InputError)?;
        let ok = plan.execute().map_err(InputError)?;
        return Ok(if ok { ExitCode::SUCCESS } else { ExitCode::FAILURE });
    }
    // Plan: the case and every solver named must be valid before anything is written.
    let case = load_case(case, ranks, &resolution_options(resolution)?, roots, permission)?;
    let mut plan = planned_solvers(&case, solvers)?;
    let named: Vec<&str> = plan.iter().map(|s| s.name()).collect();
    if case.commands().iter().any(|c| named.contains(&c.name.as_str())) {
        case.command_lines().iter().for_each(|line| eprintln!("{line}"));
    }
    let folder = claim(out, force)?;
    if vtu {
        plan = plan
            .into_iter()
            .map(|s| {
                let dir = folder.path().join(format!("{}-vtu", s.name()));
                s.writing_fields_to(&dir).unwrap_or(s)
            })
            .collect();
    }
    let mut code = ExitCode::SUCCESS;
    for warning in case.scene.warnings() {
        eprintln!("warning: {}: {warning}", case.name());
    }
    for solver in plan {
        let label = format!("{} {}", case.name(), solver.name());
        match solver::run_reported(solver.as_ref(), &case.scene, &label) {
            Ok(history) => {
                if let Err(e) = history_files::write(folder.path(), &history) {
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
                outln!(
                    "{:<22} {:>9.3} ms  -> {}",
                    solver.name(),
                    history.metadata.wall_time_s * 1e3,
                    out.join(format!("{}.csv", solver.name())).display()
                );
            }
            Err(e) => {
                eprintln!("error: {}: {}", solver.name(), text::lines(&e.to_string()));
                code = ExitCode::FAILURE;
            }
        }
    }
    Ok(code)
}

fn mesh(
    case: &Path,
    resolution: Option<&str>,
    out: &Path,
    force: bool,
    roots: &ReadRoots,
) -> Result<ExitCode, InputError> {
    // Plan: the case and the resolution must be valid before anything is written.
    let case = Case::load_with(case, roots)?;
    // The pole sizes of fem-axisym's and the decks' `[resolution]` (c/N or a length).
    let resolution = match resolution {
        Some(text) => resolution::pole_size("mesh", &case.scene, text, limits::MERIDIAN_POLE)
            .map_err(|e| InputError(format!("--resolution: {e}")))?,
        None => geo::default_resolution(&case.scene),
    };
    geo::geo_for_scene(&case.scene, resolution)?;
    let folder = claim(out, force)?;
    match geo::mesh_into(&case.scene, resolution, folder.path(), &Toolchain::default()) {
        Ok(files) => {
            outln!(
                "{}: pole element {:.3} µm, {} triangles, gmsh {:.2} s",
                case.name(),
                resolution * 1e6,
                files.triangles,
                files.wall_s
            );
            for file in [&files.geo, &files.msh41, &files.msh22_mm] {
                outln!("  {}", file.display());
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
        outln!("{}", probe.line());
    }
    // The programs the cases under cases/ would run, as SPHERECONTACT_ALLOW_COMMANDS leaves them.
    let permission = CommandPermission::from_options(false, &[]);
    outln!(
        "command solvers: {}",
        permission.as_ref().map_or_else(|e| e.to_string(), |p| p.state())
    );
    for file in spherecontact::case::case_files(&[PathBuf::from("cases")]).unwrap_or_default() {
        if let Ok(mut case) = Case::load(&file) {
            case.permit_commands(permission.as_ref().unwrap_or(&CommandPermission::refused()));
            case.command_lines().iter().for_each(|line| outln!("  {line}"));
        }
    }
    if probes.iter().all(|p| p.available()) {
        ExitCode::SUCCESS
    } else {
        outln!("some external tools are missing: run scripts/setup.sh");
        ExitCode::FAILURE
    }
}

fn list(roots: &ReadRoots) -> Result<ExitCode, InputError> {
    outln!("solvers:");
    let solvers = registry::registry();
    let width = solvers
        .iter()
        .map(|s| s.name().chars().count())
        .max()
        .unwrap_or(0);
    for solver in solvers {
        let kind = solver.kind().to_string();
        outln!("  {:<width$} {kind:<17} {}", solver.name(), solver.description());
    }
    outln!("cases:");
    for file in spherecontact::case::case_files(&[PathBuf::from("cases")]).unwrap_or_default() {
        if impact::is_impact_file(&file) {
            match spherecontact::case::load_impact(&file) {
                Ok(case) => outln!(
                    "  {:<22} {}  (impact) {}",
                    text::one_line(&case.name),
                    text::one_line(&file.display().to_string()),
                    text::one_line(case.description.lines().next().unwrap_or(""))
                ),
                Err(e) => outln!("  (invalid) {}", text::one_line(&e.to_string())),
            }
            continue;
        }
        match Case::load_with(&file, roots) {
            Ok(case) => {
                outln!(
                    "  {:<22} {}  {}",
                    case.name(),
                    text::one_line(&file.display().to_string()),
                    text::one_line(case.description.lines().next().unwrap_or(""))
                );
                case.command_lines().iter().for_each(|line| outln!("    {line}"));
            }
            Err(e) => outln!("  (invalid) {}", text::one_line(&e.to_string())),
        }
    }
    Ok(ExitCode::SUCCESS)
}
