//! The cells of a diced grid (stage: dice, second pass): each cell's positions at the
//! breakpoints become one micropolygon per segment between them (runs of still segments
//! merged), and each is kept or dropped against the depth limits, the back-face test
//! (`facing.rs`) and the buckets. A moving cell that comes nearer than `hither / 2` keeps the
//! part of its segment in front of that ([`Emitter::in_front`]). Invariants: see `dice.rs`
//! (every kept micropolygon is finite, at least `hither / 2` deep at both ends, not wholly
//! outside `[hither, yon]`, flagged as it crosses or moves, and touches a bucket); kept
//! micropolygons are recorded in cell order, then time order.

use glam::Vec3;
use reyes_hider::flags;

use super::grid::{EXTRA, Kept, STILL};

/// The largest ratio of a vertex's depths at the two ends of one micropolygon's segment
/// ([`Emitter::in_front`]): its end depth, `z0 + (z1 - z0)` in `f32`, is then within
/// `DEPTH_RATIO` ulps of the true one (a relative 6e-5).
pub(crate) const DEPTH_RATIO: f32 = 1024.0;

/// At most this many pieces of one segment (the depth ratio of `f32`'s whole range).
const MAX_DEPTH_PIECES: usize = 32;
use super::{Emitter, Quad};

/// Whether a cell is at the same place at two breakpoints: every coordinate equal, or the
/// same bits (so a vertex that is not finite at both, e.g. projected from behind the eye,
/// counts as not moving, and the cell is classified once rather than once per segment).
#[inline]
fn same(a: &Quad, b: &Quad) -> bool {
    a.iter().flatten().zip(b.iter().flatten()).all(|(x, y)| x == y || x.to_bits() == y.to_bits())
}

impl Emitter<'_> {
    /// Emit cell `cell` from its positions at each breakpoint (`(time, quad)`, in time
    /// order): one micropolygon per segment, runs of segments over which it is still merged.
    pub(super) fn emit_segments(&mut self, cell: u32, quads: &[(f32, Quad)]) {
        let n = quads.len();
        if quads.windows(2).all(|w| same(&w[0].1, &w[1].1)) {
            // Still over the whole shutter (or a single breakpoint).
            if let Some((_, q)) = quads.first() {
                self.emit(cell, (0, q), None, [0.0, 1.0]);
            }
            return;
        }
        let mut a = 0;
        while a + 1 < n {
            let mut b = a + 1;
            let still = same(&quads[a].1, &quads[b].1);
            if still {
                while b + 1 < n && same(&quads[b].1, &quads[b + 1].1) {
                    b += 1;
                }
            }
            let to = (!still).then_some((b as u32, &quads[b].1));
            self.emit(cell, (a as u32, &quads[a].1), to, [quads[a].0, quads[b].0]);
            a = b;
        }
    }

    /// The part of cell `cell`'s motion from breakpoint `from` to breakpoint `to` (over
    /// `time`) during which every vertex is at least `near` in front of the eye and some
    /// vertex is not beyond yon, as pieces over each of which no vertex's depth changes by
    /// more than [`DEPTH_RATIO`]: each piece's positions at its start and end and its times,
    /// in time order, pushed to `out` (nothing if there is no such part, or a position is
    /// not finite).
    ///
    /// Camera-space positions move linearly between breakpoints, so each vertex is in front
    /// of `near` over one interval of the segment, and all four over the intersection of
    /// theirs; each is within yon over an interval that holds an end of the segment, and
    /// some vertex within the hull of theirs (a superset where the union has a gap, which
    /// the hider's depth test then rejects).
    ///
    /// The part beyond yon and the depth ratio matter beyond the samples they save: a
    /// micropolygon is its position at the start and its displacement over the segment, and
    /// in `f32` the end depth `z0 + (z1 - z0)` of one that comes from a great depth (4e9 to
    /// 16) is lost to rounding, leaving it at depth 0 at the end, its circle of confusion
    /// the whole screen and every sample of the frame tested against it (fuzz regression
    /// `render-shrunk-lens-huge-floor-slow`). Over a piece whose depths change by at most
    /// `DEPTH_RATIO`, the end depth is within `DEPTH_RATIO` ulps of the true one.
    fn in_front(
        &self,
        cell: u32,
        from: u32,
        to: u32,
        time: [f32; 2],
        out: &mut Vec<(Quad, Quad, [f32; 2])>,
    ) {
        let g = &self.grid;
        let count = g.count as usize;
        let corners = g.corners(cell);
        let at = |b: u32| corners.map(|c| g.cam[b as usize * count + c]);
        let (p, q) = (at(from), at(to));
        let (mut lo, mut hi) = (0.0_f32, 1.0_f32);
        // The hull of the vertices' intervals within yon.
        let (mut yon_lo, mut yon_hi) = (1.0_f32, 0.0_f32);
        for (p, q) in p.iter().zip(&q) {
            if !(p.is_finite() && q.is_finite()) {
                return;
            }
            match (p.z >= self.near, q.z >= self.near) {
                (true, true) => {}
                (false, false) => return,
                // Where z(s) = p.z + s (q.z - p.z) reaches `near`.
                (true, false) => hi = hi.min((p.z - self.near) / (p.z - q.z)),
                (false, true) => lo = lo.max((self.near - p.z) / (q.z - p.z)),
            }
            let (a, b) = match (p.z <= self.yon, q.z <= self.yon) {
                (true, true) => (0.0, 1.0),
                (false, false) => continue,
                // Where z(s) reaches yon.
                (true, false) => (0.0, (self.yon - p.z) / (q.z - p.z)),
                (false, true) => ((p.z - self.yon) / (p.z - q.z), 1.0),
            };
            (yon_lo, yon_hi) = (yon_lo.min(a), yon_hi.max(b));
        }
        (lo, hi) = (lo.max(yon_lo), hi.min(yon_hi));
        // A part too short to hold a sample time is not worth a record.
        if hi - lo <= 1e-6 || hi.is_nan() || lo.is_nan() {
            return;
        }
        // Camera-space position at `s` from the nearer end, so that a point near that end
        // keeps its digits (and equal ends stay exact).
        let lerp = |p: Vec3, q: Vec3, s: f32| {
            if s <= 0.5 { p + (q - p) * s } else { q + (p - q) * (1.0 - s) }
        };
        let depth = |k: usize, s: f32| lerp(p[k], q[k], s).z;
        let project = |s: f32| {
            let mut quad = [[0.0_f32; 3]; 4];
            for (k, (p, q)) in p.iter().zip(&q).enumerate() {
                let c = lerp(*p, *q, s);
                // Rounding may leave a vertex a hair nearer than `near` at the crossing.
                let c = Vec3::new(c.x, c.y, c.z.max(self.near));
                let r = self.camera.as_ref()?.eye_to_raster(c);
                if !r.is_finite() {
                    return None;
                }
                quad[k] = [r.x, r.y, c.z];
            }
            Some(quad)
        };
        // The vertex whose depth changes most over the part, and its depths at the ends.
        let ratio = |k: usize| {
            let (a, b) = (depth(k, lo).max(self.near), depth(k, hi).max(self.near));
            a.max(b) / a.min(b)
        };
        let k = (0..4).max_by(|&a, &b| ratio(a).total_cmp(&ratio(b))).unwrap_or(0);
        // Cut points: where that vertex's depth is `DEPTH_RATIO^n` times its nearer end's.
        let (za, zb) = (depth(k, lo), depth(k, hi));
        let mut cuts = vec![lo];
        let (far, near) = (za.max(zb), za.min(zb).max(self.near));
        let mut z = near * DEPTH_RATIO;
        while z < far && cuts.len() < MAX_DEPTH_PIECES {
            // Where the depth is `z`, in the parameter of the whole segment.
            let s = lo + (hi - lo) * (za - z) / (za - zb);
            cuts.push(s);
            z *= DEPTH_RATIO;
        }
        // In time order: from the far end, the depths were taken nearest first.
        if za > zb {
            cuts[1..].reverse();
        }
        cuts.push(hi);
        let span = time[1] - time[0];
        let at_time = |s: f32| if s >= 1.0 { time[1] } else { time[0] + s * span };
        for w in cuts.windows(2) {
            let (s0, s1) = (w[0], w[1]);
            if s1.partial_cmp(&s0) != Some(std::cmp::Ordering::Greater) {
                continue;
            }
            let (Some(a), Some(b)) = (project(s0), project(s1)) else { return };
            let t = [at_time(s0), at_time(s1)];
            if t[1] > t[0] {
                out.push((a, b, t));
            }
        }
    }

    /// Classify one micropolygon of cell `cell` over its segment `time` (at breakpoint
    /// `from` at the start, at `to` at the end, or at `from` throughout when `to` is `None`)
    /// against the depth limits and buckets, and keep it or drop it.
    #[inline(always)]
    pub(super) fn emit(
        &mut self,
        cell: u32,
        from: (u32, &Quad),
        to: Option<(u32, &Quad)>,
        time: [f32; 2],
    ) {
        let mut usable = true;
        let (mut zmin, mut zmax) = (f32::INFINITY, f32::NEG_INFINITY);
        for q in [Some(from.1), to.map(|t| t.1)].into_iter().flatten() {
            for p in q {
                usable &= p[0].is_finite() && p[1].is_finite() && p[2] >= self.near;
                zmin = zmin.min(p[2]);
                zmax = zmax.max(p[2]);
            }
        }
        usable &= zmax.is_finite();
        // All beyond yon at one end (and not at both: culled below).
        let beyond_yon = |q: Option<&Quad>| q.is_some_and(|q| q.iter().all(|p| p[2] > self.yon));
        let far_end = beyond_yon(Some(from.1)) != beyond_yon(to.map(|t| t.1));
        // Some vertex's depth changes by more than `DEPTH_RATIO` over the segment.
        let deep = to.is_some_and(|(_, q)| {
            from.1.iter().zip(q).any(|(a, b)| a[2].max(b[2]) > DEPTH_RATIO * a[2].min(b[2]))
        });
        if !usable || (to.is_some() && (far_end || deep)) {
            // A moving micropolygon that comes nearer than `near` (or passes behind the
            // eye) during its segment keeps the part of the segment it is in front of it,
            // and one that is beyond yon at one end the part it is not (`in_front`).
            if let Some((to_b, _)) = to
                && from.0 & EXTRA == 0
                && !self.grid.cam.is_empty()
            {
                let mut parts = std::mem::take(&mut self.parts);
                parts.clear();
                self.in_front(cell, from.0, to_b, time, &mut parts);
                for (a, b, t) in parts.drain(..) {
                    let ia = EXTRA | self.grid.extra.len() as u32;
                    self.grid.extra.push(a);
                    let ib = EXTRA | self.grid.extra.len() as u32;
                    self.grid.extra.push(b);
                    self.emit(cell, (ia, &a), Some((ib, &b)), t);
                }
                self.parts = parts;
                return;
            }
            if !usable || !self.grid.cam.is_empty() {
                self.culled += 1;
                return;
            }
        }
        // All in front of hither, or all beyond yon, at both ends.
        if zmax < self.hither || zmin > self.yon {
            self.culled += 1;
            return;
        }
        if let Some(sign) = self.cull
            && Self::backfacing(sign, from.1, to.map(|t| t.1), self.warp)
        {
            self.culled += 1;
            self.backfacing += 1;
            return;
        }
        let crossing = zmin < self.hither || zmax > self.yon;
        let mut flags = self.grid.labels.flags | self.cell_flags;
        if crossing {
            flags |= flags::HITHER_YON_CROSSING;
        }
        let moves = to.is_some_and(|(_, q)| {
            from.1.iter().zip(q).any(|(p, q)| (0..3).any(|a| q[a] - p[a] != 0.0))
        });
        if moves || time != [0.0, 1.0] {
            flags |= flags::MOVING;
        }
        let kept = Kept { cell, from: from.0, to: to.map_or(STILL, |t| t.0), flags, time };
        let Some(range) = self.bucketer.range(&self.grid.build(&kept)) else {
            self.culled += 1;
            return;
        };
        self.ranges.push(range);
        self.grid.kept.push(kept);
        if crossing {
            self.crossing += 1;
        }
        if flags & flags::MOVING != 0 {
            self.moving += 1;
        }
        if flags & flags::TRIMMED != 0 {
            self.trim_boundary += 1;
        }
    }
}
