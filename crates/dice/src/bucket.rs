//! Bucket stage: the buckets a micropolygon's screen bound touches.
//!
//! Invariants: a micropolygon's screen bound is its vertex bound over its shutter segment
//! ([`Micropolygon::bound`]: the vertices at both ends, which bound the linear motion in
//! between) grown by the lens (`bounddof`) when there is one; it is listed
//! in exactly the buckets [`Frame::buckets_touched`] returns for that bound.

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

/// Which buckets a micropolygon touches.
#[derive(Debug, Clone)]
pub(crate) struct Bucketer {
    frame: Frame,
    lens: Option<LensSetup>,
    hither: f32,
    yon: f32,
}

/// Inclusive bucket column and row ranges, `[(x0, x1), (y0, y1)]`.
pub(crate) type BucketRange = [(u32, u32); 2];

impl Bucketer {
    /// The buckets of `frame`, seen through `lens` with depth limits `hither` and `yon`.
    pub fn new(frame: &Frame, lens: Option<LensSetup>, hither: f32, yon: f32) -> Bucketer {
        Bucketer { frame: *frame, lens, hither, yon }
    }

    /// The inclusive bucket column and row ranges `mp` touches, if any.
    pub fn range(&self, mp: &Micropolygon) -> Option<BucketRange> {
        let (lo, hi) = screen_bound(mp, self.lens.as_ref(), self.hither, self.yon);
        self.frame.buckets_touched([lo[0], lo[1]], [hi[0], hi[1]])
    }

    /// The buckets of `range` (from [`Bucketer::range`]), in raster order.
    pub fn buckets(&self, range: BucketRange) -> impl Iterator<Item = usize> + use<> {
        let [(x0, x1), (y0, y1)] = range;
        let across = self.frame.buckets_x as usize;
        (y0..=y1).flat_map(move |by| (x0..=x1).map(move |bx| by as usize * across + bx as usize))
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
            let b = Bucketer::new(&frame, lens, 0.1, 100.0);
            let listed: Vec<usize> = b.range(&mp).map(|r| b.buckets(r).collect()).unwrap_or_default();
            let (lo, hi) = screen_bound(&mp, lens.as_ref(), 0.1, 100.0);
            // The bound contains every vertex.
            for p in &v {
                for a in 0..3 {
                    prop_assert!(lo[a] <= p[a] && p[a] <= hi[a]);
                }
            }
            for i in 0..frame.bucket_count() {
                prop_assert_eq!(listed.contains(&i), touches(&frame, i, lo, hi), "bucket {}", i);
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
