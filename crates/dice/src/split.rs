//! Bound-and-split stage: decide, once per patch, whether to cull, split or dice it.
//!
//! Invariants: decisions look only at a `TEST_N x TEST_N` test grid of camera-space points
//! per breakpoint of the object's motion, so every bound grows by a safety margin (test
//! points do not bound a curved surface); one decision holds for every breakpoint, so the
//! grids of all times match vertex for vertex; a patch is culled only when it cannot produce
//! a micropolygon that touches a bucket at any time (micropolygons move linearly in raster
//! space between breakpoints, so the union of the breakpoints' bounds holds them all); a
//! diced patch never exceeds `max_grid_size` micropolygons; recursion is bounded by
//! `MAX_SPLIT_DEPTH` (and `MAX_HITHER_SPLITS` splits for straddling the hither plane).
//! With one breakpoint (no motion) every decision is the one a still object always had.
//! A surface with a control hull (a patch-mesh sub-patch or NURBS span, as a rational Bezier
//! patch) also puts the hull of each sub-patch into its depth range, raster bound and
//! side-plane tests, so its bound is conservative whatever its curvature; surfaces without
//! one are decided exactly as before.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use reyes_hider::{Frame, LensSetup};
use reyes_scene::Projection;

use crate::camera::CameraSetup;
use crate::motion::Pose;
pub(crate) use edge::{Edge, Line, OVERLAP, Sides};
pub use extent::Extent;
#[cfg(test)]
use rate::clamp_grid;
use rate::{max_lengths, stalls, step};

/// Test points per parameter direction.
pub(crate) const TEST_N: usize = 8;
/// Most splits from an object's whole parameter range to a patch (any reason).
pub(crate) const MAX_SPLIT_DEPTH: u32 = 40;
/// Most splits made because a patch straddles the hither plane.
pub(crate) const MAX_HITHER_SPLITS: u32 = 12;
/// How much finer than at its on-screen breakpoints a moving grid may be diced for the sake
/// of breakpoints where it is off screen (per side). Large enough that a grid leaving the
/// screen keeps its size as it goes (every moving scene of `scenes/` renders unchanged),
/// small enough that a fast approach off screen cannot ask for unbounded work.
const OFF_SCREEN_GROWTH: f32 = 2.0;
/// Safety margin, as a fraction of the test points' extent. Between test points a curved
/// surface bulges by at most its sagitta; a full circle sampled at 8 points bulges by about
/// 10% of its diameter, so 25% covers every shape we dice with room for perspective.
pub(crate) const MARGIN_FRACTION: f32 = 0.25;
/// Extra safety margin in raster pixels (covers flat patches with a tiny extent).
const MARGIN_PIXELS: f32 = 2.0;
/// Most micropolygons along one side of a grid before clamping (keeps counts in range).
const MAX_SIDE: f64 = 1.0e9;

/// A rectangle of an object's parameter space, with its split history.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Patch {
    /// `[u0, u1]`.
    pub u: [f32; 2],
    /// `[v0, v1]`.
    pub v: [f32; 2],
    /// Splits from the whole range.
    pub depth: u32,
    /// Of which because the patch straddled hither.
    pub hither_splits: u32,
    /// The micropolygon count its parent would have been diced into (0: unknown, at the
    /// root and after a hither split), to tell whether splitting makes progress.
    pub parent_count: u64,
    /// Consecutive splits down to this patch that did not make progress ([`rate::STALL_RATIO`]).
    pub stalls: u32,
    /// Raster extent of the whole primitive the patch was split from at each breakpoint,
    /// the scale of the relative flatness bound (unknown: the patch's own extent is used).
    pub extent: Extent,
    /// Its four sides, under crack-free dicing ([`edge`]); `None`: diced on its own.
    pub sides: Option<Arc<Sides>>,
}

impl Patch {
    /// The whole parameter range `[0, 1]^2`.
    pub fn root() -> Patch {
        Patch {
            u: [0.0, 1.0],
            v: [0.0, 1.0],
            depth: 0,
            hither_splits: 0,
            parent_count: 0,
            stalls: 0,
            extent: Extent::unknown(),
            sides: None,
        }
    }

    /// The same patch as the root of a primitive of raster extent `extent`.
    pub fn with_extent(self, extent: Extent) -> Patch {
        Patch { extent, ..self }
    }

    /// Parameter `k` of `n` equal steps across `range`, exact at both ends so that
    /// neighbouring patches share their boundary vertices.
    #[inline]
    pub fn at(range: [f32; 2], k: usize, n: usize) -> f32 {
        if k == 0 {
            range[0]
        } else if k >= n {
            range[1]
        } else {
            range[0] + (range[1] - range[0]) * (k as f32 / n as f32)
        }
    }

    /// The two halves, lower parameter half first; `count` is the micropolygon count this
    /// patch would have been diced into (0 for a hither split), which the halves remember.
    pub fn split(&self, along_u: bool, hither: bool, count: u64) -> [Patch; 2] {
        let stalled = !hither && stalls(self.parent_count, count);
        let child = Patch {
            depth: self.depth + 1,
            hither_splits: self.hither_splits + u32::from(hither),
            parent_count: count,
            stalls: if stalled {
                self.stalls + 1
            } else if hither {
                self.stalls
            } else {
                0
            },
            ..self.clone()
        };
        let (mut a, mut b) = (child.clone(), child);
        if along_u {
            let mid = 0.5 * (self.u[0] + self.u[1]);
            a.u[1] = mid;
            b.u[0] = mid;
        } else {
            let mid = 0.5 * (self.v[0] + self.v[1]);
            a.v[1] = mid;
            b.v[0] = mid;
        }
        [a, b]
    }
}

/// What to do with a patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Decision {
    /// Nothing of it can be seen.
    Cull,
    /// Split it in half (`along_u`: halve the u range), `hither`: because it straddles hither;
    /// `count`: the micropolygons it would have been diced into (0 for a hither split).
    Split { along_u: bool, hither: bool, count: u64 },
    /// Dice it into `nu x nv` micropolygons; `limited`: a split limit forced dicing;
    /// `extra`: of the `nu * nv`, those the flatness rule added to what the shading rate
    /// asked for ([`Splitter::with_flatness`]).
    Dice { nu: u32, nv: u32, limited: bool, extra: u32 },
}

/// The camera and frame facts the decisions need.
#[derive(Debug, Clone)]
pub(crate) struct Splitter {
    camera: CameraSetup,
    lens: Option<LensSetup>,
    hither: f32,
    yon: f32,
    /// Micropolygons with a vertex nearer than this are dropped (half of hither).
    near: f32,
    /// Raster extent of the bucket grid (what `Frame::buckets_touched` accepts).
    screen_lo: Vec2,
    screen_hi: Vec2,
    /// The four side planes of the (extended) view volume, as outward unit normals `n` and
    /// offsets `d`: a camera-space point `p` is off that side where `n.p + d > 0`. Through
    /// the eye (`d = 0`) for a perspective camera, parallel to the view for an orthographic
    /// one; `None` with a lens, whose blur the planes do not include.
    frustum: Option<[(Vec3, f32); 4]>,
    /// Micropolygon side length in pixels: `sqrt(shading_rate)`.
    step: f32,
    max_grid: u64,
    /// The flatness rule ([`Splitter::with_flatness`]): the largest distance in pixels
    /// between a diced grid and the true surface, absolute and as a fraction of the
    /// patch's raster extent (0: that bound is off).
    flatness: f32,
    relative_flatness: f32,
    /// Displacement (crate::displace): the most a point of the surface may move, in camera
    /// space; bounds grow by it (0: no displacement).
    displace: f32,
    /// Motion- and focus-aware dicing ([`Splitter::with_blur_factors`]): the factors on a
    /// patch's motion and defocus blur in pixels (0: off).
    motion_factor: f32,
    focus_factor: f32,
    /// A CSG operand's depth rule ([`Splitter::with_csg_depth`]).
    csg_depth: Option<flat::CsgDepth>,
}

/// The test grid of a patch: camera-space points, row `j` (v) by column `i` (u).
pub(crate) type TestGrid = [[Vec3; TEST_N]; TEST_N];

impl Splitter {
    /// Decisions for `camera` and `frame`, dicing at `shading_rate` pixels per micropolygon
    /// into grids of at most `max_grid_size` micropolygons.
    pub fn new(
        camera: &CameraSetup,
        frame: &Frame,
        shading_rate: f32,
        max_grid_size: u32,
    ) -> Splitter {
        let border = frame.border as f32;
        let screen_lo = Vec2::splat(-border);
        let screen_hi = Vec2::new(
            (frame.buckets_x as f32) * frame.bucket_w as f32 - border,
            (frame.buckets_y as f32) * frame.bucket_h as f32 - border,
        );
        let lens = camera.lens();
        let frustum = lens.is_none().then(|| {
            let k = camera.raster_scale();
            let centre = camera.raster_centre();
            let lo = screen_lo - MARGIN_PIXELS;
            let hi = screen_hi + MARGIN_PIXELS;
            // Perspective: raster_x > hi.x  <=>  kx*x + (cx - hi.x)*z > 0 for z > 0, and so
            // on. Orthographic: raster_x > hi.x  <=>  kx*x + (cx - hi.x) > 0.
            let planes = [
                (Vec3::new(k.x, 0.0, 0.0), centre.x - hi.x),
                (Vec3::new(-k.x, 0.0, 0.0), lo.x - centre.x),
                (Vec3::new(0.0, k.y, 0.0), lo.y - centre.y),
                (Vec3::new(0.0, -k.y, 0.0), centre.y - hi.y),
            ];
            match camera.projection() {
                Projection::Perspective => {
                    planes.map(|(n, d)| (Vec3::new(n.x, n.y, d).normalize_or_zero(), 0.0))
                }
                Projection::Orthographic => planes.map(|(n, d)| {
                    let len = n.length();
                    if len > 0.0 { (n / len, d / len) } else { (Vec3::ZERO, 0.0) }
                }),
            }
        });
        let hither = camera.hither();
        Splitter {
            camera: camera.clone(),
            lens,
            hither,
            yon: camera.yon(),
            near: 0.5 * hither,
            screen_lo,
            screen_hi,
            frustum,
            step: step(shading_rate),
            max_grid: u64::from(max_grid_size.max(1)),
            flatness: 0.0,
            relative_flatness: 0.0,
            displace: 0.0,
            motion_factor: 0.0,
            focus_factor: 0.0,
            csg_depth: None,
        }
    }

    /// The same decisions with the flatness rule: a grid is diced finely enough that every
    /// point of the true surface lies within `min(flatness, relative * extent)` raster
    /// pixels of the flat micropolygons, at every breakpoint and every lens position, where
    /// `extent` is the patch's raster extent (see [`flat_counts`]). A bound of 0 is off; with
    /// both off every decision is the shading rate's alone.
    pub fn with_flatness(&self, flatness: f32, relative: f32) -> Splitter {
        Splitter { flatness, relative_flatness: relative, ..self.clone() }
    }

    /// The depth below which a micropolygon vertex is not kept (`hither / 2`).
    pub fn near(&self) -> f32 {
        self.near
    }

    /// Camera-space position of object-space point `p` of the surface in `pose`, as the
    /// test grids see it.
    #[inline]
    pub(crate) fn to_camera(&self, pose: &Pose<'_>, p: Vec3) -> Vec3 {
        match pose.moment.object_to_camera() {
            Some(m) => m.project_point3(p),
            None => pose.moment.camera_point(p),
        }
    }

    /// True if the whole surface seen in `poses` lies beyond hither at every breakpoint,
    /// with the safety margin for bulges between test points: hither does not cut it open.
    pub fn beyond_hither(&self, poses: &[Pose<'_>]) -> bool {
        let root = Patch::root();
        poses.iter().all(|pose| {
            let grid = self.test_grid(pose, &root);
            let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
            for p in grid.iter().flatten() {
                if !p.is_finite() {
                    return false;
                }
                lo = lo.min(*p);
                hi = hi.max(*p);
            }
            lo.z - MARGIN_FRACTION * (hi - lo).max_element() > self.hither
        })
    }

    /// The root patch of a surface seen in `poses`, with its four sides for crack-free
    /// dicing ([`edge`]), its corners on the surface.
    pub fn root_with_sides(&self, poses: &[Pose<'_>]) -> Patch {
        self.root_sharing(poses, SharedSides::default())
    }

    /// [`Splitter::root_with_sides`], taking the sides a neighbouring surface of the same
    /// object has already made (`given`) and making the others. Two sub-patches of a patch
    /// mesh meet along a curve each evaluates from its own control points, to rounding; each
    /// halving its own copy could halve it differently, so the first one to reach a shared
    /// boundary makes its edge and the other reads it ([`SharedSides`]).
    pub fn root_sharing(&self, poses: &[Pose<'_>], given: SharedSides) -> Patch {
        let corner = |u: f32, v: f32| -> Vec<Vec3> {
            poses.iter().map(|pose| pose.surface.position(u, v)).collect()
        };
        let (c00, c10, c01, c11) =
            (corner(0.0, 0.0), corner(1.0, 0.0), corner(0.0, 1.0), corner(1.0, 1.0));
        let ends = |a: &[Vec3], b: &[Vec3]| -> Vec<[Vec3; 2]> {
            a.iter().zip(b).map(|(a, b)| [*a, *b]).collect()
        };
        let extent = given.extent.unwrap_or_else(|| self.extent(poses, &Patch::root()));
        let tol = self.edge_tolerances(&extent, poses.len());
        let edge = |line: Line, a: &[Vec3], b: &[Vec3]| {
            Arc::new(Edge::new(self, poses, line, [0.0, 1.0], &ends(a, b), &tol))
        };
        let sides = Sides {
            bottom: given.bottom.unwrap_or_else(|| edge(Line::AlongU(0.0), &c00, &c10)),
            top: given.top.unwrap_or_else(|| edge(Line::AlongU(1.0), &c01, &c11)),
            left: given.left.unwrap_or_else(|| edge(Line::AlongV(0.0), &c00, &c01)),
            right: given.right.unwrap_or_else(|| edge(Line::AlongV(1.0), &c10, &c11)),
        };
        Patch { sides: Some(Arc::new(sides)), ..Patch::root() }
    }

    /// [`Patch::split`], with the halves' sides under crack-free dicing: the new edge
    /// between them, whose ends are the points of the sides it crosses at its line.
    pub fn split(
        &self,
        poses: &[Pose<'_>],
        patch: &Patch,
        (along_u, hither, count): (bool, bool, u64),
    ) -> [Patch; 2] {
        let mut halves = patch.split(along_u, hither, count);
        let Some(sides) = &patch.sides else {
            return halves;
        };
        let (line, range, from, to) = if along_u {
            let mid = halves[0].u[1];
            (Line::AlongV(mid), patch.v, (&sides.bottom, mid), (&sides.top, mid))
        } else {
            let mid = halves[0].v[1];
            (Line::AlongU(mid), patch.u, (&sides.left, mid), (&sides.right, mid))
        };
        let ends: Vec<[Vec3; 2]> =
            (0..poses.len()).map(|b| [from.0.at(b, from.1), to.0.at(b, to.1)]).collect();
        let tol = self.edge_tolerances(&patch.extent, poses.len());
        let middle = Arc::new(Edge::new(self, poses, line, range, &ends, &tol));
        let (mut lower, mut upper) = ((**sides).clone(), (**sides).clone());
        if along_u {
            lower.right = middle.clone();
            upper.left = middle;
        } else {
            lower.top = middle.clone();
            upper.bottom = middle;
        }
        halves[0].sides = Some(Arc::new(lower));
        halves[1].sides = Some(Arc::new(upper));
        halves
    }

    /// Camera-space test points of `patch` of the surface in `pose`, at the pose's time.
    pub fn test_grid(&self, pose: &Pose<'_>, patch: &Patch) -> TestGrid {
        fn fill(pose: &Pose<'_>, patch: &Patch, to_camera: impl Fn(Vec3) -> Vec3) -> TestGrid {
            let mut grid = [[Vec3::ZERO; TEST_N]; TEST_N];
            for (j, row) in grid.iter_mut().enumerate() {
                let v = Patch::at(patch.v, j, TEST_N - 1);
                for (i, p) in row.iter_mut().enumerate() {
                    let u = Patch::at(patch.u, i, TEST_N - 1);
                    *p = to_camera(pose.surface.position(u, v));
                }
            }
            grid
        }
        // One matrix or not, decided once per grid rather than per point.
        match pose.moment.object_to_camera() {
            Some(m) => fill(pose, patch, |p| m.project_point3(p)),
            None => fill(pose, patch, |p| pose.moment.camera_point(p)),
        }
    }

    /// Camera-space control hull of `patch` of the surface in `pose` (a rational Bezier
    /// patch's sub-patch net, which encloses it), or `None` for surfaces without one.
    pub fn hull_points(&self, pose: &Pose<'_>, patch: &Patch) -> Option<Vec<Vec3>> {
        let hull = pose.surface.hull(patch.u, patch.v)?;
        Some(match pose.moment.object_to_camera() {
            Some(m) => hull.into_iter().map(|p| m.project_point3(p)).collect(),
            None => hull.into_iter().map(|p| pose.moment.camera_point(p)).collect(),
        })
    }

    /// Raster bound of the test points grown by the safety margin and, with a lens, by the
    /// blur over the margin-grown depth range; `None` unless every point is finite with z > 0.
    #[cfg(test)]
    pub fn margin_bound(&self, grid: &TestGrid) -> Option<(Vec2, Vec2)> {
        self.margin_bound_with(grid, &[])
    }

    /// [`Splitter::margin_bound`] of the test points and the `hull` points together (the
    /// hull, when a surface has one, makes the bound conservative whatever its curvature).
    fn margin_bound_with(&self, grid: &TestGrid, hull: &[Vec3]) -> Option<(Vec2, Vec2)> {
        let mut lo = Vec2::INFINITY;
        let mut hi = Vec2::NEG_INFINITY;
        let (mut zmin, mut zmax) = (f32::INFINITY, f32::NEG_INFINITY);
        for p in grid.iter().flatten().chain(hull) {
            if !(p.is_finite() && p.z > 0.0) {
                return None;
            }
            let r = self.camera.eye_to_raster(*p);
            lo = lo.min(r);
            hi = hi.max(r);
            zmin = zmin.min(p.z);
            zmax = zmax.max(p.z);
        }
        let margin = MARGIN_FRACTION * (hi - lo).max_element() + MARGIN_PIXELS;
        let (mut lo3, mut hi3) =
            ([lo.x - margin, lo.y - margin, zmin], [hi.x + margin, hi.y + margin, zmax]);
        if let Some(lens) = &self.lens {
            let mz = MARGIN_FRACTION * (zmax - zmin);
            lo3[2] -= mz;
            hi3[2] += mz;
            lens.grow(&mut lo3, &mut hi3, self.hither, self.yon);
        }
        Some((Vec2::new(lo3[0], lo3[1]), Vec2::new(hi3[0], hi3[1])))
    }

    /// [`Splitter::decide_bound`] without the bound.
    #[cfg(test)]
    pub fn decide(&self, poses: &[Pose<'_>], patch: &Patch) -> Decision {
        self.decide_bound(poses, patch).0
    }

    /// Decide what to do with `patch` of a surface seen at every breakpoint of its motion
    /// (`poses`, in time order; one pose for a still object), with the top of the patch's
    /// raster bound (see [`Splitter::decide_grids_bound`]).
    pub fn decide_bound(&self, poses: &[Pose<'_>], patch: &Patch) -> (Decision, Option<f32>) {
        if let Some(crate::shapes::Surface::Points(_)) = poses.first().map(|p| p.surface) {
            return self.decide_points(poses, patch);
        }
        if self.displace > 0.0 {
            return self.decide_displaced(poses, patch);
        }
        let hulls: Vec<Vec<Vec3>> =
            poses.iter().filter_map(|pose| self.hull_points(pose, patch)).collect();
        if !hulls.is_empty() && hulls.len() == poses.len() {
            let grids: Vec<TestGrid> =
                poses.iter().map(|pose| self.test_grid(pose, patch)).collect();
            return self.decide_grids_hulls_bound(&grids, &hulls, patch);
        }
        if let [pose] = poses {
            let grid = self.test_grid(pose, patch);
            return self.decide_grids_bound(std::slice::from_ref(&grid), patch);
        }
        let grids: Vec<TestGrid> = poses.iter().map(|pose| self.test_grid(pose, patch)).collect();
        self.decide_grids_bound(&grids, patch)
    }

    /// [`Splitter::decide_bound`] of a displaced surface: the hull of every breakpoint is
    /// the corners of the cube of half-side `displace` about each of its points (its control
    /// hull's, or its test points'), which holds every displaced point within the margin.
    fn decide_displaced(&self, poses: &[Pose<'_>], patch: &Patch) -> (Decision, Option<f32>) {
        let r = self.displace;
        let grids: Vec<TestGrid> = poses.iter().map(|pose| self.test_grid(pose, patch)).collect();
        let hulls: Vec<Vec<Vec3>> = poses
            .iter()
            .zip(&grids)
            .map(|(pose, grid)| {
                let points = self
                    .hull_points(pose, patch)
                    .unwrap_or_else(|| grid.iter().flatten().copied().collect());
                points
                    .iter()
                    .flat_map(|p| {
                        (0..8).map(move |k| {
                            let s = |bit: u32| if k & bit == 0 { -r } else { r };
                            *p + Vec3::new(s(1), s(2), s(4))
                        })
                    })
                    .collect()
            })
            .collect();
        self.decide_grids_hulls_bound(&grids, &hulls, patch)
    }

    /// Decide from the test grids of every breakpoint, with the smallest raster y of the union of the
    /// margin-grown bounds ([`Splitter::margin_bound`]) over the breakpoints that count (those
    /// ending a segment some micropolygon may be seen in): every micropolygon the patch (or
    /// any part of it) emits lies below it, up to the margin's heuristic. `None` when some of
    /// those breakpoints has a point that is not finite or not in front of the eye (no raster
    /// bound), or the patch is culled.
    pub fn decide_grids_bound(&self, grids: &[TestGrid], patch: &Patch) -> (Decision, Option<f32>) {
        self.decide_grids_hulls_bound(grids, &[], patch)
    }

    /// [`Splitter::decide_grids_bound`] with, per breakpoint, the control hull of a surface
    /// that has one (`hulls` empty for the others): the depth range, the raster bound and
    /// the side-plane tests then cover the hull as well as the test points.
    fn decide_grids_hulls_bound(
        &self,
        grids: &[TestGrid],
        hulls: &[Vec<Vec3>],
        patch: &Patch,
    ) -> (Decision, Option<f32>) {
        // `None`: no finite test point at that time, so no usable vertex.
        let per_time: Vec<Option<GridFacts<'_>>> = grids
            .iter()
            .enumerate()
            .map(|(k, g)| self.grid_facts(k, g, hulls.get(k).map(Vec::as_slice)))
            .collect();
        // Breakpoints ending a segment some micropolygon may be seen in; only they count.
        let mut live = vec![false; per_time.len()];
        if let [one] = per_time.as_slice() {
            live[0] = !self.unseen(one.as_ref(), one.as_ref());
        } else {
            for (k, w) in per_time.windows(2).enumerate() {
                if !self.unseen(w[0].as_ref(), w[1].as_ref()) {
                    live[k] = true;
                    live[k + 1] = true;
                }
            }
        }
        let facts: Vec<GridFacts<'_>> =
            per_time.into_iter().zip(&live).filter_map(|(f, &l)| f.filter(|_| l)).collect();
        if facts.is_empty() {
            return (Decision::Cull, None);
        }
        let top = facts
            .iter()
            .map(|f| f.raster.map(|(lo, _)| lo.y))
            .try_fold(f32::INFINITY, |top, y| Some(top.min(y?)));
        let mz = |f: &GridFacts<'_>| MARGIN_FRACTION * (f.hi.z - f.lo.z);
        // Straddling hither at some breakpoint: part of the grid is nearer than hither there
        // (or not finite). All of it nearer is not straddling: splitting would not help.
        let straddles = facts
            .iter()
            .any(|f| !f.all_finite || (f.lo.z < self.hither && f.hi.z + mz(f) >= self.hither));
        if straddles {
            if patch.hither_splits < MAX_HITHER_SPLITS && patch.depth < MAX_SPLIT_DEPTH {
                let (len_u, len_v) = max_lengths(&facts, |p| p.is_finite().then_some(*p));
                return (Decision::Split { along_u: len_u >= len_v, hither: true, count: 0 }, top);
            }
            return (self.dice_decision(&facts, patch, true), top);
        }
        (self.dice_decision(&facts, patch, false), top)
    }

    /// The facts of `grid` (with the control `hull` of a surface that has one), or `None` if
    /// no point of it is finite.
    fn grid_facts<'a>(
        &self,
        pose: usize,
        grid: &'a TestGrid,
        hull: Option<&'a [Vec3]>,
    ) -> Option<GridFacts<'a>> {
        let mut all_finite = true;
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for p in grid.iter().flatten() {
            if p.is_finite() {
                lo = lo.min(*p);
                hi = hi.max(*p);
            } else {
                all_finite = false;
            }
        }
        let hull = hull.unwrap_or(&[]);
        for p in hull {
            if p.is_finite() {
                lo = lo.min(*p);
                hi = hi.max(*p);
            } else {
                all_finite = false;
            }
        }
        let raster = if all_finite { self.margin_bound_with(grid, hull) } else { None };
        (lo.z <= hi.z).then_some(GridFacts { pose, grid, hull, lo, hi, all_finite, raster })
    }

    /// True if no micropolygon of the segment from test grid `a` to test grid `b` (the same
    /// grid for a still patch) can be kept and touch a bucket, even
    /// allowing for bulges between test points. A kept micropolygon is not all in front of
    /// hither at both ends nor all beyond yon at both ends (its camera-space points move
    /// linearly, so it is then so throughout), and moves linearly in raster space and depth
    /// between its two end bounds. A moving one that comes nearer than `near` keeps the part
    /// of its segment in front of it (the emitter's `in_front`), whose ends lie between the
    /// segment's: so a segment with one end entirely near the eye, or behind it, may still
    /// be seen (an object passing the eye during the shutter).
    fn unseen(&self, a: Option<&GridFacts<'_>>, b: Option<&GridFacts<'_>>) -> bool {
        let (Some(a), Some(b)) = (a, b) else {
            return true;
        };
        let mz = |f: &GridFacts<'_>| MARGIN_FRACTION * (f.hi.z - f.lo.z);
        let nearer = |f: &GridFacts<'_>, depth: f32| f.hi.z + mz(f) < depth;
        let beyond = |f: &GridFacts<'_>| f.lo.z - mz(f) > self.yon;
        if (nearer(a, self.hither) && nearer(b, self.hither)) || (beyond(a) && beyond(b)) {
            return true;
        }
        // Screen: the margin-grown raster bounds of both ends miss the bucket grid.
        if let (Some((lo_a, hi_a)), Some((lo_b, hi_b))) = (a.raster, b.raster) {
            let (lo, hi) = (lo_a.min(lo_b), hi_a.max(hi_b));
            return hi.x < self.screen_lo.x
                || hi.y < self.screen_lo.y
                || lo.x > self.screen_hi.x
                || lo.y > self.screen_hi.y;
        }
        // Some points at or behind the eye: test the frustum's side planes in camera space.
        // Kept vertices are in front of the eye, where being outside a side plane is being
        // off that side of the screen, and a micropolygon moving linearly between two
        // positions off one side stays off it.
        match (&self.frustum, a.all_finite && b.all_finite) {
            (Some(planes), true) => planes.iter().any(|(n, d)| {
                [a, b].iter().all(|f| {
                    let m3 = MARGIN_FRACTION * (f.hi - f.lo).max_element();
                    f.grid.iter().flatten().chain(f.hull).all(|p| n.dot(*p) + d > m3)
                })
            }),
            _ => false,
        }
    }
}

/// Root sides made by a neighbour ([`Splitter::root_sharing`]); a whole blobby's extent.
#[derive(Debug, Clone, Default)]
pub(crate) struct SharedSides {
    pub bottom: Option<Arc<Edge>>,
    pub top: Option<Arc<Edge>>,
    pub left: Option<Arc<Edge>>,
    pub right: Option<Arc<Edge>>,
    pub extent: Option<Extent>,
}

/// What the decisions need to know of one breakpoint's test grid.
#[derive(Debug, Clone, Copy)]
struct GridFacts<'a> {
    /// The breakpoint it is of.
    pose: usize,
    grid: &'a TestGrid,
    /// The control hull of a surface that has one (empty otherwise).
    hull: &'a [Vec3],
    /// Camera-space bound of the finite points.
    lo: Vec3,
    hi: Vec3,
    /// Every point is finite.
    all_finite: bool,
    /// [`Splitter::margin_bound`] of the grid.
    raster: Option<(Vec2, Vec2)>,
}

mod blur;
pub(crate) mod edge;
pub(crate) mod extent;
mod flat;
mod points;
mod rate;

#[cfg(test)]
mod tests;
