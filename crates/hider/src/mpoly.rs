//! The hider's input: Appendix A's `struct mpoly`, as a plain-old-data record.
//!
//! Invariants the dicer guarantees: vertices are in cyclic order 0-1-2-3 (edges 0-1, 1-2,
//! 2-3, 3-0); `x`, `y` are raster pixels of the image (pixel (x, y) covers
//! `[x, x+1) x [y, y+1)`, y down); `z` is eye-space depth and is > 0 at every vertex at
//! every time; colours are premultiplied by opacity and `trans` is per-channel
//! transmittance (1 = clear), as Appendix A's compositing expects.

use bytemuck::{Pod, Zeroable};

/// Flag bits of a micropolygon (Appendix A `struct visflags`, the subset the dicer sets).
pub mod flags {
    /// The micropolygon moves during the shutter (`speed` is not all zero).
    pub const MOVING: u32 = 1 << 0;
    /// Fully opaque in every channel at every vertex.
    pub const OPAQUE: u32 = 1 << 1;
    /// A matte object: hides what is behind it, contributes no colour or alpha.
    pub const MATTE: u32 = 1 << 3;
    /// Some vertex lies in front of hither or beyond yon at some time.
    pub const HITHER_YON_CROSSING: u32 = 1 << 4;
    /// Interpolate vertex colours at the sample (Appendix A `gouraud`) instead of vertex 0's.
    pub const GOURAUD: u32 = 1 << 6;
    /// Appendix A `glasshack`: tint what is seen through by the colour behind.
    pub const GLASS: u32 = 1 << 9;
    /// A trim curve crosses it: each sample inside is tested against the trim region
    /// (`crate::trim`).
    pub const TRIMMED: u32 = 1 << 10;
}

/// One micropolygon: a quadrilateral with per-vertex position, motion and colour.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Micropolygon {
    /// Vertices at shutter open: raster x, raster y, eye depth z.
    pub v: [[f32; 3]; 4],
    /// Displacement of each vertex over the whole shutter (Appendix A `speed`); zero if static.
    pub speed: [[f32; 3]; 4],
    /// Premultiplied colour at each vertex.
    pub color: [[f32; 3]; 4],
    /// Per-channel transmittance at each vertex (1 - opacity).
    pub trans: [[f32; 3]; 4],
    /// Bits from [`flags`].
    pub flags: u32,
    /// CSG tree id (0: not in a tree).
    pub csg_tree: u16,
    /// CSG node id of the parent slot (0: not CSG).
    pub csg_node: u16,
    /// Appendix A `glasshackopacity`.
    pub glass_opacity: f32,
    /// The part of the (normalised) shutter during which this micropolygon exists: `v` is its
    /// position at `time[0]` and `speed` its displacement from `time[0]` to `time[1]`.
    /// `[0, 1]` for the whole shutter. Piecewise-linear motion (more than two keys) is one
    /// micropolygon per segment; a micropolygon with a partial segment takes path M even if
    /// it does not move within it.
    pub time: [f32; 2],
}

impl Micropolygon {
    /// A still, opaque, non-CSG micropolygon over the whole shutter with vertices `v` (raster
    /// x, y and eye depth z, in cyclic order) and the premultiplied colour `color` at each.
    pub fn opaque(v: [[f32; 3]; 4], color: [[f32; 3]; 4]) -> Micropolygon {
        Micropolygon {
            v,
            speed: [[0.0; 3]; 4],
            color,
            trans: [[0.0; 3]; 4],
            flags: flags::OPAQUE,
            csg_tree: 0,
            csg_node: 0,
            glass_opacity: 0.0,
            time: [0.0, 1.0],
        }
    }

    /// True if the flag bit(s) `f` are all set.
    #[inline]
    pub fn has(&self, f: u32) -> bool {
        self.flags & f == f
    }

    /// True if the micropolygon exists for the whole shutter.
    #[inline]
    pub fn whole_shutter(&self) -> bool {
        self.time == [0.0, 1.0]
    }

    /// Screen-space bound over the whole shutter: `(min, max)` of x, y, z over the vertex
    /// positions at open and close (motion is linear, so this encloses every time).
    pub fn bound(&self) -> ([f32; 3], [f32; 3]) {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for k in 0..4 {
            for a in 0..3 {
                let p0 = self.v[k][a];
                let p1 = p0 + self.speed[k][a];
                lo[a] = lo[a].min(p0).min(p1);
                hi[a] = hi[a].max(p0).max(p1);
            }
        }
        (lo, hi)
    }
}
