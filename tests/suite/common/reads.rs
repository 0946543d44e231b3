//! The project folder of the read tests (`tests/hostile_reads.rs`, the read fuzzer of
//! `tests/fuzz_case.rs`): a case's tree with stored results and reference values, secrets beside
//! it, and the command line run with a guard against hangs.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::mpsc;
use std::time::Duration;

/// A string that only the secret files (and the environment of a child) hold.
pub const SECRET: &str = "SECRET-5f1e9c";

/// A file of `tests/hostile/reads/`.
pub fn hostile(name: &str) -> PathBuf {
    super::root().join("tests/hostile/reads").join(name)
}

/// Runs the command line with `args` in `cwd`, with [`SECRET`] in its environment. A run that
/// has not ended after two minutes is a hang (a FIFO read, say): it is killed and the test fails
/// rather than wait for ever. Nothing about speed is asserted.
pub fn spherecontact_guarded(args: &[&str], cwd: &Path) -> Output {
    let child = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(args)
        .current_dir(cwd)
        .env("SPHERECONTACT_TEST_SECRET", SECRET)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || send.send(child.wait_with_output().unwrap()));
    receive
        .recv_timeout(Duration::from_secs(120))
        .unwrap_or_else(|_| {
            // SAFETY: kill(2) on the pid of our own child, which has not been reaped (it hangs).
            unsafe { libc::kill(pid as libc::pid_t, libc::SIGKILL) };
            panic!("spherecontact {args:?} hung")
        })
}

/// Stdout and stderr, as text.
pub fn text(output: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

/// The control characters of `text` other than the newline.
pub fn raw_controls(text: &str) -> Vec<char> {
    text.chars().filter(|c| c.is_control() && *c != '\n').collect()
}

/// A project folder in a temporary folder: `project/cases/` (the case under test, and
/// `data/good.csv`, hertz's own results for the base path), `project/reference/values.toml`, and
/// beside the project `secret.csv`, `secret.toml` (a valid reference value whose source is the
/// secret) and `outside.csv` (a copy of good.csv).
pub struct Project {
    /// The temporary folder: `project/` and the secrets.
    pub dir: tempfile::TempDir,
}

impl Project {
    /// A new project folder.
    pub fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let project = dir.path().join("project");
        std::fs::create_dir_all(project.join("cases/data")).unwrap();
        std::fs::create_dir_all(project.join("reference")).unwrap();
        std::fs::copy(
            super::root().join("tests/hostile/reference/values.toml"),
            project.join("reference/values.toml"),
        )
        .unwrap();
        std::fs::write(
            dir.path().join("secret.csv"),
            format!("{SECRET},token\n1,{SECRET}\n"),
        )
        .unwrap();
        std::fs::write(
            dir.path().join("secret.toml"),
            format!(
                "[force_17um]\nquantity = \"normal_force\"\nvalue = 803.76\nunit = \"N\"\nsource = \"{SECRET}\"\n"
            ),
        )
        .unwrap();
        let project = Self { dir };
        project.write_good_results();
        project
    }

    /// The project folder (cases/, reference/).
    pub fn project(&self) -> PathBuf {
        self.dir.path().join("project")
    }

    /// Its cases/ folder.
    pub fn cases(&self) -> PathBuf {
        self.project().join("cases")
    }

    /// `data/good.csv`: `run --solver hertz` of the base case's path, and its copy beside the
    /// project.
    fn write_good_results(&self) {
        let template = std::fs::read_to_string(hostile("base.toml")).unwrap();
        let start = template.find("[[stored_results]]").unwrap();
        let case = self.dir.path().join("hertz-only.toml");
        std::fs::write(
            &case,
            template[..start].replace("solvers = [\"hertz\", \"lab-rig\"]", "solvers = [\"hertz\"]"),
        )
        .unwrap();
        let out = self.dir.path().join("run");
        let output = spherecontact_guarded(
            &["run", case.to_str().unwrap(), "--out", out.to_str().unwrap()],
            self.dir.path(),
        );
        assert!(output.status.success(), "{}", text(&output));
        std::fs::copy(out.join("hertz.csv"), self.cases().join("data/good.csv")).unwrap();
        std::fs::copy(out.join("hertz.csv"), self.dir.path().join("outside.csv")).unwrap();
    }

    /// Writes `cases/<name>` from the base template with the stored file and reference file
    /// named, then `edit` applied; its path.
    pub fn case(
        &self,
        name: &str,
        stored: &str,
        reference: &str,
        edit: impl Fn(String) -> String,
    ) -> PathBuf {
        let text = std::fs::read_to_string(hostile("base.toml"))
            .unwrap()
            .replace("@STORED@", stored)
            .replace("@REFERENCE@", reference);
        let file = self.cases().join(name);
        std::fs::write(&file, edit(text)).unwrap();
        file
    }

    /// `verify FILE` (with `extra` arguments) from the project folder.
    pub fn verify(&self, file: &Path, extra: &[&str]) -> Output {
        let mut args = vec!["verify", file.to_str().unwrap()];
        args.extend(extra);
        spherecontact_guarded(&args, &self.project())
    }
}

#[cfg(unix)]
pub fn symlink(target: &Path, link: &Path) {
    std::os::unix::fs::symlink(target, link).unwrap();
}
