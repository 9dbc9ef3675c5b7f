//! Surface materials: [`Material`].
//!
//! Invariant: colours and opacities are per channel, in [0, 1] once validated (a Constant's
//! colour only non-negative, unbounded); the coefficients default as in RenderMan's shaders.

use serde::{Deserialize, Serialize};

use super::{Rgb, one, white};

/// Surface materials. Colours and opacities are per channel in [0, 1].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Material {
    /// Unlit colour.
    Constant {
        /// Colour: the light the surface sends (>= 0, unbounded: above 1 it glows).
        color: Rgb,
        /// Opacity per channel.
        #[serde(default = "white")]
        opacity: Rgb,
    },
    /// Lambertian.
    Matte {
        /// Colour.
        color: Rgb,
        /// Opacity per channel.
        #[serde(default = "white")]
        opacity: Rgb,
        /// Ambient coefficient.
        #[serde(default = "one")]
        ka: f32,
        /// Diffuse coefficient.
        #[serde(default = "one")]
        kd: f32,
    },
    /// RenderMan plastic: ambient + diffuse in the surface colour, specular in `specular_color`.
    Plastic {
        /// Colour.
        color: Rgb,
        /// Opacity per channel.
        #[serde(default = "white")]
        opacity: Rgb,
        /// Ambient coefficient.
        #[serde(default = "one")]
        ka: f32,
        /// Diffuse coefficient.
        #[serde(default = "half")]
        kd: f32,
        /// Specular coefficient.
        #[serde(default = "half")]
        ks: f32,
        /// Specular roughness (> 0): the exponent is `8 / roughness`, RenderMan's `specular()`.
        #[serde(default = "tenth")]
        roughness: f32,
        /// Specular colour.
        #[serde(default = "white")]
        specular_color: Rgb,
    },
    /// RenderMan's `metal`: `Ci = Os * Cs * (ka * ambient + ks * specular)`, with the
    /// specular term of `Plastic` (`N.H` raised to `8 / roughness`) coloured by the surface.
    Metal {
        /// Colour.
        color: Rgb,
        /// Opacity per channel.
        #[serde(default = "white")]
        opacity: Rgb,
        /// Ambient coefficient.
        #[serde(default = "one")]
        ka: f32,
        /// Specular coefficient.
        #[serde(default = "one")]
        ks: f32,
        /// Specular roughness (> 0): the exponent is `8 / roughness`, RenderMan's `specular()`.
        #[serde(default = "tenth")]
        roughness: f32,
    },
    /// RenderMan's `defaultsurface`, what a renderer shades with when no surface shader is
    /// given: lit by a headlight at the eye, not by the scene's lights,
    /// `Ci = Os * Cs * (ka + kd * (N.I)^2)` with `N.I` the cosine between the unit normal and
    /// the unit viewing direction.
    DefaultSurface {
        /// Colour.
        color: Rgb,
        /// Opacity per channel.
        #[serde(default = "white")]
        opacity: Rgb,
        /// Constant term (default 0.2).
        #[serde(default = "fifth")]
        ka: f32,
        /// Headlight term (default 0.8).
        #[serde(default = "four_fifths")]
        kd: f32,
    },
    /// A shading-language surface shader: `NAME.sl` found along the scene's `shader_path`
    /// (or one of the built-in standard shaders, `@` on the path), compiled when the scene
    /// loads, with its parameters' values by name (docs/scene-format.md, "Shaders").
    Shader {
        /// The shader's name (its file is `name.sl`).
        name: String,
        /// Parameter values by name; the others keep the shader's defaults.
        #[serde(default)]
        params: std::collections::BTreeMap<String, ShaderParam>,
        /// The shader's `Cs`.
        #[serde(default = "white")]
        color: Rgb,
        /// The shader's `Os`.
        #[serde(default = "white")]
        opacity: Rgb,
    },
}

/// A shader parameter's value in RON: a number, a triple (colour, point, vector or normal),
/// a string, or a list of numbers (an array, or a matrix's 16).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ShaderParam {
    /// A float (or a triple of equal components).
    Float(f32),
    /// A colour, point, vector or normal.
    Triple((f32, f32, f32)),
    /// A string.
    Str(String),
    /// A float array or a matrix.
    List(Vec<f32>),
}

fn fifth() -> f32 {
    0.2
}

fn four_fifths() -> f32 {
    0.8
}

fn half() -> f32 {
    0.5
}
fn tenth() -> f32 {
    0.1
}
