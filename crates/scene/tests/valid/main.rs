//! Valid scenes parse to the expected values, defaults fill omitted sections, and `load`
//! reports unreadable and bad files with the right error kind and exit code. One module per
//! part of the model: the scene's sections and their defaults, `load`, motion, CSG, the
//! fields of distributed ray tracing, and rolling.

#[path = "../common/mod.rs"]
mod common;

mod csg;
mod load;
mod motion;
mod rolling;
mod scene;
mod traced;

use std::path::Path;

use reyes_scene::{Scene, parse};

/// The full example of the task and of docs/scene-format.md.
pub(crate) const FULL: &str = r#"
Scene(
  image: (width: 640, height: 480),
  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0),
           fov: 35.0, hither: 0.1, yon: 100.0, shutter: (open: 0.0, close: 1.0), lens: None),
  hider: (pixel_samples: (4, 4), jitter: true, filter: (kind: Gaussian, width: 2.0),
          bucket_size: (16, 16), shading_rate: 1.0, seed: 0),
  lights: [Ambient(color: (1.0, 1.0, 1.0), intensity: 0.1),
           Distant(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), color: (1.0, 1.0, 1.0), intensity: 1.0)],
  objects: [(name: "ball", shape: Sphere(radius: 1.0), transform: [Translate((0.0, 0.0, 0.0))],
             material: Plastic(color: (0.8, 0.1, 0.1), opacity: (1.0, 1.0, 1.0)))],
)
"#;

/// The scene `text` parses; panics with the error otherwise.
pub(crate) fn ok(text: &str) -> Scene {
    parse(text, Path::new("test.ron")).unwrap_or_else(|e| panic!("{e}"))
}

/// What ron writes for `scene` parses back to `scene`.
pub(crate) fn reads_back(scene: &Scene) {
    let text = ron::ser::to_string_pretty(scene, ron::ser::PrettyConfig::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(&ok(&text), scene);
}
