//! Which render a piece belongs to (docs/farm.md): the fingerprint every tile and checkpoint
//! file carries, and which names a checkpoint's folder.
//!
//! Invariant: the fingerprint is a function of the scene as it will be rendered (after every
//! override) and of the renderer's version alone: never of the thread count, the tile or
//! the output name, which change no bucket.

use reyes_scene::Scene;

use crate::VERSION;

/// Which render a piece belongs to: a hash of everything that decides the pixels (the whole
/// scene after the front end's overrides, the crop window and the seed among them,
/// serialised as RON, and its shading-language shaders, which RON does not hold: their
/// compiled form, values and spaces, as `Debug` prints them, which holds no hash map) and the
/// renderer's version, as 16 hex digits.
pub fn fingerprint(scene: &Scene) -> String {
    let mut text = ron::to_string(scene).unwrap_or_default();
    if scene.has_shaders() {
        text.push_str(&format!("{:?}", scene.shaders));
        for o in &scene.objects {
            text.push_str(&format!("{:?}", o.shaders));
        }
    }
    let words: Vec<u64> = text
        .as_bytes()
        .chunks(8)
        .map(|c| c.iter().rev().fold(0u64, |w, &b| w << 8 | u64::from(b)))
        .chain([text.len() as u64])
        .collect();
    let version = VERSION.bytes().fold(0u64, |w, b| w.rotate_left(8) ^ u64::from(b));
    format!("{:016x}", reyes_sampling::hash(version, &words))
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use reyes_scene::sl::exec::{Num, Value};
    use reyes_scene::{ObjectShaders, ShaderInstance};

    /// A scene whose one object is shaded by a shader with `k` set to `k`.
    fn scene(k: f32) -> reyes_scene::Scene {
        let shader =
            reyes_scene::sl::compile_str("k.sl", "surface k(float k = 0) { Ci = k; }", &[])
                .unwrap();
        let surface = ShaderInstance {
            shader: Arc::new(shader),
            params: vec![("k".into(), Value::Num(Num::scalar(k)))],
            shader_to_world: reyes_scene::sl::exec::space::IDENTITY,
            file: "k.sl".into(),
        };
        let text = "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), \
                    look_at: (0.0, 0.0, 0.0), fov: 40.0), \
                    objects: [(shape: Sphere(radius: 1.0), material: Matte(color: (1.0, 1.0, 1.0)))])";
        let mut scene = reyes_scene::parse(text, std::path::Path::new("k.ron")).unwrap();
        let shaders = ObjectShaders { surface: Some(surface), ..Default::default() };
        scene.objects[0].shaders = Some(Arc::new(shaders));
        scene
    }

    /// The shaders are part of the fingerprint though RON does not hold them, and the same
    /// scene gives the same fingerprint.
    #[test]
    fn shader_values_change_the_fingerprint() {
        assert_eq!(super::fingerprint(&scene(0.5)), super::fingerprint(&scene(0.5)));
        assert_ne!(super::fingerprint(&scene(0.5)), super::fingerprint(&scene(0.25)));
    }
}
