//! Occlusion culling in the hider's per-bucket loop (`hider.occlusion_cull`, docs/architecture.md,
//! "Occlusion culling"): the bucket's micropolygons are sampled front to back by their
//! nearest depth, each sample keeps the nearest depth an opaque surface is known to have
//! there, each pixel the largest of its samples' depths, and a micropolygon (or one of its
//! candidate samples) that lies wholly behind them is not sampled.
//!
//! Invariant: the image is the one of sampling every micropolygon in the bucket's order, bit
//! for bit. Two things make that hold:
//! - **What is skipped is never reached.** A sample's composite stops at its first opaque
//!   point, and `findfront` (reyes-csg) only ever returns a point of the least exact depth, so
//!   a point whose *smallest possible* depth is beyond the exact depth `z_O` of an opaque point
//!   `O` of the same list never influences the composite: it is never the front while `O` is
//!   in the list, it never wins a tie (its depth is strictly greater), and when it makes `O`
//!   lerp early (an overlap test), the lerp gives the same bits as the lazy one would. The
//!   depth recorded for `O` is its `maxz` grown by [`MARGIN`], above `z_O` even with the
//!   rounding of the Shepard interpolation (`lerpz`), so `minz > recorded` implies
//!   `minz > z_O`. Occluders are only non-CSG, non-matte, non-glass opaque surfaces; a CSG
//!   point is never skipped (its tree's resolution reads every point of the tree at the
//!   sample, in front of the opaque surface or not), nor one that crosses hither or yon (its
//!   depth is only known at the sample).
//! - **Lists keep their order.** `findfront` breaks ties by list order, and a sample's list
//!   holds its points most recent first. Processing front to back would change that order,
//!   so [`Occlusion::link`] inserts each point where it would have been had the micropolygons
//!   come in the bucket's order (by their position in it, the key).
//!
//! Without culling nothing here runs, and the bucket is sampled as before.

use reyes_csg::{NIL, VisPoint};

use crate::mpoly::{Micropolygon, flags};

/// Relative growth of an occluder's recorded depth over its `maxz`. The exact depth of a
/// point is a Shepard combination of its vertex depths (`lerpz`): weights rounded, normalised
/// with a rounded reciprocal and summed in four rounded steps, so it can exceed the largest
/// vertex depth by about 12 ulps (moving vertices add the rounding of `z + a*dz`); `1e-5` is
/// about 84 ulps, so culling is conservative by a wide margin and loses nothing measurable.
pub(crate) const MARGIN: f32 = 1.0 + 1.0e-5;

/// A surface whose opaque points end a sample's composite: opaque, not matte (whose
/// compositing rules read the deepest composited surface), not glass (which tints by the
/// point behind it) and not in a CSG tree (which resolves its points first).
#[inline]
pub(crate) fn occluder(mp: &Micropolygon) -> bool {
    mp.has(flags::OPAQUE)
        && mp.flags & (flags::MATTE | flags::GLASS) == 0
        && mp.csg_node == 0
        && mp.csg_tree == 0
}

/// A surface that may be skipped behind occluders: anything but CSG operands and
/// hither/yon-crossing micropolygons (see the module comment).
#[inline]
pub(crate) fn cullable(mp: &Micropolygon) -> bool {
    mp.csg_node == 0 && mp.csg_tree == 0 && !mp.has(flags::HITHER_YON_CROSSING)
}

/// The nearest depth a micropolygon can have at any sample, as its visible points' `minz`:
/// the smallest vertex depth, less any motion towards the eye over its segment.
#[inline]
pub(crate) fn nearest(mp: &Micropolygon) -> f32 {
    let mut z = f32::INFINITY;
    let mut dz = 0.0f32;
    for j in 0..4 {
        z = z.min(mp.v[j][2]);
        dz = dz.min(mp.speed[j][2]);
    }
    if mp.has(flags::MOVING) || !mp.whole_shutter() { z + dz } else { z }
}

/// One bucket's occlusion state, reused from bucket to bucket (no allocation once grown).
#[derive(Debug, Default, Clone)]
pub(crate) struct Occlusion {
    /// Culling in this bucket's main pass (never in adaptive refinement).
    pub(crate) on: bool,
    /// Samples per pixel.
    ns: usize,
    /// Per sample `pixel*NS + s`: a depth no nearer than the exact depth of some opaque
    /// occluder point in its list (+inf: none yet).
    pub(crate) depth: Vec<f32>,
    /// Per pixel: the largest `depth` of its samples.
    pixel_max: Vec<f32>,
    /// Per pixel: how many of its samples have no occluder yet (`depth` +inf). While any has
    /// none, the pixel's largest depth is +inf without looking at the others.
    open: Vec<u32>,
    /// The processing order: (nearest depth, position in the bucket's list), sorted.
    pub(crate) order: Vec<(f32, u32)>,
    /// Per visible point of the main pass: its micropolygon's position in the bucket's list.
    key: Vec<u32>,
}

impl Occlusion {
    /// Start a bucket of `p_count` pixels of `ns` samples whose micropolygons are
    /// `list` (indexing `mpolys`): everything open, and the micropolygons sorted front to back
    /// (ties by position, so the order is a function of the bucket's input alone).
    pub(crate) fn begin(
        &mut self,
        on: bool,
        (p_count, ns): (usize, usize),
        mpolys: &[Micropolygon],
        list: &[u32],
    ) {
        self.on = on;
        self.ns = ns;
        self.key.clear();
        self.order.clear();
        if !on {
            return;
        }
        self.depth.clear();
        self.depth.resize(p_count * ns, f32::INFINITY);
        self.pixel_max.clear();
        self.pixel_max.resize(p_count, f32::INFINITY);
        self.open.clear();
        self.open.resize(p_count, ns as u32);
        self.order.extend(
            list.iter().enumerate().map(|(i, &m)| (nearest(&mpolys[m as usize]), i as u32)),
        );
        self.order.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    }

    /// True if every sample of pixels `x0..=x1` by `y0..=y1` (bucket-local, `bw` across,
    /// a non-empty range) has an opaque surface strictly nearer than `zmin`.
    #[inline]
    pub(crate) fn covered(
        &self,
        (x0, x1): (i32, i32),
        (y0, y1): (i32, i32),
        bw: u32,
        zmin: f32,
    ) -> bool {
        for y in y0..=y1 {
            let row = y as usize * bw as usize;
            let pixels = &self.pixel_max[row + x0 as usize..=row + x1 as usize];
            // Not `d >= zmin`: a NaN `zmin` is never covered.
            if pixels.iter().any(|&d| d.partial_cmp(&zmin) != Some(std::cmp::Ordering::Less)) {
                return false;
            }
        }
        true
    }

    /// Link the new visible point `index` (the last of `points`, of the micropolygon at
    /// position `key` in the bucket's list) into sample `n`'s list, where it would be had the
    /// micropolygons been sampled in list order: the list is kept in decreasing key order,
    /// a new point going before the points of equal key, as a prepend would put it.
    #[inline]
    pub(crate) fn link(
        &mut self,
        points: &mut [VisPoint],
        heads: &mut [u32],
        n: usize,
        index: u32,
        key: u32,
    ) {
        self.key.push(key);
        debug_assert_eq!(self.key.len(), points.len());
        let head = heads[n];
        if head == NIL || self.key[head as usize] <= key {
            points[index as usize].next = head;
            heads[n] = index;
            return;
        }
        let mut prev = head;
        loop {
            let next = points[prev as usize].next;
            if next == NIL || self.key[next as usize] <= key {
                points[index as usize].next = next;
                points[prev as usize].next = index;
                return;
            }
            prev = next;
        }
    }

    /// An occluder's point with largest depth `maxz` now lies in sample `n`'s list.
    ///
    /// The pixel's largest depth is rescanned over its samples only when the sample that
    /// held it moves nearer; while some sample has no occluder it stays +inf unscanned. (A
    /// rescan on every first occluder of a sample, as before, cost `ns` steps each, `ns^2` a
    /// pixel: 64x64 samples ran 14 times slower per sample test than 8x8.)
    #[inline]
    pub(crate) fn record(&mut self, n: usize, maxz: f32) {
        let d = maxz * MARGIN;
        let old = self.depth[n];
        // Not `d >= old`: a NaN depth records nothing.
        if d.partial_cmp(&old) != Some(std::cmp::Ordering::Less) {
            return;
        }
        self.depth[n] = d;
        let p = n / self.ns;
        if old == f32::INFINITY {
            self.open[p] -= 1;
            if self.open[p] > 0 {
                return;
            }
        } else if old < self.pixel_max[p] {
            return;
        }
        let s = &self.depth[p * self.ns..(p + 1) * self.ns];
        self.pixel_max[p] = s.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    }
}
