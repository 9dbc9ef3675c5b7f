//! The rules of a surface [`Material`]: colours and opacities in [0, 1] (a Constant's colour
//! only non-negative, unbounded: it is emitted light), coefficients non-negative, roughness
//! positive, in field order.
//!
//! Invariant: reports under the material's path (`objects[i].material`).

use super::primitives::{Check, light_rgb, non_negative, positive, unit_rgb};
use crate::model::Material;

pub(super) fn material(at: &str, m: &Material) -> Check {
    let field = |name: &str| format!("{at}.{name}");
    match m {
        Material::Constant { color, opacity } => {
            // Unlit: its colour is the light it sends, and may exceed 1 (a lamp card).
            light_rgb(&field("color"), color)?;
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
        Material::Metal { color, opacity, ka, ks, roughness } => {
            unit_rgb(&field("color"), color)?;
            unit_rgb(&field("opacity"), opacity)?;
            non_negative(&field("ka"), *ka)?;
            non_negative(&field("ks"), *ks)?;
            positive(&field("roughness"), *roughness)
        }
        Material::DefaultSurface { color, opacity, ka, kd } => {
            unit_rgb(&field("color"), color)?;
            unit_rgb(&field("opacity"), opacity)?;
            non_negative(&field("ka"), *ka)?;
            non_negative(&field("kd"), *kd)
        }
        // The shader's parameters are checked against its declarations when it is compiled.
        Material::Shader { color, opacity, .. } => {
            unit_rgb(&field("color"), color)?;
            unit_rgb(&field("opacity"), opacity)
        }
    }
}
