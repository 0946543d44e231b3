//! Reading an input file (a case, a reference file): a regular file of bounded size, as text.
//!
//! A FIFO, a device or a directory is refused without blocking on it (the file is opened
//! non-blocking and judged by its own metadata), and a file larger than
//! [`MAX_INPUT_BYTES`](spherecontact_model::limits::MAX_INPUT_BYTES) is refused before it is read. The same
//! opening ([`open_regular`]) serves every file a case names (stored results, with their own
//! limit), and [`foreign`] reads by one rule the files that come from elsewhere (baselines, run
//! files, deck folders).

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

use spherecontact_model::limits::MAX_INPUT_BYTES;

pub mod foreign;

/// The text of the regular file at `path`, at most [`MAX_INPUT_BYTES`] long.
///
/// Errors are `io::Error`s whose message says what is allowed: a file that is not regular is
/// `InvalidInput`, one too large `FileTooLarge`, one not UTF-8 `InvalidData`.
pub fn read_text(path: &Path) -> io::Result<String> {
    let file = open_regular(path, MAX_INPUT_BYTES, Links::Follow)?;
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)?;
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
    /// Followed (a case file may be a link; a name a case gives is resolved before it is opened).
    Follow,
    /// Refused (a file a program was to write in its own folder).
    Refuse,
}

/// The regular file at `path`, opened without blocking and judged by the opened file's own
/// metadata: refused if it is not a regular file (a FIFO, a device, a folder; with
/// [`Links::Refuse`] a symbolic link) or is longer than `limit` bytes; its reads fail
/// (`FileTooLarge`) past `limit` if it grows while it is read.
pub fn open_regular(path: &Path, limit: u64, links: Links) -> io::Result<Bounded> {
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
                size(limit)
            ),
        ));
    }
    if meta.len() > limit {
        return Err(too_large(meta.len(), limit));
    }
    Ok(Bounded { file, limit, read: 0 })
}

/// A file whose reads fail once more than its limit has been read.
#[derive(Debug)]
pub struct Bounded {
    file: File,
    limit: u64,
    read: u64,
}

impl Bounded {
    /// Reads the whole file into `bytes` (at most the limit).
    pub fn read_to_end(mut self, bytes: &mut Vec<u8>) -> io::Result<usize> {
        bytes.reserve(self.file.metadata().map_or(0, |m| m.len().min(self.limit)) as usize);
        Read::read_to_end(&mut self, bytes)
    }
}

impl Read for Bounded {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        // One byte past the limit is read, to tell a file at the limit from a longer one.
        let room = (self.limit + 1 - self.read).min(buf.len() as u64) as usize;
        let n = self.file.read(&mut buf[..room])?;
        self.read += n as u64;
        if self.read > self.limit {
            return Err(too_large(self.read, self.limit));
        }
        Ok(n)
    }
}

fn too_large(bytes: u64, limit: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::FileTooLarge,
        format!("{} (allowed: at most {})", size(bytes), size(limit)),
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

/// The 1-based line and column of byte `offset` in `text`.
pub fn line_and_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
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

/// A size in bytes as a limit is written: whole MiB when it is one, else bytes.
fn size(bytes: u64) -> String {
    if bytes >= 1 << 20 && bytes.is_multiple_of(1 << 20) {
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

    #[test]
    fn a_file_that_grows_past_the_limit_while_read_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.csv");
        std::fs::write(&file, "12345").unwrap();
        let opened = open_regular(&file, 8, Links::Follow).unwrap();
        std::fs::write(&file, "123456789").unwrap();
        let e = opened.read_to_end(&mut Vec::new()).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::FileTooLarge, "{e}");
        let mut bytes = Vec::new();
        std::fs::write(&file, "12345678").unwrap();
        open_regular(&file, 8, Links::Follow)
            .unwrap()
            .read_to_end(&mut bytes)
            .unwrap();
        assert_eq!(bytes.len(), 8, "a file at the limit is read whole");
    }

    #[cfg(unix)]
    #[test]
    fn refuses_a_device_without_reading_it() {
        let e = read_text(Path::new("/dev/zero")).unwrap_err();
        assert!(e.to_string().contains("a device"), "{e}");
    }
}
