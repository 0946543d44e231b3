//! Bad command lines: each is bad input (exit code 2) with a message naming the argument and
//! what is allowed, never a panic, and nothing written — checked before any solver runs.
//!
//! Run: `cargo test --test suite hostile_cli::`.

use std::path::Path;
use std::process::Command;

use crate::common;

/// A small valid case (two solvers, a few steps).
const CASE: &str = common::SMALL_CASE;

/// The same with a flat body 1: no sphere to mesh.
fn flat_case() -> String {
    let sphere = "radius = 0.1\nyoung = 70e9\npoisson = 0.3";
    let flat = sphere.replacen("0.1", "inf", 1);
    CASE.replacen(sphere, &format!("{flat}\n\n[body2]\n{sphere}"), 1)
}

/// Runs `args` in a folder holding only case.toml, flat.toml, a-file and an empty folder; returns
/// what is wrong with the outcome, if anything.
fn judge(args: &[&str], fragments: &[&str]) -> Option<String> {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
    write("case.toml", CASE);
    write("flat.toml", &flat_case());
    write("a-file", "");
    std::fs::create_dir(dir.path().join("empty")).unwrap();
    let before = listing(dir.path());
    let output = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(args)
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let problem = if output.status.code() != Some(2) {
        Some(format!("exit code {:?}", output.status.code()))
    } else if stderr.contains("panicked") {
        Some("panicked".into())
    } else if listing(dir.path()) != before {
        Some(format!("wrote {:?}", listing(dir.path())))
    } else {
        fragments
            .iter()
            .find(|f| !stderr.contains(*f))
            .map(|f| format!("no `{f}`"))
    };
    problem.map(|p| format!("{args:?}: {p}\n    {}", stderr.trim()))
}

/// Every path under `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut paths = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path.clone());
            }
            paths.push(path.strip_prefix(dir).unwrap().display().to_string());
        }
    }
    paths.sort();
    paths
}

#[test]
fn bad_command_lines_are_bad_input_and_write_nothing() {
    // reproduce-paper reads the paper's quoted values first (beside the shipped case's folder).
    let paper = common::root().join("cases/paper-fig7.toml");
    let paper = paper.to_str().unwrap();
    let cases: &[(&[&str], &[&str])] = &[
        // The grammar (clap): usage on stderr, exit 2.
        (&[], &["Usage"]),
        (&["frobnicate"], &["unrecognized subcommand"]),
        (&["run"], &["<CASE>"]),
        (&["run", "case.toml", "--fast"], &["--fast"]),
        (&["list", "extra"], &["extra"]),
        (&["doctor", "--all"], &["--all"]),
        (
            &["bench", "case.toml", "--repeat", "0"],
            &["--repeat", "1..=10000"],
        ),
        (
            &["bench", "case.toml", "--repeat", "100000"],
            &["--repeat", "1..=10000"],
        ),
        (&["bench", "case.toml", "--repeat", "many"], &["--repeat", "many"]),
        (&["run", "case.toml", "--out"], &["--out"]),
        // Case files.
        (
            &["run", "missing.toml"],
            &["missing.toml", "cannot read the case file"],
        ),
        (&["run", "empty"], &["empty", "not a regular file (a directory"]),
        (&["run", "a-file"], &["a-file", "missing field"]),
        (&["verify", "case.toml", "missing.toml"], &["missing.toml"]),
        (&["verify", "empty/nothing.toml"], &["nothing.toml"]),
        (&["reproduce-paper", "--case", "missing.toml"], &["missing.toml"]),
        // Solvers.
        (
            &["run", "case.toml", "--solver", "ansys"],
            &["--solver", "unknown solver `ansys`"],
        ),
        (
            &["run", "case.toml", "--solver", "hretz"],
            &["--solver", "unknown solver `hretz`; did you mean `hertz`?"],
        ),
        (
            &["run", "case.toml", "--solver", ""],
            &["--solver", "unknown solver ``"],
        ),
        (
            &["run", "case.toml", "--solver", "mdr", "--solver", "mdr"],
            &["`mdr` is named twice"],
        ),
        (
            &["bench", "case.toml", "--solver", "nope", "--repeat", "1"],
            &["unknown solver `nope`"],
        ),
        // Output destinations, before any solver runs.
        (
            &["run", "case.toml", "--out", "a-file"],
            &["--out", "a-file", "not a folder"],
        ),
        (
            &["run", "case.toml", "--out", "a-file/below"],
            &["--out", "not a folder"],
        ),
        (
            &["compare", "case.toml", "--out", "a-file"],
            &["--out", "not a folder"],
        ),
        (
            &["reproduce-paper", "--case", paper, "--out", "a-file"],
            &["--out", "not a folder"],
        ),
        (
            &["bench", "case.toml", "--repeat", "1", "--out", "a-file"],
            &["--out", "not a folder"],
        ),
        (
            &["verify", "case.toml", "--junit", "empty"],
            &["--junit", "is a folder"],
        ),
        (
            &["verify", "case.toml", "--junit", "no/such/v.xml"],
            &["--junit", "does not exist"],
        ),
        (
            &["mesh", "case.toml", "--out", "a-file"],
            &["--out", "not a folder"],
        ),
        // Mesh resolutions.
        (
            &["mesh", "case.toml", "--resolution", "abc"],
            &["--resolution", "not a length"],
        ),
        (
            &["mesh", "case.toml", "--resolution", "-1um"],
            &["unexpected argument '-1'"],
        ),
        (
            &["mesh", "case.toml", "--resolution=-1um"],
            &["--resolution", "finite and positive"],
        ),
        (
            &["mesh", "case.toml", "--resolution", "inf"],
            &["--resolution", "finite and positive"],
        ),
        (
            &["mesh", "case.toml", "--resolution", "nan"],
            &["--resolution", "finite and positive"],
        ),
        (
            &["mesh", "case.toml", "--resolution", "0um"],
            &["--resolution", "finite and positive"],
        ),
        (
            &["mesh", "case.toml", "--resolution", "1nm"],
            &["--resolution", "not a length"],
        ),
        (
            &["mesh", "case.toml", "--resolution", "1e-9"],
            &["--resolution", "finer than allowed", "allowed: c/N"],
        ),
        (
            &["mesh", "case.toml", "--resolution", "1m"],
            &["--resolution", "coarser than allowed"],
        ),
        (&["mesh", "flat.toml"], &["body 1 is a flat"]),
    ];
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|(args, fragments)| judge(args, fragments))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(cases.len() >= 26, "as many as the review tried");
}

#[test]
fn a_case_folder_with_no_case_files_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("cases")).unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .arg("verify")
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("no case files"));
}

/// The write end of a pipe whose reader has gone: every write to it fails with EPIPE, as
/// `spherecontact list | head -1` once `head` has its line.
fn closed_pipe() -> std::process::Stdio {
    use std::os::fd::{FromRawFd, OwnedFd};
    let mut ends = [0; 2];
    assert_eq!(unsafe { libc::pipe(ends.as_mut_ptr()) }, 0);
    assert_eq!(unsafe { libc::close(ends[0]) }, 0);
    // The write end is this process's own, fresh from pipe(2), owned once.
    std::process::Stdio::from(unsafe { OwnedFd::from_raw_fd(ends[1]) })
}

/// Requirement: a command whose standard output is a closed pipe (`spherecontact list | head
/// -1`; `verify`'s table, `compare`'s summary piped into a pager quit early) does not panic
/// ("failed printing to stdout") and says nothing: it ends with its own exit code, what it writes
/// to files whole. Reference: ripgrep's behaviour on a broken pipe.
#[test]
fn a_closed_standard_output_ends_the_printing_quietly() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), common::SMALL_CASE).unwrap();
    let junit = dir.path().join("junit.xml");
    let runs: [(&[&str], &Path); 3] = [
        (&["list"], &common::root()),
        (
            &["verify", "case.toml", "--junit", junit.to_str().unwrap()],
            dir.path(),
        ),
        (&["compare", "case.toml", "--out", "compared"], dir.path()),
    ];
    for (args, cwd) in runs {
        let output = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
            .args(args)
            .current_dir(cwd)
            .stdout(closed_pipe())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(0), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("panicked") && !stderr.contains("Broken pipe") && !stderr.contains("error"),
            "{args:?}: {stderr}"
        );
    }
    let junit = std::fs::read_to_string(&junit).unwrap();
    assert!(junit.trim_end().ends_with("</testsuites>"), "{junit}");
    assert!(dir.path().join("compared/report.html").is_file());
}
