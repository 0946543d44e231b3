//! `spherecontact slurm`: a verification as Slurm batch jobs, written, not submitted: a job array
//! whose task K runs `verify --shard K/N`, a merge job that runs when every shard has finished
//! (`--dependency=afterok`), and `submit.sh` that submits both.
//!
//! A shard whose checks fail (exit 1) still finished its runs: its job succeeds so that the merge
//! runs and gives the verdict (the merge job fails on any NOOK or DRIFT); bad input (exit 2) or a
//! crash fails the shard's job, and Slurm cancels the merge (`--kill-on-invalid-dep=yes`) rather
//! than leaving it pending for ever.
//!
//! Tested under a real single-node Slurm (`tests/suite/slurm_cluster.rs`, `scripts/slurm-local.sh`).

use std::fmt::Write;
use std::path::{Path, PathBuf};

/// A sharded verification for Slurm.
#[derive(Clone, Debug)]
pub struct SlurmJob {
    /// The folder the jobs run in (the case paths are relative to it): absolute.
    pub root: PathBuf,
    /// The `spherecontact` program: absolute.
    pub program: PathBuf,
    /// The arguments of `verify` that select the cases (files, folders, labels, options).
    pub verify_args: Vec<String>,
    /// The arguments of `merge` besides the folders (baselines, --require-external).
    pub merge_args: Vec<String>,
    /// How many shards.
    pub shards: usize,
    /// Cores per shard (`--cpus-per-task`, `verify --jobs`).
    pub cores: usize,
    /// Where the scripts, the shards' folders and the merged results go: absolute.
    pub out: PathBuf,
    /// `--partition`, if any.
    pub partition: Option<String>,
    /// `--time` of each job, if any.
    pub time: Option<String>,
}

/// What cannot be written into a batch script.
#[derive(Debug, thiserror::Error)]
pub enum SlurmError {
    /// A folder that an `#SBATCH` line names (sbatch reads these lines itself: a double quote or a
    /// line break cannot be written in them).
    #[error(
        "{what} `{}`: cannot be named in an #SBATCH line (allowed: a UTF-8 path without `\"` or control \
         characters)",
        spherecontact_system::text::one_line(&.path.to_string_lossy())
    )]
    Path {
        /// Which folder.
        what: &'static str,
        /// The folder.
        path: PathBuf,
    },
    /// `--partition` is not a list of partition names.
    #[error(
        "--partition `{}`: not a partition name (allowed: letters, digits, `_`, `-`, `.`; several joined by `,`)",
        spherecontact_system::text::one_line(.0)
    )]
    Partition(String),
    /// `--time` is not one of Slurm's time limits.
    #[error(
        "--time `{}`: not a time limit (allowed: digits joined by `:` and `-` as Slurm reads them, e.g. \
         30, 1:00:00, 2-12:00; or UNLIMITED)",
        spherecontact_system::text::one_line(.0)
    )]
    Time(String),
    /// Writing the scripts failed.
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// `text` quoted for a POSIX shell.
fn quote(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

fn quoted(path: &Path) -> String {
    quote(&path.to_string_lossy())
}

/// `path` as the value of an `#SBATCH` option: in double quotes (sbatch splits its lines at
/// blanks outside them).
fn sbatch_path(path: &Path) -> String {
    format!("\"{}\"", path.display())
}

/// The file `log` in `folder` as the value of `#SBATCH --output`: the folder's `%` doubled (sbatch
/// expands `%a`, `%j`… there), `log`'s kept.
fn sbatch_output(folder: &Path, log: &str) -> String {
    format!("\"{}/{log}\"", folder.display().to_string().replace('%', "%%"))
}

/// Whether `path` can be written in an `#SBATCH` line.
fn check_path(what: &'static str, path: &Path) -> Result<(), SlurmError> {
    match path.to_str() {
        Some(text) if !text.chars().any(|c| c == '"' || c.is_control()) => Ok(()),
        _ => Err(SlurmError::Path {
            what,
            path: path.to_path_buf(),
        }),
    }
}

/// Whether `list` is one or more partition names joined by commas.
fn is_partition_list(list: &str) -> bool {
    list.split(',').all(|name| {
        !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'))
    })
}

/// Whether `time` has the shape of a Slurm time limit (Slurm itself judges the fields' ranges).
fn is_time_limit(time: &str) -> bool {
    matches!(time, "UNLIMITED" | "INFINITE")
        || (time.starts_with(|c: char| c.is_ascii_digit())
            && time.ends_with(|c: char| c.is_ascii_digit())
            && time.chars().all(|c| c.is_ascii_digit() || c == ':' || c == '-'))
}

/// The files and their text, in the order written.
pub type Scripts = Vec<(&'static str, String)>;

impl SlurmJob {
    /// Whether the job can be written: its folders named in `#SBATCH` lines, its partition and
    /// time limit.
    pub fn check(&self) -> Result<(), SlurmError> {
        check_path("the current folder", &self.root)?;
        check_path("--out", &self.out)?;
        if let Some(partition) = self.partition.as_ref().filter(|p| !is_partition_list(p)) {
            return Err(SlurmError::Partition(partition.clone()));
        }
        match &self.time {
            Some(time) if !is_time_limit(time) => Err(SlurmError::Time(time.clone())),
            _ => Ok(()),
        }
    }

    /// The `#SBATCH` lines every job has; `log` may hold `%a` (the array task).
    fn header(&self, name: &str, log: &str) -> String {
        let mut text = format!(
            "#!/bin/sh\n#SBATCH --job-name={name}\n#SBATCH --chdir={}\n#SBATCH --output={}\n\
             #SBATCH --ntasks=1\n#SBATCH --cpus-per-task={}\n",
            sbatch_path(&self.root),
            sbatch_output(&self.out, log),
            self.cores
        );
        for (option, value) in [("partition", &self.partition), ("time", &self.time)] {
            if let Some(value) = value {
                let _ = writeln!(text, "#SBATCH --{option}={value}");
            }
        }
        text
    }

    /// The shard folder of array task `$SLURM_ARRAY_TASK_ID` (or of shard `k`).
    fn shard_dir(&self, k: &str) -> String {
        format!("{}/shard-{k}", self.out.display())
    }

    /// The job array's, the merge's and the submitter's scripts.
    pub fn scripts(&self) -> Scripts {
        let n = self.shards;
        let program = quoted(&self.program);
        let args: String = self
            .verify_args
            .iter()
            .map(|a| format!(" {}", quote(a)))
            .collect();
        let shards = format!(
            "{}#SBATCH --array=1-{n}\nset -u\nk=$SLURM_ARRAY_TASK_ID\n\
             # Exit 1 (checks failed) still finished every run: the merge judges; 2 or a crash fails the job.\n\
             {program} verify{args} --jobs {} --shard \"$k/{n}\" --out {}\"$k\" --junit {}\"$k.xml\"\n\
             code=$?\n[ \"$code\" -le 1 ] || exit \"$code\"\n",
            self.header("spherecontact-shards", "shard-%a.log"),
            self.cores,
            quote(&self.shard_dir("")),
            quote(&format!("{}/shard-", self.out.display())),
        );
        let dirs: String = (1..=n)
            .map(|k| format!(" {}", quote(&self.shard_dir(&k.to_string()))))
            .collect();
        let merge_args: String = self.merge_args.iter().map(|a| format!(" {}", quote(a))).collect();
        let merge = format!(
            "{}#SBATCH --kill-on-invalid-dep=yes\nset -u\n{program} merge{dirs}{merge_args} --junit {} --out {}\n",
            self.header("spherecontact-merge", "merge.log"),
            quoted(&self.out.join("verify.xml")),
            quoted(&self.out.join("merged")),
        );
        let submit = format!(
            "#!/bin/sh\n# Submits the shards (a job array) and the merge, which waits for all of them.\n\
             set -eu\narray=$(sbatch --parsable {})\narray=${{array%%;*}}\n\
             merge=$(sbatch --parsable --dependency=afterok:\"$array\" {})\n\
             echo \"shards: job $array, merge: job ${{merge%%;*}}; merged JUnit: \"{}\n",
            quoted(&self.out.join("shards.sbatch")),
            quoted(&self.out.join("merge.sbatch")),
            quoted(&self.out.join("verify.xml")),
        );
        vec![
            ("shards.sbatch", shards),
            ("merge.sbatch", merge),
            ("submit.sh", submit),
        ]
    }

    /// Writes the scripts into [`SlurmJob::out`] (created if missing), `submit.sh` executable;
    /// nothing when [`SlurmJob::check`] refuses the job.
    pub fn write(&self) -> Result<(), SlurmError> {
        self.check()?;
        std::fs::create_dir_all(&self.out)?;
        for (name, text) in self.scripts() {
            let file = self.out.join(name);
            spherecontact_system::io::write_atomically(&file, text.as_bytes())?;
            if name.ends_with(".sh") {
                use std::os::unix::fs::PermissionsExt;
                std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o755))?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job() -> SlurmJob {
        SlurmJob {
            root: "/repo".into(),
            program: "/repo/target/release/spherecontact".into(),
            verify_args: vec!["cases".into(), "--label".into(), "it's".into()],
            merge_args: vec![],
            shards: 3,
            cores: 2,
            out: "/scratch/v".into(),
            partition: Some("short".into()),
            time: None,
        }
    }

    #[test]
    fn the_array_runs_each_shard_and_the_merge_depends_on_it() {
        let scripts = job().scripts();
        let (shards, merge, submit) = (&scripts[0].1, &scripts[1].1, &scripts[2].1);
        assert!(shards.contains("#SBATCH --array=1-3\n") && shards.contains("#SBATCH --partition=short\n"));
        assert!(
            shards.contains("#SBATCH --cpus-per-task=2\n#SBATCH --partition"),
            "{shards}"
        );
        assert!(
            shards.contains("verify 'cases' '--label' 'it'\\''s' --jobs 2 --shard \"$k/3\" --out '/scratch/v/shard-'\"$k\""),
            "{shards}"
        );
        assert!(
            merge.contains("merge '/scratch/v/shard-1' '/scratch/v/shard-2' '/scratch/v/shard-3' --junit"),
            "{merge}"
        );
        assert!(submit.contains("--dependency=afterok:\"$array\""), "{submit}");
    }

    #[test]
    fn folders_with_blanks_and_percent_signs_are_quoted_for_sbatch_and_the_shell() {
        let job = SlurmJob {
            root: "/my repo".into(),
            out: "/scratch/100% v".into(),
            ..job()
        };
        let scripts = job.scripts();
        let (shards, merge, submit) = (&scripts[0].1, &scripts[1].1, &scripts[2].1);
        assert!(shards.contains("#SBATCH --chdir=\"/my repo\"\n"), "{shards}");
        assert!(
            shards.contains("#SBATCH --output=\"/scratch/100%% v/shard-%a.log\"\n"),
            "{shards}"
        );
        assert!(merge.contains("#SBATCH --kill-on-invalid-dep=yes\n"), "{merge}");
        assert!(
            submit.contains("merged JUnit: \"'/scratch/100% v/verify.xml'\n"),
            "{submit}"
        );
    }

    #[test]
    fn what_an_sbatch_line_cannot_hold_is_refused_before_anything_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let refused = |job: SlurmJob| {
            let error = job.write().unwrap_err().to_string();
            assert!(!job.out.exists(), "{error}");
            error
        };
        let out = dir.path().join("v");
        let error = refused(SlurmJob {
            root: "/a\"b".into(),
            out: out.clone(),
            ..job()
        });
        assert!(
            error.starts_with("the current folder `/a\"b`: cannot be named"),
            "{error}"
        );
        let error = refused(SlurmJob {
            out: dir.path().join("new\nline"),
            ..job()
        });
        assert!(error.starts_with("--out `"), "{error}");
        let error = refused(SlurmJob {
            partition: Some("short\nrm -rf /".into()),
            out: out.clone(),
            ..job()
        });
        assert!(
            error.starts_with("--partition `short\\nrm -rf /`: not a partition name"),
            "{error}"
        );
        for bad in ["1:00:00 x", "", ":30", "1h"] {
            let error = refused(SlurmJob {
                time: Some(bad.into()),
                out: out.clone(),
                ..job()
            });
            assert!(
                error.starts_with(&format!("--time `{bad}`: not a time limit")),
                "{error}"
            );
        }
        let good = SlurmJob {
            partition: Some("short,long.q".into()),
            time: Some("2-12:00:00".into()),
            out: out.clone(),
            ..job()
        };
        good.write().unwrap();
        assert!(out.join("submit.sh").exists());
    }
}
