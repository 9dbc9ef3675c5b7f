//! Test hooks a front end reads from the environment (docs/reliability.md): they pause a run
//! at a known point, so that a test can signal it there instead of after a guessed delay,
//! and check what a stopping signal leaves behind.
//!
//! - `REYES_TEST_PAUSE=render`: after the first bucket, say `test: paused rendering` and
//!   wait (up to a minute) for a cancel request ([`reyes_render::cancel`]).
//! - `REYES_TEST_PAUSE=write`: after the first chunk of the first image file, say `test:
//!   paused writing FILE, temporary file unnamed` (or `..., temporary file TMPNAME`) and wait
//!   likewise.
//! - `REYES_TEST_NAMED_TEMPORARY=1`: write through a named temporary file even where an
//!   unnamed one is possible, as on a file system without `O_TMPFILE`.
//! - `REYES_TEST_SIGNALS=default`: the front end handles SIGINT and SIGTERM even if they were
//!   ignored at start, as for a job in the foreground of a terminal, whatever the disposition
//!   the test harness itself inherited (a CI runner may start it as a background job).
//!
//! Invariant: without these variables, nothing here changes a run.

use std::path::Path;
use std::sync::Once;
use std::time::{Duration, Instant};

use crate::job::WriteHooks;

/// The test hooks of one run, the pause taken once.
pub struct TestHooks {
    /// `REYES_TEST_PAUSE`: `render`, `write`, or None.
    pause: Option<String>,
    /// `REYES_TEST_NAMED_TEMPORARY=1`.
    pub named_temporary: bool,
    once: Once,
}

impl TestHooks {
    /// The hooks the environment asks for.
    pub fn from_env() -> TestHooks {
        let pause = std::env::var("REYES_TEST_PAUSE").ok();
        let named_temporary =
            std::env::var_os("REYES_TEST_NAMED_TEMPORARY").is_some_and(|v| v == "1");
        TestHooks { pause, named_temporary, once: Once::new() }
    }

    /// A bucket finished: with `REYES_TEST_PAUSE=render`, the first time, `say` the marker
    /// `test: paused rendering` and wait for a cancel request.
    pub fn after_bucket(&self, say: &dyn Fn(String)) {
        if self.pause.as_deref() == Some("render") {
            self.once.call_once(|| {
                say("test: paused rendering".into());
                wait_for_cancel();
            });
        }
    }

    /// The first chunk of `file` reached its temporary file (None: unnamed): with
    /// `REYES_TEST_PAUSE=write`, the first time, `say` the marker `test: paused writing FILE,
    /// temporary file ...` and wait for a cancel request.
    pub fn after_first_chunk(&self, file: &Path, temporary: Option<&Path>, say: &dyn Fn(String)) {
        if self.pause.as_deref() == Some("write") {
            self.once.call_once(|| {
                let temporary = temporary.map_or("unnamed".into(), |t| t.display().to_string());
                say(format!("test: paused writing {}, temporary file {temporary}", file.display()));
                wait_for_cancel();
            });
        }
    }
}

impl TestHooks {
    /// How a frame's files are written in a cancellable run: the render's cancel flag polled
    /// before each chunk, `pause` after the first chunk (which calls
    /// [`TestHooks::after_first_chunk`]), and a named temporary file if the hooks ask for one.
    pub fn write_hooks<'a>(&self, pause: &'a crate::job::FirstChunkHook<'a>) -> WriteHooks<'a> {
        WriteHooks {
            cancel: Some(reyes_render::cancel::flag()),
            after_first_chunk: Some(pause),
            named_temporary: self.named_temporary,
        }
    }
}

/// `REYES_TEST_SIGNALS=default`.
pub fn signals_default() -> bool {
    std::env::var_os("REYES_TEST_SIGNALS").is_some_and(|v| v == "default")
}

/// Until a cancel is requested, or a minute has passed (so a test that never signals does
/// not hang forever).
fn wait_for_cancel() {
    let until = Instant::now() + Duration::from_secs(60);
    while !reyes_render::cancel::requested() && Instant::now() < until {
        std::thread::sleep(Duration::from_millis(5));
    }
}
