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
    /// RenderMan's standard `spotlight`: a point light at `from` shining toward `to` in a
    /// cone. At a point where the unit vector from the light is `L/|L|` and
    /// `cosangle = L.A / |L|` (`A` the unit axis from `from` to `to`), the light arriving is
    /// `intensity * color * cosangle^beam_distribution / (L.L) *
    /// smoothstep(cos(cone_angle), cos(cone_angle - cone_delta), cosangle)`, and nothing
    /// outside the cone (`cosangle < cos(cone_angle)`). Angles are in degrees here (the
    /// shader's parameters are radians).
    Spot {
        /// Position in world space.
        from: V3,
        /// A point on the axis of the cone (!= `from`).
        to: V3,
        /// Colour.
        #[serde(default = "white")]
        color: Rgb,
        /// Scale on colour.
        #[serde(default = "one")]
        intensity: f32,
        /// Half-angle of the cone in degrees, in (0, 180].
        #[serde(default = "default_cone_angle")]
        cone_angle: f32,
        /// Width in degrees of the penumbra inside the cone's edge, in [0, cone_angle].
        #[serde(default = "default_cone_delta")]
        cone_delta: f32,
        /// Exponent of the fall-off of `cosangle` across the beam (>= 0).
        #[serde(default = "default_beam_distribution")]
        beam_distribution: f32,
        /// Cast hard shadows (traced shadow rays).
        #[serde(default)]
        shadows: bool,
    },
    /// A light with extent: a point light of `intensity` spread evenly over `shape`. Each
    /// shading sample sends a shadow ray to a pseudo-randomly chosen, stratified point of
    /// the shape, so a partly hidden light gives a penumbra (FIG. 22). Always shadows.
    /// The light itself is invisible to camera rays (put an object there to see it, and link
    /// that object to the light with `Object::area_light` so that it does not shadow it).
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
        /// Flat shapes emit only toward the side their normal points to (a rectangle's
        /// `edge_u x edge_v`, a disk's `normal`, a polygon's normal by the right-hand rule
        /// around its points), as RenderMan's `arealight` does; spheres ignore it. `false`:
        /// both sides.
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        one_sided: bool,
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
    /// A planar convex polygon through `points` (in order around it), emitting to both
    /// sides: general quadrilaterals and the polygons of RIB area lights.
    Polygon {
        /// The corners, 3 or more, in order around the polygon.
        points: Vec<V3>,
    },
}

impl AreaShape {
    /// Why `points` cannot be the corners of a [`AreaShape::Polygon`], if they cannot: fewer
    /// than 3, not finite, no area, not planar (a corner farther than `1e-4` of the polygon's
    /// size from the plane through the centroid with the Newell normal) or not convex (two
    /// turns of opposite sense about that normal; straight corners are allowed).
    pub fn polygon_flaw(points: &[V3]) -> Option<String> {
        if points.len() < 3 {
            return Some(format!("needs at least 3 points, got {}", points.len()));
        }
        if points.iter().flatten().any(|c| !c.is_finite()) {
            return Some("the points must be finite".into());
        }
        let p: Vec<glam::DVec3> =
            points.iter().map(|q| glam::DVec3::from(q.map(f64::from))).collect();
        let n = p.len();
        let normal: glam::DVec3 = (0..n).map(|i| p[i].cross(p[(i + 1) % n])).sum();
        let size = (0..n).map(|i| (p[i] - p[0]).length()).fold(0.0, f64::max);
        if normal.length() <= 1e-12 * size * size || size == 0.0 {
            return Some("the polygon has no area".into());
        }
        let u = normal.normalize();
        let centroid = p.iter().sum::<glam::DVec3>() / n as f64;
        if p.iter().any(|q| u.dot(*q - centroid).abs() > 1e-4 * size) {
            return Some("the polygon is not planar".into());
        }
        let turns = (0..n).map(|i| {
            let (a, b, c) = (p[i], p[(i + 1) % n], p[(i + 2) % n]);
            u.dot((b - a).cross(c - b))
        });
        if turns.into_iter().any(|t| t < -1e-9 * size * size) {
            return Some("the polygon is not convex".into());
        }
        None
    }
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

fn default_cone_angle() -> f32 {
    30.0
}
fn default_cone_delta() -> f32 {
    5.0
}
fn default_beam_distribution() -> f32 {
    2.0
}
