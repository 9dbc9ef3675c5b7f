//! Trimmed micropolygons (`RiTrimCurve` on a NURBS patch): the per-sample trim test of the
//! micropolygons that straddle a trim curve. The dicer drops the micropolygons wholly in
//! the trimmed region and flags [`crate::flags::TRIMMED`] those a trim curve crosses; for
//! each of these the renderer hands the hider a [`TrimRef`] (the patch's `(u, v)` at the
//! four vertices and which region), and a sample inside the micropolygon makes a visible
//! point only if its `(u, v)`, interpolated bilinearly at the sample (the inverse of the
//! quad's bilinear map, [`crate::bilinear_weights`]), is not trimmed away.
//!
//! Invariants: only micropolygons flagged `TRIMMED` are tested, so an untrimmed scene
//! samples exactly as before; the interpolated `(u, v)` is a convex combination of the
//! vertices', so it lies in the bound of the four, which is what the dicer classified.

use bytemuck::{Pod, Zeroable};
use reyes_scene::patches::trim::TrimRegion;

use crate::aov::bilinear_weights;

/// What the hider needs to trim one micropolygon: its trim region and the patch's `(u, v)`
/// at its vertices (in vertex order). All zero for a micropolygon that is not trimmed.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Pod, Zeroable)]
pub struct TrimRef {
    /// Index of the region among the hider's ([`crate::Hider::with_trims`]).
    pub region: u32,
    /// Parameter `(u, v)` at vertices 0..4.
    pub uv: [[f32; 2]; 4],
}

/// Whether the sample at the origin of `v` (the micropolygon's vertices relative to the
/// sample, as the inside test saw them) is trimmed away by `region`, given the vertices'
/// `(u, v)` in `t`.
pub fn trimmed_at(region: &TrimRegion, t: &TrimRef, v: &[[f32; 3]; 4]) -> bool {
    let w = bilinear_weights(v);
    let (mut u, mut s) = (0.0f64, 0.0f64);
    for (wk, uv) in w.iter().zip(&t.uv) {
        u += f64::from(*wk) * f64::from(uv[0]);
        s += f64::from(*wk) * f64::from(uv[1]);
    }
    region.removes(u, s)
}
