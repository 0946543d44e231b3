//! Writing outputs so that a reader never sees half a file: write a temporary file beside the
//! target, then rename it over the target. And checking, before any work, that an output
//! destination can be written at all.

use std::io::{ErrorKind, Write};
use std::path::Path;

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, flushed, then
/// renamed. On any error the target is left as it was.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut file = tempfile::NamedTempFile::new_in(folder)?;
    // A temporary file is private (0600); an output is an ordinary file (0644).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        file.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    file.write_all(bytes)?;
    file.as_file().sync_all()?;
    file.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// Checks, writing nothing, that `dir` is a folder that outputs can be written into, or can be
/// created: it is a folder, or its nearest existing ancestor is; and that one is writable.
///
/// Commands check their output destinations this way before any solver runs, so that a bad
/// `--out` is bad input (exit 2) and not a failure after minutes of work.
pub fn check_output_folder(dir: &Path) -> std::io::Result<()> {
    let mut existing = dir;
    loop {
        match std::fs::metadata(folder_or_here(existing)) {
            Ok(meta) if meta.is_dir() => return check_writable(folder_or_here(existing)),
            Ok(_) => return Err(invalid(format!("{} is not a folder", existing.display()))),
            Err(e) if matches!(e.kind(), ErrorKind::NotFound | ErrorKind::NotADirectory) => {
                existing = existing
                    .parent()
                    .ok_or_else(|| invalid(format!("no existing folder above {}", dir.display())))?;
            }
            Err(e) => return Err(e),
        }
    }
}

/// Checks, writing nothing, that `file` can be written atomically: it is not a folder, and its
/// folder exists and is writable.
pub fn check_output_file(file: &Path) -> std::io::Result<()> {
    if file.is_dir() {
        return Err(invalid(format!(
            "{} is a folder (allowed: a file)",
            file.display()
        )));
    }
    let folder = folder_or_here(file.parent().unwrap_or(Path::new("")));
    if !folder.is_dir() {
        return Err(invalid(format!(
            "its folder {} does not exist (allowed: a file in an existing folder)",
            folder.display()
        )));
    }
    check_writable(folder)
}

/// `path`, or `.` for the empty path (the parent of a bare file name).
fn folder_or_here(path: &Path) -> &Path {
    if path.as_os_str().is_empty() {
        Path::new(".")
    } else {
        path
    }
}

fn invalid(message: String) -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::InvalidInput, message)
}

/// Whether this process may create entries in `folder`.
fn check_writable(folder: &Path) -> std::io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        let c_path = std::ffi::CString::new(folder.as_os_str().as_bytes())
            .map_err(|_| invalid(format!("{} contains a NUL byte", folder.display())))?;
        // SAFETY: a valid NUL-terminated path; access(2) only reads it.
        if unsafe { libc::access(c_path.as_ptr(), libc::W_OK | libc::X_OK) } != 0 {
            return Err(std::io::Error::last_os_error());
        }
    }
    #[cfg(not(unix))]
    let _ = folder;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_folders_are_judged_without_writing() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("f");
        std::fs::write(&file, "").unwrap();
        assert!(check_output_folder(dir.path()).is_ok());
        assert!(check_output_folder(&dir.path().join("new/deeper")).is_ok());
        assert!(check_output_folder(&file).is_err());
        assert!(check_output_folder(&file.join("below")).is_err());
        assert!(check_output_file(&dir.path().join("v.xml")).is_ok());
        assert!(check_output_file(dir.path()).is_err());
        assert!(check_output_file(&dir.path().join("no/v.xml")).is_err());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "nothing written"
        );
    }

    #[test]
    fn replaces_the_target_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("a.csv");
        write_atomically(&target, b"one").unwrap();
        write_atomically(&target, b"two").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "two");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_missing_folder_is_an_error_not_a_partial_file() {
        let dir = tempfile::tempdir().unwrap();
        assert!(write_atomically(&dir.path().join("no/such/a.csv"), b"x").is_err());
    }
}
