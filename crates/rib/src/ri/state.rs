//! The graphics state of the RI state machine: the options of a frame and the attributes of
//! the current attribute block, with the defaults of the Specification.
//!
//! Invariants: options change only outside the world block and are snapshotted at
//! `WorldBegin`; attributes are a value type pushed and popped whole by
//! `AttributeBegin`/`AttributeEnd` (and the implicit blocks of `FrameBegin`, `WorldBegin`,
//! `SolidBegin` and `ObjectInstance`).

use reyes_scene::{Basis, Filter, FilterKind, HiderMethod};

use crate::Location;
use crate::ri::xform::Xform;

/// `Projection`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Projection {
    /// The Specification's default.
    Orthographic,
    /// `"perspective" "fov"` in degrees (default 90).
    Perspective {
        /// Field of view across the shorter screen side.
        fov: f32,
    },
}

/// One `Display` request.
#[derive(Debug, Clone, PartialEq)]
pub struct Display {
    /// The output name as written (`+name` lines name extra outputs; the `+` is removed).
    pub name: String,
    /// The display driver (`"file"`, `"framebuffer"`, `"tiff"`, `"openexr"`, ...).
    pub driver: String,
    /// The mode (`"rgba"`, `"rgb"`, `"z"`, `"rgbaz"`, ...).
    pub mode: String,
    /// True for a `+name` line: an output besides the main one.
    pub extra: bool,
    /// Where it was requested.
    pub at: Location,
}

/// The options of one frame (Spec 3.2, 4.1).
#[derive(Debug, Clone)]
pub(crate) struct FrameOptions {
    /// `RelativeDetail`: the scale on every detail (raster area of a `Detail` bound).
    pub relative_detail: f32,
    pub width: u32,
    pub height: u32,
    pub pixel_aspect: f32,
    pub frame_aspect: Option<f32>,
    pub screen_window: Option<[f32; 4]>,
    pub crop: Option<[f32; 4]>,
    pub projection: Projection,
    pub hither: f32,
    pub yon: f32,
    /// `(fstop, focallength, focaldistance)`.
    pub depth_of_field: Option<(f32, f32, f32)>,
    pub shutter: (f32, f32),
    pub pixel_samples: (u32, u32),
    pub filter: Filter,
    pub displays: Vec<Display>,
    /// The AOVs named by `Display "+name"` lines whose mode is an output variable.
    pub aovs: Vec<reyes_scene::Aov>,
    pub method: HiderMethod,
    pub jitter: bool,
    /// `Hider "hidden" "depthfilter"`.
    pub depth_filter: reyes_scene::DepthFilter,
    pub bucket_size: Option<(u32, u32)>,
    /// `Option "limits" "gridsize"`: most micropolygons in one grid.
    pub max_grid_size: Option<u32>,
    /// World to camera, set by the transformations before `WorldBegin`.
    pub camera: Xform,
    /// `Option "searchpath"`.
    pub search: crate::ri::search::SearchPaths,
    /// A shading-language `Imager`.
    pub imager: Option<reyes_scene::ShaderInstance>,
    /// Where each option family was last set, for messages about the values it produced.
    pub origins: Vec<(&'static str, Location, &'static str)>,
}

impl Default for FrameOptions {
    fn default() -> Self {
        FrameOptions {
            relative_detail: 1.0,
            width: 640,
            height: 480,
            pixel_aspect: 1.0,
            frame_aspect: None,
            screen_window: None,
            crop: None,
            projection: Projection::Orthographic,
            // The Specification's defaults are RI_EPSILON and RI_INFINITY; the hider needs a
            // positive near plane and a finite far one (docs/rib.md).
            hither: 1e-3,
            yon: 1e30,
            depth_of_field: None,
            shutter: (0.0, 0.0),
            pixel_samples: (2, 2),
            // RiGaussianFilter 2 x 2 is the Specification's default filter.
            filter: Filter { kind: FilterKind::RiGaussian, width: 2.0, height: None },
            displays: Vec::new(),
            aovs: Vec::new(),
            method: HiderMethod::Stochastic,
            jitter: true,
            depth_filter: reyes_scene::DepthFilter::Min,
            bucket_size: None,
            max_grid_size: None,
            camera: Xform::default(),
            search: Default::default(),
            imager: None,
            origins: Vec::new(),
        }
    }
}

impl FrameOptions {
    /// Remember that the scene field family `field` (e.g. `"camera.fov"`) comes from the
    /// request `name` at `at`.
    pub fn origin(&mut self, field: &'static str, at: &Location, name: &'static str) {
        self.origins.retain(|(f, _, _)| *f != field);
        self.origins.push((field, at.clone(), name));
    }
}

/// The surface shader in effect.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SurfaceShader {
    /// Its name (`"plastic"`, ...); None: the renderer's default surface.
    pub name: Option<String>,
    /// Its parameters, as written.
    pub params: Vec<crate::Param>,
    /// Where it was set.
    pub at: Option<Location>,
}

impl SurfaceShader {
    /// The shader a `Surface` or `Displacement` request names, with its parameters.
    pub(crate) fn of(r: &crate::Request) -> SurfaceShader {
        SurfaceShader {
            name: Some(r.string(0).unwrap_or_default().to_string()),
            params: r.params.clone(),
            at: Some(r.at.clone()),
        }
    }
}

/// The attributes of the current block (Spec 3.2, 4.2).
#[derive(Debug, Clone)]
pub(crate) struct Attributes {
    pub color: [f32; 3],
    pub opacity: [f32; 3],
    pub surface: SurfaceShader,
    pub shading_rate: f32,
    /// `GeometricApproximation "flatness"`, when given (else the model's default).
    pub flatness: Option<f32>,
    /// `GeometricApproximation "motionfactor"` and `"focusfactor"`, when given (else the
    /// model's default, off).
    pub motion_factor: Option<f32>,
    pub focus_factor: Option<f32>,
    pub sides: i32,
    /// `ShadingInterpolation "smooth"`: colours interpolated across micropolygons.
    pub smooth: bool,
    pub reverse_orientation: bool,
    pub matte: bool,
    pub name: Option<String>,
    /// Lights on for the primitives of this block: light slots of the frame.
    pub lights_on: Vec<usize>,
    /// `Detail`: the corners of the bound in world space (camera space at shutter open).
    pub detail: Option<[[f64; 3]; 8]>,
    /// `DetailRange`: how much of the primitives' opacity this level keeps (0: not drawn).
    pub detail_weight: f32,
    /// The `AreaLightSource` whose geometry the primitives of this block are.
    pub area_light: Option<super::area::AreaSource>,
    /// `Basis` for bicubic patches: `(u basis, u step, v basis, v step)`.
    pub basis: (Basis, u32, Basis, u32),
    /// The `Displacement` shader (its name None: none).
    pub displacement: SurfaceShader,
    /// `Attribute "displacementbound" "sphere"`, when given.
    pub displacement_bound: Option<f32>,
    /// `TextureCoordinates` as a scale: `s = repeat.0 u`, `t = repeat.1 v`.
    pub repeat: (f32, f32),
    /// `TrimCurve`: the loops every `NuPatch` of the block is trimmed by (empty: none).
    pub trim: std::sync::Arc<Vec<reyes_scene::TrimLoop>>,
    /// `Attribute "trimcurve" "sense" "outside"`: keep the inside of the loops instead.
    pub trim_outside: bool,
    /// The `Atmosphere` shader (its name None: none).
    pub atmosphere: SurfaceShader,
}

impl Default for Attributes {
    fn default() -> Self {
        Attributes {
            color: [1.0; 3],
            opacity: [1.0; 3],
            surface: SurfaceShader { name: None, params: Vec::new(), at: None },
            shading_rate: 1.0,
            flatness: None,
            motion_factor: None,
            focus_factor: None,
            sides: 2,
            smooth: false,
            reverse_orientation: false,
            matte: false,
            name: None,
            lights_on: Vec::new(),
            area_light: None,
            detail: None,
            detail_weight: 1.0,
            basis: (Basis::Bezier, 3, Basis::Bezier, 3),
            displacement: SurfaceShader { name: None, params: Vec::new(), at: None },
            displacement_bound: None,
            repeat: (1.0, 1.0),
            trim: Default::default(),
            trim_outside: false,
            atmosphere: SurfaceShader { name: None, params: Vec::new(), at: None },
        }
    }
}
