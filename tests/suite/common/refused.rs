//! The refusal every bad case gets, asserted once: exit code 2, the words that locate and explain
//! it in stderr, and nothing written (docs/security.md: "nothing half-written").

use std::path::Path;
use std::process::Command;

/// Runs `spherecontact <command…> <case> --out <a fresh folder>` (in the repository's root) and asserts that it is refused
/// before anything runs: exit code 2, every one of `parts` in stderr, and no result in the output
/// folder (at most the hidden marker of a folder claimed as the output). Returns stderr.
pub fn assert_refused(command: &[&str], case: &Path, parts: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let run = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(command)
        .arg(case)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
    let case = case.display();
    assert_eq!(run.status.code(), Some(2), "{case}: {stderr}");
    for part in parts {
        assert!(stderr.contains(part), "{case}: `{part}` missing in: {stderr}");
    }
    let written: Vec<_> = std::fs::read_dir(&out)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(
        written.iter().all(|n| n.to_string_lossy().starts_with('.')),
        "{case}: written {written:?}"
    );
    stderr
}
