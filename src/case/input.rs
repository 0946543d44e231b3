//! Reading an input file (a case, a reference file, what a command solver wrote): a regular file
//! of bounded size.
//!
//! A FIFO, a device or a directory is refused without blocking on it (the file is opened
//! non-blocking and judged by its own metadata), and a file larger than
//! [`MAX_INPUT_BYTES`](crate::limits::MAX_INPUT_BYTES) is refused before it is read.

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

use crate::limits::MAX_INPUT_BYTES;

/// The text of the regular file at `path`, at most [`MAX_INPUT_BYTES`] long.
///
/// Errors are `io::Error`s whose message says what is allowed: a file that is not regular is
/// `InvalidInput`, one too large `FileTooLarge`, one not UTF-8 `InvalidData`.
pub fn read_text(path: &Path) -> io::Result<String> {
    let (file, length) = open_regular(path, MAX_INPUT_BYTES, Links::Follow)?;
    // The file may grow between the metadata and the read: read one byte past the limit.
    let mut bytes = Vec::with_capacity(length as usize);
    file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(too_large(bytes.len() as u64, MAX_INPUT_BYTES));
    }
    String::from_utf8(bytes).map_err(|e| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text: invalid byte at offset {}",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// Whether a symbolic link at the path itself is followed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Links {
    /// Followed (a case file may be a link).
    Follow,
    /// Refused (a file a program was to write in its own folder).
    Refuse,
}

/// Opens the regular file at `path`, at most `max_bytes` long, and returns it with its length.
/// A FIFO, device, socket or folder is refused without blocking on it (the file is opened
/// non-blocking and judged by its own metadata); with [`Links::Refuse`], so is a symbolic link.
pub fn open_regular(path: &Path, max_bytes: u64, links: Links) -> io::Result<(File, u64)> {
    let file = open_without_blocking(path, links).map_err(|e| {
        if links == Links::Refuse && e.raw_os_error() == Some(libc::ELOOP) {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                "a symbolic link (allowed: a regular file)",
            )
        } else {
            e
        }
    })?;
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "not a regular file ({}; allowed: a regular file of at most {})",
                kind(&meta.file_type()),
                size(max_bytes)
            ),
        ));
    }
    if meta.len() > max_bytes {
        return Err(too_large(meta.len(), max_bytes));
    }
    Ok((file, meta.len()))
}

/// The error of a file of `bytes` over `max_bytes`.
fn too_large(bytes: u64, max_bytes: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::FileTooLarge,
        format!("{bytes} bytes (allowed: at most {})", size(max_bytes)),
    )
}

/// Opens `path` for reading; on Unix without blocking, so that opening a FIFO with no writer
/// returns at once (reads of a regular file never block anyway).
fn open_without_blocking(path: &Path, links: Links) -> io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        let no_follow = if links == Links::Refuse {
            libc::O_NOFOLLOW
        } else {
            0
        };
        options.custom_flags(libc::O_NONBLOCK | no_follow);
    }
    options.open(path)
}

/// What kind of file this is, in words.
fn kind(file_type: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO";
        }
        if file_type.is_socket() {
            return "a socket";
        }
        if file_type.is_char_device() || file_type.is_block_device() {
            return "a device";
        }
    }
    if file_type.is_dir() {
        "a directory"
    } else {
        "not a file"
    }
}

/// `bytes` in MiB (or bytes, below one), as a limit is written.
fn size(bytes: u64) -> String {
    if bytes >= 1 << 20 {
        format!("{} MiB", bytes >> 20)
    } else {
        format!("{bytes} bytes")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_small_file_and_refuses_a_directory_and_a_large_file() {
        let dir = tempfile::tempdir().unwrap();
        let small = dir.path().join("a.toml");
        std::fs::write(&small, "x = 1\n").unwrap();
        assert_eq!(read_text(&small).unwrap(), "x = 1\n");
        let e = read_text(dir.path()).unwrap_err();
        assert!(e.to_string().contains("a directory"), "{e}");
        let large = dir.path().join("b.toml");
        std::fs::write(&large, vec![b'#'; MAX_INPUT_BYTES as usize + 1]).unwrap();
        let e = read_text(&large).unwrap_err();
        assert!(e.to_string().contains("at most 4 MiB"), "{e}");
    }

    #[test]
    fn refuses_bytes_that_are_not_utf8() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.toml");
        std::fs::write(&file, b"x = \"\xff\"").unwrap();
        assert!(read_text(&file).unwrap_err().to_string().contains("offset 5"));
    }

    #[cfg(unix)]
    #[test]
    fn refuses_a_device_without_reading_it() {
        let e = read_text(Path::new("/dev/zero")).unwrap_err();
        assert!(e.to_string().contains("a device"), "{e}");
    }
}
