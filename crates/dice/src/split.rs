//! Bound-and-split stage: decide, once per patch, whether to cull, split or dice it.
//!
//! Invariants: decisions look only at a `TEST_N x TEST_N` test grid of camera-space points,
//! so every bound grows by a safety margin (test points do not bound a curved surface);
//! a patch is culled only when it cannot produce a micropolygon that touches a bucket; a
//! diced patch never exceeds `max_grid_size` micropolygons; recursion is bounded by
//! `MAX_SPLIT_DEPTH` (and `MAX_HITHER_SPLITS` splits for straddling the hither plane).

use glam::{Mat4, Vec2, Vec3};
use reyes_hider::{Frame, LensSetup};

use crate::camera::CameraSetup;
use crate::shapes::Surface;

/// Test points per parameter direction.
pub(crate) const TEST_N: usize = 8;
/// Most splits from an object's whole parameter range to a patch (any reason).
pub(crate) const MAX_SPLIT_DEPTH: u32 = 40;
/// Most splits made because a patch straddles the hither plane.
pub(crate) const MAX_HITHER_SPLITS: u32 = 20;
/// Safety margin, as a fraction of the test points' extent. Between test points a curved
/// surface bulges by at most its sagitta; a full circle sampled at 8 points bulges by about
/// 10% of its diameter, so 25% covers every shape we dice with room for perspective.
const MARGIN_FRACTION: f32 = 0.25;
/// Extra safety margin in raster pixels (covers flat patches with a tiny extent).
const MARGIN_PIXELS: f32 = 2.0;
/// Most micropolygons along one side of a grid before clamping (keeps counts in range).
const MAX_SIDE: f64 = 1.0e9;

/// A rectangle of an object's parameter space, with its split history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Patch {
    /// `[u0, u1]`.
    pub u: [f32; 2],
    /// `[v0, v1]`.
    pub v: [f32; 2],
    /// Splits from the whole range.
    pub depth: u32,
    /// Of which because the patch straddled hither.
    pub hither_splits: u32,
}

impl Patch {
    /// The whole parameter range `[0, 1]^2`.
    pub fn root() -> Patch {
        Patch { u: [0.0, 1.0], v: [0.0, 1.0], depth: 0, hither_splits: 0 }
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

    /// The two halves, lower parameter half first.
    pub fn split(&self, along_u: bool, hither: bool) -> [Patch; 2] {
        let child = Patch {
            depth: self.depth + 1,
            hither_splits: self.hither_splits + u32::from(hither),
            ..*self
        };
        let (mut a, mut b) = (child, child);
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
    /// Split it in half (`along_u`: halve the u range), `hither`: because it straddles hither.
    Split { along_u: bool, hither: bool },
    /// Dice it into `nu x nv` micropolygons; `limited`: a split limit forced dicing.
    Dice { nu: u32, nv: u32, limited: bool },
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
    /// Outward unit normals of the four side planes of the (extended) view frustum, through
    /// the eye; `None` with a lens, whose blur the planes do not include.
    frustum: Option<[Vec3; 4]>,
    /// Micropolygon side length in pixels: `sqrt(shading_rate)`.
    step: f32,
    max_grid: u64,
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
            let k = camera.pixels_per_unit();
            let centre = 0.5 * camera.image_size();
            let lo = screen_lo - MARGIN_PIXELS;
            let hi = screen_hi + MARGIN_PIXELS;
            // raster_x > hi.x  <=>  k*x + (w/2 - hi.x)*z > 0 for z > 0, and so on.
            [
                Vec3::new(k, 0.0, centre.x - hi.x),
                Vec3::new(-k, 0.0, lo.x - centre.x),
                Vec3::new(0.0, k, lo.y - centre.y),
                Vec3::new(0.0, -k, centre.y - hi.y),
            ]
            .map(|n| n.normalize_or_zero())
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
            step: shading_rate.max(1e-6).sqrt(),
            max_grid: u64::from(max_grid_size.max(1)),
        }
    }

    /// The depth below which a micropolygon vertex is not kept (`hither / 2`).
    pub fn near(&self) -> f32 {
        self.near
    }

    /// Camera-space test points of `patch`.
    pub fn test_grid(&self, surface: &Surface, object_to_camera: &Mat4, patch: &Patch) -> TestGrid {
        let mut grid = [[Vec3::ZERO; TEST_N]; TEST_N];
        for (j, row) in grid.iter_mut().enumerate() {
            let v = Patch::at(patch.v, j, TEST_N - 1);
            for (i, p) in row.iter_mut().enumerate() {
                let u = Patch::at(patch.u, i, TEST_N - 1);
                *p = object_to_camera.project_point3(surface.position(u, v));
            }
        }
        grid
    }

    /// Raster bound of the test points grown by the safety margin and, with a lens, by the
    /// blur over the margin-grown depth range; `None` unless every point is finite with z > 0.
    pub fn margin_bound(&self, grid: &TestGrid) -> Option<(Vec2, Vec2)> {
        let mut lo = Vec2::INFINITY;
        let mut hi = Vec2::NEG_INFINITY;
        let (mut zmin, mut zmax) = (f32::INFINITY, f32::NEG_INFINITY);
        for p in grid.iter().flatten() {
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

    /// Decide what to do with `patch` of `surface`.
    pub fn decide(&self, surface: &Surface, object_to_camera: &Mat4, patch: &Patch) -> Decision {
        let grid = self.test_grid(surface, object_to_camera, patch);
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
        if lo.z > hi.z {
            return Decision::Cull; // no finite point at all
        }
        // Depth: all behind hither or all beyond yon, even allowing for bulges.
        let mz = MARGIN_FRACTION * (hi.z - lo.z);
        if hi.z + mz < self.hither || lo.z - mz > self.yon {
            return Decision::Cull;
        }
        // Screen: the margin-grown raster bound misses the bucket grid.
        if let Some((r_lo, r_hi)) = self.margin_bound(&grid) {
            if r_hi.x < self.screen_lo.x
                || r_hi.y < self.screen_lo.y
                || r_lo.x > self.screen_hi.x
                || r_lo.y > self.screen_hi.y
            {
                return Decision::Cull;
            }
        } else if let (Some(planes), true) = (&self.frustum, all_finite) {
            // Some points at or behind the eye: test the frustum's side planes in camera space.
            let m3 = MARGIN_FRACTION * (hi - lo).max_element();
            for n in planes {
                if grid.iter().flatten().all(|p| n.dot(*p) > m3) {
                    return Decision::Cull;
                }
            }
        }
        let straddles = !all_finite || lo.z < self.hither;
        if straddles {
            if patch.hither_splits < MAX_HITHER_SPLITS && patch.depth < MAX_SPLIT_DEPTH {
                let (len_u, len_v) = lengths(&grid, |p| p.is_finite().then_some(*p));
                return Decision::Split { along_u: len_u >= len_v, hither: true };
            }
            return self.dice_decision(&grid, patch, true);
        }
        self.dice_decision(&grid, patch, false)
    }

    /// Grid size from projected lengths; split if too big and allowed, else clamp.
    fn dice_decision(&self, grid: &TestGrid, patch: &Patch, at_limit: bool) -> Decision {
        // Only points that may become kept vertices count (all of them unless at the limit).
        let (len_u, len_v) = lengths(grid, |p| {
            (p.is_finite() && p.z >= self.near).then(|| self.camera.eye_to_raster(*p).extend(0.0))
        });
        let count =
            |len: f32| ((f64::from(len) / f64::from(self.step)).ceil()).clamp(1.0, MAX_SIDE) as u64;
        let (nu, nv) = (count(len_u), count(len_v));
        if nu * nv <= self.max_grid {
            return Decision::Dice { nu: nu as u32, nv: nv as u32, limited: at_limit };
        }
        if !at_limit && patch.depth < MAX_SPLIT_DEPTH {
            return Decision::Split { along_u: len_u >= len_v, hither: false };
        }
        let (nu, nv) = clamp_grid(nu, nv, self.max_grid);
        Decision::Dice { nu, nv, limited: true }
    }
}

/// `(len_u, len_v)`: the longest row and the longest column of the grid, each the sum of
/// its segment lengths between the images under `map` (segments with an unmapped end skipped).
fn lengths(grid: &TestGrid, map: impl Fn(&Vec3) -> Option<Vec3>) -> (f32, f32) {
    let mapped = grid.map(|row| row.map(|p| map(&p)));
    let seg = |a: Option<Vec3>, b: Option<Vec3>| match (a, b) {
        (Some(a), Some(b)) => a.distance(b),
        _ => 0.0,
    };
    let len_u = mapped
        .iter()
        .map(|row| row.windows(2).map(|w| seg(w[0], w[1])).sum::<f32>())
        .fold(0.0_f32, f32::max);
    let len_v = (0..TEST_N)
        .map(|i| (0..TEST_N - 1).map(|j| seg(mapped[j][i], mapped[j + 1][i])).sum::<f32>())
        .fold(0.0_f32, f32::max);
    (len_u, len_v)
}

/// Shrink an `nu x nv` grid proportionally to at most `max` micropolygons (each side >= 1).
fn clamp_grid(nu: u64, nv: u64, max: u64) -> (u32, u32) {
    if nu * nv <= max {
        return (nu as u32, nv as u32);
    }
    let f = (max as f64 / (nu as f64 * nv as f64)).sqrt();
    let nu2 = ((nu as f64 * f).floor() as u64).clamp(1, max);
    let nv2 = ((nv as f64 * f).floor() as u64).clamp(1, max / nu2);
    (nu2 as u32, nv2 as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::surfaces;
    use proptest::prelude::*;
    use reyes_scene::{Camera, Hider, Image, Material, Object, Scene, Shape, Shutter};

    fn scene(lens: Option<reyes_scene::Lens>) -> Scene {
        Scene {
            image: Image { width: 160, height: 120 },
            camera: Camera {
                eye: [0.0, 0.0, 0.0],
                look_at: [0.0, 0.0, 1.0],
                up: [0.0, 1.0, 0.0],
                fov: 40.0,
                hither: 0.1,
                yon: 100.0,
                shutter: Shutter::default(),
                lens,
                motion: vec![],
            },
            hider: Hider::default(),
            lights: vec![],
            objects: vec![],
        }
    }

    fn shape_object(shape: Shape) -> Object {
        Object {
            name: String::new(),
            shape,
            transform: vec![],
            material: Material::Constant { color: [1.0; 3], opacity: [1.0; 3] },
            matte: false,
            motion: vec![],
            deform: vec![],
        }
    }

    #[test]
    fn clamp_grid_respects_the_limit() {
        assert_eq!(clamp_grid(10, 10, 256), (10, 10));
        for (nu, nv, max) in [(1000, 1000, 256), (1_000_000_000, 1, 256), (3, 500, 7), (2, 2, 1)] {
            let (a, b) = clamp_grid(nu, nv, max);
            assert!(a >= 1 && b >= 1 && u64::from(a) * u64::from(b) <= max, "{nu}x{nv} -> {a}x{b}");
        }
    }

    #[test]
    fn split_halves_share_the_midpoint() {
        let [a, b] = Patch::root().split(true, false);
        assert_eq!((a.u, b.u, a.v, b.v), ([0.0, 0.5], [0.5, 1.0], [0.0, 1.0], [0.0, 1.0]));
        let [c, d] = a.split(false, true);
        assert_eq!((c.v, d.v, c.depth, c.hither_splits), ([0.0, 0.5], [0.5, 1.0], 2, 1));
        assert_eq!(Patch::at([0.25, 0.75], 7, 7), 0.75);
    }

    #[test]
    fn patches_behind_the_eye_or_off_screen_are_culled() {
        let s = scene(None);
        let cam = CameraSetup::new(&s);
        let frame = Frame::new(160, 120, 1, 16, 16);
        let sp = Splitter::new(&cam, &frame, 1.0, 256);
        let sphere = surfaces(&shape_object(Shape::Sphere {
            radius: 1.0,
            zmin: None,
            zmax: None,
            thetamax: 360.0,
        }))
        .remove(0);
        let at = |x: f32, y: f32, z: f32| Mat4::from_translation(Vec3::new(x, y, z));
        assert_eq!(sp.decide(&sphere, &at(0.0, 0.0, -5.0), &Patch::root()), Decision::Cull);
        assert_eq!(sp.decide(&sphere, &at(0.0, 0.0, 200.0), &Patch::root()), Decision::Cull);
        assert_eq!(sp.decide(&sphere, &at(30.0, 0.0, 10.0), &Patch::root()), Decision::Cull);
        // Beside the eye, behind the frustum's left plane: culled by the planes.
        assert_eq!(sp.decide(&sphere, &at(-5.0, 0.0, 0.5), &Patch::root()), Decision::Cull);
        // Around the eye: straddles hither, split.
        assert!(matches!(
            sp.decide(&sphere, &at(0.0, 0.0, 0.5), &Patch::root()),
            Decision::Split { hither: true, .. }
        ));
        // In view: split for size (a sphere at 10 units is about 120 pixels across).
        assert!(matches!(
            sp.decide(&sphere, &at(0.0, 0.0, 10.0), &Patch::root()),
            Decision::Split { hither: false, .. }
        ));
        // Far away: diced whole.
        assert!(matches!(
            sp.decide(&sphere, &at(0.0, 0.0, 90.0), &Patch::root()),
            Decision::Dice { .. }
        ));
    }

    proptest! {
        /// The margin-grown bound of a patch's test points contains the raster position of
        /// every point of the patch (sampled densely), for spheres and tori anywhere in view.
        #[test]
        fn margin_bound_contains_the_patch(
            torus in any::<bool>(),
            pos in (-4.0f32..4.0, -3.0f32..3.0, 3.0f32..30.0),
            axis in (-1.0f32..1.0, -1.0f32..1.0, 0.1f32..1.0),
            angle in 0.0f32..360.0,
            u0 in 0.0f32..1.0, du in 0.01f32..1.0,
            v0 in 0.0f32..1.0, dv in 0.01f32..1.0,
            with_lens in any::<bool>(),
        ) {
            let lens = with_lens.then_some(reyes_scene::Lens { focal_length: 0.1, f_stop: 2.0, focal_distance: 8.0 });
            let s = scene(lens);
            let cam = CameraSetup::new(&s);
            let frame = Frame::new(160, 120, 1, 16, 16);
            let sp = Splitter::new(&cam, &frame, 1.0, 256);
            let shape = if torus {
                Shape::Torus { major_radius: 1.0, minor_radius: 0.4, phimin: 0.0, phimax: 360.0, thetamax: 360.0 }
            } else {
                Shape::Sphere { radius: 1.2, zmin: None, zmax: None, thetamax: 360.0 }
            };
            let surface = surfaces(&shape_object(shape)).remove(0);
            let m = Mat4::from_translation(Vec3::new(pos.0, pos.1, pos.2))
                * Mat4::from_axis_angle(Vec3::new(axis.0, axis.1, axis.2).normalize(), angle.to_radians());
            let patch = Patch { u: [u0, (u0 + du).min(1.0)], v: [v0, (v0 + dv).min(1.0)], depth: 0, hither_splits: 0 };
            let grid = sp.test_grid(&surface, &m, &patch);
            let (lo, hi) = sp.margin_bound(&grid).expect("in front of the eye");
            let n = 40;
            for j in 0..=n {
                for i in 0..=n {
                    let u = Patch::at(patch.u, i, n);
                    let v = Patch::at(patch.v, j, n);
                    let p_camera = m.project_point3(surface.position(u, v));
                    let r = cam.eye_to_raster(p_camera);
                    prop_assert!(r.x >= lo.x && r.y >= lo.y && r.x <= hi.x && r.y <= hi.y,
                        "{r} outside {lo}..{hi}");
                }
            }
        }
    }
}
