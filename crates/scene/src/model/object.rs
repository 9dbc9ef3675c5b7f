//! Geometric objects: [`Object`] with its traced reflection and refraction, procedural
//! pattern, rolling, colour interpolation and motion keys.
//!
//! Invariant: [`Object::new`] and its builder methods give exactly what parsing gives when
//! the fields they leave out are absent from the RON text.

use serde::{Deserialize, Serialize};

use super::{Bump, Displacement, Maps, Material, Rgb, Shape, Transform, V3, default_up, white};

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
    /// RenderMan's `ShadingRate` as an attribute of this object: target micropolygon area in
    /// pixels (> 0) for its split and dice decisions. `None`: the scene's `hider.shading_rate`.
    #[serde(default)]
    pub shading_rate: Option<f32>,
    /// RenderMan's `Sides 1`: the object is one-sided, its back faces (where the eye sees
    /// the side its normals point away from) are not drawn, whether it is closed or not
    /// (pinhole cameras only; not for CSG operands or displaced objects). `false`: RenderMan's
    /// default `Sides 2`.
    #[serde(default)]
    pub one_sided: bool,
    /// RenderMan's `GeometricApproximation "flatness"` as an attribute of this object: the
    /// geometric accuracy in pixels (>= 0) of its dicing. `None`: the scene's
    /// `hider.flatness`.
    #[serde(default)]
    pub flatness: Option<f32>,
    /// RenderMan's `GeometricApproximation "motionfactor"` as an attribute of this object
    /// (>= 0; 0 is off): coarser dicing in proportion to its motion blur in pixels. `None`:
    /// the scene's `hider.motion_factor`.
    #[serde(default)]
    pub motion_factor: Option<f32>,
    /// RenderMan's `GeometricApproximation "focusfactor"` as an attribute of this object
    /// (>= 0; 0 is off): coarser dicing in proportion to its depth-of-field blur in pixels.
    /// `None`: the scene's `hider.focus_factor`.
    #[serde(default)]
    pub focus_factor: Option<f32>,
    /// The lights that illuminate this object (RenderMan's `Illuminate` and attribute-scoped
    /// lights): indices into `Scene::lights`, each at most once, ambient lights included.
    /// `None`: every light of the scene.
    #[serde(default)]
    pub lights: Option<Vec<u32>>,
    /// Texture maps modulating the material's colour, opacity, roughness and specular
    /// coefficient (docs/lookdev.md).
    #[serde(default, skip_serializing_if = "Maps::is_empty")]
    pub maps: Maps,
    /// True micropolygon displacement.
    #[serde(default)]
    pub displacement: Option<Displacement>,
    /// Bump mapping (normals only).
    #[serde(default)]
    pub bump: Option<Bump>,
    /// Light the surface emits (linear RGB, each channel >= 0 and unbounded): added to its
    /// shaded colour, premultiplied by its opacity, whatever the lights. A lamp card glows
    /// with `emission: (4.0, 3.5, 2.5)`; values above 1 reach an EXR unclamped.
    #[serde(default)]
    pub emission: Option<Rgb>,
    /// The object is the visible surface of the area light `Scene::lights[i]` (which must be
    /// an `Area` light): shadow rays toward that light pass through it, so the emitter does
    /// not shadow its own light; it still shadows every other light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area_light: Option<u32>,
    /// Shading-language surface, displacement and atmosphere shaders (a RIB scene's; not in
    /// RON): when set they shade the object instead of `material`.
    #[serde(skip)]
    pub shaders: Option<std::sync::Arc<super::ObjectShaders>>,
}

impl Object {
    /// An object of `shape` and `material` with every other field at the value parsing
    /// gives when it is absent: no name, no transform, not a matte, no motion or deformation,
    /// `Flat` interpolation, no glass, reflection, refraction, pattern or roll, the scene's
    /// shading rate and every light.
    ///
    /// ```
    /// use reyes_scene::{Material, Object, Shape, Transform};
    ///
    /// let ball = Object::new(
    ///     Shape::Sphere { radius: 1.0, zmin: None, zmax: None, thetamax: 360.0 },
    ///     Material::Constant { color: [1.0, 0.0, 0.0], opacity: [1.0; 3] },
    /// )
    /// .named("ball")
    /// .with_transform(vec![Transform::Translate([0.0, 1.0, 0.0])]);
    /// assert_eq!(ball.name, "ball");
    /// assert!(ball.motion.is_empty() && ball.roll.is_none());
    /// ```
    pub fn new(shape: Shape, material: Material) -> Object {
        Object {
            name: String::new(),
            shape,
            transform: Vec::new(),
            material,
            matte: false,
            motion: Vec::new(),
            deform: Vec::new(),
            interpolation: Interpolation::default(),
            glass: None,
            reflect: None,
            refract: None,
            pattern: None,
            roll: None,
            shading_rate: None,
            one_sided: false,
            flatness: None,
            motion_factor: None,
            focus_factor: None,
            lights: None,
            maps: Maps::default(),
            displacement: None,
            bump: None,
            emission: None,
            area_light: None,
            shaders: None,
        }
    }

    /// Whether `light` (an index into `Scene::lights`) illuminates this object: always
    /// without a light set, else when the set lists it.
    pub fn lit_by(&self, light: usize) -> bool {
        self.lights.as_ref().is_none_or(|set| set.iter().any(|&i| i as usize == light))
    }

    /// The object's shading rate: its own, or `scene_rate` (the scene's `hider.shading_rate`).
    pub fn shading_rate_or(&self, scene_rate: f32) -> f32 {
        self.shading_rate.unwrap_or(scene_rate)
    }

    /// The same object named `name` (the name CSG leaves and messages use).
    #[must_use]
    pub fn named(mut self, name: impl Into<String>) -> Object {
        self.name = name.into();
        self
    }

    /// The same object with the object-to-world `transform` list (applied first item first).
    #[must_use]
    pub fn with_transform(mut self, transform: Vec<Transform>) -> Object {
        self.transform = transform;
        self
    }

    /// The same object with transform motion keys (which replace `transform` when rendered).
    #[must_use]
    pub fn with_motion(mut self, motion: Vec<TransformKey>) -> Object {
        self.motion = motion;
        self
    }

    /// The same object with deformation keys (which replace the shape's points when rendered).
    #[must_use]
    pub fn with_deform(mut self, deform: Vec<PointsKey>) -> Object {
        self.deform = deform;
        self
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere() -> Shape {
        Shape::Sphere { radius: 1.0, zmin: None, zmax: None, thetamax: 360.0 }
    }

    fn matte() -> Material {
        Material::Matte { color: [0.5, 0.5, 0.5], opacity: [1.0, 1.0, 1.0], ka: 1.0, kd: 1.0 }
    }

    /// `Object::new` is what the serde defaults give for a minimal object.
    #[test]
    fn new_is_a_minimal_parsed_object() {
        let parsed: Object =
            ron::from_str("(shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)))")
                .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(Object::new(sphere(), matte()), parsed);
    }

    /// Each builder sets its one field, as writing that field in RON does.
    #[test]
    fn builders_set_their_field() {
        let parsed: Object = ron::from_str(
            r#"(name: "ball", shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)),
                transform: [Scale((2.0, 2.0, 2.0))],
                motion: [(time: 0.0, transform: []), (time: 1.0, transform: [])],
                deform: [(time: 0.0, points: [])])"#,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let built = Object::new(sphere(), matte())
            .named("ball")
            .with_transform(vec![Transform::Scale([2.0, 2.0, 2.0])])
            .with_motion(vec![
                TransformKey { time: 0.0, transform: vec![] },
                TransformKey { time: 1.0, transform: vec![] },
            ])
            .with_deform(vec![PointsKey { time: 0.0, points: vec![] }]);
        assert_eq!(built, parsed);
    }
}
