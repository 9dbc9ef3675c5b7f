//! Cancelling a render from outside, e.g. from a signal handler.
//!
//! The request is one process-wide flag, as signals are process-wide: [`flag`] is what a
//! handler sets (it is a `&'static AtomicBool`, which `signal_hook::flag::register` accepts),
//! [`requested`] is what the bucket loops poll. Both hiders check it before each bucket; once
//! it is set the remaining buckets are skipped and [`crate::render`] returns
//! [`crate::RenderError::Cancelled`], so the latency is about one bucket per worker.
//!
//! Invariant: the flag is only ever set, never cleared, so a render started after a request
//! is cancelled at its first bucket.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// The process-wide cancel flag: set it (from any thread or a signal handler) to cancel the
/// current and any later render.
pub fn flag() -> &'static AtomicBool {
    &REQUESTED
}

/// Ask the current and any later render to stop.
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Whether cancellation has been requested.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// Whether `signal` was already ignored when the process started: a shell starts background
/// jobs with SIGINT ignored so that Ctrl-C spares them, and a front end installing a handler
/// that cancels renders should leave such a signal ignored. Linux tells through the `SigIgn`
/// mask of `/proc/self/status`; without it, not ignored.
pub fn ignored_at_start(signal: i32) -> bool {
    let Ok(status) = std::fs::read_to_string("/proc/self/status") else { return false };
    let mask = status.lines().find_map(|l| l.strip_prefix("SigIgn:"));
    let mask = mask.and_then(|m| u64::from_str_radix(m.trim(), 16).ok());
    match (mask, u32::try_from(signal - 1)) {
        (Some(mask), Ok(bit)) if bit < 64 => mask >> bit & 1 == 1,
        _ => false,
    }
}
