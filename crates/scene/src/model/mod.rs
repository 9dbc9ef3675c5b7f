//! The scene model: plain serde types mirroring the RON file field by field.
//!
//! Invariant: a `Scene` returned by [`crate::load`] or [`crate::parse`] has passed
//! validation, so every later stage may assume finite numbers and in-range values.
//! Vectors are `[f32; 3]`, written in RON as tuples `(x, y, z)`. Angles are in degrees.
//! World space is left-handed like RenderMan's: with the camera looking down +z and +y up,
//! +x is to the right.
//!
//! One submodule per section of the file (camera, hider, lights, objects, shapes, materials,
//! solids, ray tracing), and one for a mesh's flat [`Faces`]; every type is re-exported here, so `model::X` (and, through the
//! crate root, `reyes_scene::X`) names it whichever file it lives in.

use serde::{Deserialize, Serialize};

mod camera;
mod faces;
mod hair;
mod hider;
mod light;
mod lookdev;
mod material;
mod object;
mod output;
mod raytrace;
mod rsl;
mod shape;
mod solid;

pub use camera::*;
pub use faces::{FaceIter, Faces};
pub use hair::*;
pub use hider::*;
pub use light::*;
pub use lookdev::*;
pub use material::*;
pub use object::*;
pub use output::*;
pub use raytrace::*;
pub use rsl::*;
pub use shape::*;
pub use solid::*;

/// A 3-vector as written in the scene file: `(x, y, z)`.
pub type V3 = [f32; 3];
/// An RGB triple, linear light.
pub type Rgb = [f32; 3];

/// A whole scene: one frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Output resolution.
    pub image: Image,
    /// The camera.
    pub camera: Camera,
    /// Sampling, filtering and bucketing settings.
    #[serde(default)]
    pub hider: Hider,
    /// Light sources.
    #[serde(default)]
    pub lights: Vec<Light>,
    /// Geometric objects.
    #[serde(default)]
    pub objects: Vec<Object>,
    /// Constructive solid geometry: each solid combines closed objects (named in `objects`)
    /// with union, intersection and difference. An object used in a solid is drawn only as
    /// part of it, and may be used in one solid only.
    #[serde(default)]
    pub solids: Vec<Solid>,
    /// Settings of the distributed ray tracing (shadows, glossy reflection, translucency).
    #[serde(default)]
    pub raytrace: RayTrace,
    /// What the frame writes besides the beauty: AOVs, light groups, pixel types and
    /// compression, the background depth, the PNG view transform (docs/outputs.md).
    #[serde(default)]
    pub outputs: Outputs,
    /// The texture cache's memory bound (docs/lookdev.md).
    #[serde(default)]
    pub texture_cache: TextureCache,
    /// Folders searched for shading-language shaders (`NAME.sl`), relative to the scene
    /// file's folder; `@` is the built-in standard shaders (the default when empty).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub shader_path: Vec<String>,
    /// Shading-language light shaders and imager (a RIB scene's; not in RON).
    #[serde(skip)]
    pub shaders: SceneShaders,
}

impl Scene {
    /// Whether shading needs anything beyond the dicer's local illumination: a shadowing or
    /// area light, a reflecting or refracting object, or a pattern (then the distributed rays
    /// of reyes-shade shade the vertices). Here so that validation and the renderer agree.
    pub fn needs_ray_shading(&self) -> bool {
        // (Shading-language shaders are shaded by the dicer's grid machine, not by rays.)
        let lights = self.lights.iter().any(|l| match l {
            Light::Ambient { .. } => false,
            Light::Distant { shadows, .. }
            | Light::Point { shadows, .. }
            | Light::Spot { shadows, .. } => *shadows,
            Light::Area { .. } => true,
        });
        lights
            || self
                .objects
                .iter()
                .any(|o| o.reflect.is_some() || o.refract.is_some() || o.pattern.is_some())
    }
}

impl Scene {
    /// True if some object or light is shaded by a shading-language shader, or the scene
    /// has an imager.
    pub fn has_shaders(&self) -> bool {
        !self.shaders.is_empty() || self.objects.iter().any(|o| o.shaders.is_some())
    }

    /// Every texture map of the scene, in object order, then the order of the fields
    /// (maps, displacement, bump), for setting up and for resolving file names.
    pub fn texture_maps_mut(&mut self) -> impl Iterator<Item = &mut TextureMap> {
        self.objects.iter_mut().flat_map(|o| {
            let Maps { color, opacity, roughness, specular } = &mut o.maps;
            let displace = o.displacement.as_mut().and_then(|d| match &mut d.source {
                Scalar::Texture(m) => Some(m),
                _ => None,
            });
            let bump = o.bump.as_mut().and_then(|b| match &mut b.source {
                Scalar::Texture(m) => Some(m),
                _ => None,
            });
            [
                color.as_mut(),
                opacity.as_mut(),
                roughness.as_mut(),
                specular.as_mut(),
                displace,
                bump,
            ]
            .into_iter()
            .flatten()
        })
    }

    /// True if some object has a texture map, displacement, bump or emission (the look
    /// development of docs/lookdev.md).
    pub fn has_lookdev(&self) -> bool {
        self.objects.iter().any(|o| {
            !o.maps.is_empty()
                || o.displacement.is_some()
                || o.bump.is_some()
                || o.emission.is_some()
        }) || !self.shaders.maps.is_empty()
    }
}

fn default_up() -> V3 {
    [0.0, 1.0, 0.0]
}
fn white() -> Rgb {
    [1.0, 1.0, 1.0]
}
fn one() -> f32 {
    1.0
}
