//! `spherecontact slurm` under a real Slurm, not a mock: a single-node cluster on localhost
//! (`scripts/slurm-local.sh`: munged, slurmctld and slurmd in a private folder) runs the job arrays
//! of shards and their merge jobs as the written `submit.sh` submits them. Three submissions:
//! every check passes (the merged JUnit and summary equal a local unsharded `verify`'s); a check
//! drifts from its baseline (the shards' jobs succeed, the merge job fails with exit 1, and its
//! JUnit still equals the local one); a shard's input is bad (its job fails with exit 2 and Slurm
//! cancels the merge).
//!
//! Needs root (it starts the daemons, and installs Debian's slurm-wlm and munge when missing).
//! Without root or without a way to install them it is skipped with a message, except under
//! `CI=true`, where that is a failure.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use crate::common::{self, root};

/// How long the jobs may take before the test gives up and shows the daemons' logs: a guard
/// against a hung cluster, not a speed requirement (the jobs take seconds on an idle machine).
const PATIENCE: Duration = Duration::from_secs(600);

fn text(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// A cluster started by `scripts/slurm-local.sh start` in a folder of its own, stopped when
/// dropped.
struct Cluster {
    dir: tempfile::TempDir,
}

impl Cluster {
    /// The cluster, or `None` (after saying why) where it cannot run and CI does not require it.
    fn start() -> Option<Cluster> {
        let skip = |why: String| {
            assert!(
                std::env::var("CI").as_deref() != Ok("true"),
                "CI=true: the Slurm test must run, but {why}"
            );
            eprintln!("slurm_cluster: SKIPPED: {why}");
            None
        };
        let uid = Command::new("id").arg("-u").output().unwrap();
        if stdout(&uid).trim() != "0" {
            return skip("it needs root (it starts munged, slurmctld and slurmd)".into());
        }
        let cluster = Cluster {
            dir: tempfile::tempdir().unwrap(),
        };
        let clock = Instant::now();
        let started = cluster.script("start");
        match started.status.code() {
            Some(0) => {
                eprintln!("cluster idle after {:.1} s", clock.elapsed().as_secs_f64());
                Some(cluster)
            }
            Some(3) => skip(String::from_utf8_lossy(&started.stderr).into_owned()),
            _ => panic!(
                "scripts/slurm-local.sh start failed:\n{}{}",
                stdout(&started),
                String::from_utf8_lossy(&started.stderr)
            ),
        }
    }

    fn script(&self, action: &str) -> Output {
        Command::new("bash")
            .arg(root().join("scripts/slurm-local.sh"))
            .arg(action)
            .arg(self.dir.path())
            .output()
            .unwrap()
    }

    /// A Slurm client (or a script calling one) talking to this cluster.
    fn client(&self, program: impl AsRef<std::ffi::OsStr>) -> Command {
        let mut command = Command::new(program);
        command.env("SLURM_CONF", self.dir.path().join("slurm.conf"));
        command
    }

    /// `squeue`'s lines: job, name, state, reason.
    fn queue(&self) -> String {
        let output = self
            .client("squeue")
            .args(["-h", "-o", "%i %j %T %r"])
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "squeue: {}\n{}",
            String::from_utf8_lossy(&output.stderr),
            self.logs()
        );
        stdout(&output)
    }

    /// Each job of `id` (an array's tasks, or one job) as `(id, state, exit code)`, from
    /// slurmctld's memory of finished jobs (no accounting database here: sacct has nothing).
    fn finished(&self, id: &str) -> Vec<(String, String, String)> {
        let output = self
            .client("scontrol")
            .args(["-o", "show", "job", id])
            .output()
            .unwrap();
        let field = |line: &str, key: &str| {
            line.split_whitespace()
                .find_map(|w| w.strip_prefix(key))
                .unwrap_or("")
                .to_owned()
        };
        let mut jobs: Vec<_> = stdout(&output)
            .lines()
            .map(|line| {
                let task = field(line, "ArrayTaskId=");
                let id = if task.is_empty() {
                    id.to_owned()
                } else {
                    format!("{id}_{task}")
                };
                (id, field(line, "JobState="), field(line, "ExitCode="))
            })
            .collect();
        jobs.sort();
        eprintln!("scontrol show job {id}: {jobs:?}");
        jobs
    }

    /// The daemons' logs, for a failure's message.
    fn logs(&self) -> String {
        ["log/slurmctld.log", "log/slurmd.log", "munge/munged.log"]
            .iter()
            .map(|log| {
                let file = self.dir.path().join(log);
                format!(
                    "--- {}\n{}",
                    file.display(),
                    std::fs::read_to_string(&file).unwrap_or_default()
                )
            })
            .collect()
    }

    /// Waits until no job is queued or running, printing each new state of the queue.
    fn wait_until_idle(&self, outputs: &[&Path]) {
        let start = Instant::now();
        let mut last = String::from("?");
        loop {
            let queue = self.queue();
            if queue != last {
                eprint!("squeue after {:.1} s:\n{queue}", start.elapsed().as_secs_f64());
                last = queue;
            }
            if last.trim().is_empty() {
                return;
            }
            if start.elapsed() > PATIENCE {
                let logs: String = outputs.iter().map(|dir| job_logs(dir)).collect();
                panic!(
                    "jobs still queued after {PATIENCE:?}:\n{last}\n{}{logs}",
                    self.logs()
                );
            }
            std::thread::sleep(Duration::from_millis(250));
        }
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        let stopped = self.script("stop");
        if !stopped.status.success() {
            eprintln!(
                "scripts/slurm-local.sh stop: {}",
                String::from_utf8_lossy(&stopped.stderr)
            );
        }
    }
}

/// The jobs' own outputs in `out` (shard-K.log, merge.log).
fn job_logs(out: &Path) -> String {
    let mut logs = String::new();
    for entry in std::fs::read_dir(out).into_iter().flatten().flatten() {
        if entry.path().extension().is_some_and(|e| e == "log") {
            logs += &format!("--- {}\n{}", entry.path().display(), text(&entry.path()));
        }
    }
    logs
}

/// The array's and the merge's job ids of a submission.
struct Submitted {
    out: PathBuf,
    array: String,
    merge: String,
}

/// `spherecontact slurm SELECTION --shards N --cores 1 --out OUT` in the crate's folder, then
/// `prepare` (what changes between writing and running), then `OUT/submit.sh`.
fn submit(
    cluster: &Cluster,
    out: &Path,
    selection: &[&str],
    shards: &str,
    prepare: impl FnOnce(),
) -> Submitted {
    let mut all = vec!["slurm"];
    all.extend(selection);
    all.extend(["--shards", shards, "--cores", "1", "--out", out.to_str().unwrap()]);
    let written = common::spherecontact(&all, &root());
    common::assert_success(&written);
    prepare();
    let submitted = cluster.client(out.join("submit.sh")).output().unwrap();
    common::assert_success(&submitted);
    let said = stdout(&submitted);
    eprint!("{}: {said}", out.display());
    // "shards: job A, merge: job B; merged JUnit: …"
    let id = |after: &str| {
        let rest = &said[said.find(after).unwrap_or_else(|| panic!("{said}")) + after.len()..];
        rest[..rest.find([',', ';']).unwrap()].to_owned()
    };
    Submitted {
        out: out.to_path_buf(),
        array: id("shards: job "),
        merge: id("merge: job "),
    }
}

/// A local, unsharded `verify ARGS` into `dir` (created), which exits with `code`.
fn verify_locally(args: &[&str], dir: &Path, code: i32) {
    std::fs::create_dir(dir).unwrap();
    let mut all = vec!["verify"];
    all.extend(args);
    let junit = dir.join("verify.xml");
    let out = dir.join("out");
    all.extend(["--junit", junit.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let output = common::spherecontact(&all, &root());
    assert_eq!(
        output.status.code(),
        Some(code),
        "{}{}",
        stdout(&output),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// The merged JUnit and summary of `job` are the local run's in `local`.
fn assert_merged_as_local(job: &Submitted, local: &Path) {
    assert_eq!(text(&job.out.join("verify.xml")), text(&local.join("verify.xml")));
    assert_eq!(
        text(&job.out.join("merged/summary.txt")),
        text(&local.join("out/summary.txt"))
    );
    eprintln!(
        "{}: merged JUnit and summary equal the local run's",
        job.out.display()
    );
}

#[test]
#[ignore] // heavy: run once by .ci/run (starts a Slurm; root; installs slurm-wlm and munge if missing)
fn slurm_runs_the_shards_and_the_merge_gives_the_local_junit() {
    let Some(cluster) = Cluster::start() else {
        return;
    };
    let work = tempfile::tempdir().unwrap();
    let w = |name: &str| work.path().join(name);
    let folder = |name: &str| {
        std::fs::create_dir(w(name)).unwrap();
        w(name).to_str().unwrap().to_owned()
    };
    // A blank and a `%` in the output folder: sbatch's own parsing of #SBATCH lines meets them.
    // The fast path cases: the impact cases (also `fast`) run LAMMPS and YADE sweeps, a minute
    // of the test's time with nothing more to show about Slurm; their shards and merge are
    // scale::three_shards_merged_equal_the_unsharded_run's.
    let passing = [
        "--label",
        "fast",
        "--skip-label",
        "impact",
        "--require-external",
        "--allow-commands",
    ];
    let pass = submit(&cluster, &w("all pass %1"), &passing, "3", || {});
    // A baseline one check of hard-single-substep drifts from (4e-11 relative, over 1e-12).
    let drifting_baselines = folder("drifting");
    let baseline = text(&root().join("reference/baselines/hard-single-substep.toml"));
    assert!(baseline.contains(", 1.0256410104368015e3],\n"), "{baseline}");
    std::fs::write(
        w("drifting/hard-single-substep.toml"),
        baseline.replacen(", 1.0256410104368015e3],\n", ", 1.0256410104e3],\n", 1),
    )
    .unwrap();
    let drifting = ["--label", "hard", "--baselines", &drifting_baselines];
    let drift = submit(&cluster, &w("drift"), &drifting, "2", || {});
    // Baselines that become unreadable between writing the scripts and running them.
    let broken_baselines = folder("broken");
    let broken = submit(
        &cluster,
        &w("bad input"),
        &["--label", "hard", "--baselines", &broken_baselines],
        "2",
        || std::fs::write(w("broken/hard-grazing.toml"), "garbage = \n").unwrap(),
    );
    cluster.wait_until_idle(&[&pass.out, &drift.out, &broken.out]);
    let outputs = || job_logs(&pass.out) + &job_logs(&drift.out) + &job_logs(&broken.out);

    let ok = |k: usize, array: &str| (format!("{array}_{k}"), "COMPLETED".into(), "0:0".into());
    let pass_array: Vec<_> = (1..=3).map(|k| ok(k, &pass.array)).collect();
    assert_eq!(cluster.finished(&pass.array), pass_array, "{}", outputs());
    let pass_merge = vec![(pass.merge.clone(), "COMPLETED".into(), "0:0".into())];
    assert_eq!(cluster.finished(&pass.merge), pass_merge, "{}", outputs());
    verify_locally(&passing, &w("local-pass"), 0);
    assert_merged_as_local(&pass, &w("local-pass"));

    // Exit 1 of a shard (a check drifted) is a finished shard: the merge runs and fails.
    let drift_array: Vec<_> = (1..=2).map(|k| ok(k, &drift.array)).collect();
    assert_eq!(cluster.finished(&drift.array), drift_array, "{}", outputs());
    // A shard judges a check only when it ran all the check's solvers; the plan splits a case's
    // (case, solver) runs by cost, so mdr and hertz of hard-single-substep may fall in different
    // shards and the check be judged by the merge alone. Never by both shards; always by the merge.
    let drifted = |k: usize| text(&drift.out.join(format!("shard-{k}.xml"))).contains("DRIFT");
    assert!(
        !(drifted(1) && drifted(2)),
        "the drifting check is judged twice: {}",
        outputs()
    );
    assert!(
        text(&drift.out.join("verify.xml")).contains("DRIFT"),
        "the merge judges the drifting check: {}",
        outputs()
    );
    let drift_merge = vec![(drift.merge.clone(), "FAILED".into(), "1:0".into())];
    assert_eq!(cluster.finished(&drift.merge), drift_merge, "{}", outputs());
    verify_locally(&drifting, &w("local-drift"), 1);
    assert!(text(&w("local-drift/verify.xml")).contains("DRIFT"));
    assert_merged_as_local(&drift, &w("local-drift"));

    // Exit 2 (bad input) fails the shards' jobs, and Slurm cancels the merge that depends on them.
    let failed = |k: usize| (format!("{}_{k}", broken.array), "FAILED".into(), "2:0".into());
    assert_eq!(
        cluster.finished(&broken.array),
        vec![failed(1), failed(2)],
        "{}",
        outputs()
    );
    let cancelled = vec![(broken.merge.clone(), "CANCELLED".into(), "0:0".into())];
    assert_eq!(cluster.finished(&broken.merge), cancelled, "{}", outputs());
    assert!(text(&broken.out.join("shard-1.log"))
        .contains("(allowed: a baseline written by `spherecontact baseline update`"));
    assert!(!broken.out.join("verify.xml").exists() && !broken.out.join("merge.log").exists());
}

#[test]
fn the_jobs_get_the_read_roots_and_the_command_permission_and_bad_options_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = |name: &str| dir.path().join(name);
    let out = d("jobs");
    let readable = d("readable");
    std::fs::create_dir(&readable).unwrap();
    let args = |extra: &[&str]| {
        let mut all = vec![
            "slurm",
            "--label",
            "hard",
            "--shards",
            "2",
            "--out",
            out.to_str().unwrap(),
        ];
        all.extend([
            "--allow-read",
            readable.to_str().unwrap(),
            "--allow-commands",
            "--pass-env",
            "HOME",
        ]);
        all.extend(extra);
        common::spherecontact(&all, &root())
    };
    for (bad, error) in [
        (
            ["--partition", "short\nrm -rf /"],
            "--partition `short\\nrm -rf /`: not a partition name",
        ),
        (["--time", "1 hour"], "--time `1 hour`: not a time limit"),
    ] {
        let refused = args(&bad);
        let stderr = String::from_utf8_lossy(&refused.stderr);
        assert_eq!(refused.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(error), "{stderr}");
        assert!(!out.exists());
    }
    common::assert_success(&args(&["--partition", "short", "--time", "1:00:00"]));
    let readable = readable.canonicalize().unwrap();
    let allow_read = format!("'--allow-read' '{}'", readable.display());
    let shards = text(&out.join("shards.sbatch"));
    assert!(
        shards.contains(&allow_read) && shards.contains(" '--allow-commands' '--pass-env' 'HOME' --jobs 2"),
        "{shards}"
    );
    assert!(
        shards.contains("#SBATCH --partition=short\n#SBATCH --time=1:00:00\n"),
        "{shards}"
    );
    let merge = text(&out.join("merge.sbatch"));
    assert!(
        merge.contains(&allow_read) && !merge.contains("--allow-commands"),
        "{merge}"
    );
}
