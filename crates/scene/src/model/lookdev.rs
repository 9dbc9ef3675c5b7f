//! Look development: texture maps ([`TextureMap`], [`Maps`]), the scalar sources of
//! displacement and bump mapping ([`Scalar`], [`Displacement`], [`Bump`]) and the texture
//! cache's memory bound ([`TextureCache`]).
//!
//! Invariants: texture coordinates are the surface's parameters `(u, v)` (RenderMan's
//! default `s, t`), scaled by `repeat`; displacement and bump amounts are in object-space
//! units along the unit object-space normal; a `file` is resolved against the scene file's
//! folder when relative ([`crate::parse`]).

use serde::{Deserialize, Serialize};

/// How a texture file's values relate to linear light. There is no default: a texture's
/// colour space is always declared.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum ColorSpace {
    /// sRGB-encoded colour channels (most 8-bit PNG, JPEG and TIFF pictures); alpha linear.
    Srgb,
    /// Linear values (OpenEXR, and data maps: displacement, roughness, specular).
    Linear,
}

/// What a lookup outside the texture's `[0, 1]` square reads (RenderMan's wrap modes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum TextureWrap {
    /// Repeats.
    #[default]
    Periodic,
    /// Extends the edge texels.
    Clamp,
    /// Reads zero.
    Black,
}

/// A texture map: a file read through the MIP-mapped, footprint-filtered texture cache.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureMap {
    /// A PNG, JPEG, TIFF or OpenEXR file; relative to the scene file's folder.
    pub file: String,
    /// How its values are encoded.
    pub color_space: ColorSpace,
    /// Outside `[0, 1]`.
    #[serde(default)]
    pub wrap: TextureWrap,
    /// Texture coordinates are `(repeat.0 * u, repeat.1 * v)`: how many times the image
    /// spans the surface's parameter range each way (non-zero).
    #[serde(default = "one_one")]
    pub repeat: (f32, f32),
    /// Scale on the filter footprint (RenderMan's `"width"`, >= 0): 1 filters over the
    /// micropolygon, 0 reads the finest level at the vertex alone.
    #[serde(default = "one")]
    pub width: f32,
}

/// Texture maps modulating an object's material. A colour map multiplies the surface colour
/// (RenderMan's `paintedplastic`); the others use their first channel.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Maps {
    /// Multiplies the material colour `Cs` (RGB).
    #[serde(default)]
    pub color: Option<TextureMap>,
    /// Multiplies the opacity `Os` (RGB; a grey map is the same in each channel).
    #[serde(default)]
    pub opacity: Option<TextureMap>,
    /// Multiplies the specular roughness of Plastic and Metal (first channel; the factor
    /// is kept at or above 0.001).
    #[serde(default)]
    pub roughness: Option<TextureMap>,
    /// Multiplies the specular coefficient `ks` of Plastic and Metal (first channel).
    #[serde(default)]
    pub specular: Option<TextureMap>,
}

impl Maps {
    /// Every map that is set, with its field name.
    pub fn each(&self) -> impl Iterator<Item = (&'static str, &TextureMap)> {
        [
            ("color", &self.color),
            ("opacity", &self.opacity),
            ("roughness", &self.roughness),
            ("specular", &self.specular),
        ]
        .into_iter()
        .filter_map(|(name, m)| m.as_ref().map(|m| (name, m)))
    }

    /// True if no map is set.
    pub fn is_empty(&self) -> bool {
        self.each().next().is_none()
    }
}

/// A scalar field over a surface, the source of displacement and bump mapping.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Scalar {
    /// The same value everywhere.
    Constant(f32),
    /// Gradient noise of the object-space point (reyes-texture's `noise::fbm`, `|n| <= 2`
    /// for one octave): `fbm(frequency * P_object, octaves)`.
    Noise {
        /// Lattice cells per object-space unit (> 0).
        #[serde(default = "one")]
        frequency: f32,
        /// Octaves (1..=8), each at twice the frequency and half the amplitude.
        #[serde(default = "one_u32")]
        octaves: u32,
    },
    /// `sin(2 pi (fu u + fv v) + phase)` of the surface parameters.
    Wave {
        /// Cycles across the parameter range in u and in v.
        frequency: (f32, f32),
        /// Phase in degrees.
        #[serde(default)]
        phase: f32,
    },
    /// The first channel of a texture map, filtered over the micropolygon.
    Texture(TextureMap),
}

/// True micropolygon displacement: every grid vertex moves along its unit object-space
/// normal by `amount * (source - center)`, at every motion key alike, and normals are
/// recomputed from the displaced grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Displacement {
    /// The scalar field.
    pub source: Scalar,
    /// Scale, in object-space units.
    #[serde(default = "one")]
    pub amount: f32,
    /// Subtracted from the source before scaling (0.5 centres an 8-bit height map).
    #[serde(default)]
    pub center: f32,
    /// RenderMan's `Attribute "displacementbound" "sphere"`: the most any point moves, in
    /// object-space units (>= 0). Bounds are grown by the larger of this and the source's own
    /// bound; a vertex that moves further than a declared bound is counted and warned about.
    /// Absent: the source's own bound, with a warning.
    #[serde(default)]
    pub bound: Option<f32>,
}

/// Bump mapping: the normal as if displaced by `amount * (source - center)`, the geometry
/// not moved.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bump {
    /// The scalar field.
    pub source: Scalar,
    /// Scale, in object-space units.
    #[serde(default = "one")]
    pub amount: f32,
    /// Subtracted from the source before scaling.
    #[serde(default)]
    pub center: f32,
}

/// The texture cache shared by every thread of a render.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureCache {
    /// The most bytes of texture tiles held in memory at once (>= 65536); pyramids beyond it
    /// are read back from a temporary file as needed.
    #[serde(default = "default_cache_bytes")]
    pub max_bytes: u64,
}

impl Default for TextureCache {
    fn default() -> TextureCache {
        TextureCache { max_bytes: default_cache_bytes() }
    }
}

/// The smallest cache accepted: four tiles of 32 x 32 RGBA `f32` texels.
pub const MIN_TEXTURE_CACHE_BYTES: u64 = 65536;

fn default_cache_bytes() -> u64 {
    256 << 20
}
fn one() -> f32 {
    1.0
}
fn one_u32() -> u32 {
    1
}
fn one_one() -> (f32, f32) {
    (1.0, 1.0)
}

impl Scalar {
    /// The texture map it reads, if any.
    pub fn map(&self) -> Option<&TextureMap> {
        match self {
            Scalar::Texture(m) => Some(m),
            _ => None,
        }
    }
}
