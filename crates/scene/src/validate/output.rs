//! The rules of the `outputs` section: light groups first (the AOVs name them), then each AOV
//! in order, then the background depth and the PNG view.
//!
//! Invariant: reports at `outputs.<field>` paths, as the source map spells them.

use super::primitives::{Check, Interval, UNIT, each, fail, finite, within};
use crate::model::{AovFilter, AovSource, HiderMethod, Outputs, PixelType, Scene, ZBackground};

/// A layer or group name: non-empty ASCII letters, digits and `_`, not starting with a digit,
/// so `NAME.CHANNEL` is unambiguous in an EXR.
fn name_ok(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

pub(super) fn outputs(o: &Outputs, scene: &Scene) -> Check {
    let lights = scene.lights.len();
    for (g, group) in o.light_groups.iter().enumerate() {
        let at = format!("outputs.light_groups[{g}]");
        if !name_ok(&group.name) {
            return fail(
                format!("{at}.name"),
                format!(
                    "must be letters, digits and _ (not starting with a digit), got {:?}",
                    group.name
                ),
            );
        }
        if o.light_groups[..g].iter().any(|h| h.name == group.name) {
            return fail(
                format!("{at}.name"),
                format!("the group {:?} is defined twice", group.name),
            );
        }
        for (k, &light) in group.lights.iter().enumerate() {
            if light as usize >= lights {
                return fail(
                    format!("{at}.lights[{k}]"),
                    format!("no light {light}: the scene has {lights}"),
                );
            }
            if group.lights[..k].contains(&light) {
                return fail(format!("{at}.lights[{k}]"), format!("light {light} is listed twice"));
            }
        }
    }
    if !o.aovs.is_empty() && scene.hider.adaptive.max_level > 0 {
        return fail(
            "outputs.aovs",
            "adaptive sampling refines the beauty only, so its AOV layers would not match it; \
             remove hider.adaptive or the AOVs",
        );
    }
    if !o.aovs.is_empty() && scene.hider.method == HiderMethod::RayTrace {
        return fail(
            "outputs.aovs",
            "AOVs are written by the stochastic hider only; use hider: (method: Stochastic)",
        );
    }
    for (i, aov) in o.aovs.iter().enumerate() {
        let at = format!("outputs.aovs[{i}]");
        let name = aov.layer_name();
        if let Some(n) = &aov.name
            && !name_ok(n)
        {
            return fail(
                format!("{at}.name"),
                format!("must be letters, digits and _ (not starting with a digit), got {n:?}"),
            );
        }
        if o.aovs[..i].iter().any(|a| a.layer_name() == name) {
            let field = if aov.name.is_some() { "name" } else { "source" };
            return fail(
                format!("{at}.{field}"),
                format!("the layer {name:?} is written twice: give one a different name"),
            );
        }
        match (aov.source == AovSource::Output, &aov.variable) {
            (true, None) => {
                return fail(format!("{at}.variable"), "Output needs the variable's name");
            }
            (true, Some(v)) if !name_ok(v) => {
                return fail(
                    format!("{at}.variable"),
                    format!("must be a shading-language identifier, got {v:?}"),
                );
            }
            (false, Some(_)) => {
                return fail(format!("{at}.variable"), "only source Output names a variable");
            }
            _ if aov.source != AovSource::Output && aov.variable_type.is_some() => {
                return fail(format!("{at}.variable_type"), "only source Output has a type");
            }
            _ => {}
        }
        if aov.source.is_id() {
            if matches!(aov.filter, Some(AovFilter::Filter | AovFilter::Average)) {
                return fail(
                    format!("{at}.filter"),
                    "ids are never averaged: use Zmin, Nearest, Min or Max",
                );
            }
            if aov.pixel_type == Some(PixelType::Half) {
                return fail(
                    format!("{at}.pixel_type"),
                    "ids are 32-bit integers: remove pixel_type",
                );
            }
        }
        if aov.source.is_component() && scene.needs_ray_shading() {
            return fail(
                format!("{at}.source"),
                "Ambient, Diffuse and Specular are split from the built-in local illumination \
                 only, and this scene is shaded by distributed rays (shadows, area lights, \
                 reflection, refraction or patterns)",
            );
        }
        match (&aov.light_group, aov.source.is_component()) {
            (Some(_), false) => {
                return fail(
                    format!("{at}.light_group"),
                    "only Ambient, Diffuse and Specular take a light group",
                );
            }
            (Some(g), true) if !o.light_groups.iter().any(|h| &h.name == g) => {
                return fail(format!("{at}.light_group"), format!("no light group named {g:?}"));
            }
            _ => {}
        }
    }
    if let ZBackground::Finite(z) = o.zbackground {
        finite("outputs.zbackground", z)?;
        if z <= 0.0 {
            return fail("outputs.zbackground", format!("must be > 0, got {z}"));
        }
    }
    within("outputs.png.exposure", o.png.exposure, Interval::closed(-32.0, 32.0), " stops")?;
    if let Some(bg) = &o.png.background {
        each("outputs.png.background", bg, |p, v| within(p, v, UNIT, ""))?;
    }
    Ok(())
}
