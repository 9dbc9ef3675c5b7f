//! RenderMan points as batches: a [`PointBatch`] is up to [`BATCH`] points of one `Points`
//! shape, `u` in `[0, 1]` running over them (point `k` of `n` owns `u` in `[k/n, (k+1)/n)`),
//! split in halves of `u` and diced into one grid per batch, not one per point.
//!
//! A point is a disk facing the camera, diced as a regular `2m`-gon of `m` cells: a grid of
//! `m + 1` vertex columns and two rows per point, column `c` at angle `pi (1 - c/m)` above
//! (row 1) and below (row 0) the disk's centre; consecutive points' columns follow each
//! other in the grid, and the one cell joining two points is not emitted
//! ([`PointBatch::skips`]). The polygon's circumradius is `r sqrt(pi / (m sin(pi/m)))`, so its
//! area is the disk's `pi r^2` exactly, whatever `m` (which only shapes the outline: it is
//! chosen from the disk's raster radius, [`sides`]).
//!
//! Invariants: a batch's every point lies in the hull it reports for any range of `u`; the
//! vertex of grid column `i`, row `j` of a patch `[u0, u1]` diced `nu` across is a function of
//! the patch, `i`, `j` and `nu` alone (so every breakpoint's grid matches vertex for vertex);
//! the normal faces the camera; `dP/du x dP/dv` points along it.

use std::sync::Arc;

use glam::Vec3;
use reyes_scene::curves::Facing;
use reyes_scene::{Primvar, Shape};

use super::SurfacePoint;

/// Most points of one batch surface (a batch's `u` must resolve its points in `f32`).
pub(crate) const BATCH: usize = 4096;

/// Most sides per half disk.
const MAX_SIDES: u32 = 32;

/// A `Points` shape's data, shared by its batches.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PointData {
    pub(crate) centres: Vec<Vec3>,
    pub(crate) width: Primvar<f32>,
    pub(crate) colors: Option<Primvar<[f32; 3]>>,
    pub(crate) opacities: Option<Primvar<[f32; 3]>>,
}

/// Up to [`BATCH`] consecutive points of a `Points` shape.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PointBatch {
    pub(crate) data: Arc<PointData>,
    /// The first point and how many.
    pub(crate) first: usize,
    pub(crate) count: usize,
    /// Which way the disks face.
    pub(crate) facing: Facing,
}

/// The batches of a `Points` shape (its points replaced by `positions` when given).
pub(crate) fn batches(
    shape: &Shape,
    positions: Option<&[Vec3]>,
    facing: Facing,
) -> Vec<super::Surface> {
    let Shape::Points { points, width, colors, opacities } = shape else { return Vec::new() };
    let centres = points
        .iter()
        .enumerate()
        .map(|(i, p)| positions.and_then(|q| q.get(i).copied()).unwrap_or(Vec3::from(*p)))
        .collect();
    let data = Arc::new(PointData {
        centres,
        width: width.clone(),
        colors: colors.clone(),
        opacities: opacities.clone(),
    });
    (0..points.len())
        .step_by(BATCH)
        .map(|first| {
            let count = BATCH.min(points.len() - first);
            super::Surface::Points(Box::new(PointBatch {
                data: data.clone(),
                first,
                count,
                facing,
            }))
        })
        .collect()
}

/// Sides per half disk for a disk of raster radius `r`: enough that the polygon strays at
/// most a tenth of a pixel from the circle, at least 2 (a square).
pub(crate) fn sides(r: f32) -> u32 {
    if r.is_nan() || r <= 0.05 || !r.is_finite() {
        return 2;
    }
    let half_angle = (1.0 - (0.1 / r).min(1.0)).acos();
    ((std::f32::consts::PI / (2.0 * half_angle)).ceil() as u32).clamp(2, MAX_SIDES)
}

impl PointBatch {
    /// The batch's points whose `u` lies in `[u0, u1)` (`u1 = 1` inclusive), as indices into
    /// the batch.
    pub(crate) fn range(&self, u: [f32; 2]) -> std::ops::Range<usize> {
        let n = self.count as f32;
        let start = |x: f32| -> usize {
            if x >= 1.0 {
                self.count
            } else {
                ((x * n - 0.5).ceil().max(0.0) as usize).min(self.count)
            }
        };
        start(u[0])..start(u[1])
    }

    /// Point `k` of the batch: centre, radius.
    fn point(&self, k: usize) -> (Vec3, f32) {
        let i = self.first + k;
        let c = self.data.centres.get(i).copied().unwrap_or(Vec3::ZERO);
        (c, 0.5 * self.data.width.at(i).unwrap_or(1.0))
    }

    /// The centre of the point `u` falls on (the test grid's view of the batch).
    pub(crate) fn position(&self, u: f32, _v: f32) -> Vec3 {
        let k = ((u * self.count as f32) as usize).min(self.count.saturating_sub(1));
        self.point(k).0
    }

    /// The corners of the box about the points of `[u0, u1)`, each grown by its radius.
    pub(crate) fn hull(&self, u: [f32; 2]) -> Vec<Vec3> {
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for k in self.range(u) {
            let (c, r) = self.point(k);
            lo = lo.min(c - Vec3::splat(r));
            hi = hi.max(c + Vec3::splat(r));
        }
        if lo.x > hi.x {
            return Vec::new();
        }
        super::box_corners(lo, hi).to_vec()
    }

    /// The disk's plane at centre `c`: two unit axes `(e1, e2)` with `e1 x e2` toward the
    /// camera.
    fn axes(&self, c: Vec3) -> (Vec3, Vec3) {
        let toward = match self.facing {
            Facing::Eye(eye) => eye - c,
            Facing::Along(d) => -d,
            Facing::Normals => Vec3::Z,
        };
        let n = toward.try_normalize().unwrap_or(Vec3::Z);
        let other = if n.y.abs() < 0.9 { Vec3::Y } else { Vec3::X };
        let e1 = other.cross(n).try_normalize().unwrap_or(Vec3::X);
        (e1, n.cross(e1))
    }

    /// The points of a patch `[u0, u1]` diced `nu` across: how many, and the sides per half
    /// disk (`nu = count (m + 1) - 1`).
    fn layout(&self, u: [f32; 2], nu: usize) -> (std::ops::Range<usize>, usize) {
        let range = self.range(u);
        let m = (nu + 1) / range.len().max(1);
        (range, m.saturating_sub(1).max(1))
    }

    /// Vertex `(i, j)` of patch `u` diced `nu` across: the disk point, the normal toward the
    /// camera, and the point's colour and opacity.
    pub(crate) fn vertex(&self, u: [f32; 2], i: usize, j: usize, nu: usize) -> SurfacePoint {
        let (range, m) = self.layout(u, nu);
        let (k, c) = (range.start + i / (m + 1), i % (m + 1));
        let (centre, r) = self.point(k.min(range.end.saturating_sub(1)));
        let (e1, e2) = self.axes(centre);
        let angle = std::f32::consts::PI * (1.0 - c as f32 / m as f32);
        let mf = m as f32;
        let big = r * (std::f32::consts::PI / (mf * (std::f32::consts::PI / mf).sin())).sqrt();
        let (s, cos) = angle.sin_cos();
        let y = if j == 0 { -s } else { s };
        let p = centre + (e1 * cos + e2 * y) * big;
        let i_point = self.first + k;
        let value = |var: &Option<Primvar<[f32; 3]>>| {
            var.as_ref().and_then(|v| v.at(i_point)).map_or(Vec3::ONE, Vec3::from)
        };
        SurfacePoint {
            p,
            n: e1.cross(e2),
            tint: value(&self.data.colors),
            opacity: value(&self.data.opacities).clamp(Vec3::ZERO, Vec3::ONE),
        }
    }

    /// True for the cell joining two consecutive points, which is not emitted.
    pub(crate) fn skips(&self, u: [f32; 2], cell: usize, nu: usize) -> bool {
        let (_, m) = self.layout(u, nu);
        cell % (m + 1) == m
    }

    /// The largest raster radius of the points of `range` under `to_raster` (object space
    /// to raster), and how many points there are.
    pub(crate) fn raster_radius(
        &self,
        u: [f32; 2],
        to_raster: impl Fn(Vec3) -> Option<glam::Vec2>,
    ) -> (f32, usize) {
        let range = self.range(u);
        let count = range.len();
        let mut largest = 0.0_f32;
        for k in range {
            let (c, r) = self.point(k);
            let (e1, _) = self.axes(c);
            if let (Some(a), Some(b)) = (to_raster(c), to_raster(c + e1 * r)) {
                largest = largest.max(a.distance(b));
            }
        }
        (largest, count)
    }
}
