//! Semantic validation of a deserialised [`Scene`]: ranges, finiteness and consistency.
//!
//! Invariants: checks run in a fixed order (image, camera, hider, lights, objects, solids,
//! raytrace, each in field order) and stop at the first failure, so the reported error is stable; each failure
//! names the path of the offending value as the source map spells it (`objects[0].shape.radius`).
//! Every `f32` is checked finite before any range test on it. No check can panic: geometric
//! tests are done in `f64`, where products of finite `f32`s cannot overflow.
//!
//! Solids are checked after every object, so an operand's own shape is already valid when its
//! closure is judged. Within a solid: an operator at the root, the number of leaves, then the
//! tree in pre-order (an operator's operand count before its operands, operands left to right;
//! a leaf's name, then its earlier uses, then its closure). Paths into a tree follow the source map: variant names are transparent and
//! operands are indexed, `solids[0].tree[1][0]` is the first operand of the second operand.
//!
//! Motion keys (`camera.motion`, `objects[i].motion`, `objects[i].deform`) are checked after
//! the still values they replace, key by key: the list length first, then each key's time
//! (finite, inside the shutter, after the previous key's), then the key's contents. Area light
//! motion (`lights[i].motion`) and a rolling ball's path (`objects[i].roll.path`) follow the
//! same rules.
//!
//! Rules that tie two places together are reported at the value that breaks them: the
//! ray-tracing hider with solids at `hider.method`, a zero depth limit with reflecting or
//! refracting objects at `raytrace.max_depth`, a `roll` with hand-written `motion` at
//! `objects[i].roll`, a rest transform that moves a rolling ball's centre at that transform.

use std::collections::HashMap;

use glam::{DMat4, DVec3, DVec4};

use crate::closure::{Closure, closure};
use crate::error::clip;
use crate::model::{
    AreaShape, Camera, Csg, Hider, HiderMethod, Image, Light, Material, Object, Pattern, RayTrace,
    Rgb, Roll, Scene, Shape, Shutter, ShutterShape, Transform, V3,
};
use crate::roll;

/// Most solids in a scene: the renderer numbers CSG trees with `u16`.
pub(crate) const MAX_SOLIDS: usize = 65535;
/// Most leaves (objects) in one solid. The renderer's trees are binary and give every node
/// but the root a `u16` slot id in 1..=65535; a solid of `n` leaves has `2n - 2` slots.
pub(crate) const MAX_LEAVES: usize = 32768;

/// A validation failure: the path of the value at fault and what is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Issue {
    pub path: String,
    pub message: String,
}

type Check = Result<(), Issue>;

/// Object name -> the first object with it, and the second if any.
type Names<'a> = HashMap<&'a str, (usize, Option<usize>)>;
/// Object index -> the solid and the path of the leaf that uses it.
type Used = HashMap<usize, (usize, String)>;

fn fail(path: impl Into<String>, message: impl Into<String>) -> Check {
    Err(Issue { path: path.into(), message: message.into() })
}

/// The first rule `scene` breaks, if any.
pub(crate) fn check(scene: &Scene) -> Option<Issue> {
    check_scene(scene).err()
}

fn check_scene(scene: &Scene) -> Check {
    image(&scene.image)?;
    camera(&scene.camera)?;
    hider(&scene.hider, scene)?;
    let shutter = &scene.camera.shutter;
    for (i, light) in scene.lights.iter().enumerate() {
        self::light(&format!("lights[{i}]"), light, shutter)?;
    }
    for (i, object) in scene.objects.iter().enumerate() {
        self::object(&format!("objects[{i}]"), object, shutter)?;
    }
    solids(scene)?;
    raytrace(&scene.raytrace, scene)
}

/// Most `raytrace.max_depth`: deeper chains of mirror bounces add nothing visible.
pub(crate) const MAX_DEPTH: u32 = 64;
/// Most `raytrace.vertex_rays`.
pub(crate) const MAX_VERTEX_RAYS: u32 = 4096;
/// Gloss and blur cone half-angles must be below this, in degrees.
const MAX_SPREAD: f32 = 90.0;

/// `value` must be finite.
fn finite(path: &str, value: f32) -> Check {
    if value.is_finite() { Ok(()) } else { fail(path, format!("must be finite, got {value}")) }
}

/// Every component finite.
fn finite_all(path: &str, values: &[f32]) -> Check {
    for (i, v) in values.iter().enumerate() {
        finite(&format!("{path}[{i}]"), *v)?;
    }
    Ok(())
}

/// Finite and `> 0`.
fn positive(path: &str, value: f32) -> Check {
    finite(path, value)?;
    if value > 0.0 { Ok(()) } else { fail(path, format!("must be > 0, got {value}")) }
}

/// Finite and `>= 0`.
fn non_negative(path: &str, value: f32) -> Check {
    finite(path, value)?;
    if value >= 0.0 { Ok(()) } else { fail(path, format!("must be >= 0, got {value}")) }
}

/// Integer in `lo..=hi`.
fn int_in(path: &str, value: u32, lo: u32, hi: u32) -> Check {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        fail(path, format!("must be in {lo}..={hi}, got {value}"))
    }
}

/// A cone half-angle (gloss, blur) in `[0, 90)` degrees.
fn spread(path: &str, degrees: f32) -> Check {
    finite(path, degrees)?;
    if (0.0..MAX_SPREAD).contains(&degrees) {
        Ok(())
    } else {
        fail(path, format!("must be in [0, 90) degrees, got {degrees}"))
    }
}

/// Every component finite, and not all zero.
fn nonzero_vector(path: &str, v: &V3) -> Check {
    finite_all(path, v)?;
    if v.iter().all(|&a| a == 0.0) {
        return fail(path, "must be non-zero");
    }
    Ok(())
}

/// A sweep angle in `(0, 360]` degrees.
fn sweep(path: &str, degrees: f32) -> Check {
    finite(path, degrees)?;
    if degrees > 0.0 && degrees <= 360.0 {
        Ok(())
    } else {
        fail(path, format!("must be in (0, 360] degrees, got {degrees}"))
    }
}

/// A colour or opacity: every channel finite and in `[0, 1]`.
fn unit_rgb(path: &str, rgb: &Rgb) -> Check {
    for (i, v) in rgb.iter().enumerate() {
        let p = format!("{path}[{i}]");
        finite(&p, *v)?;
        if !(0.0..=1.0).contains(v) {
            return fail(p, format!("must be in [0, 1], got {v}"));
        }
    }
    Ok(())
}

fn dvec(v: &V3) -> DVec3 {
    DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))
}

fn image(image: &Image) -> Check {
    int_in("image.width", image.width, 1, 65536)?;
    int_in("image.height", image.height, 1, 65536)
}

fn camera(cam: &Camera) -> Check {
    finite_all("camera.eye", &cam.eye)?;
    finite_all("camera.look_at", &cam.look_at)?;
    finite_all("camera.up", &cam.up)?;
    finite("camera.fov", cam.fov)?;
    if !(cam.fov > 0.0 && cam.fov < 180.0) {
        return fail("camera.fov", format!("must be in (0, 180) degrees, got {}", cam.fov));
    }
    positive("camera.hither", cam.hither)?;
    finite("camera.yon", cam.yon)?;
    if cam.yon <= cam.hither {
        return fail("camera.yon", format!("must be > hither ({}), got {}", cam.hither, cam.yon));
    }
    orientation("camera", &cam.eye, &cam.look_at, &cam.up)?;
    finite("camera.shutter.open", cam.shutter.open)?;
    finite("camera.shutter.close", cam.shutter.close)?;
    if cam.shutter.close < cam.shutter.open {
        return fail(
            "camera.shutter.close",
            format!("must be >= shutter.open ({}), got {}", cam.shutter.open, cam.shutter.close),
        );
    }
    if let ShutterShape::Gradual { ramp } = cam.shutter.shape {
        finite("camera.shutter.shape.ramp", ramp)?;
        if !(ramp > 0.0 && ramp <= 0.5) {
            return fail("camera.shutter.shape.ramp", format!("must be in (0, 0.5], got {ramp}"));
        }
    }
    if let Some(lens) = &cam.lens {
        positive("camera.lens.focal_length", lens.focal_length)?;
        positive("camera.lens.f_stop", lens.f_stop)?;
        positive("camera.lens.focal_distance", lens.focal_distance)?;
    }
    keys(
        "camera.motion",
        &cam.motion,
        |k| k.time,
        &cam.shutter,
        |i, key| {
            let at = format!("camera.motion[{i}]");
            finite_all(&format!("{at}.eye"), &key.eye)?;
            finite_all(&format!("{at}.look_at"), &key.look_at)?;
            finite_all(&format!("{at}.up"), &key.up)?;
            orientation(&at, &key.eye, &key.look_at, &key.up)
        },
    )
}

/// The camera rules on `eye`, `look_at` and `up` (all finite), reported under `at`.
fn orientation(at: &str, eye: &V3, look_at: &V3, up: &V3) -> Check {
    if eye == look_at {
        return fail(format!("{at}.look_at"), "must differ from eye");
    }
    let view = dvec(look_at) - dvec(eye);
    let up = dvec(up);
    if up == DVec3::ZERO {
        return fail(format!("{at}.up"), "must be non-zero");
    }
    if up.cross(view).length() <= 1e-6 * up.length() * view.length() {
        return fail(
            format!("{at}.up"),
            "must not be parallel to the view direction (look_at - eye)",
        );
    }
    Ok(())
}

/// The rules every list of motion keys at `at` obeys: empty, or at least 2 keys; every
/// key's `time` finite and inside the (already valid) shutter; times strictly increasing,
/// unless the shutter is closed (`close == open`), when they all equal `open`.
/// `contents(i, key)` checks key `i`'s other fields, after its time.
fn keys<K>(
    at: &str,
    keys: &[K],
    time: impl Fn(&K) -> f32,
    shutter: &Shutter,
    mut contents: impl FnMut(usize, &K) -> Check,
) -> Check {
    if keys.len() == 1 {
        return fail(at, "motion needs at least 2 keys (or none), got 1");
    }
    let (open, close) = (shutter.open, shutter.close);
    let mut previous: Option<f32> = None;
    for (i, key) in keys.iter().enumerate() {
        let t = time(key);
        let path = format!("{at}[{i}].time");
        finite(&path, t)?;
        if t < open || t > close {
            return fail(
                path,
                format!("motion key time {t} is outside the shutter [{open}, {close}]"),
            );
        }
        if let Some(before) = previous
            && close > open
            && t <= before
        {
            return fail(
                path,
                format!("keys must be in increasing time order, got {t} after {before}"),
            );
        }
        previous = Some(t);
        contents(i, key)?;
    }
    Ok(())
}

fn hider(h: &Hider, scene: &Scene) -> Check {
    if h.method == HiderMethod::RayTrace && !scene.solids.is_empty() {
        return fail(
            "hider.method",
            "the ray-tracing hider does not evaluate CSG solids; use method: Stochastic",
        );
    }
    int_in("hider.pixel_samples[0]", h.pixel_samples.0, 1, 64)?;
    int_in("hider.pixel_samples[1]", h.pixel_samples.1, 1, 64)?;
    finite("hider.filter.width", h.filter.width)?;
    if !(h.filter.width > 0.0 && h.filter.width <= 16.0) {
        return fail(
            "hider.filter.width",
            format!("must be in (0, 16] pixels, got {}", h.filter.width),
        );
    }
    int_in("hider.bucket_size[0]", h.bucket_size.0, 1, 1024)?;
    int_in("hider.bucket_size[1]", h.bucket_size.1, 1, 1024)?;
    positive("hider.shading_rate", h.shading_rate)?;
    if h.max_grid_size < 1 {
        return fail("hider.max_grid_size", format!("must be >= 1, got {}", h.max_grid_size));
    }
    Ok(())
}

fn light(at: &str, light: &Light, shutter: &Shutter) -> Check {
    let (color, intensity) = match light {
        Light::Ambient { color, intensity } => (color, intensity),
        Light::Distant { from, to, color, intensity, .. } => {
            finite_all(&format!("{at}.from"), from)?;
            finite_all(&format!("{at}.to"), to)?;
            if from == to {
                return fail(format!("{at}.to"), "must differ from `from`");
            }
            (color, intensity)
        }
        Light::Point { from, color, intensity, .. } => {
            finite_all(&format!("{at}.from"), from)?;
            (color, intensity)
        }
        Light::Area { shape, color, intensity, .. } => {
            area_shape(&format!("{at}.shape"), shape)?;
            (color, intensity)
        }
    };
    for (i, v) in color.iter().enumerate() {
        non_negative(&format!("{at}.color[{i}]"), *v)?;
    }
    non_negative(&format!("{at}.intensity"), *intensity)?;
    if let Light::Area { motion, .. } = light {
        let at = format!("{at}.motion");
        keys(
            &at,
            motion,
            |k| k.time,
            shutter,
            |i, key| {
                finite_all(&format!("{at}[{i}].offset"), &key.offset)?;
                non_negative(&format!("{at}[{i}].intensity"), key.intensity)
            },
        )?;
    }
    Ok(())
}

/// The shape of an area light: finite; radii > 0; a disk's normal non-zero; a rectangle's
/// edges non-zero and not parallel.
fn area_shape(at: &str, shape: &AreaShape) -> Check {
    let field = |name: &str| format!("{at}.{name}");
    match shape {
        AreaShape::Sphere { center, radius } => {
            finite_all(&field("center"), center)?;
            positive(&field("radius"), *radius)
        }
        AreaShape::Disk { center, normal, radius } => {
            finite_all(&field("center"), center)?;
            nonzero_vector(&field("normal"), normal)?;
            positive(&field("radius"), *radius)
        }
        AreaShape::Rectangle { corner, edge_u, edge_v } => {
            finite_all(&field("corner"), corner)?;
            nonzero_vector(&field("edge_u"), edge_u)?;
            nonzero_vector(&field("edge_v"), edge_v)?;
            let (u, v) = (dvec(edge_u), dvec(edge_v));
            if u.cross(v).length() <= 1e-6 * u.length() * v.length() {
                return fail(field("edge_v"), "must not be parallel to edge_u");
            }
            Ok(())
        }
    }
}

fn object(at: &str, object: &Object, shutter: &Shutter) -> Check {
    shape(&format!("{at}.shape"), &object.shape)?;
    for (i, t) in object.transform.iter().enumerate() {
        transform(&format!("{at}.transform[{i}]"), t)?;
    }
    material(&format!("{at}.material"), &object.material)?;
    motion(&format!("{at}.motion"), object, shutter)?;
    deform(&format!("{at}.deform"), object, shutter)?;
    if let Some(a) = object.glass {
        let path = format!("{at}.glass");
        finite(&path, a)?;
        if !(0.0..=1.0).contains(&a) {
            return fail(path, format!("must be in [0, 1], got {a}"));
        }
    }
    if let Some(r) = &object.reflect {
        unit_rgb(&format!("{at}.reflect.color"), &r.color)?;
        spread(&format!("{at}.reflect.gloss"), r.gloss)?;
    }
    if let Some(r) = &object.refract {
        positive(&format!("{at}.refract.ior"), r.ior)?;
        unit_rgb(&format!("{at}.refract.color"), &r.color)?;
        spread(&format!("{at}.refract.blur"), r.blur)?;
    }
    if let Some(Pattern::PoolBall { color, .. }) = &object.pattern {
        unit_rgb(&format!("{at}.pattern.color"), color)?;
    }
    if let Some(r) = &object.roll {
        self::roll(at, r, object, shutter)?;
    }
    Ok(())
}

/// A rolling ball: radius > 0; `up` non-zero; a path of 2 or more keys by the motion key
/// rules, each position finite and (but for rounding) in the plane normal to `up` through the
/// previous one; `steps` in 1..=1024 and fine enough that no step turns the ball more than
/// [`roll::MAX_STEP_DEGREES`]; a bounded expansion; a rest transform that keeps the centre (the
/// object's origin) in place; no `motion` but the one the roll expands to.
fn roll(at: &str, r: &Roll, object: &Object, shutter: &Shutter) -> Check {
    let at = format!("{at}.roll");
    let field = |name: &str| format!("{at}.{name}");
    positive(&field("radius"), r.radius)?;
    nonzero_vector(&field("up"), &r.up)?;
    let up = roll::unit_up(r);
    let path = field("path");
    if r.path.len() < 2 {
        return fail(&path, format!("a roll needs at least 2 path keys, got {}", r.path.len()));
    }
    keys(
        &path,
        &r.path,
        |k| k.time,
        shutter,
        |i, key| {
            let here = format!("{path}[{i}].position");
            finite_all(&here, &key.position)?;
            let Some(before) = i.checked_sub(1).and_then(|b| r.path.get(b)) else {
                return Ok(());
            };
            let seg = roll::Segment::new(up, &before.position, &key.position);
            if seg.rise.abs() > roll::PLANE_TOLERANCE * seg.d.length() {
                return fail(
                    here,
                    format!(
                        "the ball must roll on a plane normal to roll.up, but its centre moves \
                         {} along up from path[{}]",
                        seg.rise as f32,
                        i - 1
                    ),
                );
            }
            Ok(())
        },
    )?;
    let steps = field("steps");
    int_in(&steps, r.steps, 1, roll::MAX_STEPS)?;
    let radius = f64::from(r.radius);
    for (i, pair) in r.path.windows(2).enumerate() {
        let [a, b] = pair else { continue };
        let turn =
            (roll::Segment::new(up, &a.position, &b.position).distance() / radius).to_degrees();
        if turn / f64::from(r.steps) > roll::MAX_STEP_DEGREES {
            let needed = (turn / roll::MAX_STEP_DEGREES).ceil();
            let advice = if needed <= f64::from(roll::MAX_STEPS) {
                format!("steps must be at least {needed}")
            } else {
                format!("more than {} steps would be needed: add path keys", roll::MAX_STEPS)
            };
            return fail(
                steps,
                format!(
                    "the ball turns {} degrees from path[{i}] to path[{}], more than {} degrees \
                     per step (steps {}); {advice}",
                    turn as f32,
                    i + 1,
                    roll::MAX_STEP_DEGREES,
                    r.steps
                ),
            );
        }
    }
    let count = roll::key_count(r);
    let transforms = count.saturating_mul(object.transform.len() + 3);
    if transforms > roll::MAX_TRANSFORMS {
        return fail(
            steps,
            format!(
                "the roll would generate {count} keys of up to {} transforms each, more than {} \
                 transforms in all: use fewer steps or path keys",
                object.transform.len() + 3,
                roll::MAX_TRANSFORMS
            ),
        );
    }
    for (j, t) in object.transform.iter().enumerate() {
        let moves = match t {
            Transform::Translate(v) => v.iter().any(|&x| x != 0.0),
            Transform::Matrix(rows) => rows.iter().take(3).any(|row| row[3] != 0.0),
            Transform::Rotate { .. } | Transform::Scale(_) => false,
        };
        if moves {
            return fail(
                format!("{}.transform[{j}]", parent(&at)),
                "with roll, the transform is the ball's rest orientation and must keep its \
                 centre (the object's origin) in place; roll.path places the ball",
            );
        }
    }
    if !object.motion.is_empty() && object.motion != roll::expand(r, &object.transform) {
        return fail(
            at,
            "an object cannot have both roll and motion: roll generates the motion keys; \
             remove one of them",
        );
    }
    Ok(())
}

/// `objects[0].roll` -> `objects[0]`.
fn parent(path: &str) -> &str {
    crate::locate::parent_path(path)
}

/// The ray-tracing limits: `max_depth` in 0..=64 and at least 1 when any object reflects or
/// refracts; `min_weight` in [0, 1); `vertex_rays` in 1..=4096.
fn raytrace(rt: &RayTrace, scene: &Scene) -> Check {
    int_in("raytrace.max_depth", rt.max_depth, 0, MAX_DEPTH)?;
    if rt.max_depth == 0 {
        let rays = scene.objects.iter().enumerate().find_map(|(i, o)| {
            if o.reflect.is_some() {
                Some(format!("objects[{i}].reflect"))
            } else if o.refract.is_some() {
                Some(format!("objects[{i}].refract"))
            } else {
                None
            }
        });
        if let Some(which) = rays {
            return fail(
                "raytrace.max_depth",
                format!(
                    "must be >= 1 when an object reflects or refracts ({which} asks for rays), \
                     got 0"
                ),
            );
        }
    }
    finite("raytrace.min_weight", rt.min_weight)?;
    if !(0.0..1.0).contains(&rt.min_weight) {
        return fail("raytrace.min_weight", format!("must be in [0, 1), got {}", rt.min_weight));
    }
    int_in("raytrace.vertex_rays", rt.vertex_rays, 1, MAX_VERTEX_RAYS)
}

/// Transform motion: key times, then each key's transforms by the rules of `transform`.
fn motion(at: &str, object: &Object, shutter: &Shutter) -> Check {
    keys(
        at,
        &object.motion,
        |k| k.time,
        shutter,
        |i, key| {
            for (j, t) in key.transform.iter().enumerate() {
                transform(&format!("{at}[{i}].transform[{j}]"), t)?;
            }
            Ok(())
        },
    )
}

/// Deformation motion: only of a `Mesh` or `BilinearPatch`; key times, then each key's points
/// (as many as the shape has, all finite).
fn deform(at: &str, object: &Object, shutter: &Shutter) -> Check {
    if object.deform.is_empty() {
        return Ok(());
    }
    let count = match &object.shape {
        Shape::BilinearPatch { points } => points.len(),
        Shape::Mesh { points, .. } => points.len(),
        other => {
            return fail(
                at,
                format!(
                    "deformation keys need a Mesh or BilinearPatch shape, got {}",
                    shape_name(other)
                ),
            );
        }
    };
    keys(
        at,
        &object.deform,
        |k| k.time,
        shutter,
        |i, key| {
            let path = format!("{at}[{i}].points");
            if key.points.len() != count {
                return fail(path, format!("expected {count} points, got {}", key.points.len()));
            }
            for (j, p) in key.points.iter().enumerate() {
                finite_all(&format!("{path}[{j}]"), p)?;
            }
            Ok(())
        },
    )
}

/// The variant name of a shape, for messages.
fn shape_name(shape: &Shape) -> &'static str {
    match shape {
        Shape::Sphere { .. } => "Sphere",
        Shape::Cylinder { .. } => "Cylinder",
        Shape::Cone { .. } => "Cone",
        Shape::Disk { .. } => "Disk",
        Shape::Torus { .. } => "Torus",
        Shape::Paraboloid { .. } => "Paraboloid",
        Shape::BilinearPatch { .. } => "BilinearPatch",
        Shape::Mesh { .. } => "Mesh",
    }
}

fn shape(at: &str, shape: &Shape) -> Check {
    let field = |name: &str| format!("{at}.{name}");
    match shape {
        Shape::Sphere { radius, zmin, zmax, thetamax } => {
            positive(&field("radius"), *radius)?;
            if let Some(z) = zmin {
                finite(&field("zmin"), *z)?;
            }
            if let Some(z) = zmax {
                finite(&field("zmax"), *z)?;
            }
            let lo = zmin.unwrap_or(-radius).clamp(-radius, *radius);
            let hi = zmax.unwrap_or(*radius).clamp(-radius, *radius);
            if lo >= hi {
                let culprit = if zmax.is_some() { "zmax" } else { "zmin" };
                return fail(
                    field(culprit),
                    format!(
                        "zmin must be < zmax once both are clamped to [-radius, radius], \
                         got zmin {lo} and zmax {hi}"
                    ),
                );
            }
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Cylinder { radius, zmin, zmax, thetamax } => {
            positive(&field("radius"), *radius)?;
            finite(&field("zmin"), *zmin)?;
            finite(&field("zmax"), *zmax)?;
            if zmax <= zmin {
                return fail(field("zmax"), format!("must be > zmin ({zmin}), got {zmax}"));
            }
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Cone { height, radius, thetamax } => {
            finite(&field("height"), *height)?;
            if *height == 0.0 {
                return fail(field("height"), "must be non-zero, got 0");
            }
            positive(&field("radius"), *radius)?;
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Disk { height, radius, thetamax } => {
            finite(&field("height"), *height)?;
            positive(&field("radius"), *radius)?;
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Paraboloid { rmax, zmin, zmax, thetamax } => {
            positive(&field("rmax"), *rmax)?;
            finite(&field("zmin"), *zmin)?;
            finite(&field("zmax"), *zmax)?;
            if *zmin < 0.0 {
                return fail(field("zmin"), format!("must be >= 0, got {zmin}"));
            }
            if zmax <= zmin {
                return fail(field("zmax"), format!("must be > zmin ({zmin}), got {zmax}"));
            }
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Torus { major_radius, minor_radius, phimin, phimax, thetamax } => {
            positive(&field("major_radius"), *major_radius)?;
            positive(&field("minor_radius"), *minor_radius)?;
            finite(&field("phimin"), *phimin)?;
            finite(&field("phimax"), *phimax)?;
            if phimax <= phimin {
                return fail(field("phimax"), format!("must be > phimin ({phimin}), got {phimax}"));
            }
            if f64::from(*phimax) - f64::from(*phimin) > 360.0 {
                return fail(
                    field("phimax"),
                    format!(
                        "must be at most phimin + 360 ({}), got {phimax}",
                        f64::from(*phimin) + 360.0
                    ),
                );
            }
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::BilinearPatch { points } => {
            for (i, p) in points.iter().enumerate() {
                finite_all(&format!("{at}.points[{i}]"), p)?;
            }
            Ok(())
        }
        Shape::Mesh { points, faces, colors } => {
            for (i, p) in points.iter().enumerate() {
                finite_all(&format!("{at}.points[{i}]"), p)?;
            }
            if faces.is_empty() {
                return fail(field("faces"), "must hold at least one face");
            }
            for (f, face) in faces.iter().enumerate() {
                if !(3..=4).contains(&face.len()) {
                    return fail(
                        format!("{at}.faces[{f}]"),
                        format!("a face must have 3 or 4 indices, got {}", face.len()),
                    );
                }
                for (k, &index) in face.iter().enumerate() {
                    if usize::try_from(index).unwrap_or(usize::MAX) >= points.len() {
                        return fail(
                            format!("{at}.faces[{f}][{k}]"),
                            format!(
                                "index {index} is out of range: the mesh has {} points",
                                points.len()
                            ),
                        );
                    }
                }
            }
            if let Some(colors) = colors {
                if colors.len() != points.len() {
                    return fail(
                        field("colors"),
                        format!(
                            "must have one colour per point ({}), got {}",
                            points.len(),
                            colors.len()
                        ),
                    );
                }
                for (i, c) in colors.iter().enumerate() {
                    finite_all(&format!("{at}.colors[{i}]"), c)?;
                }
            }
            Ok(())
        }
    }
}

fn transform(at: &str, t: &Transform) -> Check {
    match t {
        Transform::Translate(v) => finite_all(at, v),
        Transform::Rotate { angle, axis } => {
            finite(&format!("{at}.angle"), *angle)?;
            finite_all(&format!("{at}.axis"), axis)?;
            if axis.iter().all(|&a| a == 0.0) {
                return fail(format!("{at}.axis"), "must be non-zero");
            }
            Ok(())
        }
        Transform::Scale(v) => {
            finite_all(at, v)?;
            for (i, s) in v.iter().enumerate() {
                if *s == 0.0 {
                    return fail(format!("{at}[{i}]"), "a scale factor must be non-zero, got 0");
                }
            }
            Ok(())
        }
        Transform::Matrix(rows) => {
            for (r, row) in rows.iter().enumerate() {
                finite_all(&format!("{at}[{r}]"), row)?;
            }
            if rows[3] != [0.0, 0.0, 0.0, 1.0] {
                let [a, b, c, d] = rows[3];
                return fail(
                    format!("{at}[3]"),
                    format!(
                        "the last row must be (0, 0, 0, 1): projective transforms are not \
                         supported, got ({a}, {b}, {c}, {d})"
                    ),
                );
            }
            let row = |r: &[f32; 4]| {
                DVec4::new(f64::from(r[0]), f64::from(r[1]), f64::from(r[2]), f64::from(r[3]))
            };
            let det = DMat4::from_cols(row(&rows[0]), row(&rows[1]), row(&rows[2]), row(&rows[3]))
                .determinant();
            if det.abs() <= 1e-12 {
                return fail(
                    at,
                    format!(
                        "the matrix must be invertible (|determinant| > 1e-12), got determinant {det}"
                    ),
                );
            }
            Ok(())
        }
    }
}

fn material(at: &str, m: &Material) -> Check {
    let field = |name: &str| format!("{at}.{name}");
    match m {
        Material::Constant { color, opacity } => {
            unit_rgb(&field("color"), color)?;
            unit_rgb(&field("opacity"), opacity)
        }
        Material::Matte { color, opacity, ka, kd } => {
            unit_rgb(&field("color"), color)?;
            unit_rgb(&field("opacity"), opacity)?;
            non_negative(&field("ka"), *ka)?;
            non_negative(&field("kd"), *kd)
        }
        Material::Plastic { color, opacity, ka, kd, ks, roughness, specular_color } => {
            unit_rgb(&field("color"), color)?;
            unit_rgb(&field("opacity"), opacity)?;
            non_negative(&field("ka"), *ka)?;
            non_negative(&field("kd"), *kd)?;
            non_negative(&field("ks"), *ks)?;
            positive(&field("roughness"), *roughness)?;
            unit_rgb(&field("specular_color"), specular_color)
        }
    }
}

/// An object name for a message: quoted, escaped and clipped.
fn quoted(name: &str) -> String {
    format!("{:?}", clip(name, 64))
}

/// The CSG rules: at most [`MAX_SOLIDS`] solids; each solid's tree by [`solid`]; every
/// object used by at most one leaf of all the trees.
fn solids(scene: &Scene) -> Check {
    if scene.solids.is_empty() {
        return Ok(());
    }
    if scene.solids.len() > MAX_SOLIDS {
        return fail(
            "solids",
            format!("at most {MAX_SOLIDS} solids are allowed, got {}", scene.solids.len()),
        );
    }
    // Name -> the first two objects carrying it.
    let mut names: Names = HashMap::new();
    for (i, object) in scene.objects.iter().enumerate() {
        names
            .entry(object.name.as_str())
            .and_modify(|e| {
                e.1.get_or_insert(i);
            })
            .or_insert((i, None));
    }
    // Object index -> the leaf that uses it.
    let mut used: Used = HashMap::new();
    for (s, solid) in scene.solids.iter().enumerate() {
        self::solid(s, &solid.tree, scene, &names, &mut used)?;
    }
    Ok(())
}

/// Solid `s`: an operator at the root, at most [`MAX_LEAVES`] leaves, then every node in
/// pre-order. Iterative, so no tree depth can exhaust the stack.
fn solid(s: usize, tree: &Csg, scene: &Scene, names: &Names, used: &mut Used) -> Check {
    let at = format!("solids[{s}].tree");
    if matches!(tree, Csg::Object(_)) {
        return fail(at, "a solid needs an operator: Union, Intersection or Difference");
    }
    let mut leaves = 0usize;
    let mut stack = vec![tree];
    while let Some(node) = stack.pop() {
        match node {
            Csg::Object(_) => leaves += 1,
            Csg::Union(items) | Csg::Intersection(items) => stack.extend(items),
            Csg::Difference(a, b) => stack.extend([a.as_ref(), b.as_ref()]),
        }
    }
    if leaves > MAX_LEAVES {
        return fail(at, format!("a solid may use at most {MAX_LEAVES} objects, got {leaves}"));
    }
    let mut stack: Vec<(&Csg, String)> = vec![(tree, at)];
    while let Some((node, path)) = stack.pop() {
        let (op, items) = match node {
            Csg::Object(name) => {
                leaf(&path, s, name, scene, names, used)?;
                continue;
            }
            Csg::Difference(a, b) => {
                stack.push((b, format!("{path}[1]")));
                stack.push((a, format!("{path}[0]")));
                continue;
            }
            Csg::Union(items) => ("Union", items),
            Csg::Intersection(items) => ("Intersection", items),
        };
        if items.len() < 2 {
            return fail(path, format!("{op} needs at least 2 operands, got {}", items.len()));
        }
        for (k, item) in items.iter().enumerate().rev() {
            stack.push((item, format!("{path}[{k}]")));
        }
    }
    Ok(())
}

/// A leaf `Object(name)` at `path` in solid `s`: the name resolves to exactly one object,
/// not used by any leaf before, whose surface is closed.
fn leaf(path: &str, s: usize, name: &str, scene: &Scene, names: &Names, used: &mut Used) -> Check {
    if name.is_empty() {
        return fail(
            path,
            "an operand must name an object: unnamed objects cannot be used in solids",
        );
    }
    let index = match names.get(name) {
        None => return fail(path, format!("no object is named {}", quoted(name))),
        Some((first, Some(second))) => {
            return fail(
                path,
                format!(
                    "object name {0} is ambiguous: objects[{first}] and objects[{second}] are \
                     both named {0}",
                    quoted(name)
                ),
            );
        }
        Some((index, None)) => *index,
    };
    if let Some((other, at)) = used.get(&index) {
        return fail(
            path,
            format!("object {} is already used by solids[{other}] (at {at})", quoted(name)),
        );
    }
    let Some(object) = scene.objects.get(index) else {
        return fail(path, format!("no object is named {}", quoted(name)));
    };
    match closure(&object.shape) {
        Closure::Closed => {}
        Closure::Open(why) => {
            return fail(
                path,
                format!(
                    "object {} is not closed ({why}); CSG operands must be closed solids",
                    quoted(name)
                ),
            );
        }
        Closure::Misoriented(why) => {
            return fail(
                path,
                format!(
                    "object {} is not consistently oriented ({why}); the two faces at every \
                     edge of a closed mesh must run along it in opposite directions",
                    quoted(name)
                ),
            );
        }
    }
    used.insert(index, (s, path.to_string()));
    Ok(())
}
