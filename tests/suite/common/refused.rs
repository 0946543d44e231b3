//! The refusal every bad case gets, asserted once: exit code 2, the words that locate and explain
//! it in stderr, and nothing written (docs/security.md: "nothing half-written").

use std::path::Path;
use std::process::Command;

/// What a refused command leaves at `--out`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Left {
    /// No folder at all (`run`, `reproduce-paper`: the case is read before the folder is made).
    Nothing,
    /// The folder claimed as the output and its hidden marker only (`verify` claims it first).
    Marker,
}

/// Runs `spherecontact <command…> <case> --out <a fresh folder>` (in the repository's root) and
/// asserts that it is refused before anything runs: exit code 2, every one of `parts` in stderr,
/// and at `--out` exactly what `left` says. Returns stderr.
pub fn assert_refused(command: &[&str], case: &Path, parts: &[&str], left: Left) -> String {
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
    match left {
        Left::Nothing => assert!(!out.exists(), "{case}: the output folder was made"),
        Left::Marker => {
            let written: Vec<_> = std::fs::read_dir(&out)
                .map(|d| d.flatten().map(|e| e.file_name()).collect())
                .unwrap_or_default();
            assert!(
                written.iter().all(|n| n.to_string_lossy().starts_with('.')),
                "{case}: written {written:?}"
            );
        }
    }
    stderr
}
