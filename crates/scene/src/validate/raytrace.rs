//! The rules of the `raytrace` section, in field order.
//!
//! Invariant: runs last, after every object, since the depth limit depends on whether any
//! object reflects or refracts.

use super::primitives::{Check, Interval, fail, int_in, within};
use crate::model::{RayTrace, Scene};

/// Most `raytrace.max_depth`: deeper chains of mirror bounces add nothing visible.
const MAX_DEPTH: u32 = 64;
/// Most `raytrace.vertex_rays`.
const MAX_VERTEX_RAYS: u32 = 4096;

/// The ray-tracing limits: `max_depth` in 0..=64 and at least 1 when any object reflects or
/// refracts; `min_weight` in [0, 1); `vertex_rays` in 1..=4096.
pub(super) fn raytrace(rt: &RayTrace, scene: &Scene) -> Check {
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
    within("raytrace.min_weight", rt.min_weight, Interval::closed_open(0.0, 1.0), "")?;
    int_in("raytrace.vertex_rays", rt.vertex_rays, 1, MAX_VERTEX_RAYS)
}
