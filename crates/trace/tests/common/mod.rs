//! Shared test helpers: scene construction, shapes and placements used by several tests,
//! shooting a ray, a seeded generator, approximate comparisons. Every helper is
//! deterministic.
#![allow(dead_code)]

use reyes_sampling::SplitMix64;
use std::path::Path;

use glam::Vec3;
use reyes_scene::{Object, PointsKey, Scene, Shape, Transform, TransformKey};
use reyes_trace::{Hit, Ray, Tracer};

/// A minimal valid scene, parsed so that fields added to the model later take their
/// defaults.
const BASE: &str = "Scene(image: (width: 64, height: 64), \
    camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0)), \
    objects: [(shape: Sphere(radius: 1.0), material: Constant(color: (1.0, 1.0, 1.0)))])";

fn base() -> Scene {
    match reyes_scene::parse(BASE, Path::new("base.ron")) {
        Ok(scene) => scene,
        Err(e) => panic!("the base scene must parse: {e}"),
    }
}

/// An object with a constant material and no motion.
pub fn object(shape: Shape, transform: Vec<Transform>) -> Object {
    let mut o = base().objects.remove(0);
    o.shape = shape;
    o.transform = transform;
    o
}

/// An object moving through transform keys `(time, transforms)`.
pub fn moving(shape: Shape, keys: Vec<(f32, Vec<Transform>)>) -> Object {
    let mut o = object(shape, vec![]);
    o.motion = keys.into_iter().map(|(time, transform)| TransformKey { time, transform }).collect();
    o
}

/// An object deforming through point keys `(time, points)`.
pub fn deforming(shape: Shape, keys: Vec<(f32, Vec<[f32; 3]>)>) -> Object {
    let mut o = object(shape, vec![]);
    o.deform = keys.into_iter().map(|(time, points)| PointsKey { time, points }).collect();
    o
}

/// A scene holding `objects`, shutter `[0, 1]`.
pub fn scene(objects: Vec<Object>) -> Scene {
    scene_with_shutter(objects, 0.0, 1.0)
}

/// A scene holding `objects` with the given shutter.
pub fn scene_with_shutter(objects: Vec<Object>, open: f32, close: f32) -> Scene {
    let mut s = base();
    s.objects = objects;
    s.camera.shutter.open = open;
    s.camera.shutter.close = close;
    s
}

/// The whole unit sphere.
pub fn ball() -> Shape {
    Shape::Sphere { radius: 1.0, zmin: None, zmax: None, thetamax: 360.0 }
}

/// Scale, then rotate by `angle` degrees about `axis`, then translate by `offset`.
pub fn placed(scale: [f32; 3], angle: f32, axis: [f32; 3], offset: [f32; 3]) -> Vec<Transform> {
    vec![Transform::Scale(scale), Transform::Rotate { angle, axis }, Transform::Translate(offset)]
}

/// Transform keys sliding an object from where it is at time `t0` to `x + 2` at `t1`.
pub fn slide(t0: f32, t1: f32) -> Vec<(f32, Vec<Transform>)> {
    vec![
        (t0, vec![Transform::Translate([0.0, 0.0, 0.0])]),
        (t1, vec![Transform::Translate([2.0, 0.0, 0.0])]),
    ]
}

/// The nearest hit of the ray `origin + t dir` at `time`, without a limit.
pub fn shoot(t: &Tracer, origin: Vec3, dir: Vec3, time: f32) -> Option<Hit> {
    t.intersect(&Ray::new(origin, dir, time), f32::INFINITY)
}

/// `|a - b| <= rel * max(1, |b|)`.
pub fn close(a: f32, b: f32, rel: f32) -> bool {
    (a - b).abs() <= rel * b.abs().max(1.0)
}

/// Vectors equal within `tol` per component.
pub fn close_v(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol
}

/// A small seeded generator over the renderer's SplitMix64 stream.
pub struct Rng(SplitMix64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Rng {
        Rng(SplitMix64::from_state(seed))
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f32 {
        self.0.next_f32()
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `0..n`.
    pub fn below(&mut self, n: u32) -> u32 {
        (self.next_u64() % u64::from(n)) as u32
    }

    /// A point in the cube `[-h, h]^3`.
    pub fn in_cube(&mut self, h: f32) -> Vec3 {
        Vec3::new(self.range(-h, h), self.range(-h, h), self.range(-h, h))
    }

    /// A unit vector, uniform on the sphere.
    pub fn direction(&mut self) -> Vec3 {
        loop {
            let v = self.in_cube(1.0);
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                return v / l.sqrt();
            }
        }
    }
}
