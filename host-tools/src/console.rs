//! Standard output and standard error that never panic.
//!
//! `println!` panics when stdout is a closed pipe (`host-tools demo | head -1`) or a full device,
//! and `eprintln!` likewise for stderr. [`outln!`](crate::outln) writes to a locked stdout
//! instead: a closed pipe ends the printing quietly (the work goes on and the command exits 0, as
//! the reader has gone), any other failure is an error for the `error:` line.
//! [`errln!`](crate::errln) writes to stderr and ignores failures: there is nowhere left to report
//! them.

use std::fmt;
use std::io::{self, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once stdout's reader has gone; later output is dropped.
static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);

/// Standard output could not be written (other than a closed pipe).
#[derive(Debug)]
pub struct StdoutError(pub io::Error);

impl fmt::Display for StdoutError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write to standard output: {}", self.0)
    }
}

impl std::error::Error for StdoutError {}

/// Writes to stdout and flushes; a closed pipe is not an error. Use [`outln!`](crate::outln).
///
/// # Errors
/// [`StdoutError`] for any other write failure (e.g. a full device).
pub fn out(args: fmt::Arguments<'_>) -> Result<(), StdoutError> {
    if STDOUT_CLOSED.load(Ordering::Relaxed) {
        return Ok(());
    }
    let mut lock = io::stdout().lock();
    match lock.write_fmt(args).and_then(|()| lock.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
            STDOUT_CLOSED.store(true, Ordering::Relaxed);
            Ok(())
        }
        Err(e) => Err(StdoutError(e)),
    }
}

/// Standard output as a writer for data (an image written to `-o -`). Once its reader has gone
/// (a closed pipe) the rest is dropped and the command carries on, as [`out`] does for messages:
/// both share one flag, so neither writes on after the other has found the pipe closed.
pub struct Stdout;

impl Stdout {
    /// `r`, with a closed pipe taken as success (`none`) and remembered.
    fn closed<T>(r: io::Result<T>, none: T) -> io::Result<T> {
        match r {
            Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
                STDOUT_CLOSED.store(true, Ordering::Relaxed);
                Ok(none)
            }
            r => r,
        }
    }
}

impl Write for Stdout {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if STDOUT_CLOSED.load(Ordering::Relaxed) {
            return Ok(buf.len());
        }
        Self::closed(io::stdout().lock().write(buf), buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        if STDOUT_CLOSED.load(Ordering::Relaxed) {
            return Ok(());
        }
        Self::closed(io::stdout().lock().flush(), ())
    }
}

/// Writes to stderr, ignoring failures. Use [`errln!`](crate::errln).
pub fn err(args: fmt::Arguments<'_>) {
    let mut lock = io::stderr().lock();
    let _ = lock.write_fmt(args).and_then(|()| lock.flush());
}

/// A message about the work: to stdout, or to stderr when stdout carries the command's data
/// (`-o -`), where a message would corrupt it. Use [`sayln!`](crate::sayln).
///
/// # Errors
/// As [`out`].
pub fn say(data_on_stdout: bool, args: fmt::Arguments<'_>) -> Result<(), StdoutError> {
    if data_on_stdout {
        err(args);
        Ok(())
    } else {
        out(args)
    }
}

/// `outln!` that goes to stderr when the first argument is true (see [`say`]).
#[macro_export]
macro_rules! sayln {
    ($data_on_stdout:expr, $($arg:tt)*) => {
        $crate::console::say($data_on_stdout, format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `println!` that returns `Result<(), StdoutError>` instead of panicking.
#[macro_export]
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::console::out(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `eprintln!` that never panics.
#[macro_export]
macro_rules! errln {
    ($($arg:tt)*) => {
        $crate::console::err(format_args!("{}\n", format_args!($($arg)*)))
    };
}
