//! Adaptive sampling, opt-in ([`HiderConfig::adaptive`](crate::HiderConfig::adaptive)): the
//! patent's reduced-scale repetition (US 4,897,806, after FIGS. 5-7: "if image changes or
//! detail within a portion of a sampling area required it, the pattern of sample points can
//! be repeated in such an area portion in reduced scale").
//!
//! After a bucket's NS samples per pixel are resolved, every pixel whose samples disagree
//! ([`disagree`]: some channel of colour or alpha spreads by more than the threshold) is
//! split into its four quadrants, and each quadrant gets the same pattern again at half scale:
//! NS new samples, made by the same generator for a virtual pixel of a grid twice as fine
//! (with a seed of its own per level, so no two levels share samples). A quadrant whose new
//! samples disagree is split again, up to `max_level`.
//!
//! The estimate of a refined pixel uses, for each leaf region of its quadtree, only the NS
//! samples made for that leaf, each standing for `area / NS` of the pixel; the coarser samples
//! that triggered the split are not reused, because mixing them in would weight each leaf by
//! a random count of them (their number in a quarter pixel is not fixed once a stratum is
//! larger than the leaf). Given the quadtree, each leaf's mean is then an unbiased estimate of
//! the image's mean over the leaf (its samples are stratified within it), and the filter sees
//! each sample at its true position with its area as its weight ([`RefinedSample`]). The
//! quadtree itself depends on the samples, which is the one bias every adaptive sampler of
//! this kind has: a pixel whose first NS samples happen to agree keeps them (docs/sampling.md
//! measures its size).
//!
//! Invariants: results depend only on the bucket's inputs (every refined sample is a pure
//! function of the seed, the level and the virtual pixel's global position); refined samples
//! are tested by a plain port of `sample` (every vertex placed at the sample's time and lens
//! position, then the unrolled inside test), not by the sliced scans, so no scan-range
//! invariant is needed for them.

use reyes_csg::{Composite, NIL, Resolver, resolve_sample};
use reyes_sampling::hash;

use super::{Surface, bound};
use crate::inside::inside;
use crate::mpoly::{Micropolygon, flags};
use crate::samples::{BucketSamples, Needs, SampleSpec};
use crate::{Hider, Scratch};

/// Adaptive refinement settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adaptive {
    /// Deepest level of refinement: a leaf of level `L` is `2^-L` of the pixel across.
    pub max_level: u32,
    /// A region is split when some channel (red, green, blue, alpha, premultiplied) of its
    /// samples spreads by more than this (max - min).
    pub threshold: f32,
}

/// One refined sample: bucket-local raster position, the fraction of its pixel's area it
/// stands for, and its composite.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RefinedSample {
    /// Bucket-local raster x.
    pub x: f32,
    /// Bucket-local raster y.
    pub y: f32,
    /// Area of the sample's leaf region over the number of its samples, in pixels.
    pub weight: f32,
    /// Premultiplied colour and alpha.
    pub rgba: [f32; 4],
}

/// The contrast test: do `samples` disagree, i.e. does some channel of colour or alpha spread
/// (largest minus smallest) by more than `threshold`?
pub fn disagree(samples: &[[f32; 4]], threshold: f32) -> bool {
    let Some(first) = samples.first() else { return false };
    let (mut lo, mut hi) = (*first, *first);
    for c in samples {
        for k in 0..4 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    (0..4).any(|k| hi[k] - lo[k] > threshold)
}

/// A sample of a refinement level, as the plain test reads it.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Record {
    x: f32,
    y: f32,
    t: f32,
    lx: f32,
    ly: f32,
}

/// A region of a refined pixel: bucket pixel, and cell `(cx, cy)` of the pixel's `2^L` grid.
#[derive(Debug, Clone, Copy)]
struct Region {
    pixel: u32,
    cx: u32,
    cy: u32,
}

/// Reused buffers of the refinement.
#[derive(Debug, Default, Clone)]
pub(crate) struct RefineScratch {
    pattern: BucketSamples,
    records: Vec<Record>,
    /// `pixel_start[p]..pixel_start[p + 1]`: the level's records in bucket pixel p.
    pixel_start: Vec<u32>,
    todo: Vec<Region>,
    next: Vec<Region>,
    rgba: Vec<[f32; 4]>,
    /// The refined samples of the last bucket, as the film takes them.
    pub(crate) out: Vec<RefinedSample>,
}

impl Hider {
    /// Refine the bucket just sampled and resolved (`scratch.rgba`, `pixel*NS + s`): see the
    /// module comment. Leaves the refined samples in `scratch.refine.out` and zeroes the
    /// colours of the refined pixels' own samples in `scratch.rgba`, which the film then skips.
    pub(crate) fn refine_bucket(
        &self,
        bucket: usize,
        mpolys: &[Micropolygon],
        list: &[u32],
        scratch: &mut Scratch,
    ) {
        let mut rs = std::mem::take(&mut scratch.refine);
        rs.out.clear();
        let Some(ad) = self.config.adaptive.filter(|a| a.max_level > 0) else {
            scratch.refine = rs;
            return;
        };
        let frame = &self.frame;
        let (left, top) = frame.bucket_origin(bucket);
        let (bw, p_count, ns) =
            (frame.bucket_w, frame.pixels_per_bucket(), self.tables.ns as usize);
        rs.todo.clear();
        for pixel in 0..p_count {
            let own = &mut scratch.rgba[pixel * ns..(pixel + 1) * ns];
            if disagree(own, ad.threshold) {
                rs.todo.push(Region { pixel: pixel as u32, cx: 0, cy: 0 });
                own.fill([0.0; 4]);
            }
        }
        scratch.stats.refined_pixels += rs.todo.len() as u64;
        let points_before = scratch.points.len();
        let resolver =
            Resolver { matte: self.config.matte, trees: &self.csg, order: self.config.csg_order };
        for level in 1..=ad.max_level {
            if rs.todo.is_empty() {
                break;
            }
            let spec =
                SampleSpec { seed: hash(self.spec.seed, &[0xada9, level as u64]), ..self.spec };
            let scale = 1.0 / (1u32 << level) as f32;
            // The children of every region to split, in pixel order, NS samples each.
            rs.records.clear();
            rs.pixel_start.clear();
            rs.pixel_start.resize(p_count + 1, 0);
            rs.next.clear();
            for r in &rs.todo {
                for q in 0..4u32 {
                    rs.next.push(Region {
                        pixel: r.pixel,
                        cx: 2 * r.cx + (q & 1),
                        cy: 2 * r.cy + (q >> 1),
                    });
                }
            }
            for c in &rs.next {
                let (px, py) = (c.pixel % bw, c.pixel / bw);
                // The virtual pixel's global position on the level's grid.
                let vx = (((left + px as i32) as i64) << level) + c.cx as i64;
                let vy = (((top + py as i32) as i64) << level) + c.cy as i64;
                let id = hash(spec.seed, &[vx as u64, vy as u64]) as usize;
                rs.pattern.generate(
                    &self.tables,
                    &spec,
                    id,
                    vx as i32,
                    vy as i32,
                    1,
                    1,
                    Needs::ALL,
                );
                for s in 0..ns {
                    rs.records.push(Record {
                        x: px as f32 + (c.cx as f32 + rs.pattern.x[s]) * scale,
                        y: py as f32 + (c.cy as f32 + rs.pattern.y[s]) * scale,
                        t: rs.pattern.t[s],
                        lx: rs.pattern.lx[s],
                        ly: rs.pattern.ly[s],
                    });
                }
                rs.pixel_start[c.pixel as usize + 1] += ns as u32;
            }
            for p in 0..p_count {
                rs.pixel_start[p + 1] += rs.pixel_start[p];
            }
            let base = scratch.heads.len();
            scratch.heads.resize(base + rs.records.len(), NIL);
            for &m in list {
                self.sample_refined((m, &mpolys[m as usize]), (left, top), &rs, base, scratch);
            }
            // Resolve the level's samples.
            let mut lerps = 0;
            rs.rgba.clear();
            for n in base..scratch.heads.len() {
                let head = scratch.heads[n];
                let c = if head == NIL {
                    Composite::EMPTY
                } else {
                    resolve_sample(&mut scratch.points, head, &resolver, &mut lerps)
                };
                rs.rgba.push([c.rgb[0], c.rgb[1], c.rgb[2], c.alpha]);
            }
            scratch.stats.lerps += lerps;
            scratch.stats.extra_samples += rs.records.len() as u64;
            // Split the children that disagree, keep the others as leaves.
            rs.todo.clear();
            let weight = scale * scale / ns as f32;
            for (i, c) in rs.next.iter().enumerate() {
                let own = &rs.rgba[i * ns..(i + 1) * ns];
                if level < ad.max_level && disagree(own, ad.threshold) {
                    rs.todo.push(*c);
                    continue;
                }
                for (s, rgba) in own.iter().enumerate() {
                    let r = &rs.records[i * ns + s];
                    rs.out.push(RefinedSample { x: r.x, y: r.y, weight, rgba: *rgba });
                }
            }
        }
        scratch.stats.peak_points = scratch.stats.peak_points.max(scratch.points.len() as u64);
        scratch.stats.points += (scratch.points.len() - points_before) as u64;
        scratch.refine = rs;
    }

    /// Port of `sample` for one micropolygon against the level's records: every record in the
    /// pixels its bound (over the shutter, grown by the lens) reaches, with the vertices placed
    /// at the record's time (through the perspective warp unless `original_linear_motion`)
    /// and lens position. Hits go to list `base + record index`.
    fn sample_refined(
        &self,
        (index, mp): (u32, &Micropolygon),
        (left, top): (i32, i32),
        rs: &RefineScratch,
        base: usize,
        scratch: &mut Scratch,
    ) {
        let moving = mp.has(flags::MOVING) || !mp.whole_shutter();
        // Bucket-local vertices, as the other paths take them.
        let mut vertex = mp.v;
        for p in vertex.iter_mut() {
            p[0] -= left as f32;
            p[1] -= top as f32;
        }
        let (mut lo, mut hi) = bound(&vertex);
        if moving {
            // Linear or warped, every vertex stays between its ends.
            let end: [[f32; 3]; 4] =
                std::array::from_fn(|j| std::array::from_fn(|a| vertex[j][a] + mp.speed[j][a]));
            let (elo, ehi) = bound(&end);
            for a in 0..3 {
                lo[a] = lo[a].min(elo[a]);
                hi[a] = hi[a].max(ehi[a]);
            }
        }
        let surf = Surface::new(mp, (index, index), &lo, &hi, false);
        let lens = self.config.lens;
        if let Some(l) = &lens {
            l.grow(&mut lo, &mut hi, self.config.hither, self.config.yon);
        }
        let (bw, bh) = (self.frame.bucket_w as i64, self.frame.bucket_h as i64);
        let clamp = |v: f32, n: i64| (v.floor() as i64).clamp(-1, n);
        let (x0, x1) = (clamp(lo[0], bw).max(0), clamp(hi[0], bw).min(bw - 1));
        let (y0, y1) = (clamp(lo[1], bh).max(0), clamp(hi[1], bh).min(bh - 1));
        let [t0, t1] = mp.time;
        let warp = !self.config.original_linear_motion;
        let (mut tests, mut hits) = (0u64, 0u64);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let p = (y * bw + x) as usize;
                for i in rs.pixel_start[p] as usize..rs.pixel_start[p + 1] as usize {
                    let r = &rs.records[i];
                    if r.x < lo[0] || r.x > hi[0] || r.y < lo[1] || r.y > hi[1] {
                        continue;
                    }
                    let mut v = vertex;
                    if moving {
                        if !(r.t >= t0 && r.t < t1) {
                            continue;
                        }
                        let a = (r.t - t0) / (t1 - t0);
                        for (v, d) in v.iter_mut().zip(&mp.speed) {
                            let z = v[2] + a * d[2];
                            let b = if warp && d[2] != 0.0 { a * (v[2] + d[2]) / z } else { a };
                            *v = [v[0] + b * d[0], v[1] + b * d[1], z];
                        }
                    }
                    if let Some(l) = &lens {
                        for v in &mut v {
                            v[0] += r.lx * (l.x_a / v[2] + l.x_b);
                            v[1] += r.ly * (l.y_a / v[2] + l.y_b);
                        }
                    }
                    for v in &mut v {
                        v[0] -= r.x;
                        v[1] -= r.y;
                    }
                    tests += 1;
                    if inside(&v) {
                        hits += self.hit(base + i, &surf, &v, scratch) as u64;
                    }
                }
            }
        }
        scratch.stats.hits += hits;
        scratch.stats.misses += tests - hits;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_contrast_test_looks_at_every_channel() {
        let a = [0.2, 0.2, 0.2, 1.0];
        assert!(!disagree(&[a, a, a], 0.0));
        assert!(!disagree(&[], 0.1));
        for k in 0..4 {
            let mut b = a;
            b[k] -= 0.11;
            assert!(disagree(&[a, b], 0.1), "channel {k}");
            assert!(!disagree(&[a, b], 0.12), "channel {k}");
        }
    }
}
