//! Bucket stage: sort micropolygons into the buckets their screen bounds touch.
//!
//! Invariants: a micropolygon's screen bound is its vertex bound over its shutter segment
//! ([`Micropolygon::bound`]: the vertices at both ends, which bound the linear motion in
//! between) grown by the lens (`bounddof`) when there is one; it is listed
//! in exactly the buckets [`Frame::buckets_touched`] returns for that bound, and bucket
//! lists hold indices in increasing order because indices are inserted in increasing order.

use reyes_hider::{Frame, LensSetup, Micropolygon};

/// The screen bound `(lo, hi)` (raster x, y and eye z) that decides a micropolygon's buckets.
pub fn screen_bound(
    mp: &Micropolygon,
    lens: Option<&LensSetup>,
    hither: f32,
    yon: f32,
) -> ([f32; 3], [f32; 3]) {
    let (mut lo, mut hi) = mp.bound();
    if let Some(lens) = lens {
        lens.grow(&mut lo, &mut hi, hither, yon);
    }
    (lo, hi)
}

/// Bucket lists under construction.
#[derive(Debug, Clone)]
pub(crate) struct Bucketer {
    frame: Frame,
    lens: Option<LensSetup>,
    hither: f32,
    yon: f32,
    /// One list of micropolygon indices per bucket, raster order.
    pub buckets: Vec<Vec<u32>>,
    /// Total list entries.
    pub entries: u64,
}

impl Bucketer {
    /// Empty lists for every bucket of `frame`.
    pub fn new(frame: &Frame, lens: Option<LensSetup>, hither: f32, yon: f32) -> Bucketer {
        Bucketer {
            frame: *frame,
            lens,
            hither,
            yon,
            buckets: vec![Vec::new(); frame.bucket_count()],
            entries: 0,
        }
    }

    /// The inclusive bucket column and row ranges `mp` touches, if any.
    pub fn range(&self, mp: &Micropolygon) -> Option<[(u32, u32); 2]> {
        let (lo, hi) = screen_bound(mp, self.lens.as_ref(), self.hither, self.yon);
        self.frame.buckets_touched([lo[0], lo[1]], [hi[0], hi[1]])
    }

    /// List `index` in every bucket of `range` (from [`Bucketer::range`]).
    pub fn insert(&mut self, index: u32, range: [(u32, u32); 2]) {
        let [(x0, x1), (y0, y1)] = range;
        let across = self.frame.buckets_x as usize;
        for by in y0..=y1 {
            for bx in x0..=x1 {
                self.buckets[by as usize * across + bx as usize].push(index);
                self.entries += 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bytemuck::Zeroable;
    use proptest::prelude::*;

    fn quad(v: [[f32; 3]; 4]) -> Micropolygon {
        Micropolygon { v, ..Micropolygon::zeroed() }
    }

    /// Brute force: does the box `[lo, hi]` reach a sample position of bucket `b`?
    fn touches(frame: &Frame, b: usize, lo: [f32; 3], hi: [f32; 3]) -> bool {
        // In extended-screen coordinates (raster + border), as `buckets_touched` rounds.
        let e = frame.border as i32;
        let (left, top) = frame.bucket_origin(b);
        let (left, top) = ((left + e) as f32, (top + e) as f32);
        let (right, bottom) = (left + frame.bucket_w as f32, top + frame.bucket_h as f32);
        let (lo, hi) = (lo.map(|c| c + e as f32), hi.map(|c| c + e as f32));
        // Pixel x is touched iff lo.x < x + 1 and hi.x >= x, for some pixel of the bucket.
        lo[0] < right && hi[0] >= left && lo[1] < bottom && hi[1] >= top
    }

    proptest! {
        #[test]
        fn every_touched_bucket_is_listed(
            xs in proptest::array::uniform4(-30.0f32..130.0),
            ys in proptest::array::uniform4(-30.0f32..90.0),
            zs in proptest::array::uniform4(0.5f32..50.0),
            with_lens in any::<bool>(),
        ) {
            let frame = Frame::new(100, 60, 2, 16, 8);
            let lens = with_lens.then(|| LensSetup::new(0.05, 5.0, 300.0, -300.0));
            let v = [0, 1, 2, 3].map(|k| [xs[k], ys[k], zs[k]]);
            let mp = quad(v);
            let mut b = Bucketer::new(&frame, lens, 0.1, 100.0);
            if let Some(r) = b.range(&mp) {
                b.insert(7, r);
            }
            let (lo, hi) = screen_bound(&mp, lens.as_ref(), 0.1, 100.0);
            // The bound contains every vertex.
            for p in &v {
                for a in 0..3 {
                    prop_assert!(lo[a] <= p[a] && p[a] <= hi[a]);
                }
            }
            for (i, list) in b.buckets.iter().enumerate() {
                prop_assert_eq!(list.contains(&7), touches(&frame, i, lo, hi), "bucket {}", i);
            }
        }
    }

    #[test]
    fn lens_grows_the_bound() {
        let frame = Frame::new(64, 64, 0, 16, 16);
        let mp = quad([[20.0, 20.0, 1.0], [21.0, 20.0, 1.0], [21.0, 21.0, 1.0], [20.0, 21.0, 1.0]]);
        let pinhole = Bucketer::new(&frame, None, 0.1, 100.0);
        assert_eq!(pinhole.range(&mp), Some([(1, 1), (1, 1)]));
        // Circle of confusion at z = 1 with focus at 10: 0.1 * 100 * (1 - 0.1) = 9 pixels.
        let lens = LensSetup::new(0.1, 10.0, 100.0, -100.0);
        let blurred = Bucketer::new(&frame, Some(lens), 0.1, 100.0);
        assert_eq!(blurred.range(&mp), Some([(0, 1), (0, 1)]));
    }
}
