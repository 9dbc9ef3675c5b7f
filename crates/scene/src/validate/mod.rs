//! Semantic validation of a deserialised [`Scene`]: ranges, finiteness and consistency.
//!
//! Invariants: checks run in a fixed order (image, camera, hider, lights, objects, solids,
//! raytrace, outputs, texture cache, each in field order) and stop at the first failure, so the reported error is stable; each failure
//! names the path of the offending value as the source map spells it (`objects[0].shape.radius`).
//! Every `f32` is checked finite before any range test on it. No check can panic: geometric
//! tests are done in `f64`, where products of finite `f32`s cannot overflow.
//!
//! Solids are checked after every object, so an operand's own shape is already valid when its
//! closure is judged. Within a solid: an operator at the root, the number of leaves, then the
//! tree in pre-order (an operator's depth, at most `MAX_CSG_DEPTH`, and operand count before its
//! operands, operands left to right;
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
//!
//! Layout: one module per model section (`camera`, `hider`, `light`, `object`, `shape`,
//! `material`, `solid`, `raytrace`), the motion-key rules in `keys` and the shared check
//! primitives in `primitives`. [`check_scene`] below is the one place that fixes the order.

mod camera;
mod hair;
mod hider;
mod keys;
mod light;
mod lookdev;
mod material;
mod object;
mod output;
mod primitives;
mod raytrace;
mod shape;
mod solid;
mod subdivision;
mod trim;

use crate::model::Scene;
use primitives::Check;

/// A validation failure: the path of the value at fault and what is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Issue {
    /// Path of the offending value as RON spells it, e.g. `objects[0].shape.radius`.
    pub path: String,
    /// What is wrong, e.g. `must be > 0, got -1`.
    pub message: String,
}

/// The first rule `loops` break (see [`crate::validate_trim`]).
pub(crate) fn trim_loops(loops: &[crate::TrimLoop], domain: Option<[f32; 4]>) -> Check {
    for (i, l) in loops.iter().enumerate() {
        trim::trim_loop(&format!("trim[{i}]"), l, domain)?;
    }
    Ok(())
}

/// The first rule `scene` breaks, if any.
pub(crate) fn check(scene: &Scene) -> Option<Issue> {
    check_scene(scene).err()
}

fn check_scene(scene: &Scene) -> Check {
    camera::image(&scene.image)?;
    camera::camera(&scene.camera, &scene.image)?;
    hider::hider(&scene.hider, scene)?;
    let shutter = &scene.camera.shutter;
    for (i, light) in scene.lights.iter().enumerate() {
        light::light(&format!("lights[{i}]"), light, shutter)?;
    }
    for (i, object) in scene.objects.iter().enumerate() {
        object::object(&format!("objects[{i}]"), object, shutter, scene.lights.len())?;
        if let Some(light) = object.area_light {
            light::emitter_link(&format!("objects[{i}].area_light"), light, &scene.lights)?;
        }
    }
    solid::solids(scene)?;
    raytrace::raytrace(&scene.raytrace, scene)?;
    output::outputs(&scene.outputs, scene)?;
    lookdev::scene(scene)
}
