//! Everything the binary prints to standard output goes through [`print`] (the macros `out!` and
//! `outln!`, in place of `print!` and `println!`): when the reader has gone (`spherecontact list
//! | head -1`, a pager quit early) printing stops quietly, as ripgrep's does, never a panic
//! ("failed printing to stdout: Broken pipe"). The command itself goes on to its end and its exit
//! code, so that what it writes to files (a report, a run file, JUnit) is never left half-written.
//! Another write error (a full disk under `>`) is said once on standard error and printing stops.

use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once standard output cannot be written: nothing more is printed.
static CLOSED: AtomicBool = AtomicBool::new(false);

/// Prints `text` to standard output and flushes it, unless standard output was found closed.
pub fn print(text: std::fmt::Arguments) {
    if CLOSED.load(Ordering::Relaxed) {
        return;
    }
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_fmt(text).and_then(|()| out.flush()) {
        CLOSED.store(true, Ordering::Relaxed);
        if e.kind() != ErrorKind::BrokenPipe {
            eprintln!("error: writing to standard output: {e} (nothing more is printed there)");
        }
    }
}

/// `print!` through [`print`].
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::stdout::print(format_args!($($arg)*))
    };
}

/// `println!` through [`print`].
macro_rules! outln {
    () => {
        $crate::stdout::print(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::stdout::print(format_args!("{}\n", format_args!($($arg)*)))
    };
}
