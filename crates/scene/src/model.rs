//! The scene model: plain serde types mirroring the RON file field by field.
//!
//! Invariant: a `Scene` returned by [`crate::load`] or [`crate::parse`] has passed
//! validation, so every later stage may assume finite numbers and in-range values.
//! Vectors are `[f32; 3]`, written in RON as tuples `(x, y, z)`. Angles are in degrees.
//! World space is left-handed like RenderMan's: with the camera looking down +z and +y up,
//! +x is to the right.

use serde::{Deserialize, Serialize};

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
}

/// Distributed ray tracing (patent FIGS. 19-22, Appendix B): limits and cost.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RayTrace {
    /// Deepest chain of secondary rays (reflection and refraction bounces) followed from a
    /// shaded point; at least 1 when any object reflects or refracts.
    pub max_depth: u32,
    /// A secondary ray whose weight (the product of the reflection or transmission colours
    /// along its path, largest channel) falls below this is not traced.
    pub min_weight: f32,
    /// Rays per effect (each shadowing light, glossy reflection, refraction) per grid
    /// vertex when the stochastic hider shades vertices (>= 1).
    pub vertex_rays: u32,
}

impl Default for RayTrace {
    fn default() -> Self {
        RayTrace { max_depth: 4, min_weight: 0.01, vertex_rays: 1 }
    }
}

/// One CSG solid (Appendix A's CSG tree).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Solid {
    /// Name, for messages.
    #[serde(default)]
    pub name: String,
    /// The expression.
    pub tree: Csg,
}

/// A CSG expression. Operands must be closed: full spheres and tori, cylinders, cones and
/// paraboloids (closed by their end caps when used here), closed meshes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Csg {
    /// A closed object, by name.
    Object(String),
    /// Everything inside any operand (two or more).
    Union(Vec<Csg>),
    /// Everything inside every operand (two or more).
    Intersection(Vec<Csg>),
    /// Inside the first operand and outside the second.
    Difference(Box<Csg>, Box<Csg>),
}

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

fn default_up() -> V3 {
    [0.0, 1.0, 0.0]
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

/// Sampling, filtering and bucketing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Hider {
    /// Which visibility algorithm renders the frame.
    pub method: HiderMethod,
    /// Samples per pixel as (nx, ny): NS = nx * ny strata per pixel.
    pub pixel_samples: (u32, u32),
    /// Appendix A's `jitter on/off`. `false` is the regular grid of FIG. 3 and overrides `pattern`.
    pub jitter: bool,
    /// Which jittered spatial pattern (FIGS. 5-7) to use when `jitter` is on.
    pub pattern: SpatialPattern,
    /// How each sample's time is chosen within its time stratum (FIGS. 13-15).
    pub time_pattern: TimePattern,
    /// Reconstruction filter.
    pub filter: Filter,
    /// Bucket size in pixels (x, y).
    pub bucket_size: (u32, u32),
    /// Target micropolygon area in pixels (> 0).
    pub shading_rate: f32,
    /// Seed of every pseudo-random choice.
    pub seed: u64,
    /// Largest number of micropolygons in one diced grid; bigger primitives are split.
    pub max_grid_size: u32,
    /// Drop back-facing micropolygons of closed, opaque objects (RenderMan's `Sides 1`;
    /// pinhole cameras only): about half the micropolygons and sample tests of a scene of
    /// balls. Off by default, because the back faces also fill the cracks between grids
    /// diced at different rates: without them a few silhouette and crack pixels lose
    /// coverage (on `scenes/bench/balls.ron` 1045 pixels change, by at most 0.08).
    pub cull_back_faces: bool,
    /// Switches that reproduce the original 1985 behaviour where it differs from ours.
    pub original: Original,
}

impl Default for Hider {
    fn default() -> Self {
        Hider {
            method: HiderMethod::default(),
            pixel_samples: (4, 4),
            jitter: true,
            pattern: SpatialPattern::default(),
            time_pattern: TimePattern::default(),
            filter: Filter::default(),
            bucket_size: (16, 16),
            shading_rate: 1.0,
            seed: 0,
            max_grid_size: 256,
            cull_back_faces: false,
            original: Original::default(),
        }
    }
}

/// The visibility algorithm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum HiderMethod {
    /// Appendix A: dice into micropolygons, shade the vertices, point-sample the micropolygons.
    #[default]
    Stochastic,
    /// Appendix B: trace a primary ray per sample (same positions, times, lens positions and
    /// filter) and shade where it hits, with the distributed rays of the materials and lights.
    RayTrace,
}

/// Jittered spatial sampling patterns of the patent (FIG. 3 is `jitter: false`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum SpatialPattern {
    /// FIG. 5: one jittered pattern (one point anywhere in each cell), repeated in every pixel.
    Fig5,
    /// FIG. 6: each cell's point anywhere in the cell, new in every pixel (Appendix A's jitter).
    #[default]
    Fig6,
    /// FIG. 7: a FIG. 5 reference pattern plus a bounded random offset in every pixel.
    Fig7,
    /// Pure random: every sample uniform anywhere in its pixel, no stratification.
    Random,
    /// Owen-scrambled Sobol (0,2) per pixel; needs power-of-two `pixel_samples`, else `Fig6`.
    Sobol,
}

/// Temporal patterns of the patent (FIGS. 13-15), the counterparts in time of FIGS. 5-7.
/// With `jitter: false` every sample takes its time stratum's centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum TimePattern {
    /// FIG. 13: one pseudo-random time per stratum, the same in every pixel.
    Fig13,
    /// FIG. 14: a new pseudo-random time anywhere in the stratum for every pixel (Appendix A).
    #[default]
    Fig14,
    /// FIG. 15: a FIG. 13 reference time plus a pseudo-random shift of at most a quarter stratum.
    Fig15,
}

/// Reconstruction filter (`VisFilter`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Filter {
    /// Kernel.
    pub kind: FilterKind,
    /// Full width in pixels (> 0).
    pub width: f32,
}

impl Default for Filter {
    fn default() -> Self {
        Filter { kind: FilterKind::Gaussian, width: 2.0 }
    }
}

/// The five filter kernels of Appendix A.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FilterKind {
    /// Box.
    Box,
    /// Truncated Gaussian `exp(-r^2) - exp(-(w/2)^2)`.
    Gaussian,
    /// Separable sinc, truncated to the footprint.
    Sinc,
    /// Separable tent.
    Bartlett,
    /// Jinc `J1(2r)/r`, truncated to the footprint.
    Bessel,
}

/// Reproduce the original Appendix A behaviour where we deliberately differ
/// (see docs/appendix-a.md). All `false` by default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Original {
    /// Use the original `permute`, which is not a permutation for some NS (3.4).
    pub permute: bool,
    /// Five 512-entry jitter tables laid out back to back, read past their ends as the C did (3.2).
    pub jitter_tables: bool,
    /// Box kernel cut on signed offsets at the full width (3.16).
    pub box_filter: bool,
    /// Bartlett kernel with the full width as half-width (3.16).
    pub bartlett_filter: bool,
    /// Sinc kernel centre value 1 instead of its limit 2 (2.3).
    pub sinc_filter: bool,
    /// CSG operands compared by depth-range minima, as Appendix A's `csg_resolve_surface`
    /// did, instead of exact depths (3.15).
    pub csg_order: bool,
    /// Matte and opacity of a sample taken from the deepest composited surface, so a matte
    /// behind a transparent surface drops the whole sample (3.14).
    pub matte: bool,
    /// Sample s has time stratum s in every pixel, tying time to sub-pixel position (3.3).
    pub time_pairing: bool,
    /// The square, uncentred lens of the original (the "kludge", 3.8), with lens position
    /// tied to screen position.
    pub lens: bool,
    /// Moving micropolygons that straddle hither or yon at a sample's time are rejected for
    /// that sample instead of clipped (3.6).
    pub moving_clip: bool,
}

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

pub(crate) fn white() -> Rgb {
    [1.0, 1.0, 1.0]
}
pub(crate) fn one() -> f32 {
    1.0
}
fn deg360() -> f32 {
    360.0
}

/// A geometric object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    /// Name, for messages (and later for `measure` and CSG).
    #[serde(default)]
    pub name: String,
    /// The surface.
    pub shape: Shape,
    /// Object-to-world transforms, applied to the object in list order (first item first).
    #[serde(default)]
    pub transform: Vec<Transform>,
    /// Surface material.
    pub material: Material,
    /// Appendix A matte: hides what is behind, contributes no colour and no alpha.
    #[serde(default)]
    pub matte: bool,
    /// Transform motion: the object's transform at two or more times within the shutter, in
    /// increasing time order. When given, replaces `transform`. Each vertex moves linearly
    /// between keys (piecewise-linear motion), and is held before the first and after the last.
    #[serde(default)]
    pub motion: Vec<TransformKey>,
    /// Deformation motion of a `Mesh` or `BilinearPatch`: the shape's points at two or more
    /// times within the shutter, in increasing time order, each key with as many points as the
    /// shape. When given, replaces the shape's own points.
    #[serde(default)]
    pub deform: Vec<PointsKey>,
    /// How colour varies across a micropolygon: `Flat` uses its first vertex's colour
    /// (Appendix A without GOURAUD), `Gouraud` interpolates the vertex colours at each sample
    /// (Appendix A `gouraud`).
    #[serde(default)]
    pub interpolation: Interpolation,
    /// Appendix A's `glasshack`: when `Some(a)`, everything composited up to and including
    /// this surface is tinted by the colour of the surface directly behind it,
    /// `C *= a + (1 - a) * c_behind` (a in [0, 1]; 1 is no tint).
    #[serde(default)]
    pub glass: Option<f32>,
    /// Reflection by traced rays (FIGS. 19-20): mirror or glossy.
    #[serde(default)]
    pub reflect: Option<Reflect>,
    /// Refraction by traced rays (FIG. 21): clear or blurry translucency.
    #[serde(default)]
    pub refract: Option<Refract>,
    /// A procedural texture replacing the material colour.
    #[serde(default)]
    pub pattern: Option<Pattern>,
    /// Appendix B's rolling: the object is a ball rolling without slipping along `path`;
    /// expanded at load time into `motion` keys. Excludes `motion`.
    #[serde(default)]
    pub roll: Option<Roll>,
}

/// Traced reflection, added to the shaded colour.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Reflect {
    /// Reflectivity per channel (in [0, 1]): weight of the reflected ray's colour.
    pub color: Rgb,
    /// Gloss: half-angle in degrees of the cone around the mirror direction from which each
    /// sample's reflection direction is chosen (Appendix B's `disperseray`); 0 is a mirror.
    #[serde(default)]
    pub gloss: f32,
}

/// Traced refraction, added to the shaded colour.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Refract {
    /// Index of refraction of the object's inside relative to the outside (> 0).
    pub ior: f32,
    /// Transmission per channel (in [0, 1]): weight of the refracted ray's colour.
    #[serde(default = "white")]
    pub color: Rgb,
    /// Blur: half-angle in degrees of the cone around the Snell direction from which each
    /// sample's refraction direction is chosen; 0 is clear glass.
    #[serde(default)]
    pub blur: f32,
}

/// Procedural textures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Pattern {
    /// Appendix B's pool ball, around the object's z axis (its pole): a coloured band
    /// `|z| < 0.4722 r` (striped balls) or colour everywhere (solid balls), a dark ring
    /// `0.85 r <= |z| < 0.9 r` and an ivory number disk `|z| >= 0.9 r` at each pole.
    PoolBall {
        /// The ball's colour.
        color: Rgb,
        /// Striped (colour in the band only, ivory elsewhere) or solid.
        #[serde(default)]
        striped: bool,
    },
}

/// A ball rolling without slipping on a plane (Appendix B's `h` command and `spinangle`).
///
/// `load`/`parse` expand it into the object's `motion` keys and keep it (so error paths and a
/// written-back scene stay meaningful); the engines read only `motion`. For each path segment
/// from `p_a` to `p_b` over `[t_a, t_b]` there are `steps` keys, at `t_a + (t_b - t_a) j /
/// steps`; each key's transform list is the object's `transform` (its rest orientation,
/// applied first and required to keep the object's origin, the ball's centre, in place), then
/// the turns of the finished segments composed into one `Rotate`, then the current segment's
/// turn so far, `Rotate(angle: distance so far / radius in degrees, axis: up x (p_b - p_a))`,
/// then `Translate(centre)`. That turn keeps the contact point `centre - radius * up`
/// instantaneously at rest. The path must lie in a plane normal to `up` (a displacement along
/// `up` is an error, not silently ignored), and no step may turn the ball more than 45 degrees,
/// since vertices move on chords between keys.
///
/// Differences from Appendix B (its note 3.8): the original composed the orientation `M`
/// first and the rolls in chronological order when mapping a hit point back to the rest
/// frame, which is right only when `M` commutes with the rolls; here the rolls act after the
/// rest orientation, each later turn after the earlier ones, about world-fixed axes through
/// the centre, which is the order of the motion itself. The original's roll axis
/// `(v_y, -v_x, v_z)` is horizontal and across the motion only for motion in a z = const
/// plane with z up; here the axis is `up x direction of travel` for any plane. Its sign is
/// fixed by the no-slip condition rather than by a lost `MR1`/`MR2` construction. `roll`
/// excludes hand-written `motion`; it may be combined with `deform`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Roll {
    /// Ball radius (> 0): turning angle = distance travelled / radius.
    pub radius: f32,
    /// Normal of the plane it rolls on (non-zero).
    #[serde(default = "default_up")]
    pub up: V3,
    /// Positions of the ball's centre at two or more times within the shutter, in
    /// increasing time order; straight between them.
    pub path: Vec<RollKey>,
    /// Transform keys generated per path segment (1..=1024, and enough that no step turns
    /// the ball more than 45 degrees): rotation keys are interpolated linearly, so more keys
    /// follow the rotation more closely.
    #[serde(default = "default_roll_steps")]
    pub steps: u32,
}

/// A rolling ball's centre at one time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RollKey {
    /// Scene time, within the shutter.
    pub time: f32,
    /// Centre.
    pub position: V3,
}

fn default_roll_steps() -> u32 {
    8
}

/// Colour interpolation across a micropolygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Interpolation {
    /// One colour per micropolygon.
    #[default]
    Flat,
    /// Shepard interpolation of the four vertex colours at the sample.
    Gouraud,
}

/// An object's transform at one time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransformKey {
    /// Scene time, within the shutter.
    pub time: f32,
    /// Object-to-world transforms at that time, applied in list order.
    pub transform: Vec<Transform>,
}

/// A deforming shape's points at one time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointsKey {
    /// Scene time, within the shutter.
    pub time: f32,
    /// The shape's points at that time (same count and order as the shape's `points`).
    pub points: Vec<V3>,
}

/// Shapes. Quadrics follow RenderMan: they sweep around the object's z axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Shape {
    /// Sphere of `radius`, cut to `zmin..zmax`, swept through `thetamax` degrees.
    Sphere {
        /// Radius (> 0).
        radius: f32,
        /// Lower cut (default `-radius`).
        #[serde(default)]
        zmin: Option<f32>,
        /// Upper cut (default `radius`).
        #[serde(default)]
        zmax: Option<f32>,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Open cylinder of `radius` from `zmin` to `zmax`.
    Cylinder {
        /// Radius (> 0).
        radius: f32,
        /// Bottom.
        zmin: f32,
        /// Top (> zmin).
        zmax: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Cone with base of `radius` at z = 0 and apex at z = `height`.
    Cone {
        /// Height (!= 0).
        height: f32,
        /// Base radius (> 0).
        radius: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Disk of `radius` in the plane z = `height`, facing +z.
    Disk {
        /// Plane offset.
        #[serde(default)]
        height: f32,
        /// Radius (> 0).
        radius: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Torus around the z axis.
    Torus {
        /// Distance from the z axis to the tube centre (> 0).
        major_radius: f32,
        /// Tube radius (> 0).
        minor_radius: f32,
        /// Start of the tube angle, degrees.
        #[serde(default)]
        phimin: f32,
        /// End of the tube angle, degrees (> phimin, at most phimin + 360).
        #[serde(default = "deg360")]
        phimax: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// RenderMan paraboloid: radius `rmax` at `zmax`, `r = rmax * sqrt(z / zmax)`, cut to
    /// `zmin..zmax`.
    Paraboloid {
        /// Radius at `zmax` (> 0).
        rmax: f32,
        /// Lower cut (>= 0).
        #[serde(default)]
        zmin: f32,
        /// Top (> zmin).
        zmax: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Bilinear patch. Corners in RenderMan order: (u,v) = (0,0), (1,0), (0,1), (1,1).
    BilinearPatch {
        /// The four corners.
        points: [V3; 4],
    },
    /// Polygon mesh of triangles and quads (planar or not).
    Mesh {
        /// Vertex positions.
        points: Vec<V3>,
        /// Faces: 3 or 4 indices into `points`, in order around the face.
        faces: Vec<Vec<u32>>,
        /// Optional per-vertex colours (same length as `points`), multiplying the material colour.
        #[serde(default)]
        colors: Option<Vec<Rgb>>,
    },
}

/// One step of an object's transform.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Transform {
    /// Move by a vector.
    Translate(V3),
    /// Rotate by `angle` degrees about `axis` (right-hand rule in a left-handed world, as RenderMan).
    Rotate {
        /// Degrees.
        angle: f32,
        /// Axis (non-zero).
        axis: V3,
    },
    /// Scale per axis (no zero factor).
    Scale(V3),
    /// A 4x4 matrix, rows written top to bottom, acting on column vectors `(x, y, z, 1)`.
    Matrix([[f32; 4]; 4]),
}

/// Surface materials. Colours and opacities are per channel in [0, 1].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Material {
    /// Unlit colour.
    Constant {
        /// Colour.
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
        /// Specular roughness (> 0): exponent is `1 / roughness`.
        #[serde(default = "tenth")]
        roughness: f32,
        /// Specular colour.
        #[serde(default = "white")]
        specular_color: Rgb,
    },
}

fn half() -> f32 {
    0.5
}
fn tenth() -> f32 {
    0.1
}
