//! A diced grid as the dicer keeps it (stage: dice): its vertices once per breakpoint, its
//! shading once, and a short record per kept micropolygon, from which the record the hider
//! reads is rebuilt on demand. Invariant: [`Grid::micropolygon`] rebuilds bit for bit the
//! micropolygon the emitter classified and bucketed.

use glam::Vec3;
use reyes_hider::Micropolygon;

use super::{Labels, Quad};
use crate::split::OVERLAP;

/// One kept micropolygon of a [`Grid`]: which cell, and over which segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Kept {
    /// Cell index, `j * nu + i`.
    pub(crate) cell: u32,
    /// Breakpoint of the positions `v`.
    pub(crate) from: u32,
    /// Breakpoint of the positions at the segment's end (`speed = to - from`), or
    /// [`STILL`] (zero speed).
    pub(crate) to: u32,
    /// Flag bits.
    pub(crate) flags: u32,
    /// Normalised shutter times of the segment.
    pub(crate) time: [f32; 2],
}

/// [`Kept::to`] of a micropolygon that does not move.
pub(crate) const STILL: u32 = u32::MAX;

/// Tag of [`Kept::from`] and [`Kept::to`] naming an entry of [`Grid::extra`] (positions at a
/// time between breakpoints) rather than a breakpoint.
pub(crate) const EXTRA: u32 = 1 << 31;

/// A diced grid, stored compactly: its vertices once (each is shared by up to four
/// micropolygons) and a short record per kept micropolygon, from which
/// [`Grid::micropolygon`] builds the record the hider reads, bit for bit the one the dicer
/// classified and bucketed.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Grid {
    /// Cells across.
    pub(crate) nu: u32,
    /// Vertices per breakpoint, `(nu + 1) (nv + 1)`.
    pub(crate) count: u32,
    /// Colour and transmittance of each vertex (from shutter open).
    pub(crate) color: Vec<[f32; 3]>,
    pub(crate) trans: Vec<[f32; 3]>,
    /// Position of vertex `c` at breakpoint `b`: `pos[b * count + c]`.
    pub(crate) pos: Vec<[f32; 3]>,
    /// The object's flag bits and labels.
    pub(crate) labels: Labels,
    /// Kept micropolygons, in emission order (cell order, then time order).
    pub(crate) kept: Vec<Kept>,
    /// Camera-space position of vertex `c` at breakpoint `b`, `cam[b * count + c]`, kept
    /// only for a moving grid some vertex of which comes nearer than `near` at some
    /// breakpoint (else empty): what [`super::Emitter::emit`] needs to keep the part of a
    /// micropolygon's motion in front of the eye.
    pub(crate) cam: Vec<Vec3>,
    /// Cell positions at times between breakpoints (where such a micropolygon's kept part
    /// of its segment begins or ends), named by `EXTRA | index` in [`Kept`].
    pub(crate) extra: Vec<Quad>,
    /// Per-vertex AOV values, `aov_stride` floats per vertex (empty without AOVs).
    pub(crate) aov: Vec<f32>,
    pub(crate) aov_stride: usize,
    /// A trimmed patch's `(u, v)` at each vertex and its trim region (`uv` empty otherwise).
    pub(crate) uv: Vec<[f32; 2]>,
    pub(crate) trim_region: u32,
}

impl Grid {
    /// Kept micropolygons.
    pub fn len(&self) -> usize {
        self.kept.len()
    }

    /// Free the unused capacity (the grid is complete).
    pub fn shrink_to_fit(&mut self) {
        self.color.shrink_to_fit();
        self.trans.shrink_to_fit();
        self.pos.shrink_to_fit();
        self.aov.shrink_to_fit();
        self.uv.shrink_to_fit();
        self.kept.shrink_to_fit();
        self.cam = Vec::new();
        self.extra.shrink_to_fit();
    }

    /// Corner vertices of cell `cell`: `(i,j), (i+1,j), (i+1,j+1), (i,j+1)`.
    #[inline]
    pub(crate) fn corners(&self, cell: u32) -> [usize; 4] {
        let (i, j) = ((cell % self.nu) as usize, (cell / self.nu) as usize);
        let row = self.nu as usize + 1;
        [j * row + i, j * row + i + 1, (j + 1) * row + i + 1, (j + 1) * row + i]
    }

    /// The positions of cell `cell` at breakpoint `b`.
    #[inline]
    pub(crate) fn quad(&self, cell: u32, b: u32) -> Quad {
        let base = b as usize * self.count as usize;
        self.corners(cell).map(|c| self.pos[base + c])
    }

    /// The positions a [`Kept`] end names: breakpoint `b`, or an entry of `extra`.
    #[inline]
    pub(crate) fn end(&self, cell: u32, b: u32) -> Quad {
        if b & EXTRA != 0 { self.extra[(b & !EXTRA) as usize] } else { self.quad(cell, b) }
    }

    /// Kept micropolygon `k`.
    #[inline]
    pub fn micropolygon(&self, k: usize) -> Micropolygon {
        self.build(&self.kept[k])
    }

    /// Append kept micropolygon `k`'s AOV values, vertex by vertex (`4 * stride` floats;
    /// nothing without AOVs).
    pub fn micropolygon_aovs(&self, k: usize, out: &mut Vec<f32>) {
        let st = self.aov_stride;
        if st == 0 {
            return;
        }
        for c in self.corners(self.kept[k].cell) {
            out.extend_from_slice(&self.aov[c * st..(c + 1) * st]);
        }
    }

    /// Kept micropolygon `k`'s trim data (zeros unless it is flagged `TRIMMED`).
    pub fn trim_ref(&self, k: usize) -> reyes_hider::TrimRef {
        let m = &self.kept[k];
        if m.flags & reyes_hider::flags::TRIMMED == 0 || self.uv.is_empty() {
            return reyes_hider::TrimRef::default();
        }
        reyes_hider::TrimRef {
            region: self.trim_region,
            uv: self.corners(m.cell).map(|c| self.uv.get(c).copied().unwrap_or_default()),
        }
    }

    #[inline]
    pub(crate) fn build(&self, m: &Kept) -> Micropolygon {
        let corners = self.corners(m.cell);
        let from = self.end(m.cell, m.from);
        let mut speed = [[0.0_f32; 3]; 4];
        if m.to != STILL {
            let to = self.end(m.cell, m.to);
            for (s, (p, q)) in speed.iter_mut().zip(from.iter().zip(&to)) {
                *s = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            }
        }
        let trans = corners.map(|c| self.trans[c]);
        let mut flags = m.flags;
        // A shader's opacity: opaque where all four corners are (hider and CSG then treat the
        // micropolygon as they treat a native opaque one: it ends a sample's composite, sets
        // the depth and may occlude).
        if self.labels.shaded_opacity && trans.iter().all(|t| *t == [0.0; 3]) {
            flags |= reyes_hider::flags::OPAQUE;
        }
        Micropolygon {
            v: from,
            speed,
            color: corners.map(|c| self.color[c]),
            trans,
            flags,
            csg_tree: self.labels.csg_tree,
            csg_node: self.labels.csg_node,
            glass_opacity: self.labels.glass_opacity,
            time: m.time,
        }
    }
}

/// Push the boundary vertices of one breakpoint's raster positions `pos` (a grid of
/// `nu x nv` cells) out of the grid by [`OVERLAP`] pixels, each away from its neighbour
/// toward the inside (the diagonal one at a corner), so that two crack-free grids along a
/// shared edge overlap by a sliver instead of leaving one of rounding width between them.
pub(super) fn overlap(pos: &mut [[f32; 3]], nu: usize, nv: usize) {
    let at = |i: usize, j: usize| j * (nu + 1) + i;
    let inward = |k: usize, n: usize| {
        if k == 0 {
            1.min(n)
        } else if k == n {
            n - 1
        } else {
            k
        }
    };
    let mut moved = Vec::with_capacity(2 * (nu + nv));
    for j in 0..=nv {
        let edge_row = j == 0 || j == nv;
        let step = if edge_row { 1 } else { nu.max(1) };
        let mut i = 0;
        while i <= nu {
            let (p, q) = (pos[at(i, j)], pos[at(inward(i, nu), inward(j, nv))]);
            let (dx, dy) = (p[0] - q[0], p[1] - q[1]);
            let len = dx.hypot(dy);
            if len > 0.0 && len.is_finite() {
                let k = OVERLAP / len;
                moved.push((at(i, j), [p[0] + k * dx, p[1] + k * dy]));
            }
            i += step;
        }
    }
    for (c, [x, y]) in moved {
        pos[c][0] = x;
        pos[c][1] = y;
    }
}
