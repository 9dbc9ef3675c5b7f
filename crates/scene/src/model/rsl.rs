//! Shaders written in the RenderMan Shading Language (issue #30): an object's surface,
//! displacement and atmosphere, and the scene's light shaders and imager, each a compiled
//! shader ([`reyes_sl::CheckedShader`], shared) with its parameter values.
//!
//! Invariants: they come from a RIB front end, which compiles the shaders when the scene loads
//! and binds every value by the shader's declared type (so a value always fits its parameter);
//! they are not part of the RON format (skipped by serde, so a scene written out and read back
//! loses them, and a RON scene never has any). Matrices are the shading language's: 4x4, row
//! by row, acting on row vectors (`p' = [x y z 1] M`).

use std::sync::Arc;

pub use reyes_sl::exec::Value as ShaderValue;
use reyes_sl::exec::space::{IDENTITY, Mat};

/// One use of a compiled shader: the shader, its parameter values, and its "shader" space.
#[derive(Debug, Clone, PartialEq)]
pub struct ShaderInstance {
    /// The compiled shader, shared by every instance of the same source.
    pub shader: Arc<reyes_sl::CheckedShader>,
    /// Parameter values by name, each of the parameter's type (others take their defaults).
    pub params: Vec<(String, ShaderValue)>,
    /// From the shader's own space (where it was declared) to the model's world space.
    pub shader_to_world: Mat,
    /// The file it was compiled from, for messages.
    pub file: String,
}

impl ShaderInstance {
    /// The shader's name, for messages.
    pub fn name(&self) -> &str {
        &self.shader.name
    }

    /// The type of the shader's `output` parameter `name`, if it has one.
    pub fn output(&self, name: &str) -> Option<reyes_sl::Type> {
        let p = self.shader.param(name)?;
        matches!(p.kind, reyes_sl::ir::VarKind::Param { output: true, .. }).then_some(p.ty)
    }
}

/// A value given on the geometry for a shader parameter (a primitive variable): one value for
/// the whole primitive, or one per corner of a parametric patch (bilinear in `u`, `v`).
#[derive(Debug, Clone, PartialEq)]
pub enum PrimitiveValue {
    /// `constant` or `uniform`: one value.
    Uniform(ShaderValue),
    /// `varying` or `vertex` on a shape with four corners: the floats of the corners
    /// `(u, v) = (0, 0), (1, 0), (0, 1), (1, 1)`, each `width` floats.
    Corners {
        /// Floats per corner (1 or 3).
        width: usize,
        /// The four corners' floats.
        data: Vec<f32>,
    },
}

/// The shading-language shaders of one object.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ObjectShaders {
    /// The surface shader (None: the object's native material).
    pub surface: Option<ShaderInstance>,
    /// The displacement shader.
    pub displacement: Option<ShaderInstance>,
    /// How far (in object space) the displacement may move a point: the split and cull
    /// bounds grow by it, and cells displaced further are counted as escaped.
    pub displacement_bound: f32,
    /// The atmosphere (volume) shader, run on the surface's `Ci`, `Oi`.
    pub atmosphere: Option<ShaderInstance>,
    /// Primitive variables bound to parameters of the surface or displacement shader.
    pub primitive: Vec<(String, PrimitiveValue)>,
}

impl ObjectShaders {
    /// True if nothing is set (the object shades natively).
    pub fn is_empty(&self) -> bool {
        self.surface.is_none() && self.displacement.is_none() && self.atmosphere.is_none()
    }
}

/// The scene's shading-language lights and imager.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneShaders {
    /// Light shaders, each with its index in `Scene::lights` (where a placeholder ambient light
    /// of zero intensity holds its place, so that light sets, `Object::lights`, name it).
    pub lights: Vec<(u32, ShaderInstance)>,
    /// The imager, run over the final pixels.
    pub imager: Option<ShaderInstance>,
    /// From RenderMan's world space to the model's world space (a RIB scene's model world is
    /// its camera space at shutter open): the shaders' "world" space.
    pub world_to_model: Mat,
    /// Texture maps the shaders may read (issue #32): each string parameter value of an
    /// instance that names a file along the texture search path, with that file. The
    /// renderer loads them before rendering (a malformed one is an error then) and the
    /// `texture`, `environment`, `shadow` and `textureinfo` calls find them by the name.
    pub maps: Vec<(String, std::path::PathBuf)>,
}

impl Default for SceneShaders {
    fn default() -> Self {
        SceneShaders {
            lights: Vec::new(),
            imager: None,
            world_to_model: IDENTITY,
            maps: Vec::new(),
        }
    }
}

impl SceneShaders {
    /// True if the scene has no shading-language light or imager.
    pub fn is_empty(&self) -> bool {
        self.lights.is_empty() && self.imager.is_none()
    }
}

impl ObjectShaders {
    /// The shader run on the surface's grids that has an `output` parameter `name` (the
    /// atmosphere's, which runs last, before the surface's), with the parameter's type.
    pub fn output(&self, name: &str) -> Option<(&ShaderInstance, reyes_sl::Type)> {
        [&self.atmosphere, &self.surface]
            .into_iter()
            .flatten()
            .find_map(|i| Some((i, i.output(name)?)))
    }
}

impl super::Scene {
    /// Fills in the type of every `Output` AOV that has none from the first object whose
    /// shaders declare the variable (a float, colour, point, vector or normal, not an array);
    /// `Float` if none does. Returns the variables no shader of the scene writes, and those
    /// whose type no AOV can hold, for a warning.
    pub fn resolve_output_types(&mut self) -> Vec<String> {
        use super::{AovSource, VariableType};
        use reyes_sl::BaseType as B;
        let mut unwritten = Vec::new();
        for i in 0..self.outputs.aovs.len() {
            let aov = &self.outputs.aovs[i];
            let (AovSource::Output, Some(name)) = (aov.source, aov.variable.clone()) else {
                continue;
            };
            let found = self.objects.iter().find_map(|o| o.shaders.as_ref()?.output(&name));
            let ty = found.and_then(|(_, t)| match (t.base, t.array) {
                (B::Float, None) => Some(VariableType::Float),
                (B::Color, None) => Some(VariableType::Color),
                (B::Point, None) => Some(VariableType::Point),
                (B::Vector, None) => Some(VariableType::Vector),
                (B::Normal, None) => Some(VariableType::Normal),
                _ => None,
            });
            if ty.is_none() {
                unwritten.push(name);
            }
            let aov = &mut self.outputs.aovs[i];
            if aov.variable_type.is_none() {
                aov.variable_type = Some(ty.unwrap_or(VariableType::Float));
            }
        }
        unwritten
    }
}
