//! What a shading-language shader can ask the renderer (issue #30, Specification 3.2 §15.8):
//! `attribute()`, `option()` and `rendererinfo()` answers for one object, and the shutter's
//! `time` and `dtime`. Set up once per object ([`Info::of`]) and given to every context.
//!
//! Invariant: only what the model holds is answered; any other name returns 0 and leaves the
//! caller's variable alone, as the Specification says.

use reyes_scene::sl::exec::{GridContext, Num, Value};
use reyes_scene::{Object, Scene};

/// The answers of one object's shaders.
#[derive(Debug, Clone, Default)]
pub(crate) struct Info {
    /// `(function, name, value)`.
    answers: Vec<(&'static str, &'static str, Value)>,
    /// Shutter open (the time every grid is shaded at) and its length.
    time: f32,
    dtime: f32,
}

fn f(x: f32) -> Value {
    Value::Num(Num::scalar(x))
}

fn floats(xs: &[f32]) -> Value {
    Value::Array(xs.iter().map(|&x| f(x)).collect())
}

impl Info {
    /// The answers for `object` of `scene`.
    pub(crate) fn of(scene: &Scene, object: &Object) -> Info {
        let (w, h) = (scene.image.width as f32, scene.image.height as f32);
        let cam = &scene.camera;
        let rate = object.shading_rate.unwrap_or(scene.hider.shading_rate);
        let mut answers = vec![
            ("attribute", "identifier:name", Value::Str(object.name.clone())),
            ("attribute", "ShadingRate", f(rate)),
            ("attribute", "Sides", f(if object.one_sided { 1.0 } else { 2.0 })),
            ("attribute", "Matte", f(if object.matte { 1.0 } else { 0.0 })),
            ("option", "Format", floats(&[w, h, 1.0])),
            ("option", "DeviceResolution", floats(&[w, h, 1.0])),
            ("option", "FrameAspectRatio", f(w / h)),
            ("option", "Shutter", floats(&[cam.shutter.open, cam.shutter.close])),
            ("option", "Clipping", floats(&[cam.hither, cam.yon])),
            ("rendererinfo", "renderer", Value::Str("reyes-render".into())),
            ("rendererinfo", "versionstring", Value::Str(env!("CARGO_PKG_VERSION").into())),
        ];
        let version: Vec<f32> = env!("CARGO_PKG_VERSION")
            .split('.')
            .map(|p| p.parse().unwrap_or(0.0))
            .chain(std::iter::repeat(0.0))
            .take(4)
            .collect();
        answers.push(("rendererinfo", "version", floats(&version)));
        if let Some(crop) = scene.image.crop {
            answers.push(("option", "CropWindow", floats(&crop)));
        }
        if let Some(lens) = &cam.lens {
            let dof = [lens.f_stop, lens.focal_length, lens.focal_distance];
            answers.push(("option", "DepthOfField", floats(&dof)));
        }
        if let Some(bound) = object.shaders.as_ref().filter(|s| s.displacement.is_some()) {
            answers.push(("attribute", "displacementbound:sphere", f(bound.displacement_bound)));
            let space = Value::Str("object".into());
            answers.push(("attribute", "displacementbound:coordinatesystem", space));
        }
        let (open, close) = (cam.shutter.open, cam.shutter.close);
        Info { answers, time: open, dtime: close - open }
    }

    /// Gives `g` the answers, `time` and `dtime`.
    pub(crate) fn bind(&self, g: &mut GridContext<'_>) {
        for (function, name, v) in &self.answers {
            g.set_message(function, name, v.clone());
        }
        // Globals a shader type lacks are refused; every type reads both.
        let _ = g.set_uniform("time", &[self.time]);
        let _ = g.set_uniform("dtime", &[self.dtime]);
    }
}
