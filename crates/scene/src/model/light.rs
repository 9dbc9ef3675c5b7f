//! Light sources: [`Light`], the [`AreaShape`] of an area light and its motion keys.
//!
//! Invariant: colours are linear RGB, intensities scale them; area shapes are in world space.

use serde::{Deserialize, Serialize};

use super::{Rgb, V3, one, white};

/// A light source.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Light {
    /// Light arriving equally from everywhere.
    Ambient {
        /// Colour.
        #[serde(default = "white")]
        color: Rgb,
        /// Scale on colour.
        #[serde(default = "one")]
        intensity: f32,
    },
    /// Parallel light travelling from `from` towards `to`.
    Distant {
        /// A point the light comes from.
        from: V3,
        /// A point the light goes to.
        #[serde(default)]
        to: V3,
        /// Colour.
        #[serde(default = "white")]
        color: Rgb,
        /// Scale on colour.
        #[serde(default = "one")]
        intensity: f32,
        /// Cast hard shadows (traced shadow rays).
        #[serde(default)]
        shadows: bool,
    },
    /// A point light with inverse-square fall-off.
    Point {
        /// Position in world space.
        from: V3,
        /// Colour.
        #[serde(default = "white")]
        color: Rgb,
        /// Scale on colour: radiance arriving at distance d is `intensity * color / d^2`.
        #[serde(default = "one")]
        intensity: f32,
        /// Cast hard shadows (traced shadow rays).
        #[serde(default)]
        shadows: bool,
    },
    /// A light with extent: a point light of `intensity` spread evenly over `shape`. Each
    /// shading sample sends a shadow ray to a pseudo-randomly chosen, stratified point of
    /// the shape, so a partly hidden light gives a penumbra (FIG. 22). Always shadows.
    /// The light itself is invisible to camera rays (put an object there to see it).
    Area {
        /// The emitting shape.
        shape: AreaShape,
        /// Colour.
        #[serde(default = "white")]
        color: Rgb,
        /// Scale on colour, as for a point light at the shape's centre.
        #[serde(default = "one")]
        intensity: f32,
        /// Motion (Appendix B's moving lights): the shape's displacement and the intensity
        /// at two or more times within the shutter, in increasing time order, interpolated
        /// linearly and held outside. Empty: still, at `intensity`.
        #[serde(default)]
        motion: Vec<LightKey>,
    },
}

/// The shape of an area light, in world space.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum AreaShape {
    /// A ball (Appendix B's spherical lights).
    Sphere {
        /// Centre.
        center: V3,
        /// Radius (> 0).
        radius: f32,
    },
    /// A disk emitting to both sides.
    Disk {
        /// Centre.
        center: V3,
        /// Normal (non-zero).
        normal: V3,
        /// Radius (> 0).
        radius: f32,
    },
    /// A parallelogram `corner + a * edge_u + b * edge_v`, `a, b` in [0, 1], emitting to
    /// both sides.
    Rectangle {
        /// One corner.
        corner: V3,
        /// First edge (non-zero, not parallel to `edge_v`).
        edge_u: V3,
        /// Second edge.
        edge_v: V3,
    },
}

/// An area light at one time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightKey {
    /// Scene time, within the shutter.
    pub time: f32,
    /// Displacement of the shape from where `shape` puts it.
    #[serde(default)]
    pub offset: V3,
    /// Intensity at that time (>= 0).
    #[serde(default = "one")]
    pub intensity: f32,
}
