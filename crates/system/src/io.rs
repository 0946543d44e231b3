//! Writing outputs so that a reader never sees half a file, and never through a symbolic link:
//! write a temporary file beside the target, then rename it over the target, every folder on
//! the way opened without following links ([`nofollow`]). Claiming an output folder before any
//! work ([`claim`]): not a system folder, not a folder of someone else's files, not one another
//! run is writing. And checking, before any work, that an output file can be written at all.

mod claim;
mod nofollow;
mod system_folders;

pub use claim::{claim_file, ClaimError, OutputFolder, MARKER};

use std::path::Path;

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, flushed, then
/// renamed. On any error the target is left as it was. No component of `path` may be a
/// symbolic link, nor the name itself (an error): pass paths below a claimed [`OutputFolder`],
/// which are canonical.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    nofollow::write(path, bytes)
}

/// Creates the folder `dir` and its missing parents, as `std::fs::create_dir_all` does, but
/// never through a symbolic link (an error).
pub fn create_folder(dir: &Path) -> std::io::Result<()> {
    nofollow::open_folder(dir, true).map(drop)
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
    fn output_files_are_judged_without_writing() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("f");
        std::fs::write(&file, "").unwrap();
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
    fn links_on_the_way_or_at_the_name_are_refused_and_their_targets_untouched() {
        let dir = tempfile::tempdir().unwrap();
        let root = std::fs::canonicalize(dir.path()).unwrap();
        let (inside, outside) = (root.join("out"), root.join("elsewhere"));
        std::fs::create_dir_all(&inside).unwrap();
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::write(outside.join("target"), "theirs").unwrap();
        std::os::unix::fs::symlink(&outside, inside.join("figures")).unwrap();
        std::os::unix::fs::symlink(outside.join("target"), inside.join("mesh.geo")).unwrap();
        assert!(write_atomically(&inside.join("figures/a.svg"), b"x").is_err());
        assert!(create_folder(&inside.join("figures/deeper")).is_err());
        let error = write_atomically(&inside.join("mesh.geo"), b"x").unwrap_err();
        assert!(error.to_string().contains("symbolic link"), "{error}");
        assert_eq!(std::fs::read_to_string(outside.join("target")).unwrap(), "theirs");
        assert_eq!(
            std::fs::read_dir(&outside).unwrap().count(),
            1,
            "nothing written outside"
        );
        assert_eq!(
            std::fs::read_dir(&inside).unwrap().count(),
            2,
            "no temporary file left"
        );
    }

    #[test]
    fn folders_are_created_below_a_real_folder() {
        let dir = tempfile::tempdir().unwrap();
        let deep = std::fs::canonicalize(dir.path()).unwrap().join("a/b/c");
        create_folder(&deep).unwrap();
        create_folder(&deep).unwrap();
        write_atomically(&deep.join("f.csv"), b"1").unwrap();
        assert_eq!(std::fs::read_to_string(deep.join("f.csv")).unwrap(), "1");
    }

    #[test]
    fn a_missing_folder_is_an_error_not_a_partial_file() {
        let dir = tempfile::tempdir().unwrap();
        assert!(write_atomically(&dir.path().join("no/such/a.csv"), b"x").is_err());
    }
}
