//! Pseudo-random test inputs that are the same on every run: counter-based draws from
//! reyes-sampling's hash.
//!
//! Invariant: the `n`-th draw of a [`Uniform`] depends only on its key and `n`.

use reyes_sampling::{hash, unit};

/// Uniform numbers from a counter: the `n`-th draw (n = 1, 2, ...) in `[lo, hi)` is
/// `lo + (hi - lo) * unit(hash(key, [n]))`.
#[derive(Debug, Clone)]
pub struct Uniform {
    key: u64,
    n: u64,
}

impl Uniform {
    /// The draws of `key`, from the first.
    pub fn new(key: u64) -> Uniform {
        Uniform { key, n: 0 }
    }

    /// The next draw, in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        self.n += 1;
        lo + (hi - lo) * unit(hash(self.key, &[self.n]))
    }
}
