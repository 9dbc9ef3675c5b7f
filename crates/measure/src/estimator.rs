//! The estimator of FIG. 23's measurement: one jittered point in each of about `samples`
//! equal cells of the bounding box, their inside answers summed with the paired differences
//! that bound the standard errors (see the crate documentation).
//!
//! Invariant: cells are summed in fixed groups added in a fixed order, so the sums depend only
//! on the box, the grid, the seed and the inside test, never on threads.

use glam::DVec3;
use rayon::prelude::*;
use reyes_sampling::{SplitMix64, unit_f64};

use crate::inside::Aabb;

/// The `n`th uniform number in `[0, 1)` of the stream `key`.
#[inline]
pub(crate) fn draw(key: u64, n: u64) -> f64 {
    unit_f64(SplitMix64::at(key ^ SplitMix64::at(n.wrapping_mul(0xD1B5_4A32_D192_ED03))))
}

/// Cells per axis for about `samples` cells over a box of extents `ext`: as near cubic as
/// possible, every count even and at least 2.
pub(crate) fn grid(ext: DVec3, samples: u64) -> [u64; 3] {
    let e = ext.to_array();
    let mut n = [2u64; 3];
    let mut fixed = [false; 3];
    loop {
        let free: Vec<usize> = (0..3).filter(|&k| !fixed[k]).collect();
        if free.is_empty() {
            return n;
        }
        let taken: f64 = (0..3).filter(|&k| fixed[k]).map(|k| n[k] as f64).product();
        let budget = (samples as f64 / taken).max(1.0);
        let volume: f64 = free.iter().map(|&k| e[k]).product();
        let h = (volume / budget).powf(1.0 / free.len() as f64);
        let thin: Vec<usize> = free.iter().copied().filter(|&k| e[k] / h < 2.0).collect();
        if thin.is_empty() {
            for &k in &free {
                n[k] = 2 * ((e[k] / h / 2.0).round() as u64).max(1);
            }
            return n;
        }
        for k in thin {
            fixed[k] = true;
        }
    }
}

/// Partial sums over some cells (coordinates relative to the box centre).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Sums {
    /// Points inside.
    pub(crate) inside: u64,
    /// Sum of inside points.
    pub(crate) first: DVec3,
    /// Pairs along x whose points differ in being inside.
    pub(crate) vol_pairs: u64,
    /// Per centre coordinate k, over pairs along axis (k + 1) % 3, with
    /// `dx = I_a x_a - I_b x_b` and `di = I_a - I_b`: sums of `dx^2`, `dx di`, `di^2`.
    pub(crate) dxx: [f64; 3],
    pub(crate) dxi: [f64; 3],
    pub(crate) dii: [u64; 3],
}

impl Sums {
    pub(crate) fn add(&mut self, o: &Sums) {
        self.inside += o.inside;
        self.vol_pairs += o.vol_pairs;
        self.first += o.first;
        for k in 0..3 {
            self.dxx[k] += o.dxx[k];
            self.dxi[k] += o.dxi[k];
            self.dii[k] += o.dii[k];
        }
    }
}

/// Rows of 2 x 2 x 2 blocks summed by one task.
pub(crate) const ROWS_PER_TASK: u64 = 16;

/// Samples the box `b` with one jittered point per cell of `n` and sums the statistics.
pub(crate) fn sample(
    b: &Aabb,
    n: [u64; 3],
    seed: u64,
    inside: &(dyn Fn(DVec3, u64) -> bool + Sync),
) -> Sums {
    let ext = b.max - b.min;
    let cell = ext / DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64);
    let centre = (b.min + b.max) * 0.5;
    let seed_key = SplitMix64::at(seed);
    let [bx, by, bz] = n.map(|c| c / 2);
    let rows = by * bz;
    let tasks = rows.div_ceil(ROWS_PER_TASK);
    let parts: Vec<Sums> = (0..tasks)
        .into_par_iter()
        .map(|t| {
            let mut s = Sums::default();
            for row in t * ROWS_PER_TASK..((t + 1) * ROWS_PER_TASK).min(rows) {
                let (j0, k0) = (2 * (row % by), 2 * (row / by));
                for i0 in (0..bx).map(|i| 2 * i) {
                    // The block's 8 cells, indexed by dx + 2 dy + 4 dz.
                    let mut ins = [false; 8];
                    let mut pos = [DVec3::ZERO; 8];
                    for (c, (is, p)) in ins.iter_mut().zip(pos.iter_mut()).enumerate() {
                        let (i, j, k) =
                            (i0 + (c as u64 & 1), j0 + (c as u64 >> 1 & 1), k0 + (c as u64 >> 2));
                        let index = i + n[0] * (j + n[1] * k);
                        let key = SplitMix64::at(seed_key ^ index);
                        let jitter = DVec3::new(draw(key, 0), draw(key, 1), draw(key, 2));
                        let q = b.min + (DVec3::new(i as f64, j as f64, k as f64) + jitter) * cell;
                        *is = inside(q, key);
                        *p = q - centre;
                    }
                    for (p, _) in pos.iter().zip(&ins).filter(|(_, is)| **is) {
                        s.inside += 1;
                        s.first += *p;
                    }
                    // Volume: pairs along x (cells c and c + 1 with dx = 0).
                    for c in [0, 2, 4, 6] {
                        s.vol_pairs += u64::from(ins[c] != ins[c + 1]);
                    }
                    // Centre coordinate k: pairs along axis (k + 1) % 3, i.e. cells `step`
                    // apart in the block's index.
                    for (k, step) in [(0, 2usize), (1, 4), (2, 1)] {
                        let x = |c: usize| if ins[c] { pos[c][k] } else { 0.0 };
                        for a in (0..8).filter(|a| a & step == 0) {
                            let di = i64::from(ins[a]) - i64::from(ins[a + step]);
                            let dx = x(a) - x(a + step);
                            s.dxx[k] += dx * dx;
                            s.dxi[k] += dx * di as f64;
                            s.dii[k] += di.unsigned_abs();
                        }
                    }
                }
            }
            s
        })
        .collect();
    let mut total = Sums::default();
    for p in &parts {
        total.add(p);
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_is_even_and_near_the_sample_count() {
        assert_eq!(grid(DVec3::splat(3.0), 1_000_000), [100, 100, 100]);
        assert_eq!(grid(DVec3::splat(1.0), 1), [2, 2, 2]);
        let n = grid(DVec3::new(1000.0, 1.0, 0.001), 1_000_000);
        assert!(n.iter().all(|c| c % 2 == 0 && *c >= 2), "{n:?}");
        assert_eq!(n[2], 2);
        let total: u64 = n.iter().product();
        assert!((500_000..2_000_000).contains(&total), "{n:?}");
    }

    #[test]
    fn draws_are_uniform_looking_and_in_range() {
        let mean = (0..10_000).map(|i| draw(SplitMix64::at(i), 0)).sum::<f64>() / 10_000.0;
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
        assert!((0..1000).all(|i| (0.0..1.0).contains(&draw(i, i))));
    }
}
