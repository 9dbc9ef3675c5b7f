//! Scenes and objects built in code for tests, and the frame a scene lays out.
//!
//! Invariant: a fixture is the same scene every time (no randomness, no environment).

use std::path::Path;

pub use reyes_render::frame_for;
use reyes_scene::{
    Camera, Hider, Image, Lens, Light, Material, Object, Projection, Scene, Shape, Shutter,
    Transform,
};

/// Parse and validate RON scene text, panicking with the error (tests only).
pub fn parse(text: &str) -> Scene {
    match reyes_scene::parse(text, Path::new("test.ron")) {
        Ok(scene) => scene,
        Err(e) => panic!("{e}"),
    }
}

/// A perspective camera at `eye` looking at `look_at` with +y up (default screen window).
pub fn camera(eye: [f32; 3], look_at: [f32; 3], fov: f32, lens: Option<Lens>) -> Camera {
    Camera {
        eye,
        look_at,
        up: [0.0, 1.0, 0.0],
        projection: Projection::Perspective,
        fov,
        screen_window: None,
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

/// White matte (`ka = kd = 1`).
pub fn white_matte() -> Material {
    Material::Matte { color: [1.0; 3], opacity: [1.0; 3], ka: 1.0, kd: 1.0 }
}

/// A white matte object.
pub fn object(shape: Shape, transform: Vec<Transform>) -> Object {
    Object::new(shape, white_matte()).with_transform(transform)
}

/// A whole sphere of radius `r`.
pub fn sphere(r: f32) -> Shape {
    Shape::Sphere { radius: r, zmin: None, zmax: None, thetamax: 360.0 }
}

/// The RON text of a scene for measurement (FIG. 23): these objects (each given a grey
/// matte material) and solids, seed 7.
pub fn measure_scene(objects: &[&str], solids: &str) -> String {
    let objects: Vec<String> =
        objects.iter().map(|o| format!("({o}, material: Matte(color: (0.8, 0.8, 0.8)))")).collect();
    format!(
        "Scene(
  image: (width: 32, height: 24),
  camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0)),
  hider: (seed: 7),
  objects: [{}],
  solids: [{solids}],
)
",
        objects.join(",\n    ")
    )
}
