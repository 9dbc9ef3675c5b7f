//! Motion stage: shutter-normalised time, an object's breakpoints, and where the object and
//! the camera are at each breakpoint.
//!
//! Invariants: times are normalised over the shutter, `t = (time - open) / (close - open)`,
//! clamped to `[0, 1]`. A keyed quantity is exactly key `i` at key time `i`, its first key
//! up to the first key time, its last key from the last key time, and linear in between:
//! object transforms lerp the world-space points the two keys' matrices give, the camera
//! lerps eye, look-at point and up and then builds its basis, deformation lerps the control
//! points. An object's breakpoints are sorted and distinct, start at 0 (where every keyed
//! quantity is exactly a key, so shading sees exact geometry), and end at 1 when there is
//! more than one. An object with no keys under a camera with none, or any object when the
//! shutter is closed (`close == open`), has the single breakpoint 0: it does not move.

use glam::{Mat3, Mat4, Vec3};
use reyes_scene::curves::Facing;
use reyes_scene::{Object, Scene, Shape, Shutter};

use crate::camera::{CameraSetup, View};
use crate::shapes::{self, Surface};
use reyes_scene::{normal_matrix, object_to_world};

/// `a + (b - a) * f`: linear interpolation that is exactly `a` wherever `a == b` (so a
/// quantity held still between keys does not move by a rounding error) and at `f == 0`.
#[inline]
pub(crate) fn lerp(a: Vec3, b: Vec3, f: f32) -> Vec3 {
    a + (b - a) * f
}

/// Where a normalised time falls among key times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum KeyAt {
    /// Exactly key `i`: at its time, or held before the first or after the last key.
    Key(usize),
    /// Between key `i` and key `i + 1`, a fraction in `(0, 1)` of the way.
    Between(usize, f32),
}

/// Where `t` falls among `times` (which should be increasing). Never panics, and never
/// gives a fraction outside `(0, 1)`, even for unsorted times; `Key(0)` for no times.
pub(crate) fn locate(times: &[f32], t: f32) -> KeyAt {
    let (Some(&first), Some(&last)) = (times.first(), times.last()) else {
        return KeyAt::Key(0);
    };
    if t.is_nan() || t <= first {
        return KeyAt::Key(0);
    }
    if t >= last {
        return KeyAt::Key(times.len() - 1);
    }
    // first < t < last, so some later key time exceeds t, and it is not key 0.
    let next = times.iter().position(|&k| k > t).unwrap_or(times.len() - 1).max(1);
    let (a, b) = (times[next - 1], times[next]);
    if t <= a { KeyAt::Key(next - 1) } else { KeyAt::Between(next - 1, (t - a) / (b - a)) }
}

/// The shutter interval, for normalising scene times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ShutterTime {
    open: f32,
    /// `close - open`.
    span: f32,
}

impl ShutterTime {
    /// The interval of `shutter`.
    pub fn new(shutter: &Shutter) -> ShutterTime {
        ShutterTime { open: shutter.open, span: shutter.close - shutter.open }
    }

    /// True if the shutter is open for a positive, finite time (else nothing moves).
    pub fn is_open(&self) -> bool {
        self.span > 0.0 && self.span.is_finite()
    }

    /// Normalised time of scene time `time`, clamped to `[0, 1]`; 0 when the shutter is
    /// closed (everything is evaluated at `open`) or the time is not a number.
    pub fn normalise(&self, time: f32) -> f32 {
        if !self.is_open() {
            return 0.0;
        }
        let t = (time - self.open) / self.span;
        if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) }
    }
}

/// The camera over the shutter.
#[derive(Debug, Clone)]
pub(crate) struct CameraMotion {
    /// The camera at shutter open (projection, clipping and lens hold at every time).
    setup: CameraSetup,
    /// Normalised key times; empty for a still camera.
    times: Vec<f32>,
    /// The view of each key.
    views: Vec<View>,
    /// World-to-camera matrix of each key.
    key_world_to_camera: Vec<Mat4>,
    /// World-to-camera matrix of the still camera (or of the first key).
    still_world_to_camera: Mat4,
}

impl CameraMotion {
    /// The camera of `scene` and its motion keys.
    pub fn new(scene: &Scene) -> CameraMotion {
        let setup = CameraSetup::new(scene);
        let shutter = ShutterTime::new(&scene.camera.shutter);
        let keys = &scene.camera.motion;
        let times = keys.iter().map(|k| shutter.normalise(k.time)).collect();
        let views: Vec<View> = keys.iter().map(View::key).collect();
        let key_world_to_camera =
            views.iter().map(|v| setup.with_view(v).world_to_camera()).collect();
        let still_world_to_camera = setup.world_to_camera();
        CameraMotion { setup, times, views, key_world_to_camera, still_world_to_camera }
    }

    /// The camera at shutter open.
    pub fn setup(&self) -> &CameraSetup {
        &self.setup
    }

    /// Normalised key times (empty for a still camera).
    pub fn key_times(&self) -> &[f32] {
        &self.times
    }

    /// World-to-camera matrix at normalised time `t`.
    pub fn world_to_camera(&self, t: f32) -> Mat4 {
        match locate(&self.times, t) {
            KeyAt::Key(i) => {
                self.key_world_to_camera.get(i).copied().unwrap_or(self.still_world_to_camera)
            }
            KeyAt::Between(i, f) => match (self.views.get(i), self.views.get(i + 1)) {
                (Some(a), Some(b)) => self.setup.with_view(&a.lerp(b, f)).world_to_camera(),
                _ => self.still_world_to_camera,
            },
        }
    }
}

/// An object's object-to-world placement at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Placement {
    /// One matrix: a transform key, or the still transform.
    Matrix(Mat4),
    /// Between two transform keys: the points the two matrices give, lerped by `f`.
    Between {
        /// The earlier key's matrix.
        from: Mat4,
        /// The later key's matrix.
        to: Mat4,
        /// Fraction of the way, in `(0, 1)`.
        f: f32,
    },
}

impl Placement {
    /// World-space position of an object-space point.
    #[inline]
    pub fn world_point(&self, p_object: Vec3) -> Vec3 {
        match self {
            Placement::Matrix(m) => m.project_point3(p_object),
            Placement::Between { from, to, f } => {
                lerp(from.project_point3(p_object), to.project_point3(p_object), *f)
            }
        }
    }

    /// The matrix carrying object-space normals to world space. Shading happens at shutter
    /// open, where the placement is always one matrix; between keys this is the earlier key's.
    pub fn normal_to_world(&self) -> Mat3 {
        match self {
            Placement::Matrix(m) | Placement::Between { from: m, .. } => normal_matrix(m),
        }
    }
}

/// Where the camera is, in the object's space at normalised time `t` under `place`: the
/// eye of a perspective camera, the view direction of an orthographic one (what a
/// camera-facing ribbon turns toward). Between two transform keys, the eyes the two keys'
/// inverses give, lerped.
pub(crate) fn facing(camera: &CameraMotion, t: f32, place: &Placement) -> Facing {
    let w2c = camera.world_to_camera(t);
    let orthographic = camera.setup().projection() == reyes_scene::Projection::Orthographic;
    let seen = |m: Mat4| {
        let c2o = (w2c * m).inverse();
        if orthographic {
            Facing::Along(c2o.transform_vector3(Vec3::Z).normalize_or_zero())
        } else {
            Facing::Eye(c2o.transform_point3(Vec3::ZERO))
        }
    };
    match *place {
        Placement::Matrix(m) => seen(m),
        Placement::Between { from, to, f } => match (seen(from), seen(to)) {
            (Facing::Eye(a), Facing::Eye(b)) => Facing::Eye(lerp(a, b, f)),
            (Facing::Along(a), Facing::Along(b)) => {
                Facing::Along(lerp(a, b, f).normalize_or_zero())
            }
            (a, _) => a,
        },
    }
}

/// An object and the camera at one breakpoint.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Moment {
    /// Normalised time.
    pub t: f32,
    /// Object to world.
    pub place: Placement,
    /// World to camera.
    pub world_to_camera: Mat4,
    /// `world_to_camera * m` when the placement is one matrix `m`.
    object_to_camera: Option<Mat4>,
    /// Index of the object's surfaces at this time in [`ObjectMotion::poses`]'s sets.
    shape: usize,
}

impl Moment {
    /// The moment at normalised time `t` with placement `place`, camera `world_to_camera`
    /// and surface set `shape`.
    pub fn new(t: f32, place: Placement, world_to_camera: Mat4, shape: usize) -> Moment {
        let object_to_camera = match place {
            Placement::Matrix(m) => Some(world_to_camera * m),
            Placement::Between { .. } => None,
        };
        Moment { t, place, world_to_camera, object_to_camera, shape }
    }

    /// `world_to_camera * object_to_world` when the placement is one matrix.
    #[inline]
    pub fn object_to_camera(&self) -> Option<&Mat4> {
        self.object_to_camera.as_ref()
    }

    /// Camera-space position of an object-space point, as the bound-and-split tests see it
    /// (one matrix product when the placement is one matrix).
    #[inline]
    pub fn camera_point(&self, p_object: Vec3) -> Vec3 {
        match &self.object_to_camera {
            Some(m) => m.project_point3(p_object),
            None => self.world_to_camera.transform_point3(self.place.world_point(p_object)),
        }
    }

    /// World-space and camera-space positions of an object-space point, as diced.
    #[inline]
    pub fn world_and_camera(&self, p_object: Vec3) -> (Vec3, Vec3) {
        let p_world = self.place.world_point(p_object);
        (p_world, self.world_to_camera.transform_point3(p_world))
    }
}

/// One surface of an object at one breakpoint.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pose<'a> {
    /// The surface (its shape at this time).
    pub surface: &'a Surface,
    /// The object's placement and the camera at this time.
    pub moment: &'a Moment,
}

/// An object over the shutter: its breakpoints and its surfaces at each.
#[derive(Debug, Clone)]
pub(crate) struct ObjectMotion {
    /// One per breakpoint, in increasing time; the first at time 0.
    moments: Vec<Moment>,
    /// Surface sets: one per breakpoint for a deforming shape, else just the shape's own.
    shapes: Vec<Vec<Surface>>,
}

impl ObjectMotion {
    /// The motion of `object` seen by `camera`, with the scene's `shutter`. With `closed`
    /// (the object is a CSG operand) every surface set ends with the shape's end caps
    /// ([`shapes::end_caps`]), which move with the object.
    pub fn new(
        object: &Object,
        camera: &CameraMotion,
        shutter: &ShutterTime,
        closed: bool,
    ) -> ObjectMotion {
        let xform_times: Vec<f32> =
            object.motion.iter().map(|k| shutter.normalise(k.time)).collect();
        let xforms: Vec<Mat4> =
            object.motion.iter().map(|k| object_to_world(&k.transform)).collect();
        let still = object_to_world(&object.transform);
        // Deformation keys, each with exactly the shape's point count (missing points are
        // the shape's own, extra points are ignored), for shapes that can deform.
        let own_points =
            shapes::control_points(&object.shape).filter(|_| !object.deform.is_empty());
        let deform_times: Vec<f32> = match &own_points {
            Some(_) => object.deform.iter().map(|k| shutter.normalise(k.time)).collect(),
            None => Vec::new(),
        };
        let deform_points: Vec<Vec<Vec3>> = match &own_points {
            Some(own) => object
                .deform
                .iter()
                .map(|k| {
                    own.iter()
                        .enumerate()
                        .map(|(i, p)| k.points.get(i).map_or(*p, |q| Vec3::from(*q)))
                        .collect()
                })
                .collect(),
            None => Vec::new(),
        };

        let mut times = vec![0.0_f32];
        let keyed =
            !(xform_times.is_empty() && deform_times.is_empty() && camera.key_times().is_empty());
        if shutter.is_open() && keyed {
            times.push(1.0);
            times.extend_from_slice(&xform_times);
            times.extend_from_slice(&deform_times);
            times.extend_from_slice(camera.key_times());
            times.sort_by(f32::total_cmp);
            times.dedup();
        }

        // Camera-facing ribbons face the camera of each breakpoint: their surfaces are made
        // per breakpoint when the object or the camera moves.
        let facing_at = |t: f32, place: &Placement| facing(camera, t, place);
        let faces_camera =
            matches!(&object.shape, Shape::Curves { normals: None, .. } | Shape::Points { .. });
        let caps = if closed { shapes::end_caps(&object.shape) } else { Vec::new() };
        let with_caps = |mut set: Vec<Surface>| {
            set.extend(caps.iter().cloned());
            set
        };
        let deforming = !deform_points.is_empty();
        let per_moment = deforming || (faces_camera && times.len() > 1);
        let mut shapes = Vec::with_capacity(if per_moment { times.len() } else { 1 });
        if !per_moment {
            let open = Placement::Matrix(xforms.first().copied().unwrap_or(still));
            shapes.push(with_caps(shapes::surfaces(object, facing_at(0.0, &open))));
        }
        let mut moments = Vec::with_capacity(times.len());
        for (b, &t) in times.iter().enumerate() {
            let place = if xforms.is_empty() {
                Placement::Matrix(still)
            } else {
                match locate(&xform_times, t) {
                    KeyAt::Key(i) => Placement::Matrix(xforms[i]),
                    KeyAt::Between(i, f) => {
                        Placement::Between { from: xforms[i], to: xforms[i + 1], f }
                    }
                }
            };
            if per_moment {
                let points_object: Option<Vec<Vec3>> =
                    deforming.then(|| match locate(&deform_times, t) {
                        KeyAt::Key(i) => deform_points[i].clone(),
                        KeyAt::Between(i, f) => deform_points[i]
                            .iter()
                            .zip(&deform_points[i + 1])
                            .map(|(a, b)| lerp(*a, *b, f))
                            .collect(),
                    });
                let set = shapes::shape_surfaces(
                    &object.shape,
                    points_object.as_deref(),
                    facing_at(t, &place),
                );
                shapes.push(with_caps(set));
            }
            let shape = if per_moment { b } else { 0 };
            moments.push(Moment::new(t, place, camera.world_to_camera(t), shape));
        }
        ObjectMotion { moments, shapes }
    }

    /// A bound on how far a displacement of object-space length 1 moves a point in camera
    /// space, at any breakpoint: the largest Frobenius norm (at least the largest singular
    /// value) of the linear part of object to camera. Between two transform keys a point is
    /// lerped between the keys' images, so the larger of the two bounds it. (For affine
    /// placements; a projective matrix has no such constant.)
    pub fn largest_scale(&self) -> f32 {
        let norm = |m: Mat4, w: Mat4| {
            let l = Mat3::from_mat4(w * m);
            (l.x_axis.length_squared() + l.y_axis.length_squared() + l.z_axis.length_squared())
                .sqrt()
        };
        self.moments
            .iter()
            .map(|m| match m.place {
                Placement::Matrix(a) => norm(a, m.world_to_camera),
                Placement::Between { from, to, .. } => {
                    norm(from, m.world_to_camera).max(norm(to, m.world_to_camera))
                }
            })
            .fold(0.0, f32::max)
    }

    /// The breakpoints, the first at time 0.
    pub fn moments(&self) -> &[Moment] {
        &self.moments
    }

    /// Number of surfaces (the same at every time).
    pub fn surface_count(&self) -> usize {
        self.shapes.first().map_or(0, Vec::len)
    }

    /// Surface `index` at every breakpoint, in time order (empty if there is no such surface).
    pub fn poses(&self, index: usize) -> Vec<Pose<'_>> {
        let own = self.shapes.first().and_then(|s| s.get(index));
        self.moments
            .iter()
            .filter_map(|m| {
                let surface = self.shapes.get(m.shape).and_then(|s| s.get(index)).or(own)?;
                Some(Pose { surface, moment: m })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lerp_holds_equal_ends_exactly() {
        let a = Vec3::new(57.742737, -54.365494, 6.101306);
        for k in 0..=100 {
            assert_eq!(lerp(a, a, k as f32 / 100.0), a);
        }
        assert_eq!(lerp(a, Vec3::ZERO, 0.0), a);
        assert_eq!(lerp(Vec3::ZERO, Vec3::new(2.0, 4.0, 8.0), 0.25), Vec3::new(0.5, 1.0, 2.0));
    }

    #[test]
    fn locate_holds_outside_and_interpolates_inside() {
        let times = [0.25, 0.5, 0.75];
        assert_eq!(locate(&times, 0.0), KeyAt::Key(0));
        assert_eq!(locate(&times, 0.25), KeyAt::Key(0));
        assert_eq!(locate(&times, 0.5), KeyAt::Key(1));
        assert_eq!(locate(&times, 0.75), KeyAt::Key(2));
        assert_eq!(locate(&times, 1.0), KeyAt::Key(2));
        assert_eq!(locate(&times, 0.375), KeyAt::Between(0, 0.5));
        assert_eq!(locate(&times, 0.625), KeyAt::Between(1, 0.5));
        assert_eq!(locate(&[], 0.5), KeyAt::Key(0));
        assert_eq!(locate(&times, f32::NAN), KeyAt::Key(0));
        // Unsorted or repeated times give a key or a fraction strictly inside (0, 1).
        for times in [[0.5, 0.2, 0.9], [0.1, 0.1, 0.9], [0.9, 0.1, 0.95]] {
            for k in 0..=20 {
                if let KeyAt::Between(i, f) = locate(&times, k as f32 / 20.0) {
                    assert!(i + 1 < times.len() && f > 0.0 && f < 1.0, "{times:?} {k}: {f}");
                }
            }
        }
    }

    #[test]
    fn shutter_normalises_and_a_closed_shutter_is_time_zero() {
        let s = ShutterTime::new(&Shutter { open: 2.0, close: 4.0, ..Shutter::default() });
        assert!(s.is_open());
        assert_eq!(s.normalise(2.0), 0.0);
        assert_eq!(s.normalise(3.0), 0.5);
        assert_eq!(s.normalise(4.0), 1.0);
        assert_eq!(s.normalise(9.0), 1.0);
        let closed = ShutterTime::new(&Shutter { open: 2.0, close: 2.0, ..Shutter::default() });
        assert!(!closed.is_open());
        assert_eq!(closed.normalise(2.5), 0.0);
    }

    #[test]
    fn between_keys_the_points_are_lerped_not_the_matrices() {
        // A quarter turn about z: the lerped matrix would shrink (1,0,0) to length 0.707 at
        // the middle; the lerped points do too, but through the chord, not the arc.
        let from = Mat4::IDENTITY;
        let to = Mat4::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let mid = Placement::Between { from, to, f: 0.5 }.world_point(Vec3::X);
        assert!((mid - Vec3::new(0.5, 0.5, 0.0)).length() < 1e-6, "{mid}");
        // A projective key: the points are lerped after the homogeneous divide.
        let proj = Mat4::from_cols_array_2d(&[
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 2.0],
        ]);
        let p = Placement::Between { from, to: proj, f: 0.5 }.world_point(Vec3::new(2.0, 4.0, 6.0));
        assert!((p - Vec3::new(1.5, 3.0, 4.5)).length() < 1e-6, "{p}");
    }
}
