//! The split and dice decision of a batch of points (stage: dice): culled, halved or diced
//! into one grid, by its hull and its points' largest raster radius; and the raster extent
//! of a set of points (a blobby's bound). Invariant: one decision for every breakpoint.

use glam::{Vec2, Vec3};

use super::{Decision, MAX_SPLIT_DEPTH, Patch, Splitter, TestGrid};
use crate::motion::Pose;

impl Splitter {
    /// [`Splitter::decide_bound`] of a batch of points (`shapes/points.rs`): culled, split
    /// (halving its points) or held as the bound-and-cull tests of its hull decide, then
    /// diced into one grid of `count (m + 1) - 1` cells, `m` the sides per half disk its
    /// largest raster radius asks for, unless that is above the largest grid, when the batch
    /// is halved.
    pub(super) fn decide_points(
        &self,
        poses: &[Pose<'_>],
        patch: &Patch,
    ) -> (Decision, Option<f32>) {
        let hulls: Vec<Vec<Vec3>> =
            poses.iter().map(|pose| self.hull_points(pose, patch).unwrap_or_default()).collect();
        if hulls.iter().any(Vec::is_empty) {
            return (Decision::Cull, None);
        }
        let grids: Vec<TestGrid> = poses.iter().map(|pose| self.test_grid(pose, patch)).collect();
        let (decision, top) = self.decide_grids_hulls_bound(&grids, &hulls, patch);
        let mut radius = 0.0_f32;
        let mut count = 0;
        for pose in poses {
            let crate::shapes::Surface::Points(batch) = pose.surface else { continue };
            let (r, n) = batch.raster_radius(patch.u, |p| {
                let c = self.to_camera(pose, p);
                (c.is_finite() && c.z >= self.near).then(|| self.camera.eye_to_raster(c))
            });
            radius = radius.max(r);
            count = n;
        }
        let splittable = count > 1 && patch.depth < MAX_SPLIT_DEPTH;
        match decision {
            Decision::Cull => return (Decision::Cull, top),
            Decision::Split { hither: true, .. } if splittable => {
                return (Decision::Split { along_u: true, hither: true, count: 0 }, top);
            }
            _ => {}
        }
        let m = u64::from(crate::shapes::points::sides(radius));
        let cells = (count as u64 * (m + 1)).saturating_sub(1).max(1);
        if cells > self.max_grid && splittable {
            return (Decision::Split { along_u: true, hither: false, count: cells }, top);
        }
        let limited = cells > self.max_grid;
        (
            Decision::Dice { nu: cells.min(u64::from(u32::MAX)) as u32, nv: 1, limited, extra: 0 },
            top,
        )
    }

    /// Raster extent of camera-space points (the larger side of their raster bound; infinite
    /// when one is not in front of the eye), as [`Splitter::extent`] measures a patch.
    pub fn extent_of(&self, points_camera: impl Iterator<Item = Vec3>) -> f32 {
        let (mut lo, mut hi) = (Vec2::INFINITY, Vec2::NEG_INFINITY);
        for p in points_camera {
            if !(p.is_finite() && p.z >= self.near) {
                return f32::INFINITY;
            }
            let r = self.camera.eye_to_raster(p);
            lo = lo.min(r);
            hi = hi.max(r);
        }
        (hi - lo).max_element()
    }
}
