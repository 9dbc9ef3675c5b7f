//! The rules of look development, in field order: an object's texture maps, displacement,
//! bump and emission, and the scene's texture cache.
//!
//! Invariant: reports under the object's path (`objects[i].maps.color.repeat`); a texture
//! file is only named here (whether it can be read is known when the render loads it, as an
//! error naming the file).

use super::primitives::{
    Check, fail, finite, finite_all, int_in, light_rgb, non_negative, positive,
};
use crate::model::MIN_TEXTURE_CACHE_BYTES;
use crate::model::{Bump, Displacement, HiderMethod, Maps, Object, Scalar, Scene, TextureMap};

/// An object's maps, displacement, bump and emission.
pub(super) fn lookdev(at: &str, object: &Object) -> Check {
    maps(&format!("{at}.maps"), &object.maps)?;
    if let Some(Displacement { source, amount, center, bound }) = &object.displacement {
        let at = format!("{at}.displacement");
        scalar(&format!("{at}.source"), source)?;
        finite(&format!("{at}.amount"), *amount)?;
        finite(&format!("{at}.center"), *center)?;
        if let Some(b) = bound {
            non_negative(&format!("{at}.bound"), *b)?;
        }
    }
    if let Some(Bump { source, amount, center }) = &object.bump {
        let at = format!("{at}.bump");
        scalar(&format!("{at}.source"), source)?;
        finite(&format!("{at}.amount"), *amount)?;
        finite(&format!("{at}.center"), *center)?;
    }
    if let Some(e) = &object.emission {
        light_rgb(&format!("{at}.emission"), e)?;
    }
    Ok(())
}

fn maps(at: &str, m: &Maps) -> Check {
    for (name, map) in m.each() {
        texture(&format!("{at}.{name}"), map)?;
    }
    Ok(())
}

fn texture(at: &str, t: &TextureMap) -> Check {
    if t.file.is_empty() {
        return fail(format!("{at}.file"), "must name a file");
    }
    let repeat = format!("{at}.repeat");
    finite_all(&repeat, &[t.repeat.0, t.repeat.1])?;
    if t.repeat.0 == 0.0 || t.repeat.1 == 0.0 {
        return fail(repeat, format!("must be non-zero, got ({}, {})", t.repeat.0, t.repeat.1));
    }
    non_negative(&format!("{at}.width"), t.width)
}

fn scalar(at: &str, s: &Scalar) -> Check {
    match s {
        Scalar::Constant(v) => finite(at, *v),
        Scalar::Noise { frequency, octaves } => {
            positive(&format!("{at}.frequency"), *frequency)?;
            int_in(&format!("{at}.octaves"), *octaves, 1, 8)
        }
        Scalar::Wave { frequency, phase } => {
            finite_all(&format!("{at}.frequency"), &[frequency.0, frequency.1])?;
            finite(&format!("{at}.phase"), *phase)
        }
        Scalar::Texture(map) => texture(at, map),
    }
}

/// The scene's texture cache, and the rule that look development needs the REYES hider
/// (texture footprints and displaced grids are the dicer's).
pub(super) fn scene(scene: &Scene) -> Check {
    let bytes = scene.texture_cache.max_bytes;
    if bytes < MIN_TEXTURE_CACHE_BYTES {
        return fail(
            "texture_cache.max_bytes",
            format!("must be at least {MIN_TEXTURE_CACHE_BYTES}, got {bytes}"),
        );
    }
    if scene.hider.method == HiderMethod::RayTrace
        && let Some(i) = scene
            .objects
            .iter()
            .position(|o| !o.maps.is_empty() || o.displacement.is_some() || o.bump.is_some())
    {
        return fail(
            "hider.method",
            format!(
                "the ray-tracing hider does not read texture maps, displacement or bump \
                 (objects[{i}] has them: they need the REYES hider's grids); use Stochastic"
            ),
        );
    }
    Ok(())
}
