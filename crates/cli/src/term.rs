//! Everything the command prints goes through here, so that no write to a closed pipe or a
//! full device can panic (as `println!` and `eprintln!` do).
//!
//! Standard output: a closed pipe (`| head -0`) ends the printing quietly, any other failure
//! (`> /dev/full`) becomes a one-line error with exit code 1. Standard error: failures are
//! ignored, as there is nowhere left to report them.

use std::fmt::Display;
use std::io::{ErrorKind, Write};

use crate::Exit;

/// Print `text` to standard output and flush it. A reader that went away is not an error
/// (the output is simply not wanted); any other failure is, naming standard output.
pub(crate) fn print(text: &str) -> Result<(), Exit> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) => stdout_failed(e),
    }
}

/// What a failed write to standard output means: quiet for a closed pipe, exit 1 otherwise.
pub(crate) fn stdout_failed(e: std::io::Error) -> Result<(), Exit> {
    match e.kind() {
        ErrorKind::BrokenPipe => Ok(()),
        _ => Err(Exit::error(1, format_args!("standard output: {e}"))),
    }
}

/// One line `reyes-render: LINE` on standard error, if it can be written at all.
pub(crate) fn say(line: impl Display) {
    let _ = writeln!(std::io::stderr().lock(), "reyes-render: {line}");
}
