//! What a shading-language shader can ask the renderer (issue #30, Specification 3.2 §15.8):
//! `attribute()`, `option()` and `rendererinfo()` answers for one object, and the shutter's
//! `time` and `dtime`. Set up once per object ([`Info::of`]; an imager: [`Info::of_scene`]) and
//! given to every context.
//!
//! Invariant: only what the model holds is answered; any other name returns 0 and leaves the
//! caller's variable alone, as the Specification says.

use reyes_scene::sl::exec::{GridContext, Num, Value};
use reyes_scene::{Object, Scene};

/// The answers of one object's shaders.
#[derive(Debug, Clone, Default)]
pub struct Info {
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
    /// The answers for an imager of `scene`: the options, the renderer and the shutter.
    pub fn of_scene(scene: &Scene) -> Info {
        let (w, h) = (scene.image.width as f32, scene.image.height as f32);
        let cam = &scene.camera;
        let mut answers = vec![
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
        let (open, close) = (cam.shutter.open, cam.shutter.close);
        Info { answers, time: open, dtime: close - open }
    }

    /// The answers for `object` of `scene`: [`Info::of_scene`]'s and its attributes.
    pub(crate) fn of(scene: &Scene, object: &Object) -> Info {
        let mut info = Info::of_scene(scene);
        let rate = object.shading_rate.unwrap_or(scene.hider.shading_rate);
        info.answers.extend([
            ("attribute", "identifier:name", Value::Str(object.name.clone())),
            ("attribute", "ShadingRate", f(rate)),
            ("attribute", "Sides", f(if object.one_sided { 1.0 } else { 2.0 })),
            ("attribute", "Matte", f(if object.matte { 1.0 } else { 0.0 })),
        ]);
        if let Some(bound) = object.shaders.as_ref().filter(|s| s.displacement.is_some()) {
            let b = f(bound.displacement_bound);
            info.answers.push(("attribute", "displacementbound:sphere", b));
            let space = Value::Str("object".into());
            info.answers.push(("attribute", "displacementbound:coordinatesystem", space));
        }
        info
    }

    /// Gives `g` the answers, `time` and `dtime`.
    pub fn bind(&self, g: &mut GridContext<'_>) {
        for (function, name, v) in &self.answers {
            g.set_message(function, name, v.clone());
        }
        // Globals a shader type lacks are refused; every type reads both.
        let _ = g.set_uniform("time", &[self.time]);
        let _ = g.set_uniform("dtime", &[self.dtime]);
    }
}
