//! Frames: what is declared outside every frame holds for each of them, lights included.

use reyes_render::{RenderOptions, render};
use reyes_scene::Light;

use super::rib;

/// A light, a colour and a surface before the first `FrameBegin`, then two frames of one
/// square facing the camera (and the light) under an orthographic camera.
const TWO_FRAMES: &str = "Format 16 16 1
ScreenWindow -2 2 -2 2
PixelSamples 2 2
PixelFilter \"box\" 1 1
LightSource \"distantlight\" 1 \"intensity\" [0.8]
Color [0.5 1 1]
Surface \"matte\" \"Ka\" [0]
FrameBegin 1
WorldBegin
Translate 0 0 5
Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]
WorldEnd
FrameEnd
FrameBegin 2
WorldBegin
Translate 0 0 5
Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]
WorldEnd
FrameEnd
";

#[test]
fn a_light_declared_before_the_first_frame_lights_every_frame() {
    let loaded = rib(TWO_FRAMES).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.frames.len(), 2);
    let want = Light::Distant {
        from: [0.0; 3],
        to: [0.0, 0.0, 1.0],
        color: [1.0; 3],
        intensity: 0.8,
        shadows: false,
    };
    for frame in &loaded.frames {
        assert_eq!(frame.scene.lights, std::slice::from_ref(&want), "frame {:?}", frame.number);
        // Every light is on: the model leaves the light set out.
        assert_eq!(frame.scene.objects[0].lights, None, "frame {:?}", frame.number);
    }
    // Both frames render the same picture: the square faces the light head on (N.L = 1), so
    // matte gives Cs Kd intensity = (0.4, 0.8, 0.8) wherever it covers a whole pixel.
    let pictures: Vec<Vec<[f32; 4]>> = loaded
        .frames
        .iter()
        .map(|f| render(&f.scene, &RenderOptions::default()).unwrap().film.rgba().to_vec())
        .collect();
    assert_eq!(pictures[0], pictures[1]);
    let centre = pictures[1][8 * 16 + 8];
    for (got, want) in centre.iter().zip([0.4, 0.8, 0.8, 1.0]) {
        assert!((got - want).abs() < 1e-6, "{centre:?}");
    }
}

#[test]
fn a_light_declared_inside_a_frame_ends_with_it() {
    let text = TWO_FRAMES.replacen("LightSource \"distantlight\" 1 \"intensity\" [0.8]\n", "", 1);
    let text = text.replacen(
        "FrameBegin 1\n",
        "FrameBegin 1\nLightSource \"pointlight\" 2 \"from\" [0 0 1]\n",
        1,
    );
    let loaded = rib(&text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.frames[0].scene.lights.len(), 1);
    assert!(loaded.frames[1].scene.lights.is_empty());
}
