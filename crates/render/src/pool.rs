//! The renderer's one thread pool, and the fixed-order merge of bucket windows into the film.
//!
//! This is the only place rayon is set up: both hiders run their bucket loops inside
//! [`Pool::install`] and hand their bucket results, in bucket order, to [`merge`].
//!
//! Invariant (determinism): [`merge`] adds windows in the order of the slice it is given,
//! which callers keep in bucket raster order (rayon's `collect` of an indexed parallel
//! iterator preserves it), so floating-point sums never depend on scheduling.

use reyes_film::{Film, FilterTable, Window, splat};
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

/// Add the bucket windows of `windows` (in bucket raster order; `None` for a bucket that
/// drew nothing) to `film`, in that order, calling `each` for every bucket that drew
/// something. Returns the number of windows added.
pub fn merge<'a, T: 'a>(
    film: &mut Film,
    windows: impl IntoIterator<Item = &'a (Option<Window>, T)>,
    mut each: impl FnMut(&T),
) -> usize {
    let mut added = 0;
    for (window, extra) in windows {
        if let Some(w) = window {
            film.add(w);
            added += 1;
        }
        each(extra);
    }
    added
}
