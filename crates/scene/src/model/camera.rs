//! The view: output resolution ([`Image`]), the [`Camera`] with its motion keys, the
//! [`Shutter`] and the thin [`Lens`].
//!
//! Invariant: field defaults here are the serde defaults of the RON file (`up` is +y,
//! `fov` 45 degrees, `hither` 0.1, `yon` 1000, shutter `[0, 1]` uniform, pinhole).

use serde::{Deserialize, Serialize};

use super::{V3, default_up};

/// Output resolution in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Image {
    /// Width in pixels (> 0).
    pub width: u32,
    /// Height in pixels (> 0).
    pub height: u32,
}

/// A perspective camera. Camera space has +x right, +y up, +z forward (eye depth).
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
    /// Field of view in degrees across the shorter image side, in (0, 180).
    #[serde(default = "default_fov")]
    pub fov: f32,
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
