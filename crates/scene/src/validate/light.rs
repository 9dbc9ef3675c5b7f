//! The rules of one light: its position or shape, then colour and intensity, then a spot
//! light's cone or an area light's motion keys.
//!
//! Invariant: every check reports under the light's own path (`lights[i]`).

use super::keys::keys;
use super::primitives::{
    Check, Interval, dvec, each, fail, finite_all, non_negative, nonzero_vector, parallel,
    positive, within,
};
use crate::model::{AreaShape, Light, Shutter};

pub(super) fn light(at: &str, light: &Light, shutter: &Shutter) -> Check {
    let (color, intensity) = match light {
        Light::Ambient { color, intensity } => (color, intensity),
        Light::Distant { from, to, color, intensity, .. }
        | Light::Spot { from, to, color, intensity, .. } => {
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
    each(&format!("{at}.color"), color, non_negative)?;
    non_negative(&format!("{at}.intensity"), *intensity)?;
    if let Light::Spot { cone_angle, cone_delta, beam_distribution, .. } = light {
        let cone = format!("{at}.cone_angle");
        within(&cone, *cone_angle, Interval::open_closed(0.0, 180.0), " degrees")?;
        let delta = format!("{at}.cone_delta");
        non_negative(&delta, *cone_delta)?;
        if cone_delta > cone_angle {
            return fail(delta, format!("must be <= cone_angle ({cone_angle}), got {cone_delta}"));
        }
        non_negative(&format!("{at}.beam_distribution"), *beam_distribution)?;
    }
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
/// edges non-zero and not parallel; a polygon's points as [`AreaShape::polygon_flaw`] wants.
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
            if parallel(u, v) {
                return fail(field("edge_v"), "must not be parallel to edge_u");
            }
            Ok(())
        }
        AreaShape::Polygon { points } => match AreaShape::polygon_flaw(points) {
            Some(flaw) => fail(field("points"), flaw),
            None => Ok(()),
        },
    }
}

/// An object's link to the area light it is the visible surface of: an `Area` light.
pub(super) fn emitter_link(at: &str, light: u32, lights: &[Light]) -> Check {
    match lights.get(light as usize) {
        Some(Light::Area { .. }) => Ok(()),
        Some(_) => fail(at, format!("lights[{light}] is not an Area light")),
        None => {
            let count = lights.len();
            fail(at, format!("index {light} is out of range: the scene has {count} light(s)"))
        }
    }
}
