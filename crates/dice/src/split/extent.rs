//! The scale of the relative flatness bound: a whole primitive's raster extent, one per
//! motion breakpoint, and the tolerances it gives.
//!
//! The relative bound keeps a small primitive's silhouette within a fixed fraction of its
//! size. A primitive whose apparent size changes over the shutter (one that comes from the
//! vanishing point to the foreground) is measured against its own size at each breakpoint:
//! one scale for all of them, the smallest, would ask for the far end's precision (a
//! millionth of a pixel) where it is near and large, and dice it into millions of
//! micropolygons for nothing (fuzz regression `render-shrunk-lens-huge-floor-slow`).

use std::sync::Arc;

use glam::Vec2;

use super::{Patch, Splitter};
use crate::motion::Pose;

/// Raster extent of a whole primitive at each breakpoint (the larger side of its raster
/// bound); infinite at a breakpoint where it is unknown (a point not in front of the eye),
/// and at every one when none was measured: each patch's own extent is then used.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Extent(Option<Arc<[f32]>>);

impl Extent {
    /// No measurement: each patch is its own scale.
    pub fn unknown() -> Extent {
        Extent(None)
    }

    /// One extent per breakpoint.
    pub fn per_breakpoint(extents: Vec<f32>) -> Extent {
        Extent(Some(extents.into()))
    }

    /// The extent at breakpoint `k` (infinite if unknown there).
    pub fn at(&self, k: usize) -> f32 {
        self.0.as_ref().and_then(|e| e.get(k).copied()).unwrap_or(f32::INFINITY)
    }
}

impl Splitter {
    /// Raster extent of `patch` in `poses` for the relative flatness bound: at each
    /// breakpoint, the larger side of its test points' raster bound (infinite at a
    /// breakpoint where some point is not in front of the eye).
    pub fn extent(&self, poses: &[Pose<'_>], patch: &Patch) -> Extent {
        let extents = poses
            .iter()
            .map(|pose| {
                let grid = self.test_grid(pose, patch);
                let (mut lo, mut hi) = (Vec2::INFINITY, Vec2::NEG_INFINITY);
                for p in grid.iter().flatten() {
                    if !(p.is_finite() && p.z >= self.near) {
                        return f32::INFINITY;
                    }
                    let r = self.camera.eye_to_raster(*p);
                    lo = lo.min(r);
                    hi = hi.max(r);
                }
                (hi - lo).max_element()
            })
            .collect();
        Extent::per_breakpoint(extents)
    }

    /// The flatness tolerance in raster pixels at a breakpoint where the primitive's extent
    /// is `extent`: the smaller of the absolute bound and the relative one times `extent`
    /// (infinite with both off, or with only the relative one and no extent).
    pub(super) fn flat_tolerance(&self, extent: f32) -> f32 {
        let mut tol = f32::INFINITY;
        if self.flatness > 0.0 {
            tol = self.flatness;
        }
        if self.relative_flatness > 0.0 && extent.is_finite() {
            tol = tol.min(self.relative_flatness * extent);
        }
        tol
    }

    /// How far in raster pixels an edge's polyline may stray from the surface at each of
    /// the `n` breakpoints ([`super::edge`]): the flatness bound the grids are diced to, for
    /// a primitive of raster extent `extent` (see [`Splitter::with_flatness`]); half a
    /// micropolygon side with both bounds off; a tenth for a CSG operand. Never below a
    /// thousandth of a pixel.
    pub fn edge_tolerances(&self, extent: &Extent, n: usize) -> Vec<f32> {
        (0..n)
            .map(|k| {
                let mut tol = self.flat_tolerance(extent.at(k));
                if !tol.is_finite() {
                    tol = 0.5 * self.step;
                }
                tol *= if self.csg_depth.is_some() { super::flat::CSG_DEPTH_FRACTION } else { 1.0 };
                tol.max(1e-3)
            })
            .collect()
    }
}
