//! Claiming an output destination before any work: the folder is canonicalised (links and `..`
//! resolved), refused when it is a system folder, refused when it already holds files that the
//! harness did not write (unless forced) or holds a symbolic link, then marked as the harness's
//! and locked for as long as the process lives.
//!
//! The marker file [`MARKER`] names a folder as the harness's: a non-empty folder without it is
//! foreign. The same file carries the lock, an exclusive `flock` that the kernel releases when
//! the process ends however it ends, so a crashed run never blocks a later one; a second run
//! into a folder in use is refused with the holder's pid, which the marker records.

use std::fs::File;
use std::io::{ErrorKind, Read, Write};
use std::os::fd::OwnedFd;
use std::path::{Path, PathBuf};

use rustix::fs::{FileType, FlockOperation, Mode, OFlags};
use rustix::io::Errno;

use crate::{io::nofollow, io::system_folders};

/// The marker (and lock) file of an output folder.
pub const MARKER: &str = ".spherecontact-output";

/// The most of an existing file read to recognise it as the harness's (a marker's pid, a JUnit
/// file's opening lines).
const HEAD_BYTES: u64 = 512;

/// Why an output destination is refused.
#[derive(Debug, thiserror::Error)]
pub enum ClaimError {
    /// A system folder, or one shared by every user.
    #[error("refused: {0}")]
    System(String),
    /// A folder holding files the harness did not write.
    #[error(
        "refused: the folder holds files spherecontact did not write (`{example}`, and no {MARKER}), which \
         would be replaced (choose another folder, or pass --force to write there anyway)"
    )]
    Foreign {
        /// One of its entries.
        example: String,
    },
    /// An existing file the harness did not write.
    #[error(
        "refused: an existing file that spherecontact did not write, which would be replaced (choose \
         another name, or pass --force to replace it)"
    )]
    ForeignFile,
    /// A folder another run holds.
    #[error(
        "refused: the folder is in use by another spherecontact run{} (wait for it to end, or choose \
         another folder: two runs would mix their files)",
        pid.map(|p| format!(" (pid {p})")).unwrap_or_default()
    )]
    InUse {
        /// The other process, when the marker names it.
        pid: Option<u32>,
    },
    /// A symbolic link inside the folder.
    #[error(
        "refused: `{}` is a symbolic link (outputs are never written through links: remove it, or choose \
         another folder)",
        .0.display()
    )]
    Link(PathBuf),
    /// Not a folder, or not a file.
    #[error("refused: {0}")]
    Kind(&'static str),
    /// The file system's own error.
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// An output folder claimed for this process: canonical, marked, locked until dropped (or the
/// process ends).
#[derive(Debug)]
pub struct OutputFolder {
    path: PathBuf,
    _lock: File,
}

impl OutputFolder {
    /// Claims `dir` (created if missing) as this run's output folder; `force` accepts a folder
    /// holding files the harness did not write (and marks it as the harness's). Nothing is
    /// written when it is refused.
    pub fn claim(dir: &Path, force: bool) -> Result<OutputFolder, ClaimError> {
        Self::claim_recognising(dir, force, |_| false)
    }

    /// [`OutputFolder::claim`], a folder without the marker also taken for the harness's when
    /// every entry in it is a file that `is_ours` recognises (the baselines' folder of a
    /// repository, whose marker is not committed: every file in it a baseline the harness wrote).
    pub fn claim_recognising(
        dir: &Path,
        force: bool,
        is_ours: impl Fn(&Path) -> bool,
    ) -> Result<OutputFolder, ClaimError> {
        let path = resolve(dir)?;
        refuse_system_folder(&path)?;
        match std::fs::symlink_metadata(&path) {
            Ok(meta) if meta.is_dir() => check_existing(&path, force, &is_ours)?,
            Ok(_) => return Err(ClaimError::Kind("not a folder")),
            Err(e) if e.kind() == ErrorKind::NotFound => {}
            Err(e) => return Err(e.into()),
        }
        let folder = nofollow::open_folder(&path, true)?;
        let lock = lock_marker(&folder)?;
        Ok(OutputFolder { path, _lock: lock })
    }

    /// The folder's canonical path: every output is written below it.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// Checks, writing nothing, that `file` may be written (atomically) by the harness: its folder
/// exists and is neither `/` nor in a system tree (a shared folder such as `/tmp` is fine), the
/// name is no folder nor link, and an existing file is one that `is_ours` recognises from its
/// first bytes, unless `force`. The canonical path.
pub fn claim_file(file: &Path, force: bool, is_ours: impl Fn(&[u8]) -> bool) -> Result<PathBuf, ClaimError> {
    super::check_output_file(file)?;
    let name = file.file_name().ok_or(ClaimError::Kind("not a file name"))?;
    let folder = std::fs::canonicalize(super::folder_or_here(file.parent().unwrap_or(Path::new(""))))?;
    if let Some(why) = system_folders::file_refusal(&folder) {
        return Err(ClaimError::System(why));
    }
    let path = folder.join(name);
    match std::fs::symlink_metadata(&path) {
        Ok(meta) if meta.file_type().is_symlink() => Err(ClaimError::Link(path)),
        Ok(meta) if !meta.is_file() => Err(ClaimError::Kind("not a regular file")),
        Ok(_) if !force && !is_ours(&head(File::open(&path)?)?) => Err(ClaimError::ForeignFile),
        Ok(_) => Ok(path),
        Err(e) if e.kind() == ErrorKind::NotFound => Ok(path),
        Err(e) => Err(e.into()),
    }
}

/// `dir` made absolute and canonical: its nearest existing ancestor canonicalised (links and
/// `..` resolved), the missing folders below it appended as they are named.
fn resolve(dir: &Path) -> Result<PathBuf, ClaimError> {
    let mut existing = super::folder_or_here(dir).to_path_buf();
    let mut missing = Vec::new();
    loop {
        match std::fs::canonicalize(&existing) {
            Ok(canonical) => return Ok(missing.iter().rev().fold(canonical, |p, name| p.join(name))),
            Err(e) if e.kind() == ErrorKind::NotFound => {
                if existing.symlink_metadata().is_ok() {
                    return Err(ClaimError::Link(existing));
                }
                let name = existing
                    .file_name()
                    .ok_or(ClaimError::Kind("`..` below a folder that does not exist"))?;
                missing.push(name.to_owned());
                existing.pop();
                existing = super::folder_or_here(&existing).to_path_buf();
            }
            Err(e) if e.kind() == ErrorKind::NotADirectory => return Err(ClaimError::Kind("not a folder")),
            Err(e) => return Err(e.into()),
        }
    }
}

/// An error when the canonical `dir` is a system folder or the user's home folder.
fn refuse_system_folder(dir: &Path) -> Result<(), ClaimError> {
    let home = std::env::var_os("HOME").and_then(|h| std::fs::canonicalize(h).ok());
    match system_folders::refusal(dir, home.as_deref()) {
        Some(why) => Err(ClaimError::System(why)),
        None => Ok(()),
    }
}

/// Checks an existing folder: no link anywhere in it, and the marker present (or `force`) when
/// it holds an entry that `is_ours` does not recognise.
fn check_existing(dir: &Path, force: bool, is_ours: &dyn Fn(&Path) -> bool) -> Result<(), ClaimError> {
    if let Some(link) = find_link(dir)? {
        return Err(ClaimError::Link(link));
    }
    if force || dir.join(MARKER).symlink_metadata().is_ok() {
        return Ok(());
    }
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        if !is_ours(&entry.path()) {
            return Err(ClaimError::Foreign {
                example: crate::text::one_line(&entry.file_name().to_string_lossy()).into_owned(),
            });
        }
    }
    Ok(())
}

/// The first symbolic link found in the tree under `dir` (links are not followed).
fn find_link(dir: &Path) -> std::io::Result<Option<PathBuf>> {
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder)? {
            let entry = entry?;
            let kind = entry.file_type()?;
            if kind.is_symlink() {
                return Ok(Some(entry.path()));
            }
            if kind.is_dir() {
                folders.push(entry.path());
            }
        }
    }
    Ok(None)
}

/// Creates (or opens) the marker in `folder`, takes its lock and records this process's pid.
fn lock_marker(folder: &OwnedFd) -> Result<File, ClaimError> {
    let flags = OFlags::RDWR | OFlags::CREATE | OFlags::NOFOLLOW | OFlags::NONBLOCK | OFlags::CLOEXEC;
    let fd = rustix::fs::openat(folder, MARKER, flags, Mode::from_raw_mode(0o644)).map_err(|e| match e {
        Errno::LOOP => ClaimError::Link(PathBuf::from(MARKER)),
        e => ClaimError::Io(e.into()),
    })?;
    if FileType::from_raw_mode(rustix::fs::fstat(&fd).map_err(std::io::Error::from)?.st_mode)
        != FileType::RegularFile
    {
        return Err(ClaimError::Kind("its marker is not a regular file"));
    }
    let mut file = File::from(fd);
    match rustix::fs::flock(&file, FlockOperation::NonBlockingLockExclusive) {
        Ok(()) => {}
        Err(Errno::WOULDBLOCK) => {
            return Err(ClaimError::InUse {
                pid: holder(&mut file),
            })
        }
        Err(e) => return Err(ClaimError::Io(e.into())),
    }
    file.set_len(0)?;
    write!(
        file,
        "spherecontact output folder: the files here were written by spherecontact, which may replace them.\n\
         pid {}\n",
        std::process::id()
    )?;
    Ok(file)
}

/// The pid the marker records, if it records one.
fn holder(marker: &mut File) -> Option<u32> {
    let text = String::from_utf8(head(marker).ok()?).ok()?;
    text.lines()
        .find_map(|l| l.strip_prefix("pid ")?.trim().parse().ok())
}

/// The first bytes of `file`.
fn head(file: impl Read) -> std::io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    file.take(HEAD_BYTES).read_to_end(&mut bytes)?;
    Ok(bytes)
}
