//! Frame geometry: the extended screen and its division into buckets (`VisNewFrame`).
//!
//! Appendix A extends the screen by `Border` pixels on every side (the filter's reach)
//! and tiles the extended screen with buckets starting at `Minx = -Border`,
//! `Miny = -Border`. Bucket `(bx, by)` covers raster pixels
//! `left..left+XPerBucket` by `top..top+YPerBucket` with `left = -Border + bx*XPerBucket`;
//! its output window is that rectangle grown by `Border` on every side.

/// The extended screen and its buckets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Frame {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Filter reach in whole pixels (`VisNewFrame`: `(int)(FilterWidth/2 + 0.499)`).
    pub border: u32,
    /// Bucket width in pixels (`XPerBucket`).
    pub bucket_w: u32,
    /// Bucket height in pixels (`YPerBucket`).
    pub bucket_h: u32,
    /// Buckets across the extended screen.
    pub buckets_x: u32,
    /// Buckets down the extended screen.
    pub buckets_y: u32,
}

/// Appendix A's `Border` for a filter of full width `width`: `(int)(width/2 + 0.499)`. For a
/// filter with different x and y widths, pass the larger.
pub fn border_for_filter_width(width: f32) -> u32 {
    (width / 2.0 + 0.499).max(0.0) as u32
}

impl Frame {
    /// Lay out the buckets for an image. `bucket_w`, `bucket_h` and the image size must be > 0.
    pub fn new(width: u32, height: u32, border: u32, bucket_w: u32, bucket_h: u32) -> Frame {
        let ext_w = width + 2 * border;
        let ext_h = height + 2 * border;
        Frame {
            width,
            height,
            border,
            bucket_w,
            bucket_h,
            buckets_x: ext_w.div_ceil(bucket_w),
            buckets_y: ext_h.div_ceil(bucket_h),
        }
    }

    /// Number of buckets.
    pub fn bucket_count(&self) -> usize {
        (self.buckets_x * self.buckets_y) as usize
    }

    /// Pixels in one bucket (`PixelsPerBucket`).
    pub fn pixels_per_bucket(&self) -> usize {
        (self.bucket_w * self.bucket_h) as usize
    }

    /// Raster coordinates of the top-left pixel of bucket number `b` (raster order).
    pub fn bucket_origin(&self, b: usize) -> (i32, i32) {
        let bx = (b % self.buckets_x as usize) as i32;
        let by = (b / self.buckets_x as usize) as i32;
        (
            -(self.border as i32) + bx * self.bucket_w as i32,
            -(self.border as i32) + by * self.bucket_h as i32,
        )
    }

    /// Inclusive range of bucket columns and rows whose pixels a screen-space box
    /// `[min, max]` (raster x, y) can touch, or `None` if it misses the extended screen.
    /// A sample of pixel `x` lies in `[x, x+1)`, so pixel `x` can be touched iff
    /// `min.x < x + 1` and `max.x >= x`.
    pub fn buckets_touched(&self, min: [f32; 2], max: [f32; 2]) -> Option<[(u32, u32); 2]> {
        let mut out = [(0, 0); 2];
        let sizes = [self.bucket_w, self.bucket_h];
        let counts = [self.buckets_x, self.buckets_y];
        for a in 0..2 {
            if !(min[a].is_finite() && max[a].is_finite()) {
                return None;
            }
            // Extended-screen coordinates start at -border.
            let lo = (min[a] + self.border as f32).floor();
            let hi = (max[a] + self.border as f32).floor();
            let last_px = (counts[a] * sizes[a]) as f32 - 1.0;
            if hi < 0.0 || lo > last_px {
                return None;
            }
            let lo = lo.max(0.0) as u32 / sizes[a];
            let hi = hi.min(last_px) as u32 / sizes[a];
            out[a] = (lo, hi);
        }
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn border_matches_appendix_a_table() {
        // 3.17: W = 1 -> 0, 1.5 -> 1, 2 -> 1, 3 -> 1, 3.01 -> 2, 4 -> 2.
        for (w, b) in [(1.0, 0), (1.5, 1), (2.0, 1), (3.0, 1), (3.01, 2), (4.0, 2)] {
            assert_eq!(border_for_filter_width(w), b, "width {w}");
        }
    }

    #[test]
    fn buckets_cover_extended_screen() {
        let f = Frame::new(100, 50, 1, 16, 16);
        assert_eq!((f.buckets_x, f.buckets_y), (7, 4)); // 102/16 -> 7, 52/16 -> 4
        assert_eq!(f.bucket_origin(0), (-1, -1));
        assert_eq!(f.bucket_origin(8), (15, 15));
        assert_eq!(f.buckets_touched([-5.0, -5.0], [-1.5, 3.0]), None);
        assert_eq!(f.buckets_touched([14.2, 0.0], [15.0, 0.5]), Some([(0, 1), (0, 0)]));
        assert_eq!(f.buckets_touched([14.2, 0.0], [14.9, 0.5]), Some([(0, 0), (0, 0)]));
    }
}
