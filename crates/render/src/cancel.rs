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
