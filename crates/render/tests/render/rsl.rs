//! RON scenes with shading-language surfaces (`Shader(name, params)`, `shader_path`): the
//! shader found, compiled and bound by its declared types, and every mistake a one-line
//! error at the material.

use std::path::Path;

use reyes_render::{RenderOptions, render};
use reyes_scene::parse;

const SIZE: u32 = 24;

/// A square filling the picture under an orthographic camera, lit by an ambient and a
/// distant light, with the material `material`.
fn scene(material: &str, path: &str) -> String {
    format!(
        "Scene(
  image: (width: {SIZE}, height: {SIZE}),
  camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), projection: Orthographic,
           screen_window: Some((-1.0, 1.0, -1.0, 1.0))),
  hider: (pixel_samples: (2, 2)),
  {path}
  lights: [Ambient(intensity: 0.2), Distant(from: (-1.0, 1.0, -2.0), to: (0.0, 0.0, 0.0))],
  objects: [(shape: Sphere(radius: 0.9), material: {material})],
)"
    )
}

fn load(dir: &Path, text: &str) -> Result<reyes_scene::Scene, String> {
    parse(text, &dir.join("s.ron")).map_err(|e| e.to_string())
}

fn rgba(s: &reyes_scene::Scene) -> Vec<[f32; 4]> {
    render(s, &RenderOptions::default()).unwrap().film.rgba().to_vec()
}

/// A shader of the scene's folder with its parameters set: each covered pixel is the
/// product the shader computes, exactly (a constant surface: every sample has the value).
#[test]
fn a_shader_material_runs_with_its_parameters() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("tinted.sl"),
        "surface tinted(float k = 1; color tint = 1; string tag = \"\"; float w[2] = {0, 0}) {\n\
         Oi = Os; Ci = Os * Cs * tint * k * (w[0] + w[1]) * match(\"^on$\", tag); }",
    )
    .unwrap();
    let m = "Shader(name: \"tinted\", color: (0.5, 1.0, 1.0), \
             params: {\"k\": 0.5, \"tint\": (1.0, 0.5, 0.25), \"tag\": \"on\", \"w\": [0.75, 0.25]})";
    let s = load(dir.path(), &scene(m, "")).unwrap_or_else(|e| panic!("{e}"));
    let px = rgba(&s);
    let centre = px[(SIZE / 2 * SIZE + SIZE / 2) as usize];
    assert_eq!(centre, [0.25, 0.25, 0.125, 1.0]);
}

/// The built-in `plastic` (`@`) with the native Plastic's parameters gives the native
/// Plastic's picture: the same formulas under the same lights, equal to float rounding.
#[test]
fn the_built_in_plastic_matches_the_native_plastic() {
    let dir = tempfile::tempdir().unwrap();
    let shader = "Shader(name: \"plastic\", color: (0.8, 0.5, 0.3), \
                  params: {\"Ka\": 1.0, \"Kd\": 0.6, \"Ks\": 0.4, \"roughness\": 0.2})";
    let native = "Plastic(color: (0.8, 0.5, 0.3), ka: 1.0, kd: 0.6, ks: 0.4, roughness: 0.2)";
    let a = rgba(&load(dir.path(), &scene(shader, "shader_path: [\"@\"],")).unwrap());
    let b = rgba(&load(dir.path(), &scene(native, "")).unwrap());
    let mut lit = 0;
    for (p, q) in a.iter().zip(&b) {
        for k in 0..4 {
            assert!((p[k] - q[k]).abs() <= 2e-6, "{p:?} vs {q:?}");
        }
        lit += usize::from(p[0] > 0.3);
    }
    assert!(lit > 100, "{lit} lit pixels");
}

#[test]
fn shader_mistakes_are_one_line_at_the_material() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("wrongkind.sl"), "light wrongkind() { }").unwrap();
    std::fs::write(dir.path().join("broken.sl"), "surface broken() { Ci = nothing; }").unwrap();
    let cases = [
        ("Shader(name: \"absent\")", "no shader \"absent\": no absent.sl along the shader path"),
        ("Shader(name: \"plastic\", params: {\"Kx\": 1.0})", "has no parameter \"Kx\""),
        ("Shader(name: \"plastic\", params: {\"Ks\": \"x\"})", "\"Ks\": a string does not fit"),
        ("Shader(name: \"wrongkind\")", "is not a surface shader"),
        ("Shader(name: \"broken\")", "broken.sl:1:"),
    ];
    for (material, want) in cases {
        let err = load(dir.path(), &scene(material, "")).unwrap_err();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("objects[0].material") && err.contains(want), "{err}");
        assert!(err.contains("s.ron:"), "{err}");
    }
}
