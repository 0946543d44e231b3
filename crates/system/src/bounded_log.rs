//! A program's output stream kept in a log file of bounded size, never whole in memory.
//!
//! The file keeps the stream's first bytes (start-up, version, configuration) up to
//! [`MAX_PROGRAM_LOG_BYTES`] − [`PROGRAM_LOG_TAIL_BYTES`], then, when there was more, a line
//! saying how many bytes were dropped, then the stream's last [`PROGRAM_LOG_TAIL_BYTES`] (where a
//! failure shows). While the program runs the harness holds only that tail in memory; at the
//! end it reads back the log's first and last [`EXCERPT_BYTES`] for its messages and version
//! probes.

use std::collections::VecDeque;
use std::fs::File;
use std::io::{self, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use spherecontact_model::limits::{MAX_PROGRAM_LOG_BYTES, PROGRAM_LOG_TAIL_BYTES};

/// How much of the start and of the end of a log the harness reads back into memory [bytes].
pub const EXCERPT_BYTES: u64 = 64 << 10;

/// One output stream of a program, being written to its log.
pub struct BoundedLog {
    file: File,
    path: PathBuf,
    /// Bytes of the stream written to the file's head so far.
    head: u64,
    /// Bytes of the stream seen in all.
    total: u64,
    /// The last [`PROGRAM_LOG_TAIL_BYTES`] (at most) of what came after the head.
    last: VecDeque<u8>,
}

impl BoundedLog {
    /// A log written to a new file at `path`.
    pub fn create(path: &Path) -> io::Result<Self> {
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(true)
            .open(path)?;
        Ok(BoundedLog {
            file,
            path: path.to_path_buf(),
            head: 0,
            total: 0,
            last: VecDeque::new(),
        })
    }

    /// The head's capacity: the log's cap less the tail kept at the end.
    fn head_capacity() -> u64 {
        MAX_PROGRAM_LOG_BYTES - PROGRAM_LOG_TAIL_BYTES as u64
    }

    /// Takes the next bytes of the stream.
    pub fn write(&mut self, bytes: &[u8]) -> io::Result<()> {
        self.total += bytes.len() as u64;
        let to_head = (Self::head_capacity() - self.head).min(bytes.len() as u64) as usize;
        self.file.write_all(&bytes[..to_head])?;
        self.head += to_head as u64;
        let rest = &bytes[to_head..];
        let keep = &rest[rest.len().saturating_sub(PROGRAM_LOG_TAIL_BYTES)..];
        let overflow = (self.last.len() + keep.len()).saturating_sub(PROGRAM_LOG_TAIL_BYTES);
        self.last.drain(..overflow);
        self.last.extend(keep);
        Ok(())
    }

    /// Bytes of the stream that are in neither the file's head nor its tail.
    pub fn dropped(&self) -> u64 {
        self.total - self.head - self.last.len() as u64
    }

    /// Ends the log: the tail, after a line that counts what was dropped when anything was.
    /// Returns the log's text when short, else its first and last [`EXCERPT_BYTES`] around a
    /// line that names the log.
    pub fn finish(mut self) -> io::Result<String> {
        let dropped = self.dropped();
        if dropped > 0 {
            writeln!(
                self.file,
                "\n[spherecontact: {dropped} bytes of output dropped here: a program's log keeps its first {} \
                 and its last {} bytes (limits::MAX_PROGRAM_LOG_BYTES)]",
                Self::head_capacity(),
                PROGRAM_LOG_TAIL_BYTES
            )?;
        }
        let (front, back) = self.last.as_slices();
        self.file.write_all(front)?;
        self.file.write_all(back)?;
        self.file.flush()?;
        self.excerpt()
    }

    /// The log's first and last [`EXCERPT_BYTES`] (all of it when short), read back.
    fn excerpt(&mut self) -> io::Result<String> {
        let length = self.file.stream_position()?;
        let mut read_at = |offset: u64, bytes: u64| -> io::Result<Vec<u8>> {
            let mut buffer = Vec::new();
            self.file.seek(SeekFrom::Start(offset))?;
            (&mut self.file).take(bytes).read_to_end(&mut buffer)?;
            Ok(buffer)
        };
        if length <= 2 * EXCERPT_BYTES {
            return Ok(String::from_utf8_lossy(&read_at(0, length)?).into_owned());
        }
        let mut text = read_at(0, EXCERPT_BYTES)?;
        let skipped = length - 2 * EXCERPT_BYTES;
        text.extend_from_slice(
            format!(
                "\n[… {skipped} bytes not shown here; the whole log: {}]\n",
                self.path.display()
            )
            .as_bytes(),
        );
        text.extend(read_at(length - EXCERPT_BYTES, EXCERPT_BYTES)?);
        Ok(String::from_utf8_lossy(&text).into_owned())
    }
}
