//! `spherecontact slurm`: a verification as Slurm batch jobs, written, not submitted: a job array
//! whose task K runs `verify --shard K/N`, a merge job that runs when every shard has finished
//! (`--dependency=afterok`), and `submit.sh` that submits both.
//!
//! A shard whose checks fail (exit 1) still finished its runs: its job succeeds so that the merge
//! runs and gives the verdict (the merge job fails on any NOOK or DRIFT); bad input (exit 2) or a
//! crash fails the shard's job, and the merge does not run.

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

/// `text` quoted for a POSIX shell.
fn quote(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

fn quoted(path: &Path) -> String {
    quote(&path.to_string_lossy())
}

/// The files and their text, in the order written.
pub type Scripts = Vec<(&'static str, String)>;

impl SlurmJob {
    /// The `#SBATCH` lines every job has.
    fn header(&self, name: &str, log: &str) -> String {
        let mut text = format!(
            "#!/bin/sh\n#SBATCH --job-name={name}\n#SBATCH --chdir={}\n#SBATCH --output={}\n\
             #SBATCH --ntasks=1\n#SBATCH --cpus-per-task={}\n",
            self.root.display(),
            self.out.join(log).display(),
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
            "{}set -u\n{program} merge{dirs}{merge_args} --junit {} --out {}\n",
            self.header("spherecontact-merge", "merge.log"),
            quoted(&self.out.join("verify.xml")),
            quoted(&self.out.join("merged")),
        );
        let submit = format!(
            "#!/bin/sh\n# Submits the shards (a job array) and the merge, which waits for all of them.\n\
             set -eu\narray=$(sbatch --parsable {})\narray=${{array%%;*}}\n\
             merge=$(sbatch --parsable --dependency=afterok:\"$array\" {})\n\
             echo \"shards: job $array, merge: job ${{merge%%;*}}; merged JUnit: {}\"\n",
            quoted(&self.out.join("shards.sbatch")),
            quoted(&self.out.join("merge.sbatch")),
            self.out.join("verify.xml").display(),
        );
        vec![
            ("shards.sbatch", shards),
            ("merge.sbatch", merge),
            ("submit.sh", submit),
        ]
    }

    /// Writes the scripts into [`SlurmJob::out`] (created if missing), `submit.sh` executable.
    pub fn write(&self) -> std::io::Result<()> {
        std::fs::create_dir_all(&self.out)?;
        for (name, text) in self.scripts() {
            let file = self.out.join(name);
            crate::io::write_atomically(&file, text.as_bytes())?;
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

    #[test]
    fn the_array_runs_each_shard_and_the_merge_depends_on_it() {
        let job = SlurmJob {
            root: "/repo".into(),
            program: "/repo/target/release/spherecontact".into(),
            verify_args: vec!["cases".into(), "--label".into(), "it's".into()],
            merge_args: vec![],
            shards: 3,
            cores: 2,
            out: "/scratch/v".into(),
            partition: Some("short".into()),
            time: None,
        };
        let scripts = job.scripts();
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
}
