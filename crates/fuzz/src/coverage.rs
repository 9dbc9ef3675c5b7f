//! Edge coverage from the compiler's SanitizerCoverage pass, without a runtime library.
//!
//! `cargo xtask fuzz` builds this crate (and everything it links) with
//! `-C passes=sancov-module -C llvm-args=-sanitizer-coverage-level=3
//! -C llvm-args=-sanitizer-coverage-trace-pc-guard`: the pass gives every edge of the control
//! flow graph a 32-bit guard, calls [`__sanitizer_cov_trace_pc_guard_init`] once at start-up
//! with the guards' array, and [`__sanitizer_cov_trace_pc_guard`] each time an edge is taken.
//! The init numbers the guards 1..=n; the trace bumps a saturating 8-bit hit counter per guard.
//!
//! Built without those flags (a plain `cargo test`), nothing calls the two functions:
//! [`instrumented`] is false, every run sees zero edges, and the fuzzer is a plain mutational
//! one over its corpus.
//!
//! The counters are packed eight to a 64-bit word, so that clearing them and folding them into
//! the map between executions touches one word per eight edges (most are zero): that, not the
//! target, was the larger cost of an execution with one byte read at a time. A counter is
//! bumped by a relaxed load and store of its word, so two threads taking edges of one word at
//! once may lose a count: coverage is a heuristic, and the loaders run on one thread.
//!
//! Invariant: counters are only read and cleared by the thread that runs the target, between
//! executions ([`Map::merge`]); other threads only bump them.

#![allow(unsafe_code)]

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering::Relaxed};

/// The most guards counted; later ones share counters (they wrap around).
const CAPACITY: usize = 1 << 22;

/// One 8-bit hit counter per guard, eight to a word (guard `i` is byte `i % 8` of word
/// `i / 8`); guard 0 collects guards not yet numbered.
static COUNTERS: [AtomicU64; CAPACITY / 8] = [const { AtomicU64::new(0) }; CAPACITY / 8];
/// How many guards have been numbered (the instrumented edges of the program).
static GUARDS: AtomicUsize = AtomicUsize::new(0);

/// Called by the instrumentation once per module with its guards; numbers them from 1.
///
/// # Safety
/// `start..stop` must be the guard array the compiler emitted (valid, writable `u32`s).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn __sanitizer_cov_trace_pc_guard_init(start: *mut u32, stop: *mut u32) {
    // SAFETY: the compiler passes the bounds of its own guard section.
    unsafe {
        if start == stop || *start != 0 {
            return;
        }
        let n = stop.offset_from(start) as usize;
        let base = GUARDS.fetch_add(n, Relaxed);
        for i in 0..n {
            *start.add(i) = ((base + i) % (CAPACITY - 1) + 1) as u32;
        }
    }
}

/// Called by the instrumentation on every edge taken.
///
/// # Safety
/// `guard` must point at one of the guards numbered by [`__sanitizer_cov_trace_pc_guard_init`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn __sanitizer_cov_trace_pc_guard(guard: *mut u32) {
    // SAFETY: the compiler passes a pointer into its guard section.
    let index = unsafe { *guard } as usize;
    if let Some(word) = COUNTERS.get(index / 8) {
        let shift = (index % 8) * 8;
        let w = word.load(Relaxed);
        if (w >> shift) & 0xff != 0xff {
            word.store(w + (1 << shift), Relaxed);
        }
    }
}

/// True when the program was built with the coverage instrumentation.
pub fn instrumented() -> bool {
    GUARDS.load(Relaxed) > 0
}

/// The number of instrumented edges in the program (0 when not instrumented).
pub fn edges_total() -> usize {
    GUARDS.load(Relaxed)
}

/// The words of the counters in use.
fn live() -> &'static [AtomicU64] {
    &COUNTERS[..GUARDS.load(Relaxed).min(CAPACITY - 1) / 8 + 1]
}

/// Calls `f(guard, hits)` for every non-zero counter, clearing it.
fn drain(mut f: impl FnMut(usize, u8)) {
    for (w, word) in live().iter().enumerate() {
        let bits = word.load(Relaxed);
        if bits != 0 {
            word.store(0, Relaxed);
            for (b, hits) in bits.to_le_bytes().into_iter().enumerate() {
                if hits != 0 {
                    f(w * 8 + b, hits);
                }
            }
        }
    }
}

/// Clears every counter (before an execution whose coverage is wanted alone).
pub fn clear() {
    for word in live() {
        if word.load(Relaxed) != 0 {
            word.store(0, Relaxed);
        }
    }
}

/// The class of a hit count, as one bit (AFL's buckets): 1, 2, 3, 4-7, 8-15, 16-31, 32-127,
/// 128+. An input is new when it takes an edge a new number of times in this coarse sense.
fn bucket(hits: u8) -> u8 {
    match hits {
        0 => 0,
        1 => 1,
        2 => 2,
        3 => 4,
        4..=7 => 8,
        8..=15 => 16,
        16..=31 => 32,
        32..=127 => 64,
        128.. => 128,
    }
}

/// The coverage seen so far: per edge, the hit-count classes seen.
#[derive(Debug, Clone, Default)]
pub struct Map {
    seen: Vec<u8>,
    edges: usize,
}

impl Map {
    /// An empty map.
    pub fn new() -> Map {
        Map::default()
    }

    /// Edges taken at least once.
    pub fn edges(&self) -> usize {
        self.edges
    }

    /// Folds the counters of the last execution in and clears them; true if they showed an
    /// edge or a hit-count class not seen before.
    pub fn merge(&mut self) -> bool {
        let len = live().len() * 8;
        if self.seen.len() < len {
            self.seen.resize(len, 0);
        }
        let mut new = false;
        drain(|i, hits| new |= self.add(i, hits));
        new
    }

    /// Folds in counters read elsewhere (a child process's [`dump`]); true if anything was new.
    pub fn merge_pairs(&mut self, pairs: &[(u32, u8)]) -> bool {
        let mut new = false;
        for &(i, hits) in pairs {
            let i = i as usize;
            if i >= self.seen.len() {
                self.seen.resize(i + 1, 0);
            }
            new |= self.add(i, hits);
        }
        new
    }

    fn add(&mut self, i: usize, hits: u8) -> bool {
        let b = bucket(hits);
        let old = self.seen[i];
        if old & b == b {
            return false;
        }
        if old == 0 {
            self.edges += 1;
        }
        self.seen[i] = old | b;
        true
    }
}

/// The counters now non-zero, as `(guard, hits)` pairs, in little-endian bytes (5 a pair) for
/// a parent process to [`parse`]; clears them.
pub fn dump() -> Vec<u8> {
    let mut out = Vec::new();
    drain(|i, hits| {
        out.extend_from_slice(&(i as u32).to_le_bytes());
        out.push(hits);
    });
    out
}

/// The pairs of a [`dump`] (a truncated last pair is dropped).
pub fn parse(bytes: &[u8]) -> Vec<(u32, u8)> {
    bytes.chunks_exact(5).map(|p| (u32::from_le_bytes([p[0], p[1], p[2], p[3]]), p[4])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_are_single_bits_growing_with_the_count() {
        let mut last = 0;
        for hits in 1..=255u8 {
            let b = bucket(hits);
            assert_eq!(b.count_ones(), 1, "{hits}");
            assert!(b >= last, "{hits}");
            last = b;
        }
        assert_eq!(bucket(0), 0);
    }

    #[test]
    fn a_map_reports_new_edges_and_new_count_classes_once() {
        let mut m = Map::new();
        assert!(m.merge_pairs(&[(3, 1), (7, 2)]));
        assert_eq!(m.edges(), 2);
        assert!(!m.merge_pairs(&[(3, 1)]), "same edge, same class");
        assert!(m.merge_pairs(&[(3, 5)]), "same edge, new class");
        assert_eq!(m.edges(), 2);
        assert!(m.merge_pairs(&[(100, 1)]));
        assert_eq!(m.edges(), 3);
    }

    #[test]
    fn dumps_parse_back() {
        let bytes: Vec<u8> = [(1u32, 9u8), (70_000, 255)]
            .iter()
            .flat_map(|(i, h)| i.to_le_bytes().into_iter().chain([*h]))
            .collect();
        assert_eq!(parse(&bytes), vec![(1, 9), (70_000, 255)]);
        assert_eq!(parse(&bytes[..7]), vec![(1, 9)]);
    }
}
