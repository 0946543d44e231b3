//! What a run leaves outside its own folders. YADE made an empty folder `/tmp/yade-XXXXXX` at its
//! start (the name is fixed in its `Omega`: TMPDIR is not read) and, run with `-x`, never removed
//! it; its IPython wrote `~/.ipython/`. One of each was left behind per run before issue 42.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The `/tmp/yade-*` folders now.
fn yade_folders() -> BTreeSet<PathBuf> {
    std::fs::read_dir("/tmp")
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .filter(|e| e.file_name().to_string_lossy().starts_with("yade-"))
                .map(|e| e.path())
                .collect()
        })
        .unwrap_or_default()
}

/// The names in `folder`.
fn entries(folder: &Path) -> Vec<String> {
    std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// Writes `case` as `case.toml` in a fresh folder and runs `spherecontact run case.toml --solver
/// SOLVER --out out` there, with HOME and TMPDIR empty folders of its own; asserts that it
/// succeeds and leaves nothing behind: HOME and TMPDIR empty again (but for the version probes'
/// files, below), no new `/tmp/yade-*`. A YADE that another test started meanwhile holds its
/// `/tmp/yade-*` for its few seconds of start-up: a new folder counts as left behind when it is
/// still there a minute later (one left behind never goes; a YADE of another program that
/// leaves one while this runs is counted too). Nothing about speed is asserted.
pub fn assert_run_leaves_nothing(case: &str, solver: &str) {
    let dir = tempfile::tempdir().unwrap();
    let (home, tmp) = (dir.path().join("home"), dir.path().join("tmp"));
    for folder in [&home, &tmp] {
        std::fs::create_dir(folder).unwrap();
    }
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let before = yade_folders();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(["run", "case.toml", "--solver", solver, "--out", "out"])
        .current_dir(dir.path())
        .env("HOME", &home)
        .env("TMPDIR", &tmp)
        .output()
        .unwrap();
    super::assert_success(&output);
    // The toolchain's version probes (every tool, once a process) leave what those programs
    // always do, not YADE's: gmsh FLTK's preferences (~/.fltk), LAMMPS's OpenMPI its session
    // folder ($TMPDIR/ompi.<host>.<uid>, one a user, reused).
    let home_left: Vec<String> = entries(&home).into_iter().filter(|e| e != ".fltk").collect();
    assert_eq!(home_left, Vec::<String>::new(), "left in HOME");
    let tmp_left: Vec<String> = entries(&tmp)
        .into_iter()
        .filter(|e| !e.starts_with("ompi."))
        .collect();
    assert_eq!(tmp_left, Vec::<String>::new(), "left in TMPDIR");
    let mut left: Vec<PathBuf> = Vec::new();
    for _ in 0..60 {
        left = yade_folders().difference(&before).cloned().collect();
        if left.is_empty() {
            break;
        }
        std::thread::sleep(Duration::from_secs(1));
    }
    assert!(left.is_empty(), "{solver} left {left:?} behind");
}
