//! Writes stay where they belong: nothing is written through a symbolic link, into a system
//! folder, over files the harness did not write (without `--force`), or into a folder another
//! run is writing. Every refusal is exit code 2 with nothing written, before any solver runs.
//! The hostile folders are made in temporary folders at test time.
//!
//! Run: `cargo test --test suite hostile_writes::` (a few seconds; the `mesh` test needs gmsh, the stale
//! lock test the `flock` program of util-linux).

use std::os::unix::fs::symlink;
use std::path::Path;
use std::process::{Command, Output};

use spherecontact::io::{OutputFolder, MARKER};
use spherecontact::toolchain::{Tool, Toolchain};

use crate::common;

/// A folder holding `case.toml` (hertz and mdr, a few steps) and whatever a test adds.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), common::SMALL_CASE).unwrap();
    dir
}

/// Runs `spherecontact` with `args` in `cwd`.
fn spherecontact(args: &[&str], cwd: &Path) -> Output {
    common::spherecontact(args, cwd)
}

/// Asserts a refusal: exit code 2, stderr holding every fragment, no panic.
fn assert_refused(output: &Output, fragments: &[&str]) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for fragment in fragments {
        assert!(stderr.contains(fragment), "no `{fragment}` in: {stderr}");
    }
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Marks `dir` (created) as an output folder of the harness, as an earlier run would have.
fn own_folder(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join(MARKER), "").unwrap();
}

#[test]
fn a_symlinked_figures_folder_pointing_outside_is_not_written_through() {
    let dir = workspace();
    let (out, outside) = (dir.path().join("out"), dir.path().join("outside"));
    own_folder(&out);
    std::fs::create_dir(&outside).unwrap();
    symlink(&outside, out.join("figures")).unwrap();
    for force in [false, true] {
        let mut args = vec!["compare", "case.toml", "--out", "out"];
        args.extend(force.then_some("--force"));
        assert_refused(
            &spherecontact(&args, dir.path()),
            &["--out out", "figures", "symbolic link"],
        );
    }
    assert!(
        names(&outside).is_empty(),
        "written through the link: {:?}",
        names(&outside)
    );
    assert_eq!(names(&out), [MARKER, "figures"], "nothing written");
}

#[test]
fn a_symlinked_solvers_folder_or_a_link_deeper_in_the_tree_is_refused_too() {
    let dir = workspace();
    let (out, outside) = (dir.path().join("out"), dir.path().join("outside"));
    own_folder(&out.join("data"));
    std::fs::write(out.join(MARKER), "").unwrap();
    std::fs::create_dir(&outside).unwrap();
    symlink(&outside, out.join("solvers")).unwrap();
    assert_refused(
        &spherecontact(&["compare", "case.toml", "--out", "out"], dir.path()),
        &["solvers", "symbolic link"],
    );
    std::fs::remove_file(out.join("solvers")).unwrap();
    symlink(&outside, out.join("data/solvers")).unwrap();
    assert_refused(
        &spherecontact(&["compare", "case.toml", "--out", "out"], dir.path()),
        &["solvers", "symbolic link"],
    );
    assert!(names(&outside).is_empty());
}

#[test]
fn a_symlink_at_mesh_geo_does_not_overwrite_its_target() {
    let dir = workspace();
    let out = dir.path().join("out");
    own_folder(&out);
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "precious").unwrap();
    symlink(&victim, out.join("mesh.geo")).unwrap();
    assert_refused(
        &spherecontact(&["mesh", "case.toml", "--out", "out"], dir.path()),
        &["mesh.geo", "symbolic link"],
    );
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    assert_eq!(names(&out), [MARKER, "mesh.geo"], "nothing written");
}

#[test]
fn mesh_writes_its_files_and_gmsh_logs_into_the_folder_through_no_link() {
    let dir = workspace();
    let run = spherecontact(
        &["mesh", "case.toml", "--resolution", "c/10", "--out", "out"],
        dir.path(),
    );
    let out = dir.path().join("out");
    if let Err(e) = Toolchain::default().require(Tool::Gmsh) {
        // Without gmsh the run fails (exit 1) having written only the folder's marker.
        eprintln!("mesh_writes_its_files…: gmsh absent ({e}): checking the failure only");
        assert_eq!(run.status.code(), Some(1));
        assert_eq!(names(&out), [MARKER]);
        return;
    }
    common::assert_success(&run);
    assert_eq!(
        names(&out),
        [
            MARKER,
            "gmsh.stderr",
            "gmsh.stdout",
            "mesh.geo",
            "mesh.msh",
            "mesh_p1_mm.msh"
        ],
        "gmsh's work folder is private; only its results are written"
    );
    let printed = String::from_utf8_lossy(&run.stdout);
    let triangles = std::fs::read_to_string(out.join("mesh_p1_mm.msh"))
        .unwrap()
        .lines()
        .filter(|l| l.split_whitespace().nth(1) == Some("2") && l.split_whitespace().count() > 5)
        .count();
    assert!(printed.contains(&format!("{triangles} triangles")), "{printed}");
}

#[test]
fn the_root_and_system_folders_are_refused_also_through_a_link_or_dot_dot() {
    let dir = workspace();
    symlink("/etc", dir.path().join("etc-link")).unwrap();
    let up = "../".repeat(dir.path().components().count() + 2) + "etc";
    for out in [
        "/",
        "/etc",
        "/etc/spherecontact-out",
        "/usr/local/out",
        "/proc",
        "etc-link",
        &up,
    ] {
        let run = spherecontact(&["run", "case.toml", "--out", out], dir.path());
        assert_refused(&run, &["--out", "refused"]);
        assert!(
            !Path::new("/etc/hertz.csv").exists(),
            "--out {out} wrote into /etc"
        );
    }
    let junit = spherecontact(&["verify", "case.toml", "--junit", "/etc/verify.xml"], dir.path());
    assert_refused(&junit, &["--junit", "/etc holds"]);
    assert!(!Path::new("/etc/verify.xml").exists());
    assert!(!Path::new("/etc/spherecontact-out").exists());
    assert!(!Path::new("/usr/local/out").exists());
}

#[test]
fn the_home_folder_itself_is_refused_but_a_folder_in_it_is_not() {
    let dir = workspace();
    let home = dir.path().join("home");
    std::fs::create_dir(&home).unwrap();
    let run = |out: &str| {
        Command::new(env!("CARGO_BIN_EXE_spherecontact"))
            .args(["run", "case.toml", "--out", out])
            .current_dir(dir.path())
            .env("HOME", &home)
            .output()
            .unwrap()
    };
    assert_refused(&run("home"), &["home folder"]);
    assert!(names(&home).is_empty());
    common::assert_success(&run("home/out"));
}

#[test]
fn a_foreign_folder_with_a_report_is_refused_without_force_and_taken_over_with_it() {
    let dir = workspace();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("report.md"), "my own notes").unwrap();
    let refused = spherecontact(&["compare", "case.toml", "--out", "out"], dir.path());
    assert_refused(&refused, &["--out out", "report.md", "did not write", "--force"]);
    assert_eq!(names(&out), ["report.md"], "nothing written");
    assert_eq!(
        std::fs::read_to_string(out.join("report.md")).unwrap(),
        "my own notes"
    );
    common::assert_success(&spherecontact(
        &["compare", "case.toml", "--out", "out", "--force"],
        dir.path(),
    ));
    assert!(std::fs::read_to_string(out.join("report.md"))
        .unwrap()
        .contains("cli-test"));
    assert!(
        out.join(MARKER).is_file(),
        "the folder is now marked as the harness's"
    );
}

#[test]
fn an_own_folder_is_reused_without_force_and_a_user_symlink_to_a_folder_is_followed_once() {
    let dir = workspace();
    common::assert_success(&spherecontact(&["run", "case.toml", "--out", "out"], dir.path()));
    common::assert_success(&spherecontact(&["run", "case.toml", "--out", "out"], dir.path()));
    assert_eq!(
        names(&dir.path().join("out")),
        [
            MARKER,
            "hertz.csv",
            "hertz.json",
            "mdr.csv",
            "mdr.fields.csv",
            "mdr.json"
        ]
    );
    // A link naming the output folder itself is the user's choice: resolved once, then written
    // below its target without following any further link.
    std::fs::create_dir(dir.path().join("real")).unwrap();
    symlink(dir.path().join("real"), dir.path().join("alias")).unwrap();
    common::assert_success(&spherecontact(
        &["run", "case.toml", "--out", "alias/new"],
        dir.path(),
    ));
    assert!(dir.path().join("real/new/mdr.csv").is_file());
}

#[test]
fn a_second_run_into_a_folder_in_use_is_refused_naming_the_holder() {
    let dir = workspace();
    let out = dir.path().join("out");
    let held = OutputFolder::claim(&out, false).unwrap();
    let before = names(&out);
    let pid = format!("pid {}", std::process::id());
    for args in [
        &["run", "case.toml", "--out", "out"][..],
        &["mesh", "case.toml", "--out", "out"],
        &["compare", "case.toml", "--out", "out", "--force"],
    ] {
        assert_refused(&spherecontact(args, dir.path()), &["--out out", "in use", &pid]);
    }
    assert_eq!(names(&out), before, "nothing written");
    drop(held);
    common::assert_success(&spherecontact(&["run", "case.toml", "--out", "out"], dir.path()));
}

#[test]
fn the_lock_of_a_killed_holder_does_not_block_a_later_run() {
    let dir = workspace();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    // Another process holds the folder's lock: a shell opens the marker, flock(1) locks that
    // open file (flock(2), the harness's own kind of lock), and the shell becomes `sleep`,
    // which keeps it open, so that killing this one process is killing the holder.
    let mut holder = Command::new("sh")
        .arg("-c")
        .arg(r#"exec 9>>"$1" && flock -x 9 && exec sleep 600"#)
        .arg("sh")
        .arg(out.join(MARKER))
        .spawn()
        .unwrap();
    let refused = (0..200).find_map(|_| {
        std::thread::sleep(std::time::Duration::from_millis(50));
        let run = spherecontact(&["run", "case.toml", "--out", "out"], dir.path());
        (run.status.code() == Some(2)).then_some(run)
    });
    assert_refused(&refused.expect("the held folder was never refused"), &["in use"]);
    holder.kill().unwrap();
    holder.wait().unwrap();
    // Killed: its lock went with it, although the marker (the lock file) stays.
    assert!(out.join(MARKER).exists());
    common::assert_success(&spherecontact(&["run", "case.toml", "--out", "out"], dir.path()));
    // A marker naming a process long gone, and no lock: the folder is free.
    std::fs::write(out.join(MARKER), "pid 999999999\n").unwrap();
    common::assert_success(&spherecontact(&["run", "case.toml", "--out", "out"], dir.path()));
}

#[test]
fn a_junit_file_the_harness_did_not_write_is_not_replaced_without_force() {
    let dir = workspace();
    std::fs::write(dir.path().join("notes.xml"), "<mine/>").unwrap();
    let verify = |extra: &[&str]| {
        let mut args = vec!["verify", "case.toml", "--junit", "notes.xml"];
        args.extend(extra);
        spherecontact(&args, dir.path())
    };
    assert_refused(&verify(&[]), &["--junit notes.xml", "did not write", "--force"]);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("notes.xml")).unwrap(),
        "<mine/>"
    );
    common::assert_success(&verify(&["--force"]));
    assert!(spherecontact::report::junit::is_ours(
        &std::fs::read(dir.path().join("notes.xml")).unwrap()
    ));
    common::assert_success(&verify(&[]));
    symlink(dir.path().join("notes.xml"), dir.path().join("link.xml")).unwrap();
    let linked = spherecontact(
        &["verify", "case.toml", "--junit", "link.xml", "--force"],
        dir.path(),
    );
    assert_refused(&linked, &["symbolic link"]);
}
