//! Standard output for the commands' tables and JSON.
//!
//! `println!` panics when standard output is a closed pipe (`vbi run | head`). A reader that has
//! closed the pipe has what it wanted, so [`outln!`] drops the rest of the text instead and the
//! command goes on (its `--out` files are still written whole). Any other write error is said once
//! on standard error.

use std::fmt;
use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether a write error other than a closed pipe was already reported.
static REPORTED: AtomicBool = AtomicBool::new(false);

/// Writes one line on standard output; see the module comment for errors.
pub fn write_line(text: fmt::Arguments<'_>) {
    let mut out = std::io::stdout().lock();
    if let Err(error) = writeln!(out, "{text}") {
        report(&error);
    }
}

/// Says a write error on standard error, once, unless it is a closed pipe.
pub fn report(error: &std::io::Error) {
    if error.kind() != ErrorKind::BrokenPipe && !REPORTED.swap(true, Ordering::Relaxed) {
        eprintln!("warning: writing to standard output failed: {error}");
    }
}

/// `println!` that neither panics nor fails on a closed pipe.
macro_rules! outln {
    () => {
        $crate::console::write_line(format_args!(""))
    };
    ($($argument:tt)*) => {
        $crate::console::write_line(format_args!($($argument)*))
    };
}
pub(crate) use outln;
