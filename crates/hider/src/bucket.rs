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

use reyes_csg::{
    Composite, LERP_DONE, NIL, Resolver, VisPoint, lerpz, resolve_sample, shepard_weights,
};

use crate::inside::inside;
use crate::mpoly::{Micropolygon, flags};
use crate::samples::{BucketSamples, Needs};
use crate::{Hider, Scratch};

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
fn scan(lo: f32, hi: f32, rmin: f32, rmax: f32, n: u32) -> (i32, i32) {
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

/// What one micropolygon contributes to every visible point it creates.
struct Surface<'a> {
    mp: &'a Micropolygon,
    zmin: f32,
    zmax: f32,
    crossing: bool,
}

impl Hider {
    /// Scan range of one axis, or the whole bucket when bound culling is off.
    #[inline]
    fn scan(&self, lo: f32, hi: f32, rmin: f32, rmax: f32, n: u32) -> (i32, i32) {
        if self.config.scan_all { (0, n as i32 - 1) } else { scan(lo, hi, rmin, rmax, n) }
    }

    /// Port of `sample`: test one sample (at the origin of `v`) against a micropolygon and
    /// push a visible point on list `nsample` if it is hit.
    #[inline(always)]
    fn sample(&self, nsample: usize, s: &Surface, v: &[[f32; 3]; 4], scratch: &mut Scratch) {
        if s.crossing && self.config.original_moving_clip && s.mp.has(flags::MOVING) {
            // Appendix A: a moving micropolygon straddling hither or yon at this sample's time
            // is rejected outright instead of clipped (appendix-a.md 3.6).
            let zlo = v[0][2].min(v[1][2]).min(v[2][2]).min(v[3][2]);
            let zhi = v[0][2].max(v[1][2]).max(v[2][2]).max(v[3][2]);
            if zlo < self.config.hither || zhi > self.config.yon {
                scratch.stats.misses += 1;
                return;
            }
        }
        if !inside(v) {
            scratch.stats.misses += 1;
            return;
        }
        let (minz, maxz, lerped) = if s.crossing {
            let z = lerpz(v);
            scratch.stats.lerps += 1;
            if !(z >= self.config.hither && z <= self.config.yon) {
                scratch.stats.misses += 1;
                return;
            }
            (z, z, LERP_DONE)
        } else {
            (s.zmin, s.zmax, 0)
        };
        let mp = s.mp;
        let (color, trans) =
            if mp.has(flags::GOURAUD) { gouraud(v, mp) } else { (mp.color[0], mp.trans[0]) };
        let index = scratch.points.len() as u32;
        scratch.points.push(VisPoint {
            v: *v,
            minz,
            maxz,
            color,
            trans,
            flags: (mp.flags & !LERP_DONE) | lerped,
            csg_tree: mp.csg_tree,
            csg_node: mp.csg_node,
            glass_opacity: mp.glass_opacity,
            next: scratch.heads[nsample],
        });
        scratch.heads[nsample] = index;
        scratch.stats.hits += 1;
    }

    /// Port of `VisEndBucket` up to `CSGResolve`: sample every micropolygon of the bucket
    /// (`list` indexes `mpolys`) and resolve each sample. Leaves per-sample composites in
    /// `scratch.rgba` / `scratch.z`, indexed `pixel*NS + s`.
    pub(crate) fn sample_bucket(
        &self,
        bucket: usize,
        mpolys: &[Micropolygon],
        list: &[u32],
        scratch: &mut Scratch,
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
        let t_sample = std::time::Instant::now();
        for &m in list {
            let mp = &mpolys[m as usize];
            scratch.stats.micropolygons += 1;
            let mut vertex = mp.v;
            for p in vertex.iter_mut() {
                p[0] -= left as f32;
                p[1] -= top as f32;
            }
            let (lo, hi) = bound(&vertex);

            let surface_z = |lo: [f32; 3], hi: [f32; 3]| Surface {
                mp,
                zmin: lo[2],
                zmax: hi[2],
                crossing: mp.has(flags::HITHER_YON_CROSSING),
            };
            if mp.has(flags::MOVING) || !mp.whole_shutter() {
                self.path_moving(&samples, &vertex, mp, lo, hi, ns, bw, bh, scratch);
            } else if self.config.lens.is_some() {
                let s = surface_z(lo, hi);
                self.path_lens(&samples, &vertex, &s, lo, hi, ns, bw, bh, scratch);
            } else {
                let s = surface_z(lo, hi);
                self.path_pinhole(&samples, &vertex, &s, lo, hi, ns, bw, bh, scratch);
            }
        }
        scratch.stats.peak_points = scratch.stats.peak_points.max(scratch.points.len() as u64);
        scratch.stats.points += scratch.points.len() as u64;
        let t_resolve = std::time::Instant::now();
        scratch.stats.sample_ns += (t_resolve - t_sample).as_nanos() as u64;
        // CSGResolve: every sample, front to back.
        scratch.rgba.clear();
        scratch.z.clear();
        let mut lerps = 0;
        let resolver =
            Resolver { matte: self.config.matte, trees: &self.csg, order: self.config.csg_order };
        for nsample in 0..n {
            let head = scratch.heads[nsample];
            let c = if head == NIL {
                Composite::EMPTY
            } else {
                resolve_sample(&mut scratch.points, head, &resolver, &mut lerps)
            };
            scratch.rgba.push([c.rgb[0], c.rgb[1], c.rgb[2], c.alpha]);
            scratch.z.push(c.z);
        }
        scratch.stats.lerps += lerps;
        scratch.stats.resolve_ns += t_resolve.elapsed().as_nanos() as u64;
        scratch.samples = samples;
    }

    /// Path P: static micropolygon, pinhole camera.
    #[allow(clippy::too_many_arguments)]
    fn path_pinhole(
        &self,
        smp: &BucketSamples,
        vertex: &[[f32; 3]; 4],
        surf: &Surface,
        lo: [f32; 3],
        hi: [f32; 3],
        ns: usize,
        bw: u32,
        bh: u32,
        scratch: &mut Scratch,
    ) {
        let p_count = (bw * bh) as usize;
        for s in 0..ns {
            let r = smp.reach_space[s];
            let (x0, x1) = self.scan(lo[0], hi[0], r[0], r[1], bw);
            let (y0, y1) = self.scan(lo[1], hi[1], r[2], r[3], bh);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let pixel = y as usize * bw as usize + x as usize;
                    let k = s * p_count + pixel;
                    let (rx, ry) = (smp.x[k], smp.y[k]);
                    let v = vertex.map(|p| [p[0] - rx, p[1] - ry, p[2]]);
                    self.sample(pixel * ns + s, surf, &v, scratch);
                }
            }
        }
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
    #[allow(clippy::too_many_arguments)]
    fn path_lens(
        &self,
        smp: &BucketSamples,
        vertex: &[[f32; 3]; 4],
        surf: &Surface,
        lo: [f32; 3],
        hi: [f32; 3],
        ns: usize,
        bw: u32,
        bh: u32,
        scratch: &mut Scratch,
    ) {
        let Some(lens) = self.config.lens else { return };
        let p_count = (bw * bh) as usize;
        let inv_z = vertex.map(|p| 1.0 / p[2]);
        // Range of the displacement per unit lens offset over the depth range (clamped to
        // hither/yon as bounddof does); monotone in 1/z, so the ends hold the extremes.
        let (z0, z1) = (
            lo[2].max(self.config.hither),
            hi[2].min(self.config.yon).max(lo[2].max(self.config.hither)),
        );
        let (cx0, cy0) = lens.coc(z0);
        let (cx1, cy1) = lens.coc(z1);
        let (cx_lo, cx_hi) = (cx0.min(cx1), cx0.max(cx1));
        let (cy_lo, cy_hi) = (cy0.min(cy1), cy0.max(cy1));
        for lambda in 0..ns {
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
            let r = smp.reach_lens[lambda];
            let (x0, x1) = self.scan(lo[0] + dx0, hi[0] + dx1, r[0], r[1], bw);
            let (y0, y1) = self.scan(lo[1] + dy0, hi[1] + dy1, r[2], r[3], bh);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let pixel = y as usize * bw as usize + x as usize;
                    let s = smp.by_lens[lambda * p_count + pixel] as usize;
                    let k = s * p_count + pixel;
                    let (lx, ly) = (smp.lx[k], smp.ly[k]);
                    let (ax, ay) = (lx * lens.x_a, ly * lens.y_a);
                    let rx = smp.x[k] - lx * lens.x_b;
                    let ry = smp.y[k] - ly * lens.y_b;
                    let mut v = [[0.0f32; 3]; 4];
                    for j in 0..4 {
                        v[j] = [
                            vertex[j][0] - rx + ax * inv_z[j],
                            vertex[j][1] - ry + ay * inv_z[j],
                            vertex[j][2],
                        ];
                    }
                    self.sample(pixel * ns + s, surf, &v, scratch);
                }
            }
        }
    }

    /// Path M: moving micropolygon (with the lens if there is one). Time slice `tau` holds one
    /// sample per pixel with time in `[ta, tb]` (`slice_times`). Within the micropolygon's
    /// shutter segment `[t0, t1]` a vertex is at `v + a * speed` with `a = (t - t0)/(t1 - t0)`,
    /// so over the slice its box is the start box plus `[min(a_a m, a_b m), max(a_a M, a_b M)]`
    /// per axis (m, M: smallest and largest speed component). For a uniform shutter and a whole
    /// segment that is exactly Appendix A's box slid by `speedbox / NS` per slice (3.5).
    #[allow(clippy::too_many_arguments)]
    fn path_moving(
        &self,
        smp: &BucketSamples,
        vertex: &[[f32; 3]; 4],
        mp: &Micropolygon,
        mut lo: [f32; 3],
        mut hi: [f32; 3],
        ns: usize,
        bw: u32,
        bh: u32,
        scratch: &mut Scratch,
    ) {
        let p_count = (bw * bh) as usize;
        let (slo, shi) = bound(&mp.speed);
        // z range over the whole segment: the visible points' depth range.
        lo[2] += slo[2].min(0.0);
        hi[2] += shi[2].max(0.0);
        let surf =
            Surface { mp, zmin: lo[2], zmax: hi[2], crossing: mp.has(flags::HITHER_YON_CROSSING) };
        let lens = self.config.lens;
        if let Some(l) = &lens {
            l.grow(&mut lo, &mut hi, self.config.hither, self.config.yon);
        }
        let [t0, t1] = mp.time;
        // An empty (or NaN) segment exists at no time.
        if t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        let inv_len = 1.0 / (t1 - t0);
        for tau in 0..ns {
            let [ta, tb] = self.slice_times[tau];
            if tb < t0 || ta >= t1 {
                continue;
            }
            let aa = (ta.max(t0) - t0) * inv_len;
            let ab = (tb.min(t1) - t0) * inv_len;
            let bx0 = lo[0] + (aa * slo[0]).min(ab * slo[0]);
            let bx1 = hi[0] + (aa * shi[0]).max(ab * shi[0]);
            let by0 = lo[1] + (aa * slo[1]).min(ab * slo[1]);
            let by1 = hi[1] + (aa * shi[1]).max(ab * shi[1]);
            let r = smp.reach_time[tau];
            let (x0, x1) = self.scan(bx0, bx1, r[0], r[1], bw);
            let (y0, y1) = self.scan(by0, by1, r[2], r[3], bh);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let pixel = y as usize * bw as usize + x as usize;
                    let s = smp.by_time[tau * p_count + pixel] as usize;
                    let k = s * p_count + pixel;
                    let t = smp.t[k];
                    if t < t0 || t >= t1 {
                        continue; // outside this micropolygon's segment: not tested
                    }
                    let alpha = (t - t0) * inv_len;
                    let mut v = [[0.0f32; 3]; 4];
                    for j in 0..4 {
                        v[j] = [
                            vertex[j][0] + alpha * mp.speed[j][0],
                            vertex[j][1] + alpha * mp.speed[j][1],
                            vertex[j][2] + alpha * mp.speed[j][2],
                        ];
                    }
                    let (rx, ry) = match &lens {
                        Some(l) => {
                            let (lx, ly) = (smp.lx[k], smp.ly[k]);
                            let (ax, ay) = (lx * l.x_a, ly * l.y_a);
                            for p in v.iter_mut() {
                                p[0] += ax / p[2];
                                p[1] += ay / p[2];
                            }
                            (smp.x[k] - lx * l.x_b, smp.y[k] - ly * l.y_b)
                        }
                        None => (smp.x[k], smp.y[k]),
                    };
                    for p in v.iter_mut() {
                        p[0] -= rx;
                        p[1] -= ry;
                    }
                    self.sample(pixel * ns + s, &surf, &v, scratch);
                }
            }
        }
    }
}

/// Port of `gouraud`: the vertex colours and transmittances weighted by the Shepard weights of
/// `lerpz` at the sample point.
#[inline]
pub fn gouraud(v: &[[f32; 3]; 4], mp: &Micropolygon) -> ([f32; 3], [f32; 3]) {
    let w = shepard_weights(v);
    let mut c = [0.0; 3];
    let mut t = [0.0; 3];
    for (k, wk) in w.iter().enumerate() {
        for a in 0..3 {
            c[a] += wk * mp.color[k][a];
            t[a] += wk * mp.trans[k][a];
        }
    }
    (c, t)
}
