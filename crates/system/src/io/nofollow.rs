//! Folders opened and files written without following a symbolic link anywhere on the way.
//!
//! A path is walked one component at a time from `/` (or the working folder for a relative
//! path), each folder opened relative to the one before with `O_NOFOLLOW | O_DIRECTORY`; the
//! file is then created, written and renamed relative to the last folder's descriptor. A link
//! put in place at any moment, before or during the walk, makes the walk fail rather than lead
//! it elsewhere: no write ever goes through a link. Callers therefore hand in paths free of
//! links, such as an output folder canonicalised when it was claimed ([`super::claim`]).

use std::ffi::OsStr;
use std::fs::File;
use std::io::Write;
use std::os::fd::{AsFd, OwnedFd};
use std::path::{Component, Path};
use std::sync::atomic::{AtomicU64, Ordering};

use rustix::fs::{AtFlags, FileType, Mode, OFlags};
use rustix::io::Errno;

/// How each folder on the way is opened: for its name only where the system allows (`O_PATH`
/// needs search permission alone, as a path lookup does), never through a link.
#[cfg(any(target_os = "linux", target_os = "android"))]
const FOLDER: OFlags = OFlags::PATH
    .union(OFlags::DIRECTORY)
    .union(OFlags::NOFOLLOW)
    .union(OFlags::CLOEXEC);
#[cfg(not(any(target_os = "linux", target_os = "android")))]
const FOLDER: OFlags = OFlags::RDONLY
    .union(OFlags::DIRECTORY)
    .union(OFlags::NOFOLLOW)
    .union(OFlags::CLOEXEC);

/// Distinguishes the temporary files of one process.
static TEMPORARY: AtomicU64 = AtomicU64::new(0);

/// Opens the folder `dir` without following a link on the way; with `create`, the missing
/// folders are created (mode 0755 before the umask) as `create_dir_all` would.
pub(super) fn open_folder(dir: &Path, create: bool) -> std::io::Result<OwnedFd> {
    let start = if dir.is_absolute() { "/" } else { "." };
    let mut fd = rustix::fs::openat(rustix::fs::CWD, start, FOLDER, Mode::empty())?;
    for component in dir.components() {
        let name = match component {
            Component::Normal(name) => name,
            Component::RootDir | Component::CurDir => continue,
            Component::ParentDir | Component::Prefix(_) => {
                return Err(refused(dir, "`..` in an output path (allowed: a canonical path)"))
            }
        };
        fd = match rustix::fs::openat(&fd, name, FOLDER, Mode::empty()) {
            Err(Errno::NOENT) if create => {
                match rustix::fs::mkdirat(&fd, name, Mode::from_raw_mode(0o755)) {
                    Ok(()) | Err(Errno::EXIST) => {}
                    Err(e) => return Err(e.into()),
                }
                rustix::fs::openat(&fd, name, FOLDER, Mode::empty())
            }
            other => other,
        }
        .map_err(|e| explain(&fd, name, dir, e))?;
    }
    Ok(fd)
}

/// Writes `bytes` to `path` atomically and without following links: a temporary file in the
/// same folder (created exclusively, never through a link), flushed, then renamed over the
/// name. A link at the name itself is refused, not replaced; on any error the target is left
/// as it was and the temporary file removed.
pub(super) fn write(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let (folder, name) = split(path)?;
    let dir = open_folder(folder, false)?;
    refuse_link_at(&dir, name, path)?;
    let (temporary, file) = create_temporary(&dir, name)?;
    let written = fill(file, bytes).and_then(|()| Ok(rustix::fs::renameat(&dir, &temporary, &dir, name)?));
    if written.is_err() {
        let _ = rustix::fs::unlinkat(&dir, &temporary, AtFlags::empty());
    }
    written
}

/// The folder and the file name of `path`.
fn split(path: &Path) -> std::io::Result<(&Path, &OsStr)> {
    let Some(Component::Normal(name)) = path.components().next_back() else {
        return Err(refused(path, "not a file name"));
    };
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    Ok((folder, name))
}

/// An error when `name` in `dir` is a symbolic link.
fn refuse_link_at(dir: &OwnedFd, name: &OsStr, path: &Path) -> std::io::Result<()> {
    match rustix::fs::statat(dir, name, AtFlags::SYMLINK_NOFOLLOW) {
        Ok(stat) if FileType::from_raw_mode(stat.st_mode) == FileType::Symlink => Err(refused(
            path,
            "a symbolic link (outputs are never written through links)",
        )),
        _ => Ok(()),
    }
}

/// A new temporary file beside `name` in `dir`: its name and the open file (mode 0644).
fn create_temporary(dir: &OwnedFd, name: &OsStr) -> std::io::Result<(String, File)> {
    let flags = OFlags::WRONLY | OFlags::CREATE | OFlags::EXCL | OFlags::NOFOLLOW | OFlags::CLOEXEC;
    loop {
        let n = TEMPORARY.fetch_add(1, Ordering::Relaxed);
        let temporary = format!(".{}.{}-{n}.tmp", name.to_string_lossy(), std::process::id());
        match rustix::fs::openat(dir, temporary.as_str(), flags, Mode::from_raw_mode(0o600)) {
            Ok(fd) => {
                // An output is an ordinary file, whatever the umask.
                rustix::fs::fchmod(&fd, Mode::from_raw_mode(0o644))?;
                return Ok((temporary, File::from(fd)));
            }
            Err(Errno::EXIST) => continue,
            Err(e) => return Err(e.into()),
        }
    }
}

/// Writes `bytes` into `file` and flushes them to the disk.
fn fill(mut file: File, bytes: &[u8]) -> std::io::Result<()> {
    file.write_all(bytes)?;
    file.sync_all()
}

/// The error of opening `name` in `dir` on the way to `path`, in words when a link is the cause.
fn explain(dir: &impl AsFd, name: &OsStr, path: &Path, e: Errno) -> std::io::Error {
    let link = rustix::fs::statat(dir, name, AtFlags::SYMLINK_NOFOLLOW)
        .is_ok_and(|s| FileType::from_raw_mode(s.st_mode) == FileType::Symlink);
    if link {
        refused(
            path,
            &format!(
                "`{}` on the way is a symbolic link (outputs are never written through links)",
                name.to_string_lossy()
            ),
        )
    } else {
        e.into()
    }
}

fn refused(path: &Path, why: &str) -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!("{}: refused: {why}", path.display()),
    )
}
