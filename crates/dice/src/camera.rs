//! Camera stage: world -> camera (eye) space and eye -> raster projection (`EyeToScreenXY`).
//!
//! Invariants: camera space is +x right, +y up, +z forward (eye depth), built from an
//! orthonormal basis; raster space is pixels with y down, pixel (x, y) covering
//! `[x, x+1) x [y, y+1)`. Screen space is RenderMan's: a perspective camera puts a point at
//! `(x/z, y/z) / tan(fov/2)`, an orthographic one at `(x, y)`, and the screen window
//! `[left, right, bottom, top]` fills the image (left to right, top to bottom), so
//! `raster = centre + (kx sx, -ky sy)` for screen `(sx, sy)`. Without a screen window the
//! window is RenderMan's default (the shorter side spans [-1, 1]: the field of view spans
//! the shorter image side) and the mapping is computed exactly as it was before screen
//! windows existed (`centre = size / 2`, `kx = ky = (S/2) / tan(fov/2)`), bit for bit.
//! Perspective projection is only meaningful for `z > 0`; callers never project a point
//! with `z <= 0`. An orthographic camera has no depth of field: its lens is ignored. A
//! moving camera (`camera.motion`) changes only the view (eye, look-at point, up vector);
//! the projection, screen window, clipping depths and lens are the same at every time.

use glam::{Mat4, Vec2, Vec3};
use reyes_hider::LensSetup;
use reyes_scene::view::{self, ViewBasis as Basis, ViewError};
use reyes_scene::{Camera, Lens, Projection, Scene};

use crate::DiceError;

/// Where a camera is and where it looks, in world space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct View {
    /// Eye position.
    pub eye: Vec3,
    /// A point the camera looks at.
    pub look_at: Vec3,
    /// Up direction (need not be perpendicular to the view direction).
    pub up: Vec3,
}

impl View {
    /// The still view of `camera` (its `eye`, `look_at` and `up`).
    pub fn still(camera: &Camera) -> View {
        View {
            eye: Vec3::from(camera.eye),
            look_at: Vec3::from(camera.look_at),
            up: Vec3::from(camera.up),
        }
    }

    /// The view of motion key `k`.
    pub fn key(k: &reyes_scene::CameraKey) -> View {
        View { eye: Vec3::from(k.eye), look_at: Vec3::from(k.look_at), up: Vec3::from(k.up) }
    }

    /// The view at shutter open: the first motion key if the camera moves, else the still view.
    pub fn at_open(camera: &Camera) -> View {
        camera.motion.first().map_or_else(|| View::still(camera), View::key)
    }

    /// Each of eye, look-at point and up vector interpolated linearly by `f` (exactly
    /// unchanged where the two views agree).
    pub fn lerp(&self, other: &View, f: f32) -> View {
        use crate::motion::lerp;
        View {
            eye: lerp(self.eye, other.eye, f),
            look_at: lerp(self.look_at, other.look_at, f),
            up: lerp(self.up, other.up, f),
        }
    }
}

/// The camera basis of `view`, or why it has none (eye at look_at, up along the view): the
/// scene crate's [`view::basis`], which validation checks every camera view with.
fn basis(view: &View) -> Result<Basis, DiceError> {
    view::basis(view.eye, view.look_at, view.up).map_err(|e| match e {
        ViewError::NoDirection => DiceError::EyeAtLookAt,
        ViewError::UpParallel => DiceError::UpParallelToView,
    })
}

/// Check that the scene's camera has a well-defined view basis: the still view, or every
/// motion key when the camera moves (the keys replace the still view).
pub(crate) fn check_camera(camera: &Camera) -> Result<(), DiceError> {
    if camera.motion.is_empty() {
        basis(&View::still(camera)).map(|_| ())
    } else {
        camera.motion.iter().try_for_each(|k| basis(&View::key(k)).map(|_| ()))
    }
}

/// Where shaded points are seen from: what gives the viewing vector `V` of the illumination
/// models.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Viewer {
    /// A perspective camera's eye (or any single point): every point is seen from it.
    Eye(Vec3),
    /// An orthographic camera on the plane through `eye`, looking along the unit `forward`:
    /// every point is seen straight along its line of sight, `V = -forward`.
    Along {
        /// A point of the camera's eye plane.
        eye: Vec3,
        /// The unit view direction.
        forward: Vec3,
    },
}

impl Viewer {
    /// A point `p_world` is seen from: the eye, or (orthographic) the point
    /// `p_world - forward * max(depth, 1)` on its line of sight on the camera's side (at least
    /// a unit away, so that the direction to it is accurate), `depth` its eye depth.
    #[inline]
    pub fn seen_from(&self, p_world: Vec3) -> Vec3 {
        match *self {
            Viewer::Eye(eye) => eye,
            Viewer::Along { eye, forward } => {
                p_world - forward * (p_world - eye).dot(forward).max(1.0)
            }
        }
    }
}

/// World-to-camera transform and raster projection of a scene's camera.
#[derive(Debug, Clone, PartialEq)]
pub struct CameraSetup {
    eye_world: Vec3,
    basis: Basis,
    /// Image width in pixels.
    width: f32,
    /// Image height in pixels.
    height: f32,
    projection: Projection,
    /// Raster position of screen `(0, 0)`.
    centre: Vec2,
    /// Raster pixels per unit of screen-space `x/z` and `y/z` (perspective) or camera-space
    /// `x` and `y` (orthographic): without a screen window both are `(S/2) / tan(fov/2)`
    /// (perspective) or `S/2` (orthographic), `S` the shorter side.
    scale: Vec2,
    hither: f32,
    yon: f32,
    lens: Option<Lens>,
}

/// The raster mapping `(centre, scale)` of `cam` on a `width x height` image (see the module
/// documentation): the scene crate's [`view::raster_mapping`], which validation checks.
fn raster_mapping(cam: &Camera, width: f32, height: f32) -> (Vec2, Vec2) {
    view::raster_mapping(cam, width, height)
}

impl CameraSetup {
    /// Set up the camera of `scene`, seen from where it is at shutter open (its first motion
    /// key if it moves; the other keys are [`crate::dice_scene`]'s business).
    ///
    /// A degenerate camera (eye at `look_at`, or `up` parallel to the view) has no basis;
    /// [`crate::dice_scene`] reports it as an error, and here it falls back to looking
    /// down +z with +y up (or +x right when the view is along y) so that this never panics.
    pub fn new(scene: &Scene) -> CameraSetup {
        let cam = &scene.camera;
        let view = View::at_open(cam);
        let basis = basis(&view).unwrap_or_else(|_| fallback_basis(&view));
        let width = scene.image.width as f32;
        let height = scene.image.height as f32;
        let (centre, scale) = raster_mapping(cam, width, height);
        CameraSetup {
            eye_world: view.eye,
            basis,
            width,
            height,
            projection: cam.projection,
            centre,
            scale,
            hither: cam.hither,
            yon: cam.yon,
            // RenderMan ignores depth of field under an orthographic projection.
            lens: cam.lens.filter(|_| cam.projection == Projection::Perspective),
        }
    }

    /// The same camera (projection, clipping, lens) seen from `view`, falling back as
    /// [`CameraSetup::new`] does when `view` has no basis (an interpolated view can be
    /// degenerate even when the keys are not).
    pub(crate) fn with_view(&self, view: &View) -> CameraSetup {
        let basis = basis(view).unwrap_or_else(|_| fallback_basis(view));
        CameraSetup { eye_world: view.eye, basis, ..self.clone() }
    }

    /// The same camera (projection, clipping, lens) where `scene`'s camera is at normalised
    /// shutter time `t` (0 at open, 1 at close): its motion keys' eye, look-at point and up
    /// vector interpolated linearly as the dicer does (held before the first key and after
    /// the last), then the basis built from them. A still camera, or any camera when the
    /// shutter is closed, gives its view at shutter open. A degenerate interpolated view
    /// falls back as [`CameraSetup::new`] does.
    pub fn at_time(&self, scene: &Scene, t: f32) -> CameraSetup {
        self.with_view(&view_at(&scene.camera, t))
    }

    /// The primary ray of raster position `raster` (pixels, y down) and lens position
    /// `lens` (in lens-radius units, as the hider's samples), in world space: `(origin,
    /// dir)` with the origin on the lens (eye depth 0) and `dir` scaled so that its eye-depth
    /// component is 1, so the ray parameter of a point is its eye depth.
    ///
    /// The ray holds exactly the points the stochastic hider draws at `raster` for that lens
    /// position: it displaces a point at eye depth `z` projected at `P` to
    /// `P + (lx (x_a/z + x_b), ly (y_a/z + y_b))` (see [`LensSetup`]). Solving
    /// `X = cx + k x/z + lx (x_a/z + x_b)` for the eye-space `x` gives the line
    /// `x(z) = z (X - cx - lx x_b)/k - lx x_a/k` (and `y(z) = z (cy - Y + ly y_b)/k + ly y_a/k`,
    /// raster y pointing down): the lens point is `(-lx x_a/k, ly y_a/k, 0)` = `-R (lx, ly)`
    /// in eye space, and at the focal distance the line passes through the pinhole point of
    /// `raster` (the plane of focus is the plane `z = focal_distance`). A pinhole camera (or
    /// `lens == (0, 0)`) gives the ray from the eye through the pinhole point. (`k` stands for
    /// the raster scale `kx` across and `ky` down, `(cx, cy)` for the raster centre.)
    ///
    /// An orthographic camera's ray leaves the eye plane at the camera-space point
    /// `((X - cx)/kx, (cy - Y)/ky, 0)` along the view direction (`dir` = forward), which
    /// holds every point the hider draws at `raster`; it has no lens.
    pub fn primary_ray(&self, raster: Vec2, lens: (f32, f32)) -> (Vec3, Vec3) {
        let (kx, ky) = (self.scale.x, self.scale.y);
        let (cx, cy) = (self.centre.x, self.centre.y);
        let (lx, ly) = lens;
        let Basis { right, up, forward } = self.basis;
        if self.projection == Projection::Orthographic {
            let o = Vec2::new((raster.x - cx) / kx, (cy - raster.y) / ky);
            return (self.eye_world + right * o.x + up * o.y, forward);
        }
        let (o, d) = match self.lens() {
            Some(l) => (
                Vec2::new(-lx * l.x_a / kx, ly * l.y_a / ky),
                Vec2::new((raster.x - cx - lx * l.x_b) / kx, (cy - raster.y + ly * l.y_b) / ky),
            ),
            None => (Vec2::ZERO, Vec2::new((raster.x - cx) / kx, (cy - raster.y) / ky)),
        };
        let origin = self.eye_world + right * o.x + up * o.y;
        let dir = right * d.x + up * d.y + forward;
        (origin, dir)
    }

    /// The world-to-camera matrix (rigid: rows are right, up, forward; the eye maps to 0).
    pub fn world_to_camera(&self) -> Mat4 {
        self.basis.world_to_camera(self.eye_world)
    }

    /// Appendix A's `EyeToScreenXY`: raster position of a camera-space point with `z > 0`
    /// (perspective: `centre + (kx x/z, -ky y/z)`; orthographic: `centre + (kx x, -ky y)`).
    #[inline]
    pub fn eye_to_raster(&self, p_camera: Vec3) -> Vec2 {
        let (c, k) = (self.centre, self.scale);
        match self.projection {
            Projection::Perspective => {
                Vec2::new(c.x + k.x * p_camera.x / p_camera.z, c.y - k.y * p_camera.y / p_camera.z)
            }
            Projection::Orthographic => Vec2::new(c.x + k.x * p_camera.x, c.y - k.y * p_camera.y),
        }
    }

    /// Where this camera sees shaded points from (its eye, or along its view direction).
    pub fn viewer(&self) -> Viewer {
        match self.projection {
            Projection::Perspective => Viewer::Eye(self.eye_world),
            Projection::Orthographic => {
                Viewer::Along { eye: self.eye_world, forward: self.basis.forward }
            }
        }
    }

    /// The projection.
    pub fn projection(&self) -> Projection {
        self.projection
    }

    /// Port of `VisCameraSetup`: the depth-of-field constants, or `None` for a pinhole camera
    /// (and for any orthographic camera).
    pub fn lens(&self) -> Option<LensSetup> {
        let lens = self.lens?;
        let radius = lens.radius();
        let a_raster = self.eye_to_raster(Vec3::new(0.0, 0.0, 1.0));
        let b_raster = self.eye_to_raster(Vec3::new(1.0, 1.0, 1.0));
        Some(LensSetup::new(
            radius,
            lens.focal_distance,
            b_raster.x - a_raster.x,
            b_raster.y - a_raster.y,
        ))
    }

    /// Eye position in world space.
    pub fn eye_world(&self) -> Vec3 {
        self.eye_world
    }

    /// Near clipping depth (camera-space z).
    pub fn hither(&self) -> f32 {
        self.hither
    }

    /// Far clipping depth (camera-space z).
    pub fn yon(&self) -> f32 {
        self.yon
    }

    /// Raster pixels per unit of `x/z` (perspective) or of camera-space `x` (orthographic),
    /// across: without a screen window `(min(width, height)/2) / tan(fov/2)` or
    /// `min(width, height)/2`, the same down. See [`CameraSetup::raster_scale`] for both.
    pub fn pixels_per_unit(&self) -> f32 {
        self.scale.x
    }

    /// Raster pixels per unit of screen `x/z` and `y/z` (perspective) or camera-space `x`
    /// and `y` (orthographic): `(kx, ky)`, different when the screen window's aspect is not
    /// the image's.
    pub fn raster_scale(&self) -> Vec2 {
        self.scale
    }

    /// Raster position of the screen-space origin (the view axis): the image centre
    /// without a screen window.
    pub fn raster_centre(&self) -> Vec2 {
        self.centre
    }

    /// Image size in pixels, `(width, height)`.
    pub fn image_size(&self) -> Vec2 {
        Vec2::new(self.width, self.height)
    }
}

/// The view of `camera` at normalised shutter time `t`: as `CameraMotion::world_to_camera`
/// (key times normalised over the shutter, held outside the keys, eye, look-at point and up
/// lerped between them), without allocating.
fn view_at(camera: &Camera, t: f32) -> View {
    use crate::motion::ShutterTime;
    let keys = &camera.motion;
    let (Some(first), Some(last)) = (keys.first(), keys.last()) else {
        return View::still(camera);
    };
    let shutter = ShutterTime::new(&camera.shutter);
    if !shutter.is_open() {
        return View::key(first);
    }
    let time = |k: &reyes_scene::CameraKey| shutter.normalise(k.time);
    if t.is_nan() || t <= time(first) {
        return View::key(first);
    }
    if t >= time(last) {
        return View::key(last);
    }
    // time(first) < t < time(last): some later key's time exceeds t, and it is not key 0.
    let next = keys.iter().position(|k| time(k) > t).unwrap_or(keys.len() - 1).max(1);
    let (a, b) = (&keys[next - 1], &keys[next]);
    let (ta, tb) = (time(a), time(b));
    if t <= ta { View::key(a) } else { View::key(a).lerp(&View::key(b), (t - ta) / (tb - ta)) }
}

/// A usable basis for a degenerate view (see [`CameraSetup::new`]).
fn fallback_basis(view: &View) -> Basis {
    let forward = (view.look_at - view.eye).try_normalize().unwrap_or(Vec3::Z);
    let up_guess = if forward.y.abs() < 0.9 { Vec3::Y } else { Vec3::Z };
    let right = up_guess.cross(forward).try_normalize().unwrap_or(Vec3::X);
    Basis { right, up: forward.cross(right), forward }
}

#[cfg(test)]
mod tests {
    use super::*;
    use reyes_scene::Shutter;
    use reyes_testkit::fixtures;
    use reyes_testkit::random::Uniform;

    /// A `w x h` scene of nothing, with no lights, seen by a pinhole camera (`up` as given,
    /// otherwise the testkit camera).
    fn scene(eye: [f32; 3], look_at: [f32; 3], up: [f32; 3], fov: f32, w: u32, h: u32) -> Scene {
        let camera = Camera { up, ..fixtures::camera(eye, look_at, fov, None) };
        Scene { lights: vec![], ..fixtures::scene(w, h, camera, vec![]) }
    }

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn centre_projects_to_image_centre() {
        let cam =
            CameraSetup::new(&scene([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 60.0, 640, 480));
        let p = cam.eye_to_raster(Vec3::new(0.0, 0.0, 7.0));
        assert_eq!(p, Vec2::new(320.0, 240.0));
    }

    #[test]
    fn field_of_view_edges_hit_the_shorter_sides() {
        let fov = 35.0_f32;
        let cam =
            CameraSetup::new(&scene([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], fov, 640, 480));
        let t = (0.5 * fov.to_radians()).tan();
        let z = 3.0;
        // Top and bottom edges of the (shorter) vertical field of view.
        let top = cam.eye_to_raster(Vec3::new(0.0, t * z, z));
        let bottom = cam.eye_to_raster(Vec3::new(0.0, -t * z, z));
        assert!(close(top.y, 0.0, 1e-3) && close(top.x, 320.0, 1e-3), "{top}");
        assert!(close(bottom.y, 480.0, 1e-3), "{bottom}");
        // The image corners: the horizontal extent scales by the aspect ratio.
        let corner = cam.eye_to_raster(Vec3::new(t * z * 640.0 / 480.0, -t * z, z));
        assert!(close(corner.x, 640.0, 1e-3) && close(corner.y, 480.0, 1e-3), "{corner}");
        let corner = cam.eye_to_raster(Vec3::new(-t * z * 640.0 / 480.0, t * z, z));
        assert!(close(corner.x, 0.0, 1e-3) && close(corner.y, 0.0, 1e-3), "{corner}");
    }

    #[test]
    fn portrait_image_uses_width_as_the_shorter_side() {
        let cam =
            CameraSetup::new(&scene([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 90.0, 200, 400));
        let p = cam.eye_to_raster(Vec3::new(1.0, 0.0, 1.0));
        assert!(close(p.x, 200.0, 1e-3), "{p}");
        assert!(close(cam.pixels_per_unit(), 100.0, 1e-3));
    }

    #[test]
    fn world_to_camera_basis() {
        // Looking from (1,2,3) towards -x with a tilted up vector.
        let s = scene([1.0, 2.0, 3.0], [-4.0, 2.0, 3.0], [0.3, 1.0, 0.0], 45.0, 100, 100);
        let cam = CameraSetup::new(&s);
        let m = cam.world_to_camera();
        let eye = m.transform_point3(Vec3::new(1.0, 2.0, 3.0));
        assert!(eye.length() < 1e-6, "{eye}");
        let look = m.transform_point3(Vec3::new(-4.0, 2.0, 3.0));
        assert!((look - Vec3::new(0.0, 0.0, 5.0)).length() < 1e-5, "{look}");
        // World +y is camera up; looking down -x, world +z is to the right (left-handed).
        let up = m.transform_vector3(Vec3::Y);
        assert!((up - Vec3::Y).length() < 1e-6, "{up}");
        let right = m.transform_vector3(Vec3::Z);
        assert!((right - Vec3::X).length() < 1e-6, "{right}");
    }

    #[test]
    fn degenerate_cameras_are_reported_and_do_not_panic() {
        let s = scene([0.0; 3], [0.0; 3], [0.0, 1.0, 0.0], 45.0, 10, 10);
        assert_eq!(check_camera(&s.camera), Err(DiceError::EyeAtLookAt));
        let _ = CameraSetup::new(&s).world_to_camera();
        let s = scene([0.0; 3], [0.0, -5.0, 0.0], [0.0, 1.0, 0.0], 45.0, 10, 10);
        assert_eq!(check_camera(&s.camera), Err(DiceError::UpParallelToView));
        let m = CameraSetup::new(&s).world_to_camera();
        assert!(m.is_finite());
    }

    #[test]
    fn motion_keys_replace_the_still_view() {
        use reyes_scene::CameraKey;
        // A degenerate still view is not used when the camera has keys.
        let mut s = scene([0.0; 3], [0.0; 3], [0.0, 1.0, 0.0], 45.0, 10, 10);
        let key = |time: f32, eye: [f32; 3]| CameraKey {
            time,
            eye,
            look_at: [0.0, 0.0, 10.0],
            up: [0.0, 1.0, 0.0],
        };
        s.camera.motion = vec![key(0.0, [1.0, 2.0, 0.0]), key(1.0, [3.0, 2.0, 0.0])];
        assert_eq!(check_camera(&s.camera), Ok(()));
        // The setup is the camera at shutter open: the first key.
        let cam = CameraSetup::new(&s);
        assert_eq!(cam.eye_world(), Vec3::new(1.0, 2.0, 0.0));
        let p = cam.world_to_camera().transform_point3(Vec3::new(0.0, 0.0, 10.0));
        assert!(p.x.abs() < 1e-5 && p.y.abs() < 1e-5, "looks at its look_at: {p}");
        // A degenerate key is reported.
        s.camera.motion[1].eye = [0.0, 0.0, 10.0];
        assert_eq!(check_camera(&s.camera), Err(DiceError::EyeAtLookAt));
        // An interpolated view may be degenerate even when the keys are not: it falls back.
        let a = View::key(&key(0.0, [0.0, 0.0, 0.0]));
        let b = View { up: [0.0, -1.0, 0.0].into(), ..a };
        let mid = cam.with_view(&a.lerp(&b, 0.5));
        assert!(mid.world_to_camera().is_finite());
    }

    #[test]
    fn primary_rays_hold_what_the_stochastic_hider_draws() {
        // Random cameras, lenses and eye-space points: the raster position where the hider
        // draws the point for a lens position (pinhole projection plus the lens displacement)
        // must give a ray through the point, reaching it at parameter = its eye depth.
        let mut uniform = Uniform::new(0x7e57);
        for case in 0..200 {
            let mut r = |lo: f32, hi: f32| uniform.range(lo, hi);
            let eye = [r(-5.0, 5.0), r(-5.0, 5.0), r(-5.0, 5.0)];
            let look_at = [r(-5.0, 5.0), r(-5.0, 5.0), r(-5.0, 5.0)];
            let up = [r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0)];
            let (w, h) = ((r(16.0, 800.0)) as u32, (r(16.0, 800.0)) as u32);
            let mut s = scene(eye, look_at, up, r(10.0, 120.0), w, h);
            if check_camera(&s.camera).is_err() {
                continue;
            }
            if case % 4 != 0 {
                s.camera.lens = Some(Lens {
                    focal_length: r(0.01, 2.0),
                    f_stop: r(1.0, 16.0),
                    focal_distance: r(0.5, 20.0),
                });
            }
            let cam = CameraSetup::new(&s);
            let to_world = cam.world_to_camera().inverse();
            for _ in 0..20 {
                let z = r(0.2, 60.0);
                let p = Vec3::new(r(-1.0, 1.0) * z, r(-1.0, 1.0) * z, z);
                let (lx, ly) = (r(-1.0, 1.0), r(-1.0, 1.0));
                let mut raster = cam.eye_to_raster(p);
                if let Some(l) = cam.lens() {
                    let (dx, dy) = l.coc(z);
                    raster += Vec2::new(lx * dx, ly * dy);
                }
                let (o, d) = cam.primary_ray(raster, (lx, ly));
                let p_world = to_world.transform_point3(p);
                let on_ray = o + d * z;
                let tol = 2e-5 * (1.0 + p_world.abs().max_element() + o.abs().max_element());
                assert!(
                    (on_ray - p_world).abs().max_element() <= tol * (1.0 + z),
                    "case {case}: {on_ray} vs {p_world} (z {z}, lens {lx} {ly})"
                );
                // The ray parameter is eye depth: the origin is at depth 0, dir has depth 1.
                let m = cam.world_to_camera();
                assert!(m.transform_point3(o).z.abs() <= 1e-4 * (1.0 + o.length()));
                assert!((m.transform_vector3(d).z - 1.0).abs() <= 1e-5);
            }
        }
    }

    #[test]
    fn lens_points_lie_on_the_lens_and_rays_meet_in_the_plane_of_focus() {
        let mut s = scene([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 60.0, 200, 100);
        s.camera.lens = Some(Lens { focal_length: 1.0, f_stop: 2.0, focal_distance: 5.0 });
        let cam = CameraSetup::new(&s);
        let raster = Vec2::new(130.0, 40.0);
        let (o0, d0) = cam.primary_ray(raster, (0.0, 0.0));
        assert_eq!(o0, Vec3::ZERO, "lens centre is the eye");
        let focus = o0 + d0 * 5.0;
        for lens in [(1.0, 0.0), (0.0, 1.0), (-0.6, 0.8)] {
            let (o, d) = cam.primary_ray(raster, lens);
            // Radius 0.25 = 0.5 * 1 / 2; the lens point is -R (lx, ly) in eye space.
            let want = Vec3::new(-0.25 * lens.0, -0.25 * lens.1, 0.0);
            assert!((o - want).length() < 1e-6, "{o} vs {want}");
            assert!((o + d * 5.0 - focus).length() < 1e-5, "every lens ray meets the focus");
        }
    }

    #[test]
    fn at_time_interpolates_the_camera_keys_as_the_dicer() {
        use crate::motion::CameraMotion;
        use reyes_scene::CameraKey;
        let mut s = scene([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 45.0, 10, 10);
        let cam = CameraSetup::new(&s);
        assert_eq!(cam.at_time(&s, 0.7), cam, "a still camera does not move");
        s.camera.shutter = Shutter { open: 1.0, close: 3.0, ..Shutter::default() };
        s.camera.motion = vec![
            CameraKey {
                time: 1.5,
                eye: [0.0, 0.0, 0.0],
                look_at: [0.0, 0.0, 5.0],
                up: [0.0, 1.0, 0.0],
            },
            CameraKey {
                time: 2.0,
                eye: [2.0, 0.0, 0.0],
                look_at: [1.0, 0.0, 5.0],
                up: [0.3, 1.0, 0.0],
            },
            CameraKey {
                time: 3.0,
                eye: [2.0, 4.0, 1.0],
                look_at: [1.0, 0.0, 5.0],
                up: [0.0, 1.0, 0.0],
            },
        ];
        let cam = CameraSetup::new(&s);
        let motion = CameraMotion::new(&s);
        for t in [0.0, 0.1, 0.25, 0.3, 0.5, 0.51, 0.9, 1.0] {
            let a = cam.at_time(&s, t).world_to_camera();
            assert_eq!(a, motion.world_to_camera(t), "t {t}");
        }
        assert_eq!(cam.at_time(&s, 0.0).eye_world(), Vec3::ZERO);
        assert_eq!(cam.at_time(&s, 0.5).eye_world(), Vec3::new(2.0, 0.0, 0.0));
        assert_eq!(cam.at_time(&s, 0.75).eye_world(), Vec3::new(2.0, 2.0, 0.5));
        // A closed shutter: the first key throughout.
        s.camera.shutter.close = 1.0;
        assert_eq!(cam.at_time(&s, 0.9).eye_world(), Vec3::ZERO);
    }

    #[test]
    fn lens_matches_thin_lens_formula() {
        let mut s = scene([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 40.0, 320, 240);
        assert!(CameraSetup::new(&s).lens().is_none());
        s.camera.lens = Some(Lens { focal_length: 0.05, f_stop: 2.8, focal_distance: 4.0 });
        let cam = CameraSetup::new(&s);
        let lens = cam.lens().expect("lens");
        let r = 0.5 * 0.05 / 2.8;
        let k = cam.pixels_per_unit();
        for z in [0.5_f32, 1.0, 4.0, 10.0, 100.0] {
            let expect = r * k * (1.0 / z - 1.0 / 4.0);
            let (dx, dy) = lens.coc(z);
            assert!(close(dx, expect, 1e-4 * (1.0 + expect.abs())), "z {z}: {dx} vs {expect}");
            // Raster y grows downward, so the y displacement has the opposite sign.
            assert!(close(dy, -expect, 1e-4 * (1.0 + expect.abs())), "z {z}: {dy} vs {}", -expect);
        }
        assert!(lens.coc(4.0).0.abs() < 1e-6, "in focus at the focal distance");
    }
}
