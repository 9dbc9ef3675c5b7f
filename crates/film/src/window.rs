//! The splat: one bucket's per-sample composites filtered into a bordered window (stage: film,
//! called once per bucket, possibly on several threads, each with its own [`Window`]).
//!
//! Invariants: a window covers the bucket grown by `border` on every side
//! (`x0 = bucket_left - border`, `w = bw + 2 border`); its rgba holds the filtered,
//! premultiplied contributions of this bucket's samples only (neighbouring windows overlap by
//! `2 border` pixels and are summed by [`crate::Film::add`]); its z holds, for pixels inside the
//! bucket, the minimum of the pixel's own sample depths, and `+inf` for border pixels.

use crate::FilterTable;

/// The filtered output of one bucket: Appendix A's bordered `Pixel` buffer, handed to
/// `DisplayWindow` (3.17).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Window {
    /// Raster x of the window's left column (`bucket_left - border`).
    pub x0: i32,
    /// Raster y of the window's top row (`bucket_top - border`).
    pub y0: i32,
    /// Width in pixels (`bw + 2 border`).
    pub w: u32,
    /// Height in pixels (`bh + 2 border`).
    pub h: u32,
    /// Premultiplied linear rgba, row-major `[y * w + x]`.
    pub rgba: Vec<[f32; 4]>,
    /// Depth of the nearest opaque surface, unfiltered: the minimum over the pixel's own
    /// samples inside the bucket, `+inf` where there is none and in the border.
    pub z: Vec<f32>,
}

impl Window {
    /// An empty window; [`splat`] sizes it (and keeps its allocations for the next bucket).
    pub fn new() -> Window {
        Window::default()
    }

    /// The rgba of raster pixel `(x, y)`, if the window covers it.
    pub fn rgba_at(&self, x: i32, y: i32) -> Option<[f32; 4]> {
        self.index(x, y).map(|k| self.rgba[k])
    }

    /// The depth of raster pixel `(x, y)`, if the window covers it.
    pub fn z_at(&self, x: i32, y: i32) -> Option<f32> {
        self.index(x, y).map(|k| self.z[k])
    }

    fn index(&self, x: i32, y: i32) -> Option<usize> {
        let lx = usize::try_from(i64::from(x) - i64::from(self.x0)).ok()?;
        let ly = usize::try_from(i64::from(y) - i64::from(self.y0)).ok()?;
        let (w, h) = (self.w as usize, self.h as usize);
        (lx < w && ly < h).then_some(ly * w + lx)
    }
}

/// Filter one bucket's samples into `out`.
///
/// Port of `filter` and `applyboxfilter` (Appendix A 2.8). The bucket is `bw x bh` pixels with
/// its top-left pixel at raster `(bucket_left, bucket_top)`. `rgba` and `z` are indexed by
/// Appendix A's `nsample = pixel * NS + s`, `pixel = y * bw + x` (bucket-local): `rgba` is the
/// sample's premultiplied composite (all zeros if nothing is visible or the front is a matte;
/// such samples are skipped, as the C skips null and matte heads), `z` the depth of its
/// nearest opaque surface (`+inf` if none).
///
/// Sample `s` of bucket pixel `(x, y)` adds `w[s][j][i] * rgba` to window pixel `(x + i, y + j)`,
/// i.e. raster pixel `(bucket_left + x + i - border, bucket_top + y + j - border)`. For the
/// box of width 1 (`table.box_fast()`, border 0) it adds `rgba / NS` to its own pixel
/// (`applyboxfilter`). Each window pixel's contributions are summed in `f64`, in a fixed order,
/// and rounded to `f32` once, so the result is deterministic and a fully covered pixel's
/// weights add up to 1 to within f32 rounding.
///
/// `out` is resized and cleared; once it has seen the largest bucket, no allocation happens.
///
/// # Panics
///
/// If `rgba.len()` or `z.len()` differs from `bw * bh * table.ns()`.
#[allow(clippy::too_many_arguments)] // the signature mirrors the hider/film hand-off
pub fn splat(
    table: &FilterTable,
    bucket_left: i32,
    bucket_top: i32,
    bw: u32,
    bh: u32,
    rgba: &[[f32; 4]],
    z: &[f32],
    out: &mut Window,
) {
    let ns = table.ns();
    let border = table.border();
    let fw = table.footprint() as usize;
    let (bwu, bhu) = (bw as usize, bh as usize);
    let samples = bwu * bhu * ns;
    assert_eq!(rgba.len(), samples, "splat: rgba has the wrong number of samples");
    assert_eq!(z.len(), samples, "splat: z has the wrong number of samples");

    let b = border as usize;
    let ww = bwu + 2 * b;
    let wh = bhu + 2 * b;
    // The table caps the border far below i32::MAX, so `border as i32` is exact.
    out.x0 = bucket_left.saturating_sub(border as i32);
    out.y0 = bucket_top.saturating_sub(border as i32);
    out.w = ww as u32;
    out.h = wh as u32;
    out.rgba.clear();
    out.rgba.resize(ww * wh, [0.0; 4]);
    out.z.clear();
    out.z.resize(ww * wh, f32::INFINITY);

    // Depth: unfiltered minimum over the pixel's own samples.
    for y in 0..bhu {
        for x in 0..bwu {
            let first = (y * bwu + x) * ns;
            let zmin = z[first..first + ns].iter().fold(f32::INFINITY, |m, &v| m.min(v));
            out.z[(y + b) * ww + x + b] = zmin;
        }
    }

    if samples == 0 {
        return; // an empty bucket: its window is all border, zero colour
    }

    if table.box_fast() {
        // applyboxfilter: border is 0, each sample adds 1/NS of itself to its own pixel.
        let one_over_ns = f64::from(1.0 / ns as f32);
        for (dst, pixel_samples) in out.rgba.iter_mut().zip(rgba.chunks_exact(ns)) {
            let mut acc = [0.0_f64; 4];
            for c in pixel_samples {
                if !is_empty(c) {
                    for k in 0..4 {
                        acc[k] += one_over_ns * f64::from(c[k]);
                    }
                }
            }
            *dst = acc.map(|v| v as f32);
        }
        return;
    }

    // filter: the C scatters each sample over its footprint. We gather instead: each window
    // pixel sums, in f64, exactly the terms the scatter would add to it, and is rounded to
    // f32 once. The result is the same sum without the rounding drift of adding up to
    // NS * fw² small f32 terms one by one. Window pixel (wx, wy) receives sample s of bucket
    // pixel (wx - i, wy - j) with weight w[s][j][i].
    let weights = table.weights();
    let per_sample = fw * fw;
    for wy in 0..wh {
        // j ranges over the rows whose source pixel y = wy - j lies inside the bucket.
        let j_lo = wy.saturating_sub(bhu - 1);
        let j_hi = wy.min(fw - 1);
        for wx in 0..ww {
            let i_lo = wx.saturating_sub(bwu - 1);
            let i_hi = wx.min(fw - 1);
            let mut acc = [0.0_f64; 4];
            for j in j_lo..=j_hi {
                let y = wy - j;
                for i in i_lo..=i_hi {
                    let x = wx - i;
                    let first = (y * bwu + x) * ns;
                    let tap = j * fw + i;
                    for (s, c) in rgba[first..first + ns].iter().enumerate() {
                        if is_empty(c) {
                            continue;
                        }
                        let f = f64::from(weights[s * per_sample + tap]);
                        for k in 0..4 {
                            acc[k] += f * f64::from(c[k]);
                        }
                    }
                }
            }
            out.rgba[wy * ww + wx] = acc.map(|v| v as f32);
        }
    }
}

/// A sample that contributes nothing (no visible surface, or a matte in front).
fn is_empty(c: &[f32; 4]) -> bool {
    c.iter().all(|&v| v == 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Film;
    use crate::table::tests::{GRIDS, KINDS, WIDTHS, all_original, grid_locations};
    use reyes_scene::{FilterKind, Original};

    fn table(kind: FilterKind, width: f32, n: u32, original: &Original) -> FilterTable {
        FilterTable::new(kind, width, n, n, &grid_locations(n, n), original)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn unit_gain_in_middle_bucket() {
        // A 3x3 grid of buckets, every sample (1,1,1,1): every pixel of the middle bucket must
        // receive total weight 1, through every table.
        let (bw, bh) = (5_u32, 4_u32);
        let mut win = Window::new();
        for original in [Original::default(), all_original()] {
            for kind in KINDS {
                for width in WIDTHS {
                    for n in GRIDS {
                        let t = table(kind, width, n, &original);
                        let samples = (bw * bh) as usize * t.ns();
                        let rgba = vec![[1.0_f32; 4]; samples];
                        let z = vec![1.0_f32; samples];
                        let mut film = Film::new(3 * bw, 3 * bh);
                        for by in 0..3 {
                            for bx in 0..3 {
                                let (l, top) = ((bx * bw) as i32, (by * bh) as i32);
                                splat(&t, l, top, bw, bh, &rgba, &z, &mut win);
                                film.add(&win);
                            }
                        }
                        for y in bh..2 * bh {
                            for x in bw..2 * bw {
                                let p = film.pixel(x, y).unwrap_or([f32::NAN; 4]);
                                for v in p {
                                    assert!(
                                        (v - 1.0).abs() <= 1e-5,
                                        "{kind:?} W={width} {n}x{n} {original:?} ({x},{y}): {p:?}"
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn box_fast_path_equals_general_path() {
        for n in GRIDS {
            let loc = grid_locations(n, n);
            let o = Original::default();
            let fast = FilterTable::new(FilterKind::Box, 1.0, n, n, &loc, &o)
                .unwrap_or_else(|e| panic!("{e}"));
            assert!(fast.box_fast());
            // The next float above 1: same border (0) and weights, but the general path.
            let just_over_one = f32::from_bits(1.0_f32.to_bits() + 1);
            let general = FilterTable::new(FilterKind::Box, just_over_one, n, n, &loc, &o)
                .unwrap_or_else(|e| panic!("{e}"));
            assert!(!general.box_fast());
            assert_eq!(general.weights(), fast.weights());
            let (bw, bh) = (3_u32, 2_u32);
            let samples = (bw * bh) as usize * fast.ns();
            // Varied colours, some empty samples.
            let rgba: Vec<[f32; 4]> = (0..samples)
                .map(|k| {
                    if k % 5 == 0 {
                        [0.0; 4]
                    } else {
                        let v = k as f32 * 0.037;
                        [
                            v.sin().abs(),
                            v.cos().abs(),
                            (0.5 * v).fract(),
                            0.25 + 0.5 * (k % 2) as f32,
                        ]
                    }
                })
                .collect();
            let z: Vec<f32> = (0..samples).map(|k| 1.0 + k as f32).collect();
            let (mut a, mut b) = (Window::new(), Window::new());
            splat(&fast, 7, -3, bw, bh, &rgba, &z, &mut a);
            splat(&general, 7, -3, bw, bh, &rgba, &z, &mut b);
            assert_eq!(a, b, "{n}x{n}");
        }
    }

    #[test]
    fn window_geometry_and_depth() {
        let t = table(FilterKind::Gaussian, 2.0, 2, &Original::default());
        assert_eq!(t.border(), 1);
        let (bw, bh) = (2_u32, 2_u32);
        let ns = t.ns();
        let mut rgba = vec![[0.0_f32; 4]; 4 * ns];
        let mut z = vec![f32::INFINITY; 4 * ns];
        // Pixel (1, 0): one opaque sample at depth 3, another at depth 2 (both visible).
        rgba[ns] = [0.5, 0.5, 0.5, 1.0];
        z[ns] = 3.0;
        rgba[ns + 1] = [0.5, 0.5, 0.5, 1.0];
        z[ns + 1] = 2.0;
        let mut w = Window::new();
        splat(&t, 10, 20, bw, bh, &rgba, &z, &mut w);
        assert_eq!((w.x0, w.y0, w.w, w.h), (9, 19, 4, 4));
        assert_eq!(w.z_at(11, 20), Some(2.0));
        assert_eq!(w.z_at(10, 20), Some(f32::INFINITY));
        assert_eq!(w.z_at(9, 19), Some(f32::INFINITY), "border pixel");
        assert_eq!(w.z_at(8, 19), None);
        // Sample 0 of pixel (1,0) (raster (11,20)) reaches raster (10..=12, 19..=21) only.
        for y in 19..23 {
            for x in 9..13 {
                let p = w.rgba_at(x, y).unwrap_or([f32::NAN; 4]);
                let reachable = (10..=12).contains(&x) && (19..=21).contains(&y);
                let weight_sum: f32 = (0..2)
                    .map(|s| {
                        let (i, j) = (x - 10, y - 19);
                        if reachable { t.sample_weights(s)[(j * 3 + i) as usize] } else { 0.0 }
                    })
                    .sum();
                assert!((p[3] - weight_sum).abs() < 1e-7, "({x},{y}): {p:?} vs {weight_sum}");
                assert!((p[0] - 0.5 * weight_sum).abs() < 1e-7);
            }
        }
        // Re-splatting a smaller bucket into the same window reuses and resizes it.
        let cap = w.rgba.capacity();
        splat(&t, 0, 0, 1, 1, &rgba[..ns], &z[..ns], &mut w);
        assert_eq!((w.w, w.h, w.rgba.len()), (3, 3, 9));
        assert_eq!(w.rgba.capacity(), cap);
        assert!(w.rgba.iter().all(|p| *p == [0.0; 4]));
    }
}
