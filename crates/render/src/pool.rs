//! The renderer's one thread pool, and the splat of a bucket's samples into its window.
//!
//! This is the only place rayon is set up: both hiders run their bucket loops inside
//! [`Pool::install`] and add their bucket results to the film in bucket raster order
//! ([`crate::buckets`]).
//!
//! Invariant (determinism): the bucket loops `collect` indexed parallel iterators, which
//! keeps bucket raster order, so floating-point sums never depend on scheduling.

use reyes_film::{FilterTable, Window, splat};
use reyes_hider::Frame;

use crate::RenderError;

/// Worker threads for one render: a pool of the requested size, or rayon's global pool.
pub struct Pool {
    pool: Option<rayon::ThreadPool>,
}

impl Pool {
    /// A pool of `threads` workers (None: rayon's global pool, one thread per core).
    pub fn new(threads: Option<usize>) -> Result<Pool, RenderError> {
        let pool = match threads {
            Some(n) => Some(rayon::ThreadPoolBuilder::new().num_threads(n).build()?),
            None => None,
        };
        Ok(Pool { pool })
    }

    /// Run `work` with this pool's workers serving its parallel iterators.
    pub fn install<R: Send>(&self, work: impl FnOnce() -> R + Send) -> R {
        match &self.pool {
            Some(pool) => pool.install(work),
            None => work(),
        }
    }
}

/// Splat bucket `b`'s per-sample colours `rgba` and depths `z` (laid out `pixel * NS + s`)
/// through the filter `table` into `window`, the bucket's pixels plus the filter's border.
pub fn splat_bucket(
    table: &FilterTable,
    frame: &Frame,
    b: usize,
    rgba: &[[f32; 4]],
    z: &[f32],
    window: &mut Window,
) {
    let (left, top) = frame.bucket_origin(b);
    splat(table, left, top, frame.bucket_w, frame.bucket_h, rgba, z, window);
}
