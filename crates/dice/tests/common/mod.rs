//! Shared helpers for the integration tests: scene builders and raster geometry.
#![allow(dead_code)]

use reyes_dice::{Diced, dice_scene};
use reyes_hider::{Frame, Micropolygon};
use reyes_scene::{Camera, Lens, Object, Scene};
#[allow(unused_imports)]
pub use reyes_testkit::fixtures::{camera, frame_for as frame_of, object, scene, sphere};

/// The camera at the origin looking down +z with field of view `fov`, through `lens`.
pub fn camera_ahead(fov: f32, lens: Option<Lens>) -> Camera {
    camera([0.0; 3], [0.0, 0.0, 1.0], fov, lens)
}

/// A `width x height` scene of `objects` seen by the pinhole [`camera_ahead`]`(fov)`.
pub fn scene_ahead(width: u32, height: u32, fov: f32, objects: Vec<Object>) -> Scene {
    scene(width, height, camera_ahead(fov, None), objects)
}

/// Dice a scene in its own frame, panicking on error.
pub fn dice(scene: &Scene) -> (Diced, Frame) {
    let frame = frame_of(scene);
    let diced = dice_scene(scene, &frame).expect("dice");
    (diced, frame)
}

/// Signed raster-space area of a micropolygon (shoelace over its cyclic vertices).
pub fn signed_area(mp: &Micropolygon) -> f64 {
    let mut a = 0.0;
    for k in 0..4 {
        let p = mp.v[k];
        let q = mp.v[(k + 1) % 4];
        a += f64::from(p[0]) * f64::from(q[1]) - f64::from(q[0]) * f64::from(p[1]);
    }
    0.5 * a
}

/// Is raster point `(x, y)` inside the micropolygon (as two triangles 0-1-2 and 0-2-3,
/// edges inclusive within `eps`)?
pub fn inside(mp: &Micropolygon, x: f32, y: f32, eps: f32) -> bool {
    let tri = |a: [f32; 3], b: [f32; 3], c: [f32; 3]| {
        let e = |p: [f32; 3], q: [f32; 3]| (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]);
        let (d0, d1, d2) = (e(a, b), e(b, c), e(c, a));
        let scale = 1.0
            + (b[0] - a[0]).abs()
            + (b[1] - a[1]).abs()
            + (c[0] - a[0]).abs()
            + (c[1] - a[1]).abs();
        let tol = eps * scale;
        (d0 >= -tol && d1 >= -tol && d2 >= -tol) || (d0 <= tol && d1 <= tol && d2 <= tol)
    };
    tri(mp.v[0], mp.v[1], mp.v[2]) || tri(mp.v[0], mp.v[2], mp.v[3])
}

/// Does some micropolygon listed in the bucket of raster point `(x, y)` cover it (within
/// 1e-4)?
pub fn covered(d: &Diced, frame: &Frame, x: f32, y: f32) -> bool {
    d.buckets[bucket_of(frame, x, y)].iter().any(|&i| inside(&d.mpolys[i as usize], x, y, 1e-4))
}

/// Bucket number of the bucket holding raster pixel `(x, y)`.
pub fn bucket_of(frame: &Frame, x: f32, y: f32) -> usize {
    let bx = ((x + frame.border as f32).floor() as u32 / frame.bucket_w).min(frame.buckets_x - 1);
    let by = ((y + frame.border as f32).floor() as u32 / frame.bucket_h).min(frame.buckets_y - 1);
    (by * frame.buckets_x + bx) as usize
}
