//! Stratified pseudo-random numbers for the distributed effects of one sample.
//!
//! The patent's point (FIGS. 19-22): a pixel's `n` samples each choose *one* ray among
//! those a light or a surface allows, and the choices are stratified across the samples,
//! so that the pixel filter averages `n` well-spread rays without tracing more. A
//! [`Strata`] is the stream of one member (`index`) of such a set of `count` members (the
//! samples of a pixel, or the rays of a tile of grid vertices). Each call of
//! [`Strata::next_2d`] opens a new *dimension* (one per effect and bounce: the first
//! light's shadow ray, then the second's, the glossy direction, ...). In every dimension
//! the set's members take distinct cells of a `gx x gy = count` grid of the unit square,
//! in an order scrambled per set and per dimension, each jittered within its cell.
//!
//! Invariant: the numbers depend only on `(seed, set, index, count)` and the call order,
//! never on threads or on other sets; different dimensions are decorrelated.

use crate::permute::keyed as permute;
use crate::rng::{hash, unit};

/// The stream of stratified choices of one member of a set.
#[derive(Debug, Clone)]
pub struct Strata {
    key: u64,
    index: u32,
    count: u32,
    gx: u32,
    dim: u32,
}

impl Strata {
    /// Member `index` of a set of `count` members (`index < count`, `count >= 1`), the set
    /// named by `set` (e.g. a hash of the pixel), under the scene's `seed`.
    pub fn new(seed: u64, set: u64, index: u32, count: u32) -> Strata {
        let count = count.max(1);
        debug_assert!(index < count, "member {index} of a set of {count}");
        Strata {
            key: hash(seed, &[0x5354_5241_5441, set]),
            index: index % count,
            count,
            gx: grid_width(count),
            dim: 0,
        }
    }

    /// The members in the set.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The next dimension's point in `[0, 1)^2`: this member's cell of the dimension's
    /// scrambled `gx x gy` grid, jittered.
    pub fn next_2d(&mut self) -> (f32, f32) {
        let d = u64::from(self.dim);
        self.dim += 1;
        let cell = permute(self.index, self.count, hash(self.key, &[d]));
        let gy = self.count / self.gx;
        let (cx, cy) = (cell % self.gx, cell / self.gx);
        let j = hash(self.key, &[d, u64::from(self.index) + 1]);
        let (jx, jy) = (unit(j), unit(j << 24));
        ((cx as f32 + jx) / self.gx as f32, (cy as f32 + jy) / gy as f32)
    }

    /// Pass over `dims` dimensions without drawing them: afterwards the stream is where
    /// `dims` calls of [`Strata::next_2d`] would have left it. A shader that may or may not
    /// use a dimension (a light whose sample is not needed) skips it, so that the set's
    /// members keep drawing the same dimension for the same effect.
    pub fn skip(&mut self, dims: u32) {
        self.dim = self.dim.saturating_add(dims);
    }

    /// The next dimension's number in `[0, 1)`: this member's stratum of `count`, jittered.
    pub fn next_1d(&mut self) -> f32 {
        let d = u64::from(self.dim);
        self.dim += 1;
        let cell = permute(self.index, self.count, hash(self.key, &[d]));
        let j = unit(hash(self.key, &[d, u64::from(self.index) + 1]));
        (cell as f32 + j) / self.count as f32
    }
}

/// The largest divisor of `n` not above `sqrt(n)`: the grid is `gx x (n / gx)`, as square
/// as `n` allows (a prime `n` gives one row of `n` strata in y).
fn grid_width(n: u32) -> u32 {
    let mut g = (n as f64).sqrt() as u32;
    while g > 1 && !n.is_multiple_of(g) {
        g -= 1;
    }
    g.max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_dimension_puts_one_member_in_each_cell() {
        for count in [1, 4, 6, 16, 7] {
            let gx = grid_width(count);
            let gy = count / gx;
            let mut streams: Vec<Strata> =
                (0..count).map(|i| Strata::new(3, 9, i, count)).collect();
            for _dim in 0..5 {
                let mut seen = vec![false; count as usize];
                for s in &mut streams {
                    let (x, y) = s.next_2d();
                    assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
                    let cell = (y * gy as f32) as u32 * gx + (x * gx as f32) as u32;
                    assert!(!seen[cell as usize], "count {count}: cell {cell} twice");
                    seen[cell as usize] = true;
                }
            }
        }
    }

    #[test]
    fn dimensions_and_sets_differ() {
        let mut a = Strata::new(1, 2, 0, 16);
        let (p, q) = (a.next_2d(), a.next_2d());
        assert_ne!(p, q);
        let mut b = Strata::new(1, 3, 0, 16);
        assert_ne!(p, b.next_2d());
        let mut c = Strata::new(1, 2, 0, 16);
        assert_eq!(p, c.next_2d(), "same inputs, same numbers");
    }
}
