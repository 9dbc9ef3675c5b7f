//! Trimmed NURBS patches in the dicer (`RiTrimCurve`): each grid vertex of a trimmed patch
//! carries the patch's `(u, v)`; a cell whose parameter rectangle lies wholly in the
//! trimmed region is dropped before shading, and one a trim curve crosses is flagged
//! `TRIMMED` so the hider tests each of its samples (`reyes_hider::trim`). The trim is thus
//! exact at the curve (to the flattening tolerance of `reyes_scene::patches::trim`), not at
//! the dice.
//!
//! Invariant: dropping is conservative. The hider's `(u, v)` at a sample is a convex
//! combination of the cell's corner values computed in `f32`, so it lies in their bound up
//! to rounding; the bound is grown by [`margin`] before it is classified, so a cell is
//! dropped only if every sample in it would have been trimmed away.

use std::sync::Arc;

use reyes_scene::Shape;
use reyes_scene::patches::trim::{Coverage, TrimRegion, span_domains};

/// What the dicer needs to trim one object's grids.
#[derive(Debug, Clone)]
pub(crate) struct TrimSetup {
    /// The object's trim region, shared with the hider.
    pub region: Arc<TrimRegion>,
    /// Its index among the frame's regions (`reyes_hider::TrimRef::region`).
    pub index: u32,
    /// Per surface (NURBS span), the parameter rectangle `[u0, u1, v0, v1]` it covers.
    spans: Vec<[f64; 4]>,
}

impl TrimSetup {
    /// The setup of `shape` if it is a trimmed `NuPatch`, its region numbered `index`.
    pub fn of(shape: &Shape, index: usize) -> Option<TrimSetup> {
        let region = TrimRegion::of(shape)?;
        Some(TrimSetup {
            region: Arc::new(region),
            index: index as u32,
            spans: span_domains(shape),
        })
    }

    /// The patch's `(u, v)` at the point `(s, t)` of surface `surface` (a span's own
    /// parameters); `(s, t)` itself for a surface that is not a span (never diced here).
    pub fn uv(&self, surface: usize, s: f32, t: f32) -> [f32; 2] {
        match self.spans.get(surface) {
            Some([u0, u1, v0, v1]) => {
                [(u0 + f64::from(s) * (u1 - u0)) as f32, (v0 + f64::from(t) * (v1 - v0)) as f32]
            }
            None => [s, t],
        }
    }

    /// Where the cell with corner parameters `uv` lies against the trimmed region.
    pub fn classify(&self, uv: [[f32; 2]; 4]) -> Coverage {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in uv {
            for a in 0..2 {
                lo[a] = lo[a].min(f64::from(p[a]));
                hi[a] = hi[a].max(f64::from(p[a]));
            }
        }
        if !(lo[0].is_finite() && lo[1].is_finite() && hi[0].is_finite() && hi[1].is_finite()) {
            return Coverage::Boundary;
        }
        let m = margin(lo, hi);
        self.region.classify([lo[0] - m, hi[0] + m, lo[1] - m, hi[1] + m])
    }
}

/// How far the hider's interpolated `(u, v)` can stray outside the bound `lo..hi` of the
/// corner values: its weights are `f32` (each off by a few ulps, their sum off 1 by as
/// much) and the sum is taken in `f64`, so by a few times 2^-24 of the largest coordinate;
/// 2^-18 of it leaves a factor of 64 to spare.
fn margin(lo: [f64; 2], hi: [f64; 2]) -> f64 {
    let size = lo.iter().chain(&hi).fold(0.0f64, |a, &c| a.max(c.abs()));
    size * (2.0f64).powi(-18) + f64::from(f32::MIN_POSITIVE)
}
