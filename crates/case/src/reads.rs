//! The files a case may read: the files its own tree holds, and nothing else unless the command
//! line allows a folder (`--allow-read DIR`).
//!
//! A case names files that the harness reads while it loads the case (stored results, reference
//! values) or afterwards (`reproduce-paper`'s `../reference/paper.toml`). A case file may come
//! from anyone (a paper's supplement, a colleague), so a name it gives resolves only inside:
//!
//! - **the case file's folder**, and every folder below it;
//! - **the nearest `reference/` folder**: the `reference/` folder of the case file's folder or of
//!   its nearest ancestor that has one, where this repository keeps its stored values with their
//!   provenance (`cases/x.toml` names `../reference/hertz.toml`, `cases/hard/y.toml`
//!   `../../reference/limits.toml`). Only that folder, not its parent; and only a real folder, not a
//!   symbolic link (a case's folder could otherwise carry `reference -> /`);
//! - **the folders allowed on the command line** (`--allow-read DIR`, repeatable).
//!
//! A name is resolved to its canonical path (absolute, no `..`, every symbolic link followed)
//! before it is judged, so that neither `../..`, an absolute path nor a link that leads out
//! reaches a file outside these roots. The file must then be a regular file of bounded size,
//! checked on the opened file ([`spherecontact_system::input`]). See docs/security.md, "Files a case may read".

use std::path::{Path, PathBuf};

/// The folders that every case may read besides its own tree: those of `--allow-read`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ReadRoots {
    /// Canonical folders.
    allowed: Vec<PathBuf>,
}

/// A name that cannot be read: it leads out of the case's tree, or does not exist.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file is outside every folder the case may read.
    #[error(
        "`{name}` is outside the folders this case may read ({}; allowed: a file in the case's \
         folder or below it, or in the nearest `reference/` folder; `--allow-read DIR` allows \
         another folder)",
        shown(roots)
    )]
    Outside {
        /// The name as the case gives it.
        name: String,
        /// The folders it may read.
        roots: Vec<PathBuf>,
    },
    /// The name does not lead to an existing file.
    #[error("`{name}`: cannot read it: {source}")]
    Missing {
        /// The name as the case gives it.
        name: String,
        /// Why.
        source: std::io::Error,
    },
    /// A folder given to `--allow-read` is not an existing folder.
    #[error("--allow-read {}: {why} (allowed: an existing folder)", folder.display())]
    NotAFolder {
        /// The folder as given.
        folder: PathBuf,
        /// Why.
        why: String,
    },
}

fn shown(roots: &[PathBuf]) -> String {
    let roots: Vec<_> = roots.iter().map(|r| r.display().to_string()).collect();
    spherecontact_system::text::one_line(&roots.join(", ")).into_owned()
}

impl ReadRoots {
    /// The roots of `--allow-read`: each an existing folder, kept canonical.
    pub fn new(folders: &[PathBuf]) -> Result<Self, ReadError> {
        let allowed = folders
            .iter()
            .map(|folder| {
                let not_a_folder = |why: String| ReadError::NotAFolder {
                    folder: folder.clone(),
                    why,
                };
                let canonical = folder.canonicalize().map_err(|e| not_a_folder(e.to_string()))?;
                if canonical.is_dir() {
                    Ok(canonical)
                } else {
                    Err(not_a_folder("not a folder".into()))
                }
            })
            .collect::<Result<_, _>>()?;
        Ok(Self { allowed })
    }

    /// The folders of `--allow-read`, canonical (to give the same roots to another process).
    pub fn folders(&self) -> &[PathBuf] {
        &self.allowed
    }

    /// What the case file at `case_file` may read.
    pub fn tree(&self, case_file: &Path) -> CaseTree {
        let folder = match case_file.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let mut roots = Vec::new();
        if let Ok(own) = folder.canonicalize() {
            if let Some(reference) = own.ancestors().map(|a| a.join("reference")).find(|r| r.exists()) {
                if is_real_folder(&reference) {
                    roots.push(reference);
                }
            }
            roots.insert(0, own);
        }
        roots.extend(self.allowed.iter().cloned());
        CaseTree { folder, roots }
    }
}

/// True for a folder that is not reached through a symbolic link at its last component.
fn is_real_folder(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.is_dir())
}

/// The folders one case may read, and the folder its relative names start from.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseTree {
    /// The case file's folder as given: relative names are joined onto it.
    folder: PathBuf,
    /// The canonical folders whose files the case may read.
    roots: Vec<PathBuf>,
}

impl CaseTree {
    /// The canonical path of the file the case calls `name` (relative to the case file's
    /// folder, or absolute), if it lies inside one of the case's roots.
    pub fn resolve(&self, name: &str) -> Result<PathBuf, ReadError> {
        let path = self
            .folder
            .join(name)
            .canonicalize()
            .map_err(|source| ReadError::Missing {
                name: name.to_owned(),
                source,
            })?;
        if self.roots.iter().any(|root| path.starts_with(root)) {
            Ok(path)
        } else {
            Err(ReadError::Outside {
                name: name.to_owned(),
                roots: self.roots.clone(),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A project folder: `cases/sub/c.toml`, `reference/r.toml`, `secret` beside them.
    fn project() -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("cases/sub")).unwrap();
        std::fs::create_dir_all(dir.path().join("reference")).unwrap();
        for file in ["cases/sub/data.csv", "reference/r.toml", "secret"] {
            std::fs::write(dir.path().join(file), "x").unwrap();
        }
        dir
    }

    #[test]
    fn names_resolve_inside_the_case_folder_and_the_nearest_reference_folder() {
        let dir = project();
        let tree = ReadRoots::default().tree(&dir.path().join("cases/sub/c.toml"));
        assert!(tree.resolve("data.csv").is_ok());
        assert!(tree.resolve("../../reference/r.toml").is_ok());
        for outside in ["../../secret", "../../reference/../secret", "/etc/passwd"] {
            let e = tree.resolve(outside).unwrap_err();
            assert!(matches!(e, ReadError::Outside { .. }), "{outside}: {e}");
        }
        assert!(matches!(
            tree.resolve("nothing.csv"),
            Err(ReadError::Missing { .. })
        ));
    }

    #[cfg(unix)]
    #[test]
    fn links_that_lead_out_are_refused_and_allowed_roots_admit() {
        let dir = project();
        let case = dir.path().join("cases/sub/c.toml");
        std::os::unix::fs::symlink(dir.path().join("secret"), dir.path().join("cases/sub/link")).unwrap();
        let e = ReadRoots::default().tree(&case).resolve("link").unwrap_err();
        assert!(e.to_string().contains("--allow-read"), "{e}");
        let roots = ReadRoots::new(&[dir.path().to_path_buf()]).unwrap();
        assert!(roots.tree(&case).resolve("link").is_ok());
        assert!(ReadRoots::new(&[dir.path().join("secret")]).is_err());
    }

    #[cfg(unix)]
    #[test]
    fn a_reference_folder_that_is_a_link_is_no_root() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("case")).unwrap();
        std::os::unix::fs::symlink("/", dir.path().join("case/reference")).unwrap();
        let tree = ReadRoots::default().tree(&dir.path().join("case/c.toml"));
        assert!(tree.resolve("reference/etc/passwd").is_err());
    }
}
