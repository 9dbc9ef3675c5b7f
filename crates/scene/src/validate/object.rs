//! The rules of one object, in field order: shape, transforms, material, motion and
//! deformation keys, glass, reflection, refraction, pattern, a rolling ball, then its shading
//! rate and light set, then its look development (`lookdev`).
//!
//! Invariant: every check reports under the object's own path (`objects[i]`); the shape and
//! transforms are valid before any motion key is judged against them.

use super::keys::keys;
use super::material::material;
use super::primitives::{
    Check, UNIT, fail, finite_all, finite_each, int_in, non_negative, nonzero_vector, positive,
    spread, unit_rgb, within,
};
use super::shape::{shape, transforms};
use crate::model::{Object, Pattern, Roll, Shape, Shutter, Transform};
use crate::roll;

pub(super) fn object(at: &str, object: &Object, shutter: &Shutter, lights: usize) -> Check {
    shape(&format!("{at}.shape"), &object.shape)?;
    transforms(&format!("{at}.transform"), &object.transform)?;
    material(&format!("{at}.material"), &object.material)?;
    motion(&format!("{at}.motion"), object, shutter)?;
    deform(&format!("{at}.deform"), object, shutter)?;
    if let Some(a) = object.glass {
        within(&format!("{at}.glass"), a, UNIT, "")?;
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
    if let Some(rate) = object.shading_rate {
        positive(&format!("{at}.shading_rate"), rate)?;
    }
    if let Some(flatness) = object.flatness {
        non_negative(&format!("{at}.flatness"), flatness)?;
    }
    if let Some(factor) = object.motion_factor {
        non_negative(&format!("{at}.motion_factor"), factor)?;
    }
    if let Some(factor) = object.focus_factor {
        non_negative(&format!("{at}.focus_factor"), factor)?;
    }
    if let Some(set) = &object.lights {
        light_set(&format!("{at}.lights"), set, lights)?;
    }
    super::lookdev::lookdev(at, object)
}

/// A light set: every index names one of the scene's `count` lights, none twice.
fn light_set(at: &str, set: &[u32], count: usize) -> Check {
    for (k, &light) in set.iter().enumerate() {
        let here = format!("{at}[{k}]");
        if light as usize >= count {
            let lights = if count == 1 { "light" } else { "lights" };
            return fail(
                here,
                format!("index {light} is out of range: the scene has {count} {lights}"),
            );
        }
        if let Some(first) = set.iter().take(k).position(|&l| l == light) {
            return fail(here, format!("light {light} is listed twice (also at lights[{first}])"));
        }
    }
    Ok(())
}

/// Transform motion: key times, then each key's transforms by the rules of `transform`.
fn motion(at: &str, object: &Object, shutter: &Shutter) -> Check {
    keys(
        at,
        &object.motion,
        |k| k.time,
        shutter,
        |i, key| transforms(&format!("{at}[{i}].transform"), &key.transform),
    )
}

/// Deformation motion: only of a `Mesh`, `BilinearPatch`, `PatchMesh`, `NuPatch` or
/// `SubdivisionMesh`; key
/// times, then each key's points (as many as the shape has control points, all finite; a
/// NURBS key gives positions `(x/w, y/w, z/w)` and keeps the shape's weights).
fn deform(at: &str, object: &Object, shutter: &Shutter) -> Check {
    if object.deform.is_empty() {
        return Ok(());
    }
    let count = match &object.shape {
        Shape::BilinearPatch { points } => points.len(),
        Shape::Mesh { points, .. } => points.len(),
        Shape::PatchMesh { points, .. } => points.len(),
        Shape::NuPatch { points, .. } => points.len(),
        Shape::SubdivisionMesh { points, .. } => points.len(),
        Shape::Curves { points, .. } | Shape::Points { points, .. } => points.len(),
        other => {
            return fail(
                at,
                format!(
                    "deformation keys need a Mesh, BilinearPatch, PatchMesh, NuPatch, \
                     SubdivisionMesh, Curves or Points shape, got {}",
                    other.name()
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
            finite_each(&path, &key.points)
        },
    )
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
