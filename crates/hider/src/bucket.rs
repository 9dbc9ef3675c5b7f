//! The hider's hot loop: port of `VisEndBucket` and `sample` (Appendix A 2.5, 2.10).
//!
//! For each micropolygon of the bucket, one of three paths (as in Appendix A) tests it
//! against every sample whose scan range its bound reaches:
//! - **P** static, pinhole: vertices translated to the sample;
//! - **D** static, finite aperture: each vertex also shifted by the lens offset over its depth;
//! - **M** moving (with or without lens): vertices moved to the sample's time first, scanning
//!   time slice by time slice with Appendix A's sliding bound (`speedbox / NS`).
//!
//! A sample inside the quad (and, for a hither/yon-crossing quad, with its interpolated depth
//! between hither and yon) gets a visible point pushed on its list. Then every sample's list is
//! resolved front to back (`CSGResolve`). Invariants: nothing here allocates once the scratch
//! buffers have grown to the bucket's needs; results depend only on the bucket's inputs.
//!
//! One loop, [`Bucket::scan`], serves the three paths: they differ only in each slice's box,
//! how they read a row of a slice's samples, and how they place the vertices ([`Place`]);
//! every path is a monomorphised copy of it. Layout for speed (docs/performance.md, "Hider
//! inner loop"): the loop gathers a micropolygon's candidate samples, in scan order, into a
//! [`Batch`] of [`LANES`] on the stack and tests them together with [`inside_mask`] (the
//! unrolled test's exact arithmetic, lane by lane, so the compiler vectorises it); hits go to
//! [`Hider::hit`]. Paths D and M read their samples from [`SliceSamples`], built once per
//! bucket in slice order. The same (sample, micropolygon) pairs are tested as by a plain port,
//! and each sample's list gets its points in the same order, so images and statistics are
//! unchanged bit for bit. The batch, the per-path vertex placements and the lane test are in
//! `bucket/lanes.rs`, the making and resolving of visible points in `bucket/visible.rs`; the
//! loop that drives them is here.

use reyes_csg::{Composite, NIL, Resolver, resolve_sample};

use crate::aov::AovPlan;

use crate::mpoly::{Micropolygon, flags};
use crate::samples::{BucketSamples, Needs};
use crate::{Hider, Scratch};

mod adaptive;
mod lanes;
mod occlusion;
mod slices;
mod visible;
pub(crate) use adaptive::RefineScratch;
pub use adaptive::{Adaptive, RefinedSample, disagree};
use lanes::{
    Batch, Candidate, LANES, MovingSample, PinholeSample, Place, PlaceLens, PlaceMoving,
    PlacePinhole, inside_mask,
};
pub(crate) use occlusion::Occlusion;
pub(crate) use slices::{SliceSample, SliceSamples};
pub use visible::gouraud;

/// Port of `bound`: the x, y, z bounding box of four points. (The original's two-compare
/// sorting network is an optimisation of exactly this.)
#[inline]
fn bound(v: &[[f32; 3]; 4]) -> ([f32; 3], [f32; 3]) {
    let mut lo = v[0];
    let mut hi = v[0];
    for p in &v[1..] {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    (lo, hi)
}

/// Inclusive pixel range (bucket-local) whose samples, lying at pixel + `[rmin, rmax]`, can
/// fall in `[lo, hi]`; empty when `first > last`.
#[inline]
fn pixel_range(lo: f32, hi: f32, rmin: f32, rmax: f32, n: u32) -> (i32, i32) {
    // floor() is a libm call on baseline x86-64; truncation equals floor for the non-negative
    // values that survive the clamp at 0, and a negative upper end means an empty range.
    let last = hi - rmin;
    if last.is_nan() || last < 0.0 {
        return (1, 0);
    }
    let first = (lo - rmax).max(0.0) as i32; // NaN -> 0
    let last = (last as i32).min(n as i32 - 1);
    if first <= last { (first, last) } else { (1, 0) }
}

/// Slack, in pixels, of a moving micropolygon's row spans (against rounding in the bounds).
const ROW_SLACK: f32 = 1.0e-2;

/// The stretch `[a0, a1]` of `[aa, ab]` over which a box whose low edge is `lo + a * m` and
/// high edge `hi + a * big_m` reaches the range `[r_lo, r_hi]`: `lo + a m <= r_hi` and
/// `hi + a M >= r_lo`. `None` if there is none.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn stretch(
    aa: f32,
    ab: f32,
    lo: f32,
    m: f32,
    r_hi: f32,
    hi: f32,
    big_m: f32,
    r_lo: f32,
) -> Option<(f32, f32)> {
    let (mut a0, mut a1) = (aa, ab);
    // lo + a m <= r_hi
    if m > 0.0 {
        a1 = a1.min((r_hi - lo) / m);
    } else if m < 0.0 {
        a0 = a0.max((r_hi - lo) / m);
    } else if lo > r_hi {
        return None;
    }
    // hi + a M >= r_lo
    if big_m > 0.0 {
        a0 = a0.max((r_lo - hi) / big_m);
    } else if big_m < 0.0 {
        a1 = a1.min((r_lo - hi) / big_m);
    } else if hi < r_lo {
        return None;
    }
    // NaN-safe: only a proper (possibly single-point) stretch is kept.
    (a0 <= a1).then_some((a0, a1))
}

/// What one micropolygon contributes to every visible point it creates.
struct Surface<'a> {
    mp: &'a Micropolygon,
    /// Its index in the bucket's micropolygons.
    index: u32,
    zmin: f32,
    zmax: f32,
    crossing: bool,
    /// Its position in the bucket's list (the order its points take in the sample lists).
    order: u32,
    /// Occlusion culling: its candidate samples may be skipped where an occluder is nearer
    /// than `zmin`, and its points are occluders (`bucket/occlusion.rs`).
    cull: bool,
    occluder: bool,
}

impl<'a> Surface<'a> {
    /// Micropolygon `mp` (its index in `mpolys` and its position in the bucket's list) with
    /// the depth range of the bound `lo..hi`; with `occlusion`, culled and culling.
    #[inline]
    fn new(
        mp: &'a Micropolygon,
        (index, order): (u32, u32),
        lo: &[f32; 3],
        hi: &[f32; 3],
        occlusion: bool,
    ) -> Surface<'a> {
        Surface {
            mp,
            index,
            zmin: lo[2],
            zmax: hi[2],
            crossing: mp.has(flags::HITHER_YON_CROSSING),
            order,
            cull: occlusion && occlusion::cullable(mp),
            occluder: occlusion && occlusion::occluder(mp),
        }
    }
}

/// What every path needs for one bucket: the hider's tables and configuration, the bucket's
/// samples (as generated and in slice order), its size, and the scratch that receives the
/// visible points and the statistics.
struct Bucket<'a> {
    hider: &'a Hider,
    smp: &'a BucketSamples,
    slices: &'a SliceSamples,
    /// Samples per pixel (`NS`): also the number of slices of every path.
    ns: usize,
    /// Bucket size in pixels, and the pixel count `bw * bh`.
    bw: u32,
    bh: u32,
    p_count: usize,
    scratch: &'a mut Scratch,
}

impl Hider {
    /// Port of `VisEndBucket` up to `CSGResolve`: sample every micropolygon of the bucket
    /// (`list` indexes `mpolys`) and resolve each sample. Leaves per-sample composites in
    /// `scratch.rgba` / `scratch.z`, indexed `pixel*NS + s`.
    pub(crate) fn sample_bucket(
        &self,
        bucket: usize,
        mpolys: &[Micropolygon],
        list: &[u32],
        scratch: &mut Scratch,
        aov: Option<(&AovPlan, &[f32])>,
    ) {
        let frame = &self.frame;
        let (left, top) = frame.bucket_origin(bucket);
        let (bw, bh) = (frame.bucket_w, frame.bucket_h);
        let p_count = frame.pixels_per_bucket();
        let ns = self.tables.ns as usize;
        let n = p_count * ns;
        scratch.heads.clear();
        scratch.heads.resize(n, NIL);
        scratch.points.clear();
        scratch.point_mp.clear();
        scratch.keep_mp = aov.is_some();
        let mut samples = std::mem::take(&mut scratch.samples);
        // Times are read only by path M, lens positions only with a lens.
        let needs = Needs {
            time: list.iter().any(|&m| {
                let mp = &mpolys[m as usize];
                mp.has(flags::MOVING) || !mp.whole_shutter()
            }),
            lens: self.config.lens.is_some(),
        };
        samples.generate(&self.tables, &self.spec, bucket, left, top, bw, bh, needs);
        let static_lens = needs.lens
            && list.iter().any(|&m| {
                let mp = &mpolys[m as usize];
                !mp.has(flags::MOVING) && mp.whole_shutter()
            });
        let mut slices = std::mem::take(&mut scratch.slices);
        slices.build(&samples, self.config.lens, (needs.time, static_lens), ns, p_count);
        let t_sample = std::time::Instant::now();
        // Occlusion culling samples front to back (`bucket/occlusion.rs`); without it, in
        // the list's order.
        let cull = self.config.occlusion_cull;
        scratch.occlusion.begin(cull, (p_count, ns), mpolys, list);
        let order = std::mem::take(&mut scratch.occlusion.order);
        let mut b =
            Bucket { hider: self, smp: &samples, slices: &slices, ns, bw, bh, p_count, scratch };
        let reach = b.reach();
        // `order` is filled only when culling: the list's own order otherwise.
        #[allow(clippy::needless_range_loop)]
        for k in 0..list.len() {
            let pos = if cull { order[k].1 } else { k as u32 };
            let m = list[pos as usize];
            let mp = &mpolys[m as usize];
            b.scratch.stats.micropolygons += 1;
            let mut vertex = mp.v;
            for p in vertex.iter_mut() {
                p[0] -= left as f32;
                p[1] -= top as f32;
            }
            let (lo, hi) = bound(&vertex);
            if cull && b.occluded(mp, lo, hi, reach) {
                b.scratch.stats.occlusion_culled += 1;
                continue;
            }

            let surface_z = |lo: [f32; 3], hi: [f32; 3]| Surface::new(mp, (m, pos), &lo, &hi, cull);
            if mp.has(flags::MOVING) || !mp.whole_shutter() {
                b.path_moving(mp, (m, pos), &vertex, lo, hi);
            } else if self.config.lens.is_some() {
                b.path_lens(&surface_z(lo, hi), &vertex, lo, hi);
            } else {
                b.path_pinhole(&surface_z(lo, hi), &vertex, lo, hi);
            }
        }
        scratch.occlusion.order = order;
        // Adaptive refinement samples in list order, without culling.
        scratch.occlusion.on = false;
        scratch.stats.peak_points = scratch.stats.peak_points.max(scratch.points.len() as u64);
        scratch.stats.points += scratch.points.len() as u64;
        let t_resolve = std::time::Instant::now();
        scratch.stats.sample_ns += (t_resolve - t_sample).as_nanos() as u64;
        // CSGResolve: every sample, front to back.
        scratch.rgba.clear();
        scratch.rgba.resize(n, [0.0; 4]);
        scratch.z.clear();
        scratch.z.resize(n, 0.0);
        let mut lerps = 0;
        let resolver =
            Resolver { matte: self.config.matte, trees: &self.csg, order: self.config.csg_order };
        if let Some((plan, data)) = aov {
            self.resolve_aovs(plan, (mpolys, data), &resolver, &mut lerps, scratch);
        } else {
            let out = scratch.rgba.iter_mut().zip(scratch.z.iter_mut());
            for ((rgba, z), &head) in out.zip(&scratch.heads) {
                let c = if head == NIL {
                    Composite::EMPTY
                } else {
                    resolve_sample(&mut scratch.points, head, &resolver, &mut lerps)
                };
                *rgba = [c.rgb[0], c.rgb[1], c.rgb[2], c.alpha];
                *z = c.z;
            }
        }
        scratch.stats.lerps += lerps;
        scratch.stats.resolve_ns += t_resolve.elapsed().as_nanos() as u64;
        scratch.samples = samples;
        scratch.slices = slices;
    }
}

impl Bucket<'_> {
    /// Where any sample of the bucket can lie: the union of every slice's reach (offsets
    /// from the pixel corner), and the largest lens offset along x and y (0 for a pinhole).
    fn reach(&self) -> ([f32; 4], [f32; 2]) {
        let mut r = [f32::INFINITY, f32::NEG_INFINITY, f32::INFINITY, f32::NEG_INFINITY];
        for s in &self.smp.reach_space[..self.ns] {
            r = [r[0].min(s[0]), r[1].max(s[1]), r[2].min(s[2]), r[3].max(s[3])];
        }
        let mut l = [0.0f32; 2];
        if self.hider.config.lens.is_some() {
            for s in &self.smp.lens_range[..self.ns] {
                l = [l[0].max(s[0].abs()).max(s[1].abs()), l[1].max(s[2].abs()).max(s[3].abs())];
            }
        }
        (r, l)
    }

    /// Occlusion culling of a whole micropolygon (bucket-local bound `lo..hi` at shutter
    /// open): true if every sample it could touch, over its shutter segment and the lens,
    /// already has an opaque surface strictly nearer than the nearest depth it can have
    /// there. The box is the union of the boxes every path scans: path M's slice boxes lie
    /// within the bound plus the motion's range (the warp keeps its parameter in [0, 1]),
    /// and the lens shifts by at most the largest lens offset times the circle of confusion
    /// at an end of the clamped depth range (as `bounddof`).
    fn occluded(
        &self,
        mp: &Micropolygon,
        mut lo: [f32; 3],
        mut hi: [f32; 3],
        (reach, lens_max): ([f32; 4], [f32; 2]),
    ) -> bool {
        if !occlusion::cullable(mp) {
            return false;
        }
        if mp.has(flags::MOVING) || !mp.whole_shutter() {
            let (slo, shi) = bound(&mp.speed);
            for a in 0..3 {
                lo[a] += slo[a].min(0.0);
                hi[a] += shi[a].max(0.0);
            }
        }
        let zmin = lo[2];
        let config = &self.hider.config;
        if let Some(l) = &config.lens {
            let z0 = lo[2].max(config.hither);
            let z1 = hi[2].min(config.yon).max(z0);
            let (x0, y0) = l.coc(z0);
            let (x1, y1) = l.coc(z1);
            let bx = x0.abs().max(x1.abs()) * lens_max[0];
            let by = y0.abs().max(y1.abs()) * lens_max[1];
            lo[0] -= bx;
            hi[0] += bx;
            lo[1] -= by;
            hi[1] += by;
        }
        let (xs, ys) = if config.scan_all {
            ((0, self.bw as i32 - 1), (0, self.bh as i32 - 1))
        } else {
            (
                pixel_range(lo[0], hi[0], reach[0], reach[1], self.bw),
                pixel_range(lo[1], hi[1], reach[2], reach[3], self.bh),
            )
        };
        if xs.0 > xs.1 || ys.0 > ys.1 {
            return false;
        }
        self.scratch.occlusion.covered(xs, ys, self.bw, zmin)
    }

    /// The loop of `VisEndBucket` every path runs for one micropolygon (Appendix A 2.5). For
    /// each slice `k` of the path (sample index `s`, lens stratum `lambda` or time slice `tau`):
    /// the micropolygon's box over the slice, `slice_box(k)` = `[x lo, x hi, y lo, y hi]`
    /// (`None`: it exists at no time of the slice), and the reach of the slice's samples,
    /// `reach[k]`, give the pixels to scan, row by row, each row's span narrowed by
    /// `row_span(k, y, span)` (the identity but for a moving micropolygon, whose box within a
    /// slice is crossed row by row); `rows(k)` reads the slice's samples and
    /// `rows(k)(first, last)` yields the candidates of pixels `first..=last` in pixel order.
    /// Each candidate is `sample`d (2.10): gathered into a batch, tested [`LANES`] at a time,
    /// and on a hit pushed as a visible point, in the same order ([`Bucket::drain`]).
    #[inline(always)]
    fn scan<C: Candidate, I: Iterator<Item = C>, R: FnMut(usize, usize) -> I>(
        &mut self,
        place: &impl Place,
        surf: &Surface,
        reach: &[[f32; 4]],
        mut slice_box: impl FnMut(usize) -> Option<[f32; 4]>,
        mut row_span: impl FnMut(usize, usize, (i32, i32)) -> (i32, i32),
        mut rows: impl FnMut(usize) -> R,
    ) {
        // Locals rather than loads through `self` in the loop (measured: fewer instructions).
        let (ns, bw, bh, scan_all) = (self.ns, self.bw, self.bh, self.hider.config.scan_all);
        // Scan range of one axis, or the whole bucket when bound culling is off.
        let pixels = |lo, hi, rmin, rmax, n: u32| {
            if scan_all { (0, n as i32 - 1) } else { pixel_range(lo, hi, rmin, rmax, n) }
        };
        let mut b = Batch::new();
        let mut skipped = 0;
        for (k, r) in reach[..ns].iter().enumerate() {
            let Some([bx0, bx1, by0, by1]) = slice_box(k) else { continue };
            let (x0, x1) = pixels(bx0, bx1, r[0], r[1], bw);
            let (y0, y1) = pixels(by0, by1, r[2], r[3], bh);
            if x0 > x1 || y0 > y1 {
                continue;
            }
            let mut row = rows(k);
            for y in y0 as usize..=y1 as usize {
                let (x0, x1) = if scan_all { (x0, x1) } else { row_span(k, y, (x0, x1)) };
                if x0 > x1 {
                    continue;
                }
                let row_start = y * bw as usize;
                for c in row(row_start + x0 as usize, row_start + x1 as usize) {
                    // Behind an opaque surface at this sample: it cannot be seen there.
                    if surf.cull && surf.zmin > self.scratch.occlusion.depth[c.n()] {
                        skipped += 1;
                        continue;
                    }
                    c.append(&mut b);
                    if b.full() {
                        self.drain(&mut b, place, surf, false);
                    }
                }
            }
        }
        self.drain(&mut b, place, surf, true);
        self.scratch.stats.hits += b.hits;
        self.scratch.stats.misses += b.tests - b.hits;
        self.scratch.stats.occluded_tests += skipped;
    }

    /// Test the batch's entries against the micropolygon, [`LANES`] at a time, and push a
    /// visible point for each hit, in entry order (the order the samples were gathered). With
    /// `all`, every entry; otherwise only whole batches, the rest moving to the front.
    #[inline(always)]
    fn drain(&mut self, b: &mut Batch, place: &impl Place, surf: &Surface, all: bool) {
        let end = if all { b.fill.div_ceil(LANES) } else { b.fill / LANES } * LANES;
        // NaN positions past the entries (never inside: every vertex counts as "down").
        for i in b.fill..end {
            b.x[i] = f32::NAN;
            b.y[i] = f32::NAN;
        }
        for base in (0..end).step_by(LANES) {
            let (x, y) = place.lanes(b, base);
            let mut mask = inside_mask(&x, &y);
            while mask != 0 {
                let i = base + mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let v = place.one(b, i);
                b.hits += self.hider.hit(b.n[i] as usize, surf, &v, self.scratch) as u64;
            }
        }
        let tested = end.min(b.fill);
        b.tests += tested as u64;
        let rest = b.fill - tested;
        for i in 0..rest {
            b.x[i] = b.x[tested + i];
            b.y[i] = b.y[tested + i];
            b.ax[i] = b.ax[tested + i];
            b.ay[i] = b.ay[tested + i];
            b.alpha[i] = b.alpha[tested + i];
            b.n[i] = b.n[tested + i];
        }
        b.fill = rest;
    }

    /// Path P: static micropolygon, pinhole camera: the vertices translated to each sample.
    /// Sample `s` of pixel `p` is `smp.x[p*NS + s]`, its list index too.
    // Inlined into `sample_bucket`, as LLVM did by itself before `scan` was shared: out of
    // line it ran 1-2% more instructions per bucket.
    #[inline(always)]
    fn path_pinhole(&mut self, surf: &Surface, vertex: &[[f32; 3]; 4], lo: [f32; 3], hi: [f32; 3]) {
        let (smp, ns, p_count) = (self.smp, self.ns, self.p_count);
        let place = PlacePinhole {
            vx: vertex.map(|p| p[0]),
            vy: vertex.map(|p| p[1]),
            vz: vertex.map(|p| p[2]),
        };
        let slice_box = |_| Some([lo[0], hi[0], lo[1], hi[1]]);
        let (xs, ys) = (&smp.x[..p_count * ns], &smp.y[..p_count * ns]);
        let rows = |s: usize| {
            move |first, last| {
                let pixels = first..=last;
                pixels.map(move |p| {
                    let n = p * ns + s;
                    PinholeSample { x: xs[n], y: ys[n], n }
                })
            }
        };
        self.scan(&place, surf, &smp.reach_space, slice_box, |_, _, span| span, rows);
    }

    /// Path D: static micropolygon, finite aperture. Each vertex moves by
    /// `l * (Dof_a / z + Dof_b)`; the depth-independent `l * Dof_b` is folded into the sample.
    ///
    /// Appendix A scans the whole `bounddof` box for every sample index. Here, as path M does
    /// for time, the samples are taken lens stratum by lens stratum: stratum `lambda`'s samples
    /// have lens positions in `lens_range[lambda]`, so the micropolygon can only be displaced
    /// by `l * c(z)` with `l` in that range and `c(z) = Dof_a/z + Dof_b` over its depth range,
    /// and the box is grown by exactly that. The same samples are tested for a hit; only
    /// samples that cannot hit are skipped (checked against `scan_all` in the tests).
    // Inlined into `sample_bucket`, as LLVM did by itself before `scan` was shared: out of
    // line it ran 1-2% more instructions per bucket.
    #[inline(always)]
    fn path_lens(&mut self, surf: &Surface, vertex: &[[f32; 3]; 4], lo: [f32; 3], hi: [f32; 3]) {
        let config = &self.hider.config;
        let Some(lens) = config.lens else { return };
        let (smp, slices, p_count) = (self.smp, self.slices, self.p_count);
        let inv_z = vertex.map(|p| 1.0 / p[2]);
        // Range of the displacement per unit lens offset over the depth range (clamped to
        // hither/yon as bounddof does); monotone in 1/z, so the ends hold the extremes.
        let (z0, z1) =
            (lo[2].max(config.hither), hi[2].min(config.yon).max(lo[2].max(config.hither)));
        let (cx0, cy0) = lens.coc(z0);
        let (cx1, cy1) = lens.coc(z1);
        let (cx_lo, cx_hi) = (cx0.min(cx1), cx0.max(cx1));
        let (cy_lo, cy_hi) = (cy0.min(cy1), cy0.max(cy1));
        let place = PlaceLens {
            vx: vertex.map(|p| p[0]),
            vy: vertex.map(|p| p[1]),
            vz: vertex.map(|p| p[2]),
            inv_z,
        };
        let slice_box = |lambda: usize| {
            let lr = smp.lens_range[lambda];
            let px = [lr[0] * cx_lo, lr[0] * cx_hi, lr[1] * cx_lo, lr[1] * cx_hi];
            let py = [lr[2] * cy_lo, lr[2] * cy_hi, lr[3] * cy_lo, lr[3] * cy_hi];
            let (dx0, dx1) = (
                px.iter().copied().fold(f32::INFINITY, f32::min),
                px.iter().copied().fold(f32::NEG_INFINITY, f32::max),
            );
            let (dy0, dy1) = (
                py.iter().copied().fold(f32::INFINITY, f32::min),
                py.iter().copied().fold(f32::NEG_INFINITY, f32::max),
            );
            Some([lo[0] + dx0, hi[0] + dx1, lo[1] + dy0, hi[1] + dy1])
        };
        let (recs, ns) = (&slices.by_lens[..p_count * self.ns], self.ns);
        let rows =
            |lambda: usize| move |first, last| (first..=last).map(move |p| &recs[p * ns + lambda]);
        self.scan(&place, surf, &smp.reach_lens, slice_box, |_, _, span| span, rows);
    }

    /// Path M: moving micropolygon (with the lens if there is one). Time slice `tau` holds one
    /// sample per pixel with time in `[ta, tb]` (`slice_times`). Within the micropolygon's
    /// shutter segment `[t0, t1]` a vertex is at `v + a * speed` with `a = (t - t0)/(t1 - t0)`,
    /// so over the slice its box is the start box plus `[min(a_a m, a_b m), max(a_a M, a_b M)]`
    /// per axis (m, M: smallest and largest speed component). For a uniform shutter and a whole
    /// segment that is exactly Appendix A's box slid by `speedbox / NS` per slice (3.5).
    fn path_moving(
        &mut self,
        mp: &Micropolygon,
        index: (u32, u32),
        vertex: &[[f32; 3]; 4],
        mut lo: [f32; 3],
        mut hi: [f32; 3],
    ) {
        let (hider, smp, slices, p_count) = (self.hider, self.smp, self.slices, self.p_count);
        let (slo, shi) = bound(&mp.speed);
        // z range over the whole segment: the visible points' depth range.
        lo[2] += slo[2].min(0.0);
        hi[2] += shi[2].max(0.0);
        let surf = Surface::new(mp, index, &lo, &hi, hider.config.occlusion_cull);
        let lens = hider.config.lens;
        if let Some(l) = &lens {
            l.grow(&mut lo, &mut hi, hider.config.hither, hider.config.yon);
        }
        let [t0, t1] = mp.time;
        // An empty (or NaN) segment exists at no time.
        if t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        let inv_len = 1.0 / (t1 - t0);
        let warp = Warp::new(mp, !hider.config.original_linear_motion);
        let slice_box = |tau: usize| {
            let [ta, tb] = hider.slice_times[tau];
            if tb < t0 || ta >= t1 {
                return None;
            }
            let aa = (ta.max(t0) - t0) * inv_len;
            let ab = (tb.min(t1) - t0) * inv_len;
            let (aa, ab) = warp.range(aa, ab);
            Some([
                lo[0] + (aa * slo[0]).min(ab * slo[0]),
                hi[0] + (aa * shi[0]).max(ab * shi[0]),
                lo[1] + (aa * slo[1]).min(ab * slo[1]),
                hi[1] + (aa * shi[1]).max(ab * shi[1]),
            ])
        };
        // Within a slice the box slides with `a` in `[aa, ab]`: row `y`'s samples, at
        // `y + [reach lo, reach hi]`, can only meet it while its y extent
        // `[lo + a m, hi + a M]` reaches them, and only where its x extent is over that
        // stretch of `a`. For a fast micropolygon that is a short run of each row, not the
        // whole slice box (which is as long as a slice's motion). Conservative by
        // `ROW_SLACK` pixels, so no sample that can hit is skipped.
        let reach = &smp.reach_time;
        let bw = self.bw;
        let row_span = |tau: usize, y: usize, span: (i32, i32)| {
            if !warp.narrows() {
                return span;
            }
            let [ta, tb] = hider.slice_times[tau];
            let aa = (ta.max(t0) - t0) * inv_len;
            let ab = (tb.min(t1) - t0) * inv_len;
            let (aa, ab) = warp.range(aa, ab);
            let r = &reach[tau];
            let (y_lo, y_hi) = (y as f32 + r[2] - ROW_SLACK, y as f32 + r[3] + ROW_SLACK);
            let Some((a0, a1)) = stretch(aa, ab, lo[1], slo[1], y_hi, hi[1], shi[1], y_lo) else {
                return (1, 0);
            };
            let x_lo = lo[0] + (a0 * slo[0]).min(a1 * slo[0]) - ROW_SLACK;
            let x_hi = hi[0] + (a0 * shi[0]).max(a1 * shi[0]) + ROW_SLACK;
            let (x0, x1) = pixel_range(x_lo, x_hi, r[0], r[1], bw);
            (x0.max(span.0), x1.min(span.1))
        };
        let (recs, ns) = (&slices.by_time[..p_count * self.ns], self.ns);
        let rows = |tau: usize| {
            move |first, last| {
                // Outside this micropolygon's segment: not tested.
                let in_segment = (first..=last)
                    .map(move |p| -> &SliceSample { &recs[p * ns + tau] })
                    .filter(move |r| !(r.t < t0 || r.t >= t1));
                in_segment.map(move |r| MovingSample { r, alpha: (r.t - t0) * inv_len })
            }
        };
        let (v, speed) = (transpose(vertex), transpose(&mp.speed));
        let z1 = std::array::from_fn(|j| mp.v[j][2] + mp.speed[j][2]);
        match (lens.is_some(), warp.on) {
            (true, false) => {
                let place = PlaceMoving::<true, false> { v, speed, z1 };
                self.scan(&place, &surf, &smp.reach_time, slice_box, row_span, rows);
            }
            (false, false) => {
                let place = PlaceMoving::<false, false> { v, speed, z1 };
                self.scan(&place, &surf, &smp.reach_time, slice_box, row_span, rows);
            }
            (true, true) => {
                let place = PlaceMoving::<true, true> { v, speed, z1 };
                self.scan(&place, &surf, &smp.reach_time, slice_box, row_span, rows);
            }
            (false, true) => {
                let place = PlaceMoving::<false, true> { v, speed, z1 };
                self.scan(&place, &surf, &smp.reach_time, slice_box, row_span, rows);
            }
        }
    }
}

/// Path M's perspective-correct time warp (Appendix A's `ALPHABETA`) for one micropolygon,
/// as its bounds see it. Vertex `j` has made the fraction `beta_j(alpha) = alpha / (alpha +
/// (1 - alpha) r_j)` of its raster displacement at `alpha`, with `r_j = z0/z1` its depth ratio
/// over the segment (1 for a vertex whose depth does not change). Each `beta_j` increases
/// with `alpha` and decreases with `r_j`, so over `[aa, ab]` every vertex's `beta` lies in
/// `[beta(aa; r_max), beta(ab; r_min)]`, and since every `beta` is in `[0, 1]`, the box
/// `lo + beta * [min speed, max speed]` over that range holds the micropolygon: the bounds
/// stay conservative. The row spans of path M assume one parameter for all four vertices,
/// which holds only if every `r_j` is the same; otherwise rows are not narrowed.
#[derive(Debug, Clone, Copy)]
struct Warp {
    /// Some vertex's depth changes and the warp is asked for.
    on: bool,
    r_min: f32,
    r_max: f32,
}

impl Warp {
    /// Relative slack on the warped range, against the rounding of `alpha z1 / z` in the
    /// sample test versus `alpha / (alpha + (1 - alpha) r)` here.
    const SLACK: f32 = 1.0e-6;

    fn new(mp: &Micropolygon, perspective: bool) -> Warp {
        let (mut r_min, mut r_max) = (f32::INFINITY, f32::NEG_INFINITY);
        let mut on = false;
        for j in 0..4 {
            let dz = mp.speed[j][2];
            let r = if dz == 0.0 { 1.0 } else { mp.v[j][2] / (mp.v[j][2] + dz) };
            on |= dz != 0.0;
            r_min = r_min.min(r);
            r_max = r_max.max(r);
        }
        Warp { on: on && perspective, r_min, r_max }
    }

    fn beta(a: f32, r: f32) -> f32 {
        a / (a + (1.0 - a) * r)
    }

    /// The range of every vertex's `beta` over `alpha` in `[aa, ab]` (the identity when off).
    #[inline]
    fn range(&self, aa: f32, ab: f32) -> (f32, f32) {
        if !self.on {
            return (aa, ab);
        }
        let lo = Warp::beta(aa, self.r_max) - Warp::SLACK;
        let hi = Warp::beta(ab, self.r_min) + Warp::SLACK;
        // NaN-safe: 0/0 at alpha = 0 cannot happen (r > 0), but keep the ends in [0, 1].
        (lo.max(0.0), hi.min(1.0))
    }

    /// Whether path M's row spans may treat the four vertices as one parameter.
    #[inline]
    fn narrows(&self) -> bool {
        !self.on || self.r_min == self.r_max
    }
}

/// Rows of a 4-vertex array as columns: `out[a][j] = v[j][a]`.
fn transpose(v: &[[f32; 3]; 4]) -> [[f32; 4]; 3] {
    let mut out = [[0.0; 4]; 3];
    for (a, row) in out.iter_mut().enumerate() {
        *row = [v[0][a], v[1][a], v[2][a], v[3][a]];
    }
    out
}
