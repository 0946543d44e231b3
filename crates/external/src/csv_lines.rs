//! The physical line of each record a CSV reader reads: 1-based, every line break counted, a
//! blank line and a CRLF line end alike. What a message names as a results file's line is the
//! line an editor shows.
//!
//! The csv crate's own `Position::line` is short of it: it is taken before the reader has passed
//! the line breaks in front of a record, so that a record after a CRLF line end (Python's csv
//! writes them: the dolfinx decks, a user's own law) or after a blank line is placed a line too
//! early. Its `Position::byte` is right: the start of that run of line breaks. So the bytes are
//! counted as the reader takes them ([`counted`]): the line of a record is one more than the
//! line feeds before its first byte past the run.
//!
//! Streamed: the breaks are kept only between the record last placed and the reader's read-ahead
//! (its buffer), so a file is never held whole, provided each record is placed
//! ([`Lines::of`]) as it is read.

use std::cell::RefCell;
use std::collections::VecDeque;
use std::io::Read;
use std::rc::Rc;

/// What the counting reader has seen and the lines placed so far.
#[derive(Default)]
struct State {
    /// Bytes read so far.
    read: u64,
    /// The line breaks (`\r`, `\n`) at or after the last record placed: offset and byte.
    breaks: VecDeque<(u64, u8)>,
    /// Line feeds before the first of `breaks`.
    feeds: u64,
    /// The line of the last record placed.
    line: u64,
}

/// A reader that notes the line breaks of what passes through it, for [`Lines`].
pub struct Counted<R> {
    inner: R,
    state: Rc<RefCell<State>>,
}

impl<R: Read> Read for Counted<R> {
    fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buffer)?;
        let mut state = self.state.borrow_mut();
        let start = state.read;
        for (k, &byte) in buffer[..n].iter().enumerate() {
            if byte == b'\n' || byte == b'\r' {
                state.breaks.push_back((start + k as u64, byte));
            }
        }
        state.read += n as u64;
        Ok(n)
    }
}

/// The lines of the records read through a [`Counted`] reader.
pub struct Lines {
    state: Rc<RefCell<State>>,
}

/// `input`, counted, and the [`Lines`] of what a CSV reader reads from it.
pub fn counted<R: Read>(input: R) -> (Counted<R>, Lines) {
    let state = Rc::new(RefCell::new(State {
        line: 1,
        ..State::default()
    }));
    (
        Counted {
            inner: input,
            state: Rc::clone(&state),
        },
        Lines { state },
    )
}

impl Lines {
    /// The 1-based line of the record at `position` (records are placed in the order read); the
    /// last line placed where the reader gives no position.
    pub fn of(&self, position: Option<&csv::Position>) -> u64 {
        let mut state = self.state.borrow_mut();
        let Some(position) = position else {
            return state.line;
        };
        let mut at = position.byte();
        // The breaks before the record's run of them, then the run itself.
        while let Some(&(offset, byte)) = state.breaks.front() {
            if offset > at {
                break;
            }
            if offset == at {
                at += 1;
            }
            state.feeds += u64::from(byte == b'\n');
            state.breaks.pop_front();
        }
        state.line = state.feeds + 1;
        state.line
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The line of every record of `text`, as placed by [`Lines`].
    fn lines_of(text: &str) -> Vec<u64> {
        let (input, lines) = counted(text.as_bytes());
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .from_reader(input);
        reader
            .records()
            .map(|r| lines.of(r.unwrap().position()))
            .collect()
    }

    /// Requirement: a record's line is the line an editor shows, counting every line break: LF
    /// and CRLF ends, blank lines (skipped by the reader, counted here), a quoted cell over two
    /// lines (the record's first line). Reference: the lines counted by hand.
    #[test]
    fn every_line_break_is_counted() {
        assert_eq!(lines_of("a,b\n1,2\n3,4\n"), [1, 2, 3]);
        assert_eq!(lines_of("a,b\r\n1,2\r\n3,4\r\n"), [1, 2, 3]);
        assert_eq!(lines_of("a,b\n\n1,2\n\n\n3,4"), [1, 3, 6]);
        assert_eq!(lines_of("a,b\r\n\r\n1,2\r\n\r\n\r\n3,4\r\n"), [1, 3, 6]);
        assert_eq!(lines_of("\na,b\n\"x\ny\",2\n3,4\n"), [2, 3, 5]);
    }

    /// Requirement: a long file is placed right far down (the reader refills its buffer many
    /// times), and only the breaks of the read-ahead are kept.
    #[test]
    fn a_long_file_is_counted_in_a_bounded_memory() {
        let mut text = String::from("step,value\r\n");
        for k in 1..5000 {
            text.push_str(&format!("{k},1.0\r\n"));
            if k % 7 == 0 {
                text.push_str("\r\n");
            }
        }
        let (input, lines) = counted(text.as_bytes());
        let mut reader = csv::ReaderBuilder::new().from_reader(input);
        let mut most = 0;
        for (k, record) in reader.records().enumerate() {
            let record = record.unwrap();
            let step = k as u64 + 1;
            // Step k is on line k + 1, after ⌊(k − 1)/7⌋ blank lines.
            assert_eq!(lines.of(record.position()), step + 1 + (step - 1) / 7);
            most = most.max(lines.state.borrow().breaks.len());
        }
        assert!(most < 4000, "{most} breaks kept");
    }
}
