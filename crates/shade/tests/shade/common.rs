//! Shared helpers of the reyes-shade integration tests: scenes from RON text, averages over
//! a stratified set, and geometry.
#![allow(dead_code)]

use std::path::Path;

use glam::Vec3;
use reyes_sampling::Strata;
use reyes_scene::Scene;
use reyes_shade::{Shading, SurfacePoint, Traced};
use reyes_trace::{Ray, Tracer};

/// A scene from the RON fields after `image` and `camera` (lights, objects, raytrace, ...).
/// Panics with the parse error when the text is not a valid scene.
pub fn scene(fields: &str) -> Scene {
    scene_with_shutter(fields, 0.0, 1.0)
}

/// [`scene`] with the camera's shutter `[open, close]`.
pub fn scene_with_shutter(fields: &str, open: f32, close: f32) -> Scene {
    let text = format!(
        "Scene(image: (width: 8, height: 8), \
         camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0), \
                  shutter: (open: {open:?}, close: {close:?})), {fields})"
    );
    match reyes_scene::parse(&text, Path::new("test.ron")) {
        Ok(s) => s,
        Err(e) => panic!("test scene does not parse: {e}\n{text}"),
    }
}

/// A RON `BilinearPatch` object of a parallelogram `corner + a eu + b ev`, with `rest`
/// (material and any other fields).
pub fn patch(corner: Vec3, eu: Vec3, ev: Vec3, rest: &str) -> String {
    let p = [corner, corner + eu, corner + ev, corner + eu + ev];
    let pts: Vec<String> = p.iter().map(|p| format!("({:?}, {:?}, {:?})", p.x, p.y, p.z)).collect();
    // A fixed-size array is a tuple in RON.
    format!("(shape: BilinearPatch(points: ({})), {rest})", pts.join(", "))
}

/// The white matte floor of the light tests, with no ambient term: the square
/// `|x|, |z| <= half` of the plane y = 0, as a RON [`patch`] object.
pub fn white_floor(half: f32) -> String {
    patch(
        Vec3::new(-half, 0.0, -half),
        Vec3::new(2.0 * half, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0 * half),
        "material: Matte(color: (1.0, 1.0, 1.0), ka: 0.0)",
    )
}

/// Mean of `shade_surface`'s colour over the `count` members of stratified set `set`.
pub fn shade_mean(shading: &Shading, at: &SurfacePoint, count: u32, set: u64) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for i in 0..count {
        let mut s = Strata::new(7, set, i, count);
        sum += Vec3::from(shading.shade_surface(at, &mut s).0);
    }
    sum / count as f32
}

/// Mean of `trace`'s premultiplied colour over the `count` members of stratified set `set`.
pub fn trace_mean(shading: &Shading, ray: &Ray, count: u32, set: u64) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for i in 0..count {
        let mut s = Strata::new(7, set, i, count);
        let Traced { rgba, .. } = shading.trace(ray, f32::INFINITY, &mut s);
        sum += Vec3::new(rgba[0], rgba[1], rgba[2]);
    }
    sum / count as f32
}

/// Trace one ray with member 0 of a set of one.
pub fn trace_one(shading: &Shading, ray: &Ray) -> Traced {
    shading.trace(ray, f32::INFINITY, &mut Strata::new(7, 0, 0, 1))
}

/// Build the tracer of a scene (the shading borrows both).
pub fn tracer(scene: &Scene) -> Tracer {
    Tracer::new(scene)
}

/// A point of object `object` on the plane y = 0 at `(x, 0, z)`, normal +y, seen from above.
pub fn floor_point(object: u32, x: f32, z: f32, time: f32) -> SurfacePoint {
    let p = Vec3::new(x, 0.0, z);
    SurfacePoint {
        object,
        p_world: p,
        n_world: Vec3::Y,
        p_object: p,
        tint: Vec3::ONE,
        from: Vec3::new(0.0, 20.0, -20.0),
        time,
        looked: reyes_dice::Looked::NONE,
    }
}

/// The integral of `f` over `[a, b]` by composite Simpson with `n` (even) intervals.
pub fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for k in 1..n {
        s += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}
