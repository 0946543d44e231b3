//! The case files a command names: a file as given, a folder as every `.toml` under it.

use std::path::{Path, PathBuf};

/// A case folder that cannot be listed.
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot list cases: {error}", dir.display())]
pub struct ListError {
    /// The folder.
    pub dir: PathBuf,
    /// Why.
    pub error: std::io::Error,
}

/// The case files named: a file as given, a folder as every `.toml` under it, recursively, in
/// sorted order. Symbolic links to folders are not followed (a link to an ancestor would make
/// the walk endless).
pub fn case_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, ListError> {
    let mut files = Vec::new();
    for path in paths {
        if std::fs::symlink_metadata(path).is_ok_and(|m| m.is_dir()) {
            files.extend(toml_files(path)?);
        } else {
            files.push(path.clone());
        }
    }
    Ok(files)
}

/// Every `.toml` file under `dir`, recursively, sorted.
fn toml_files(dir: &Path) -> Result<Vec<PathBuf>, ListError> {
    let list = |error| ListError {
        dir: dir.to_path_buf(),
        error,
    };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(list)? {
        let entry = entry.map_err(list)?;
        let path = entry.path();
        if entry.file_type().map_err(list)?.is_dir() {
            files.extend(toml_files(&path)?);
        } else if path.extension().is_some_and(|e| e == "toml") {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}
