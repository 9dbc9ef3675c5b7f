//! Test hooks, read from the environment (docs/reliability.md): they let the tests signal a
//! render at a known point instead of after a guessed delay.
//!
//! - `REYES_TEST_PAUSE=render`: after the first bucket, print
//!   `reyes-render: test: paused rendering` on stderr and wait (up to a minute) for a
//!   stopping signal.
//! - `REYES_TEST_PAUSE=write`: after the first chunk of the first image file, print
//!   `reyes-render: test: paused writing FILE, temporary file unnamed` (or `..., temporary
//!   file TMPNAME`) and wait likewise.
//! - `REYES_TEST_NAMED_TEMPORARY=1`: write through a named temporary file even where an
//!   unnamed one is possible, as on a file system without `O_TMPFILE`.
//! - `REYES_TEST_SIGNALS=default`: handle SIGINT and SIGTERM even if they were ignored at
//!   start, as for a job in the foreground of a terminal, whatever the disposition the test
//!   harness itself inherited (a CI runner may start it as a background job).

use std::path::Path;
use std::time::{Duration, Instant};

use crate::term::say;

/// Where `REYES_TEST_PAUSE` asks to pause.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pause {
    /// Nowhere (the variable is unset or has another value).
    Never,
    /// After the first bucket.
    Render,
    /// After the first chunk written.
    Write,
}

/// `REYES_TEST_PAUSE`.
pub(crate) fn pause() -> Pause {
    match std::env::var("REYES_TEST_PAUSE").as_deref() {
        Ok("render") => Pause::Render,
        Ok("write") => Pause::Write,
        _ => Pause::Never,
    }
}

/// `REYES_TEST_SIGNALS=default`.
pub(crate) fn signals_default() -> bool {
    std::env::var_os("REYES_TEST_SIGNALS").is_some_and(|v| v == "default")
}

/// `REYES_TEST_NAMED_TEMPORARY=1`.
pub(crate) fn named_temporary() -> bool {
    std::env::var_os("REYES_TEST_NAMED_TEMPORARY").is_some_and(|v| v == "1")
}

/// Print the marker `test: paused rendering`, then wait for a stopping signal.
pub(crate) fn pause_rendering() {
    say("test: paused rendering");
    wait_for_stop();
}

/// Print the marker `test: paused writing FILE, temporary file ...`, then wait for a stopping
/// signal.
pub(crate) fn pause_writing(file: &Path, temporary: Option<&Path>) {
    match temporary {
        None => {
            say(format_args!("test: paused writing {}, temporary file unnamed", file.display()))
        }
        Some(t) => say(format_args!(
            "test: paused writing {}, temporary file {}",
            file.display(),
            t.display()
        )),
    }
    wait_for_stop();
}

/// Until the cancel flag is set, or a minute has passed (so a test that never signals does
/// not hang forever).
fn wait_for_stop() {
    let until = Instant::now() + Duration::from_secs(60);
    while !reyes_render::cancel::requested() && Instant::now() < until {
        std::thread::sleep(Duration::from_millis(5));
    }
}
