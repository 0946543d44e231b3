//! `verify` and its family (`merge`, `baseline update`, `slurm`): the arguments, the plan (cases
//! read and selected, outputs claimed, baselines loaded; nothing run) and its execution.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Subcommand;
use spherecontact::case::ReadRoots;
use spherecontact::conclusion::Conclusion;
use spherecontact::external::permission;
use spherecontact::judged::Suite;
use spherecontact::report::junit;
use spherecontact::runfile::{CaseRecord, RunFile};
use spherecontact::schedule::Judged;
use spherecontact::text::one_line;
use spherecontact::{baseline, io, merge, plan, schedule};

use super::Jobs;
use crate::{claim, resolution_options, CommandOptions, InputError};

/// The arguments of `verify`.
#[derive(clap::Args)]
pub(crate) struct VerifyArgs {
    /// Case files or folders (every .toml under them); default: cases/.
    cases: Vec<PathBuf>,
    /// Write JUnit XML here.
    #[arg(long, value_name = "FILE")]
    junit: Option<PathBuf>,
    #[command(flatten)]
    require: Require,
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
    #[command(flatten)]
    jobs: Jobs,
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
    #[command(flatten)]
    commands: CommandOptions,
    /// Replace a --junit file that spherecontact did not write, or write --out into a folder
    /// that holds files it did not write.
    #[arg(long)]
    force: bool,
}

/// What `verify`, `merge` and `slurm`'s jobs count as failures besides failing checks.
#[derive(clap::Args, Clone, Copy, Default)]
pub(crate) struct Require {
    /// Count a check that is N/A (a solver not installed) as a failure, as CI does.
    #[arg(long)]
    require_external: bool,
    /// Count a case that has no baseline in --baselines as a failure, as CI does (without it,
    /// such a case is said, NOBASE, and passes).
    #[arg(long)]
    require_baselines: bool,
}

/// The arguments of `slurm`.
#[derive(clap::Args)]
pub(crate) struct SlurmArgs {
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
    /// Written into the shards' and the merge's command lines.
    #[command(flatten)]
    require: Require,
    /// The non-regression baselines.
    #[arg(long, value_name = "DIR", default_value = baseline::DIR)]
    baselines: PathBuf,
    /// Written into the shards' command line: the jobs run what is allowed now.
    #[command(flatten)]
    commands: CommandOptions,
}

/// What `baseline` does.
#[derive(Subcommand)]
pub(crate) enum BaselineAction {
    /// Run cases and rewrite their baselines.
    Update {
        /// Case files or folders; default: every .toml under cases/.
        cases: Vec<PathBuf>,
        /// The baselines' folder.
        #[arg(long, value_name = "DIR", default_value = baseline::DIR)]
        baselines: PathBuf,
        #[command(flatten)]
        jobs: Jobs,
        #[command(flatten)]
        commands: CommandOptions,
    },
}

/// Where `verify` and `merge` write, checked before any work.
pub(crate) struct Outputs {
    /// The JUnit file as given, and its canonical path (claimed).
    junit: Option<(PathBuf, PathBuf)>,
    /// The output folder, claimed (and locked) for this run.
    out: Option<io::OutputFolder>,
    require: Require,
}

impl Outputs {
    pub(crate) fn checked(
        junit: Option<PathBuf>,
        out: Option<PathBuf>,
        require: Require,
        force: bool,
    ) -> Result<Self, InputError> {
        let junit = junit
            .map(|file| {
                io::claim_file(&file, force, junit::is_ours)
                    .map(|canonical| (file.clone(), canonical))
                    .map_err(|e| InputError(format!("--junit {}: {e}", file.display())))
            })
            .transpose()?;
        let out = out.map(|dir| claim(&dir, force)).transpose()?;
        Ok(Outputs { junit, out, require })
    }

    /// Prints the verdicts of the judged cases (path and impact) and writes the JUnit and
    /// summary; `compared` says which had no baseline in which folder.
    fn write(&self, judged: &[Judged], compared: &Compared) -> Result<ExitCode, InputError> {
        let suites: Vec<Suite> = judged
            .iter()
            .map(|j| {
                let mut suite = j.suite();
                if compared.without.contains(&suite.name) {
                    let file = baseline::file(&compared.dir, &suite.name).display().to_string();
                    suite.no_baseline = Some(one_line(&file).into_owned());
                }
                suite
            })
            .collect();
        let conclusion = Conclusion {
            suites: &suites,
            require_external: self.require.require_external,
            require_baselines: self.require.require_baselines,
        };
        let text = conclusion.text();
        out!("{text}");
        if let Some((file, canonical)) = &self.junit {
            io::write_atomically(canonical, conclusion.junit().as_bytes())
                .map_err(|e| InputError(format!("--junit {}: {e}", file.display())))?;
        }
        if let Some(folder) = &self.out {
            io::write_atomically(&folder.path().join("summary.txt"), text.as_bytes())
                .map_err(|e| InputError(format!("--out {}: {e}", folder.path().display())))?;
            write_impact_report(judged, &folder.path().join("impact"))?;
        }
        Ok(if conclusion.passed() {
            ExitCode::SUCCESS
        } else {
            ExitCode::FAILURE
        })
    }
}

/// How the judged cases met their baselines: the folder, and the cases that have none there.
struct Compared {
    dir: PathBuf,
    without: Vec<String>,
}

/// The impact cases' report *How far is your DEM code from exact Mindlin–Deresiewicz in
/// impact?* into `dir` (`DIR/impact/` of `verify --out DIR` and `merge --out DIR`, beside
/// `summary.txt`), when impact cases were judged.
fn write_impact_report(judged: &[Judged], dir: &Path) -> Result<(), InputError> {
    let impacts: Vec<_> = judged
        .iter()
        .filter_map(|j| match j {
            Judged::Impact(run) => Some(run),
            Judged::Path(_) => None,
        })
        .collect();
    if impacts.is_empty() {
        return Ok(());
    }
    spherecontact::report::impact::document(impacts, false)
        .and_then(|document| document.write(dir))
        .map_err(|e| InputError(format!("--out {}: {e}", dir.display())))
}

/// The cases of `verify` (path and impact cases), read and selected, with their baselines;
/// nothing run yet.
struct VerifyPlan {
    files: Vec<CaseRecord>,
    options: plan::CaseOptions,
    plan: plan::Plan,
    baselines: std::collections::BTreeMap<String, baseline::Baseline>,
}

fn verify_plan(
    files: Vec<PathBuf>,
    selection: &plan::Selection,
    options: &plan::CaseOptions,
    baselines: &Path,
    reading: baseline::Reading,
) -> Result<VerifyPlan, InputError> {
    let files = spherecontact::case::case_files(&if files.is_empty() {
        vec![PathBuf::from("cases")]
    } else {
        files
    })?;
    let (mut selected, mut cases) = (Vec::new(), Vec::new());
    for file in files {
        let text = spherecontact::case::read_case_file(&file).map_err(plan::PlanError::from)?;
        let case = options.parse_member(&file, &text)?;
        if selection.selects(&case) {
            selected.push(CaseRecord::new(file, &text, &case));
            cases.push(case);
        }
    }
    if cases.is_empty() {
        return Err(InputError(
            "no case files to verify (none given, or none selected by label)".into(),
        ));
    }
    let baselines = baseline::load_all(baselines, &cases, reading)?;
    let commands: Vec<String> = cases
        .iter()
        .flat_map(|case| match case {
            plan::Member::Path(case) => case.command_lines(),
            plan::Member::Impact(case) => spherecontact::impact::own_run::command_lines(case),
        })
        .collect();
    commands.iter().for_each(|line| outln!("{line}"));
    if !commands.is_empty() && !options.permission.is_allowed() {
        outln!(
            "verify: the programs cases name will not run: {}",
            permission::how_to_allow()
        );
    }
    let plan = plan::Plan::new(cases, |case, solver| baselines.get(case.name())?.wall_s(solver));
    Ok(VerifyPlan {
        files: selected,
        options: options.clone(),
        plan,
        baselines,
    })
}

/// `verify`: the plan checked and built (nothing written on bad input), then executed.
pub(crate) fn verify_command(args: VerifyArgs, roots: &ReadRoots) -> Result<ExitCode, InputError> {
    let selection = plan::Selection::new(&args.labels, &args.skip_labels)?;
    let jobs = args.jobs.cores();
    let shard = args.shard.map(|s| s.parse::<plan::Shard>()).transpose()?;
    let options = plan::CaseOptions {
        ranks: args.ranks,
        resolutions: resolution_options(&args.resolution)?,
        roots: roots.clone(),
        permission: args.commands.permission()?,
    };
    let outputs = Outputs::checked(args.junit, args.out, args.require, args.force)?;
    let plan = verify_plan(
        args.cases,
        &selection,
        &options,
        &args.baselines,
        baseline::Reading::Compare,
    )?;
    verify_cases(plan, shard, jobs, &outputs, args.baselines)
}

fn verify_cases(
    verify: VerifyPlan,
    shard: Option<plan::Shard>,
    jobs: usize,
    outputs: &Outputs,
    dir: PathBuf,
) -> Result<ExitCode, InputError> {
    let plan = match shard {
        Some(shard) => verify.plan.shard(shard),
        None => verify.plan,
    };
    let finished = schedule::execute(&plan, jobs);
    let chosen = verify.options.chosen_solvers();
    if let Some(folder) = &outputs.out {
        RunFile::new(&plan, &finished, verify.files, verify.options, shard)
            .write(folder.path())
            .map_err(|e| InputError(format!("--out {}: {e}", folder.path().display())))?;
    }
    let mut judged = schedule::judge(plan, finished);
    let without = baseline::compare_all(
        &verify.baselines,
        judged.iter_mut().map(Judged::baselined_mut),
        &chosen,
    );
    outputs.write(&judged, &Compared { dir, without })
}

pub(crate) fn merge_runs(
    dirs: &[PathBuf],
    dir: &Path,
    outputs: &Outputs,
    roots: &ReadRoots,
) -> Result<ExitCode, InputError> {
    let merged = merge::merge(dirs, roots)?;
    let baselines = baseline::load_all(dir, &merged.plan.cases, baseline::Reading::Compare)?;
    for (dir, (shard, wall_s)) in dirs.iter().zip(&merged.shards) {
        // The folder's name and the run file's shard field as text (crates/system/src/text.rs): one line each.
        let shard = one_line(shard.as_deref().unwrap_or("whole"));
        let dir = dir.display().to_string();
        eprintln!(
            "merge: {} (shard {shard}): runs {wall_s:.2} s wall in all",
            one_line(&dir)
        );
    }
    let mut judged = schedule::judge(merged.plan, merged.finished);
    let without = baseline::compare_all(
        &baselines,
        judged.iter_mut().map(Judged::baselined_mut),
        &merged.options.chosen_solvers(),
    );
    let compared = Compared {
        dir: dir.to_path_buf(),
        without,
    };
    outputs.write(&judged, &compared)
}

pub(crate) fn update_baselines(
    cases: Vec<PathBuf>,
    dir: &Path,
    jobs: Jobs,
    roots: &ReadRoots,
    commands: &CommandOptions,
) -> Result<ExitCode, InputError> {
    let options = plan::CaseOptions {
        roots: roots.clone(),
        permission: commands.permission()?,
        ..plan::CaseOptions::default()
    };
    // Claimed as an output folder before any case runs: no system folder, no link, no foreign
    // file (a folder of baselines only, or marked), one run at a time.
    let folder = io::OutputFolder::claim_recognising(dir, false, baseline::is_baseline_file)
        .map_err(|e| InputError(format!("--baselines {}: {e}", dir.display())))?;
    let verify = verify_plan(
        cases,
        &plan::Selection::default(),
        &options,
        dir,
        baseline::Reading::Replace,
    )?;
    let finished = schedule::execute(&verify.plan, jobs.cores());
    for judged in schedule::judge(verify.plan, finished) {
        let run = judged.baselined();
        let baseline = baseline::Baseline::of(run);
        let file = baseline::file(dir, run.case_name());
        io::write_atomically(
            &baseline::file(folder.path(), run.case_name()),
            baseline.to_toml().as_bytes(),
        )
        .map_err(|e| InputError(format!("--baselines {}: {e}", file.display())))?;
        outln!(
            "baseline: {} ({} checks with a value, {} solvers ran)",
            file.display(),
            baseline.checks.len(),
            baseline.solvers.len()
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// Checks the cases and writes the Slurm scripts of `args` (nothing is submitted). The jobs get
/// the folders `--allow-read` gives and the permission to run command solvers in force now.
pub(crate) fn slurm(args: SlurmArgs, roots: &ReadRoots) -> Result<ExitCode, InputError> {
    let selection = plan::Selection::new(&args.labels, &args.skip_labels)?;
    let permission = args.commands.permission()?;
    let options = plan::CaseOptions {
        roots: roots.clone(),
        ..plan::CaseOptions::default()
    };
    verify_plan(
        args.cases.clone(),
        &selection,
        &options,
        &args.baselines,
        baseline::Reading::Compare,
    )?;
    let root = std::env::current_dir()?;
    let mut merge_args = vec!["--baselines".to_owned(), text(&root.join(&args.baselines))?];
    for folder in roots.folders() {
        merge_args.extend(["--allow-read".to_owned(), text(folder)?]);
    }
    if args.require.require_external {
        merge_args.push("--require-external".into());
    }
    if args.require.require_baselines {
        merge_args.push("--require-baselines".into());
    }
    let mut verify_args = args
        .cases
        .iter()
        .map(|c| text(c))
        .collect::<Result<Vec<_>, _>>()?;
    for (option, list) in [("--label", &args.labels), ("--skip-label", &args.skip_labels)] {
        verify_args.extend(list.iter().flat_map(|l| [option.to_owned(), l.clone()]));
    }
    verify_args.extend(merge_args.iter().cloned());
    if permission.is_allowed() {
        verify_args.push("--allow-commands".into());
    }
    for name in &args.commands.pass_env {
        verify_args.extend(["--pass-env".to_owned(), name.clone()]);
    }
    let mut job = spherecontact::slurm::SlurmJob {
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
    job.check()?;
    let folder = claim(&args.out, false)?;
    job.out = folder.path().to_path_buf();
    job.write()
        .map_err(|e| InputError(format!("--out {}: {e}", args.out.display())))?;
    outln!(
        "slurm: scripts in {}: run {}",
        args.out.display(),
        job.out.join("submit.sh").display()
    );
    Ok(ExitCode::SUCCESS)
}

/// `path` as the text of a script's argument: a path that is not UTF-8 is refused.
fn text(path: &Path) -> Result<String, InputError> {
    path.to_str().map(str::to_owned).ok_or_else(|| {
        InputError(format!(
            "`{}`: not UTF-8 (a batch script is text)",
            path.display()
        ))
    })
}
