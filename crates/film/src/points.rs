//! Samples at their true positions with their own weights: adaptive sampling's refined
//! samples (`reyes_hider::RefinedSample`), added to a bucket window that [`crate::splat`] has
//! just filled.
//!
//! A table sample stands for `1/NS` of its pixel and is weighed at its stratum's centre
//! (Appendix A). A refined sample stands for `area` of its pixel (its leaf region's area over
//! its number of samples) and is weighed at its own position: `kernel(p - c) * area * NS /
//! sum`, on the scale of the table's entries ([`FilterTable::weight_at`]). Since each refined
//! sample is uniform within a region of exactly that area, its expected contribution is the
//! filter's integral over the region, so a refined pixel's value estimates the filtered image
//! without bias for any kernel (for the one-pixel box, the plain area-weighted mean).
//!
//! Invariant (determinism): points are added in the order given, each point's terms summed in
//! `f64` per window pixel and rounded once into the window.

use crate::table::FilterTable;
use crate::window::Window;

/// Add `points` (bucket-local raster position, area weight, premultiplied RGBA) to `out`, the
/// window [`crate::splat`] made for the same bucket and table.
pub fn splat_points(
    table: &FilterTable,
    points: impl IntoIterator<Item = ([f32; 2], f32, [f32; 4])>,
    out: &mut Window,
) {
    let b = table.border() as i64;
    let (ww, wh) = (out.w as i64, out.h as i64);
    // Window pixels whose centre is within the larger half-width (plus one) of the point.
    let reach = (0.5 * table.width().max(table.height())).ceil() as i64 + 1;
    for ([x, y], area, rgba) in points {
        if rgba.iter().all(|&v| v == 0.0) {
            continue;
        }
        let (wx, wy) = ((x.floor() as i64) + b, (y.floor() as i64) + b);
        if table.box_fast() {
            // One-pixel box: all of the sample goes to its own pixel (as `applyboxfilter`),
            // never to a neighbour it touches on a pixel edge.
            if (0..ww).contains(&wx) && (0..wh).contains(&wy) {
                let dst = &mut out.rgba[(wy * ww + wx) as usize];
                for k in 0..4 {
                    dst[k] = (f64::from(dst[k]) + f64::from(area) * f64::from(rgba[k])) as f32;
                }
            }
            continue;
        }
        for py in (wy - reach).max(0)..=(wy + reach).min(wh - 1) {
            for px in (wx - reach).max(0)..=(wx + reach).min(ww - 1) {
                // Window pixel (px, py) is bucket pixel (px - b, py - b).
                let dx = x - ((px - b) as f32 + 0.5);
                let dy = y - ((py - b) as f32 + 0.5);
                let f = table.weight_at(dx, dy, area);
                if f == 0.0 {
                    continue;
                }
                let dst = &mut out.rgba[(py * ww + px) as usize];
                for k in 0..4 {
                    dst[k] = (f64::from(dst[k]) + f * f64::from(rgba[k])) as f32;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::splat;
    use reyes_scene::{FilterKind, Original};

    fn grid(n: u32) -> Vec<[f32; 2]> {
        // Any one-to-one stratum order will do for these tests.
        (0..n * n).map(|q| [(q / n) as f32 / n as f32, (q % n) as f32 / n as f32]).collect()
    }

    #[test]
    fn a_point_at_a_stratum_centre_weighs_as_the_table_does() {
        // The same sample through the table and as a point of area 1/NS: the same window.
        let n = 2;
        for (kind, width) in
            [(FilterKind::Gaussian, 2.0), (FilterKind::Box, 1.0), (FilterKind::RiCatmullRom, 3.0)]
        {
            let t = FilterTable::new(kind, width, n, n, &grid(n), &Original::default()).unwrap();
            let (bw, bh) = (3u32, 2u32);
            let ns = (n * n) as usize;
            let mut rgba = vec![[0.0f32; 4]; (bw * bh) as usize * ns];
            // Sample s = 3 of bucket pixel (1, 1): stratum corner (0.5, 0.5), centre (0.75, 0.75).
            rgba[(bw as usize + 1) * ns + 3] = [0.25, 0.5, 1.0, 1.0];
            let z = vec![1.0f32; rgba.len()];
            let mut by_table = Window::new();
            splat(&t, 0, 0, bw, bh, &rgba, &z, &mut by_table);
            let mut by_point = Window::new();
            splat(&t, 0, 0, bw, bh, &vec![[0.0; 4]; rgba.len()], &z, &mut by_point);
            let point = ([1.75f32, 1.75], 0.25f32, [0.25f32, 0.5, 1.0, 1.0]);
            splat_points(&t, [point], &mut by_point);
            for (a, b) in by_table.rgba.iter().zip(&by_point.rgba) {
                for k in 0..4 {
                    assert!((a[k] - b[k]).abs() < 1e-6, "{kind:?}: {a:?} vs {b:?}");
                }
            }
        }
    }

    #[test]
    fn area_weights_of_a_whole_pixel_sum_to_its_value() {
        // Points of total area 1 and colour 1 in one pixel: unit gain there through a
        // one-pixel box, nothing in its neighbour.
        let t =
            FilterTable::new(FilterKind::Box, 1.0, 2, 2, &grid(2), &Original::default()).unwrap();
        let mut w = Window::new();
        splat(&t, 0, 0, 2, 2, &[[0.0; 4]; 16], &[1.0; 16], &mut w);
        let pts = (0..64).map(|i| {
            ([1.0 + (i % 8) as f32 / 8.0 + 0.01, (i / 8) as f32 / 8.0 + 0.01], 1.0 / 64.0, [1.0; 4])
        });
        splat_points(&t, pts, &mut w);
        assert!((w.rgba[1][3] - 1.0).abs() < 1e-6 && w.rgba[0][3] == 0.0, "{:?}", w.rgba);
    }
}
