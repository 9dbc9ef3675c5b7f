//! Shared helpers for the integration tests: scene builders and raster geometry.
#![allow(dead_code)]

use reyes_dice::{Diced, dice_scene};
use reyes_hider::{Frame, Micropolygon, border_for_filter_width};
use reyes_scene::{
    Camera, Hider, Image, Lens, Light, Material, Object, Scene, Shape, Shutter, Transform,
};

/// A camera at `eye` looking at `look_at` with +y up.
pub fn camera(eye: [f32; 3], look_at: [f32; 3], fov: f32, lens: Option<Lens>) -> Camera {
    Camera {
        eye,
        look_at,
        up: [0.0, 1.0, 0.0],
        fov,
        hither: 0.1,
        yon: 1000.0,
        shutter: Shutter::default(),
        lens,
        motion: Vec::new(),
    }
}

/// A scene of `objects` seen by `camera`, default hider, one ambient and one distant light.
pub fn scene(width: u32, height: u32, camera: Camera, objects: Vec<Object>) -> Scene {
    Scene {
        image: Image { width, height },
        camera,
        hider: Hider::default(),
        lights: vec![
            Light::Ambient { color: [1.0; 3], intensity: 0.2 },
            Light::Distant {
                from: [1.0, 1.0, -1.0],
                to: [0.0; 3],
                color: [1.0; 3],
                intensity: 1.0,
                shadows: false,
            },
        ],
        objects,
        solids: Vec::new(),
        raytrace: Default::default(),
    }
}

/// A white matte object.
pub fn object(shape: Shape, transform: Vec<Transform>) -> Object {
    Object {
        name: String::new(),
        shape,
        transform,
        material: Material::Matte { color: [1.0; 3], opacity: [1.0; 3], ka: 1.0, kd: 1.0 },
        matte: false,
        motion: Vec::new(),
        deform: Vec::new(),
        interpolation: Default::default(),
        glass: None,
        reflect: None,
        refract: None,
        pattern: None,
        roll: None,
    }
}

/// A whole sphere of radius `r`.
pub fn sphere(r: f32) -> Shape {
    Shape::Sphere { radius: r, zmin: None, zmax: None, thetamax: 360.0 }
}

/// The frame `Frame::new` lays out for the scene's image and hider settings.
pub fn frame_of(scene: &Scene) -> Frame {
    Frame::new(
        scene.image.width,
        scene.image.height,
        border_for_filter_width(scene.hider.filter.width),
        scene.hider.bucket_size.0,
        scene.hider.bucket_size.1,
    )
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

/// Bucket number of the bucket holding raster pixel `(x, y)`.
pub fn bucket_of(frame: &Frame, x: f32, y: f32) -> usize {
    let bx = ((x + frame.border as f32).floor() as u32 / frame.bucket_w).min(frame.buckets_x - 1);
    let by = ((y + frame.border as f32).floor() as u32 / frame.bucket_h).min(frame.buckets_y - 1);
    (by * frame.buckets_x + bx) as usize
}
