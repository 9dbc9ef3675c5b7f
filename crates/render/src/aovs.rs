//! The scene's AOVs as stage settings (docs/outputs.md): what the hider takes from each
//! sample ([`AovPlan`]), how the film filters each AOV ([`AovChannels`]) and how the file
//! names and stores it ([`AovLayer`]).
//!
//! Invariant: the per-sample channels of the plan are the AOVs' channels in scene order, so
//! AOV `i`'s film channels, its plan value and its layer all start at the same offset.

use reyes_dice::VertexAovs;
use reyes_film::{AovChannels, AovFilm, AovLayer};
use reyes_hider::{AovPlan, AovValue};
use reyes_scene::{AovSource, Scene};

/// The AOVs of a frame, set up.
#[derive(Debug, Clone, PartialEq)]
pub struct AovSetup {
    /// What the hider takes from each sample.
    pub plan: AovPlan,
    /// How the film filters each AOV.
    pub channels: Vec<AovChannels>,
    /// How the file stores each AOV.
    pub layers: Vec<AovLayer>,
}

/// A frame's rendered AOVs.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderedAovs {
    /// The pixels, every AOV's channels side by side.
    pub film: AovFilm,
    /// The layers, in scene order.
    pub layers: Vec<AovLayer>,
}

impl AovSetup {
    /// The setup of `scene`'s AOVs, or `None` if it writes none.
    pub fn for_scene(scene: &Scene) -> Option<AovSetup> {
        let vertex = VertexAovs::for_scene(scene)?;
        let o = &scene.outputs;
        let (mut values, mut background) = (Vec::new(), Vec::new());
        let (mut channels, mut layers) = (Vec::new(), Vec::new());
        let mut start = 0;
        for aov in &o.aovs {
            let front = |offset, len, interpolate| AovValue::Vertex { offset, len, interpolate };
            let value = match aov.source {
                AovSource::Ci => AovValue::Color,
                AovSource::Oi => AovValue::Opacity,
                AovSource::Z => AovValue::Depth,
                AovSource::ZMidpoint => AovValue::MidDepth,
                AovSource::N => front(VertexAovs::N, 3, true),
                AovSource::P => front(VertexAovs::P, 3, true),
                AovSource::S => front(VertexAovs::S, 1, true),
                AovSource::T => front(VertexAovs::T, 1, true),
                AovSource::DPdtime => AovValue::Velocity,
                AovSource::ObjectId => front(VertexAovs::OBJECT_ID, 1, false),
                AovSource::MaterialId => front(VertexAovs::MATERIAL_ID, 1, false),
                AovSource::Ambient | AovSource::Diffuse | AovSource::Specular => {
                    let group = aov.light_group.as_ref().map(|name| {
                        o.light_groups
                            .iter()
                            .find(|g| &g.name == name)
                            .map_or(Vec::new(), |g| g.lights.clone())
                    });
                    let offset = vertex
                        .component(aov.source, group.as_deref())
                        .expect("VertexAovs stores every component an AOV names");
                    AovValue::Shaded { offset }
                }
                AovSource::Output => {
                    let name = aov.variable.as_deref().unwrap_or_default();
                    let (offset, len) =
                        vertex.output(name).expect("VertexAovs stores every output an AOV names");
                    front(offset, len, true)
                }
            };
            let len = value.len();
            debug_assert_eq!(len, aov.channels().len());
            let depth = matches!(aov.source, AovSource::Z | AovSource::ZMidpoint);
            let bg = if depth { o.zbackground.value() } else { 0.0 };
            background.extend(std::iter::repeat_n(bg, len));
            values.push(value);
            channels.push(AovChannels { start, len, filter: aov.filter_or_default() });
            layers.push(AovLayer {
                name: aov.layer_name(),
                channels: aov.channels().to_vec(),
                start,
                integer: aov.source.is_id(),
                pixel_type: aov.pixel_type.unwrap_or(o.pixel_type),
                compression: aov.compression.unwrap_or(o.compression),
            });
            start += len;
        }
        let plan = AovPlan { stride: vertex.stride(), values, background };
        Some(AovSetup { plan, channels, layers })
    }

    /// True if some AOV is a shading component (`__ambient`, `__diffuse`, `__specular`).
    pub fn has_components(scene: &Scene) -> bool {
        scene.outputs.aovs.iter().any(|a| a.source.is_component())
    }
}
