//! Port of `tablesinit`: the jitter tables and `Location` (and, for the original square lens,
//! `Lens`). The filter table, also built by `tablesinit` in Appendix A, lives in reyes-film
//! (`FilterTable::new`), built from [`Tables::location`].
//!
//! Invariants: `location[s]` is the lower-left corner `(x/nx, y/ny)` of sample s's spatial
//! stratum; with the default `permute` every stratum has exactly one sample. Jitter values lie
//! in `[0, 1/nx)` (x, lens x), `[0, 1/ny)` (y, lens y), `[0, 1/NS)` (time); with jitter off
//! they are the stratum centres.

use reyes_sampling::Drand;
use reyes_sampling::permute::stratum_locations;

/// Appendix A's `NJITTER`: entries in each jitter table.
pub const NJITTER: usize = 512;

/// The five jitter tables in Appendix A's static-storage order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Table {
    /// `XJitter`.
    X = 0,
    /// `YJitter`.
    Y = 1,
    /// `TJitter`.
    T = 2,
    /// `LXJitter`.
    LensX = 3,
    /// `LYJitter`.
    LensY = 4,
}

/// The per-frame sampling tables.
#[derive(Debug, Clone)]
pub struct Tables {
    /// Strata across a pixel (`NxGrid`).
    pub nx: u32,
    /// Strata down a pixel (`NyGrid`).
    pub ny: u32,
    /// Samples per pixel (`NS`).
    pub ns: u32,
    /// `Location[s]`: lower-left corner of sample s's stratum, in pixel units.
    pub location: Vec<[f32; 2]>,
    /// The five tables back to back, each `len` long.
    jitter: Vec<f32>,
    /// Entries per table.
    len: usize,
    /// Read past a table's end into the next one, as the C did (wrapping after the last).
    overrun: bool,
}

impl Tables {
    /// Port of `tablesinit(nx, ny)` for buckets of `pixels_per_bucket` pixels.
    ///
    /// `original_tables`: five 512-entry tables read past their ends exactly as the C static
    /// arrays were (appendix-a.md 3.2); reads past the last table wrap to the first (the C read
    /// unrelated memory there). Otherwise each table is long enough for the largest index the
    /// sampling loops read, `7*NS + 2*P + 17` plus the bucket offset, and never shorter than 512,
    /// so wherever the original did not overrun, both give the same numbers.
    /// `original_permute`: the original `permute`; strata it leaves unassigned keep location
    /// (0, 0) (the C left them uninitialised).
    pub fn new(
        nx: u32,
        ny: u32,
        pixels_per_bucket: usize,
        jitter: bool,
        seed: u64,
        original_tables: bool,
        original_permute: bool,
    ) -> Tables {
        let ns = nx * ny;
        let len = if original_tables {
            NJITTER
        } else {
            NJITTER.max(7 * ns as usize + 2 * pixels_per_bucket + 18)
        };
        let mut table = vec![0.0f32; 5 * len];
        let (fx, fy, fns) = (nx as f32, ny as f32, ns as f32);
        if jitter {
            let mut d = Drand::new(seed);
            for s in 0..len {
                table[s] = d.next_f32() / fx;
                table[len + s] = d.next_f32() / fy;
                table[2 * len + s] = d.next_f32() / fns;
                table[3 * len + s] = d.next_f32() / fx;
                table[4 * len + s] = d.next_f32() / fy;
            }
        } else {
            // Regular grid (FIG. 3): every sample at its stratum centre. (The listing's loop
            // body is missing; the centres are what `MaxXJitter = 0.5/nx` implies.)
            for s in 0..len {
                table[s] = 0.5 / fx;
                table[len + s] = 0.5 / fy;
                table[2 * len + s] = 0.5 / fns;
                table[3 * len + s] = 0.5 / fx;
                table[4 * len + s] = 0.5 / fy;
            }
        }
        let location = stratum_locations(nx, ny, original_permute);
        Tables { nx, ny, ns, location, jitter: table, len, overrun: original_tables }
    }

    /// Entry `index` of `table` (index already includes the bucket's random offset).
    #[inline]
    pub fn get(&self, table: Table, index: usize) -> f32 {
        let i = table as usize * self.len + index;
        if self.overrun { self.jitter[i % self.jitter.len()] } else { self.jitter[i] }
    }

    /// Entries per table.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Never true: there are always five non-empty tables.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_sample_per_stratum() {
        for (nx, ny) in [(1, 1), (2, 2), (3, 4), (4, 4), (5, 5), (8, 8), (7, 3)] {
            let t = Tables::new(nx, ny, 256, true, 1, false, false);
            let mut seen = vec![false; (nx * ny) as usize];
            for l in &t.location {
                let q = ((l[0] * nx as f32).round() as u32 * ny + (l[1] * ny as f32).round() as u32)
                    as usize;
                assert!(!seen[q], "{nx}x{ny}: stratum {q} twice");
                seen[q] = true;
            }
        }
    }

    #[test]
    fn default_tables_cover_the_largest_index() {
        // 4x4 samples, 16x16 buckets: Appendix A reads up to index 641 of 512 (3.2).
        let t = Tables::new(4, 4, 256, true, 1, false, false);
        // Largest index read: offset 22 + i (7*15 + 2*255) + 4; the table must be longer.
        assert!(t.len() > 22 + 7 * 15 + 2 * 255 + 4);
        let o = Tables::new(4, 4, 256, true, 1, true, false);
        assert_eq!(o.len(), NJITTER);
        // The original reads YJitter[600] from the start of TJitter, which is in [0, 1/16).
        assert_eq!(o.get(Table::Y, 600), o.get(Table::T, 600 - NJITTER));
    }

    #[test]
    fn tables_agree_where_the_original_does_not_overrun() {
        let a = Tables::new(4, 4, 64, true, 9, false, false);
        let b = Tables::new(4, 4, 64, true, 9, true, false);
        assert_eq!(a.len(), b.len());
        for i in 0..NJITTER {
            assert_eq!(a.get(Table::LensY, i), b.get(Table::LensY, i));
        }
    }

    #[test]
    fn jitter_ranges() {
        let t = Tables::new(4, 2, 64, true, 3, false, false);
        for i in 0..t.len() {
            assert!((0.0..0.25).contains(&t.get(Table::X, i)));
            assert!((0.0..0.5).contains(&t.get(Table::Y, i)));
            assert!((0.0..0.125).contains(&t.get(Table::T, i)));
        }
    }
}
