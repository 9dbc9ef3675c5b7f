//! What a frame writes besides the beauty: the [`Outputs`] section, its arbitrary output
//! variables ([`Aov`]), light groups, EXR pixel types and compression, the background depth,
//! the PNG preview's view transform and the header's render time.
//!
//! Invariant: `Default` of every type here is what an absent RON field gives, and the default
//! `Outputs` writes exactly what the renderer wrote before AOVs existed (RGBA and Z, float, ZIP)
//! but for the background depth ([`ZBackground`]).

use serde::{Deserialize, Serialize};

use super::Rgb;

/// The `outputs` section of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Outputs {
    /// Arbitrary output variables, each written as its own layer of the EXR, in this order.
    pub aovs: Vec<Aov>,
    /// Named sets of lights (indices into `Scene::lights`) for the shading components'
    /// `light_group`.
    pub light_groups: Vec<LightGroup>,
    /// Depth written where no surface is visible (the `Z` channel and the `z` AOV).
    pub zbackground: ZBackground,
    /// Pixel type of the top-level R, G, B, A and Z channels.
    pub pixel_type: PixelType,
    /// Compression of the top-level layer.
    pub compression: Compression,
    /// Write the render time (seconds) in the EXR header. Off by default: it is the one header
    /// value that differs between two renders of the same scene, so with it on the file is no
    /// longer byte-identical from run to run.
    pub render_time: bool,
    /// The view transform of the PNG preview.
    pub png: PngView,
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs {
            aovs: Vec::new(),
            light_groups: Vec::new(),
            zbackground: ZBackground::default(),
            pixel_type: PixelType::Float,
            compression: Compression::Zip,
            render_time: false,
            png: PngView::default(),
        }
    }
}

/// One arbitrary output variable.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Aov {
    /// What is written.
    pub source: AovSource,
    /// The layer name in the EXR (`None`: the source's name, with `_GROUP` appended for a
    /// light group). Letters, digits and `_` only, unique in the file.
    #[serde(default)]
    pub name: Option<String>,
    /// How samples become pixels (`None`: [`AovSource::default_filter`]).
    #[serde(default)]
    pub filter: Option<AovFilter>,
    /// Pixel type of a float layer (ids are always 32-bit unsigned integers).
    #[serde(default)]
    pub pixel_type: Option<PixelType>,
    /// Compression of this layer (`None`: the top level's).
    #[serde(default)]
    pub compression: Option<Compression>,
    /// For `Ambient`, `Diffuse` and `Specular`: only the lights of this group (a name in
    /// `light_groups`); `None`: every light.
    #[serde(default)]
    pub light_group: Option<String>,
    /// For `Output`: the shader output variable written (an `output varying` parameter of the
    /// objects' surface or atmosphere shaders; 0 where an object's shaders have none).
    #[serde(default)]
    pub variable: Option<String>,
    /// For `Output`: the variable's type, which decides the layer's channels (`None`: the
    /// type the scene's shaders declare, else `Float`).
    #[serde(default)]
    pub variable_type: Option<VariableType>,
}

/// The type of a shader output variable written as an AOV.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum VariableType {
    /// One channel, Y.
    Float,
    /// R, G, B.
    Color,
    /// X, Y, Z (camera space).
    Point,
    /// X, Y, Z (camera space).
    Vector,
    /// X, Y, Z (camera space).
    Normal,
}

impl VariableType {
    /// The channel names within the layer.
    pub fn channels(self) -> &'static [&'static str] {
        match self {
            VariableType::Float => &["Y"],
            VariableType::Color => &["R", "G", "B"],
            _ => &["X", "Y", "Z"],
        }
    }
}

impl Aov {
    /// An AOV of `source` with every other field at its default.
    pub fn new(source: AovSource) -> Aov {
        Aov {
            source,
            name: None,
            filter: None,
            pixel_type: None,
            compression: None,
            light_group: None,
            variable: None,
            variable_type: None,
        }
    }

    /// An AOV of the shader output variable `name`, of type `ty` (`None`: as the shaders
    /// declare it).
    pub fn output(name: &str, ty: Option<VariableType>) -> Aov {
        Aov { variable: Some(name.to_string()), variable_type: ty, ..Aov::new(AovSource::Output) }
    }

    /// The channel names within the layer.
    pub fn channels(&self) -> &'static [&'static str] {
        match self.source {
            AovSource::Output => self.variable_type.unwrap_or(VariableType::Float).channels(),
            s => s.channels(),
        }
    }

    /// The layer name: `name`, else the source's name with `_GROUP` for a light group (an
    /// output variable's: the variable's name).
    pub fn layer_name(&self) -> String {
        match (&self.name, &self.light_group) {
            (Some(n), _) => n.clone(),
            (None, _) if self.source == AovSource::Output => {
                self.variable.clone().unwrap_or_else(|| "output".to_string())
            }
            (None, Some(g)) => format!("{}_{g}", self.source.name()),
            (None, None) => self.source.name().to_string(),
        }
    }

    /// The filter: the AOV's own, else the source's default.
    pub fn filter_or_default(&self) -> AovFilter {
        self.filter.unwrap_or(self.source.default_filter())
    }
}

/// What an AOV holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum AovSource {
    /// The beauty colour, premultiplied (RenderMan's `Ci`): channels R, G, B.
    Ci,
    /// The composited opacity per channel (`Oi`): R, G, B.
    Oi,
    /// Camera-space depth of the front-most visible surface, opaque or not: Z.
    Z,
    /// Halfway between the front-most visible surface's depth and the next surface's behind
    /// it at the sample (infinite where there is none; `zbackground` where nothing is
    /// seen): Z. The depth of a shadow map under `depthfilter "midpoint"`; rendering it
    /// turns occlusion culling off (the surfaces behind are needed).
    ZMidpoint,
    /// Unit outward surface normal in camera space at shutter open (not face-forwarded):
    /// X, Y, Z.
    N,
    /// Camera-space position at shutter open: X, Y, Z.
    P,
    /// The surface parameter s (the shape's u): Y.
    S,
    /// The surface parameter t (the shape's v): Y.
    T,
    /// Screen-space motion over the shutter, in raster pixels per shutter interval (x right,
    /// y down): X, Y.
    DPdtime,
    /// 1 + the object's index in `objects` (0: background), as a 32-bit unsigned integer: id.
    ObjectId,
    /// 1 + the index of the first object with an equal material (0: background), as a 32-bit
    /// unsigned integer: id.
    MaterialId,
    /// The built-in shaders' ambient term, premultiplied (`__ambient`); the Constant
    /// material's colour counts as ambient: R, G, B.
    Ambient,
    /// The diffuse term (`__diffuse`): R, G, B.
    Diffuse,
    /// The specular term (`__specular`): R, G, B.
    Specular,
    /// A shader's output variable (`Aov::variable`), interpolated across micropolygons as N
    /// and P are: the channels of its type (`Aov::variable_type`).
    Output,
}

impl AovSource {
    /// Every source, in the order docs/outputs.md lists them.
    pub const ALL: [AovSource; 15] = [
        AovSource::Ci,
        AovSource::Oi,
        AovSource::Z,
        AovSource::ZMidpoint,
        AovSource::N,
        AovSource::P,
        AovSource::S,
        AovSource::T,
        AovSource::DPdtime,
        AovSource::ObjectId,
        AovSource::MaterialId,
        AovSource::Ambient,
        AovSource::Diffuse,
        AovSource::Specular,
        AovSource::Output,
    ];

    /// The conventional name (the layer name by default).
    pub fn name(self) -> &'static str {
        match self {
            AovSource::Ci => "Ci",
            AovSource::Oi => "Oi",
            AovSource::Z => "z",
            AovSource::ZMidpoint => "z_midpoint",
            AovSource::N => "N",
            AovSource::P => "P",
            AovSource::S => "s",
            AovSource::T => "t",
            AovSource::DPdtime => "dPdtime",
            AovSource::ObjectId => "object_id",
            AovSource::MaterialId => "material_id",
            AovSource::Ambient => "__ambient",
            AovSource::Diffuse => "__diffuse",
            AovSource::Specular => "__specular",
            AovSource::Output => "output",
        }
    }

    /// The channel names within the layer.
    pub fn channels(self) -> &'static [&'static str] {
        match self {
            AovSource::Ci
            | AovSource::Oi
            | AovSource::Ambient
            | AovSource::Diffuse
            | AovSource::Specular => &["R", "G", "B"],
            AovSource::Z | AovSource::ZMidpoint => &["Z"],
            AovSource::N | AovSource::P => &["X", "Y", "Z"],
            AovSource::S | AovSource::T => &["Y"],
            AovSource::DPdtime => &["X", "Y"],
            AovSource::ObjectId | AovSource::MaterialId => &["id"],
            AovSource::Output => &["Y"],
        }
    }

    /// True for the integer sources (ids).
    pub fn is_id(self) -> bool {
        matches!(self, AovSource::ObjectId | AovSource::MaterialId)
    }

    /// True for the shading components, which take a light group.
    pub fn is_component(self) -> bool {
        matches!(self, AovSource::Ambient | AovSource::Diffuse | AovSource::Specular)
    }

    /// The filter used when the AOV names none: the beauty's for everything but depth and
    /// ids, which take the sample nearest the camera (`Zmin`), so they are never averaged.
    pub fn default_filter(self) -> AovFilter {
        match self {
            AovSource::Z | AovSource::ObjectId | AovSource::MaterialId => AovFilter::Zmin,
            AovSource::ZMidpoint => AovFilter::Min,
            _ => AovFilter::Filter,
        }
    }
}

/// How an AOV's samples become a pixel (RenderMan's `"filter"` of a `Display`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum AovFilter {
    /// The beauty's reconstruction filter and weights, over its whole footprint.
    #[default]
    Filter,
    /// Per channel, the smallest value among the pixel's own samples.
    Min,
    /// Per channel, the largest value among the pixel's own samples.
    Max,
    /// Per channel, the mean of the pixel's own samples.
    Average,
    /// Every channel of the pixel's sample whose front surface is nearest the camera
    /// (background samples last; ties to the lower sample index).
    Zmin,
    /// Every channel of the pixel's sample nearest the pixel's centre (ties to the lower
    /// sample index).
    Nearest,
}

/// A named set of lights.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightGroup {
    /// The group's name (letters, digits and `_`).
    pub name: String,
    /// Indices into `Scene::lights`, each at most once.
    pub lights: Vec<u32>,
}

/// Depth where no surface is visible.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum ZBackground {
    /// A finite depth (default [`ZBackground::DEFAULT`]): differences and squares of depths
    /// stay finite, so `oiiotool --diff` of two renders reports a finite error.
    Finite(f32),
    /// `+inf`, the exact "nothing there" (what this renderer wrote before).
    Infinite,
}

impl ZBackground {
    /// The default background depth, 1e30: RenderMan's RI_INFINITY, far beyond any yon the
    /// model accepts, and small enough that its square (1e60) is finite in double precision.
    pub const DEFAULT: f32 = 1.0e30;

    /// The depth written.
    pub fn value(self) -> f32 {
        match self {
            ZBackground::Finite(z) => z,
            ZBackground::Infinite => f32::INFINITY,
        }
    }
}

impl Default for ZBackground {
    fn default() -> Self {
        ZBackground::Finite(ZBackground::DEFAULT)
    }
}

/// EXR pixel type of a float layer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum PixelType {
    /// 16-bit half float.
    Half,
    /// 32-bit float.
    #[default]
    Float,
}

/// EXR compression of a layer (those the `exr` crate writes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Compression {
    /// Uncompressed.
    None,
    /// Lossless zlib over blocks of 16 lines.
    #[default]
    Zip,
    /// Lossless wavelet compression.
    Piz,
    /// DWAA: lossy DCT compression of half colour channels in blocks of 32 lines, at the
    /// default level (45); float and other channels are stored losslessly.
    Dwaa,
}

/// The PNG preview's view transform: exposure, optional background, sRGB encoding, ordered
/// dither.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PngView {
    /// Exposure in stops: colour is multiplied by `2^exposure` before encoding.
    pub exposure: f32,
    /// Composite over this linear colour (the PNG is then opaque); `None`: keep alpha.
    pub background: Option<Rgb>,
    /// Ordered (8x8 Bayer) dither of the 8-bit quantisation.
    pub dither: bool,
}

impl Default for PngView {
    fn default() -> Self {
        PngView { exposure: 0.0, background: None, dither: true }
    }
}
