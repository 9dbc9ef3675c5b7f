//! The view: output resolution ([`Image`]), the [`Camera`] with its [`Projection`], screen
//! window and motion keys, the [`Shutter`] and the thin [`Lens`].
//!
//! Invariant: field defaults here are the serde defaults of the RON file (`up` is +y,
//! `fov` 45 degrees, `hither` 0.1, `yon` 1000, shutter `[0, 1]` uniform, pinhole,
//! perspective, RenderMan's default screen window).

use serde::{Deserialize, Serialize};

use super::{V3, default_up};

/// Output resolution in pixels, and the part of the frame to render.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Image {
    /// Width in pixels (> 0).
    pub width: u32,
    /// Height in pixels (> 0).
    pub height: u32,
    /// RenderMan's `CropWindow`: `[xmin, xmax, ymin, ymax]` in screen fractions (0 is the
    /// left and top edge, 1 the right and bottom), `0 <= min < max <= 1`. Only the pixels of
    /// [`Image::crop_pixels`] are rendered and written, each with exactly the value it has in
    /// the whole frame. None: the whole frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crop: Option<[f32; 4]>,
}

impl Image {
    /// A `width x height` image without a crop window.
    pub fn new(width: u32, height: u32) -> Image {
        Image { width, height, crop: None }
    }

    /// The pixels the crop window selects, `[x0, x1, y0, y1]` half-open: as the RenderMan
    /// Interface Specification (3.2, `RiCropWindow`) defines them, columns
    /// `ceil(width * xmin)` to `ceil(width * xmax) - 1`, rows likewise. The whole image
    /// without a crop window. May be empty for a window thinner than a pixel (validation
    /// refuses that).
    pub fn crop_pixels(&self) -> [u32; 4] {
        let Some([x0, x1, y0, y1]) = self.crop else {
            return [0, self.width, 0, self.height];
        };
        // In f32, as RenderMan's float arithmetic does (0.2 * 80 is 16, not 16.0000002).
        let at = |f: f32, n: u32| ((n as f32 * f).ceil().max(0.0) as u32).min(n);
        [at(x0, self.width), at(x1, self.width), at(y0, self.height), at(y1, self.height)]
    }
}

/// The camera. Camera space has +x right, +y up, +z forward (eye depth).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Eye position in world space.
    pub eye: V3,
    /// A point the camera looks at.
    pub look_at: V3,
    /// Up direction (need not be perpendicular to the view direction).
    #[serde(default = "default_up")]
    pub up: V3,
    /// How camera space maps to screen space (RenderMan's `Projection`).
    #[serde(default)]
    pub projection: Projection,
    /// Field of view in degrees, in (0, 180): with the default screen window it spans the
    /// shorter image side. A perspective camera maps `tan(fov / 2)` in `x/z` (and `y/z`) to 1
    /// in screen space; an orthographic camera ignores it.
    #[serde(default = "default_fov")]
    pub fov: f32,
    /// RenderMan's `ScreenWindow`: `[left, right, bottom, top]`, the part of screen space that
    /// fills the image (left edge to right edge, bottom edge to top edge), with
    /// `left < right` and `bottom < top`. `None`: RenderMan's default, `[-a, a, -1, 1]` for a
    /// frame aspect `a = width / height >= 1`, else `[-1, 1, -1/a, 1/a]`.
    #[serde(default)]
    pub screen_window: Option<[f32; 4]>,
    /// Near clipping depth (eye-space z), > 0.
    #[serde(default = "default_hither")]
    pub hither: f32,
    /// Far clipping depth, > hither.
    #[serde(default = "default_yon")]
    pub yon: f32,
    /// Shutter interval.
    #[serde(default)]
    pub shutter: Shutter,
    /// Thin lens for depth of field; `None` is a pinhole camera.
    #[serde(default)]
    pub lens: Option<Lens>,
    /// Camera motion: eye, look-at point and up vector at two or more times within the
    /// shutter, in increasing time order. Empty: the camera is still (`eye`, `look_at`, `up`).
    /// When given, these keys replace `eye`, `look_at` and `up`; between keys each is
    /// interpolated linearly, and before the first or after the last key it is held.
    #[serde(default)]
    pub motion: Vec<CameraKey>,
}

/// How camera space maps to screen space (RenderMan's `Projection`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Projection {
    /// Screen position `(x/z, y/z) / tan(fov/2)` of a camera-space point (RenderMan's
    /// `"perspective"` with its `fov`).
    #[default]
    Perspective,
    /// Screen position `(x, y)`: camera-space units, parallel to the view direction, whatever
    /// the depth (RenderMan's `"orthographic"`). Depth of field does not apply: a `lens` is
    /// ignored, as RenderMan ignores `DepthOfField` under an orthographic projection.
    Orthographic,
}

/// The camera at one time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraKey {
    /// Scene time, within the shutter.
    pub time: f32,
    /// Eye position.
    pub eye: V3,
    /// A point the camera looks at.
    pub look_at: V3,
    /// Up direction.
    #[serde(default = "default_up")]
    pub up: V3,
}

fn default_fov() -> f32 {
    45.0
}
fn default_hither() -> f32 {
    0.1
}
fn default_yon() -> f32 {
    1000.0
}

/// Shutter interval in scene time units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shutter {
    /// Opening time.
    pub open: f32,
    /// Closing time (>= open).
    pub close: f32,
    /// How the shutter weights time (the density of sample times).
    #[serde(default)]
    pub shape: ShutterShape,
}

impl Default for Shutter {
    fn default() -> Self {
        Shutter { open: 0.0, close: 1.0, shape: ShutterShape::Uniform }
    }
}

/// Time density of the shutter (patent FIGS. 13-16).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ShutterShape {
    /// Fully open for the whole interval: sample times uniform (FIGS. 13-15).
    #[default]
    Uniform,
    /// Opens and closes gradually, weighting the middle of the interval (FIG. 16): the density
    /// rises linearly over the first `ramp` of the interval, is flat, and falls linearly over
    /// the last `ramp` (a trapezoid; `ramp` in (0, 0.5], 0.5 is a triangle).
    Gradual {
        /// Fraction of the interval taken by the opening (and by the closing).
        ramp: f32,
    },
}

/// Thin-lens parameters (Appendix A's `VisCamera`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Lens {
    /// Focal length in world units (> 0).
    pub focal_length: f32,
    /// f-number (> 0). Lens radius is `0.5 * focal_length / f_stop`.
    pub f_stop: f32,
    /// Distance of the plane in focus, eye-space z (> 0).
    pub focal_distance: f32,
}

impl Lens {
    /// The lens radius, `0.5 * focal_length / f_stop`, as the renderer computes it (validation
    /// checks that it is finite).
    pub fn radius(&self) -> f32 {
        0.5 * self.focal_length / self.f_stop
    }
}
