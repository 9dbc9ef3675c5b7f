//! Option requests of the RI state machine (Spec 3.2, 4.1): camera, display and hider
//! options, each kept in the frame's [`FrameOptions`](super::state::FrameOptions) with where it was set.
//!
//! Invariant: options never change inside the world block, where the Specification freezes
//! them (there they are ignored with a warning, an error under `--strict`); every value is checked where the model needs it checked first (sizes, counts, names).

use reyes_scene::{Aov, AovFilter, AovSource, DepthFilter, FilterKind, HiderMethod, VariableType};

use super::frame::Machine;
use super::search::Kind;
use super::state::{Display, Projection};
use crate::{Request, RequestKind as K, RibError, Warning};

impl Machine {
    /// Options: only outside the world block. Inside it (exporters write `Display` or
    /// `Imager` there) the option is ignored with a warning, as RenderMan renderers do; an
    /// error under `--strict`.
    pub(super) fn option(&mut self, r: &Request) -> Result<(), RibError> {
        if self.in_world() {
            return self.tolerate(
                &r.at,
                r.name(),
                "options cannot change inside the world block",
                "ignored for this frame",
            );
        }
        if r.kind == K::Imager && self.sl_imager(r)? {
            return Ok(());
        }
        let mut warnings = Vec::new();
        self.set_option(r, &mut warnings)?;
        for (key, w) in warnings {
            self.warn_once(key, w);
        }
        Ok(())
    }

    fn set_option(
        &mut self,
        r: &Request,
        warned: &mut Vec<(String, Warning)>,
    ) -> Result<(), RibError> {
        let o = &mut self.frame_options;
        let v = |i| r.float(i).unwrap_or(0.0);
        match r.kind {
            K::Format => {
                let (w, h) = (r.int(0).unwrap_or(0), r.int(1).unwrap_or(0));
                if w < 1 || h < 1 {
                    return Err(r.error(format!("resolution must be at least 1x1, got {w}x{h}")));
                }
                o.width = w as u32;
                o.height = h as u32;
                o.pixel_aspect = r.float(2).unwrap_or(1.0);
                o.origin("image", &r.at, r.name());
                if o.pixel_aspect != 1.0 && o.pixel_aspect > 0.0 {
                    let w = r.warning("pixel aspect ratios other than 1 are not supported: square pixels are used");
                    warned.push(("pixelaspect".to_string(), w));
                }
            }
            K::FrameAspectRatio => {
                o.frame_aspect = Some(v(0));
                o.origin("camera.screen_window", &r.at, r.name());
            }
            K::ScreenWindow => {
                let s = r.floats(0).map(<[f32]>::to_vec).unwrap_or_else(|| (0..4).map(v).collect());
                o.screen_window = Some([s[0], s[1], s[2], s[3]]);
                o.origin("camera.screen_window", &r.at, r.name());
            }
            K::CropWindow => {
                let s = r.floats(0).map(<[f32]>::to_vec).unwrap_or_else(|| (0..4).map(v).collect());
                // RI Spec 3.2: the window is clamped to [0, 1]; validation refuses one that
                // selects no pixel (or that is reversed).
                let c = |x: f32| x.clamp(0.0, 1.0);
                o.crop = Some([c(s[0]), c(s[1]), c(s[2]), c(s[3])]);
                o.origin("image.crop", &r.at, r.name());
            }
            K::Projection => {
                let name = r.string(0).unwrap_or_default();
                o.projection = match name {
                    "perspective" => {
                        let fov = r
                            .param("fov")
                            .and_then(|p| p.floats())
                            .and_then(|f| f.first().copied())
                            .unwrap_or(90.0);
                        Projection::Perspective { fov }
                    }
                    "orthographic" => Projection::Orthographic,
                    other => {
                        return Err(r.error(format!(
                            "unknown projection \"{other}\" (perspective or orthographic)"
                        )));
                    }
                };
                o.origin("camera.fov", &r.at, r.name());
                o.origin("camera.projection", &r.at, r.name());
            }
            K::Clipping => {
                o.hither = v(0);
                o.yon = v(1);
                o.origin("camera.hither", &r.at, r.name());
                o.origin("camera.yon", &r.at, r.name());
            }
            K::DepthOfField => {
                o.depth_of_field = if r.args.is_empty() {
                    None
                } else {
                    let f = v(0);
                    if f.is_infinite() { None } else { Some((f, v(1), v(2))) }
                };
                o.origin("camera.lens", &r.at, r.name());
            }
            K::Shutter => {
                o.shutter = (v(0), v(1));
                o.origin("camera.shutter", &r.at, r.name());
            }
            K::PixelSamples => {
                let (x, y) = (v(0), v(1));
                let round =
                    |s: f32| if s.is_finite() && s >= 1.0 { Some(s.round() as u32) } else { None };
                let (Some(x), Some(y)) = (round(x), round(y)) else {
                    return Err(r.error(format!("samples must be at least 1, got {x} {y}")));
                };
                o.pixel_samples = (x, y);
                o.origin("hider.pixel_samples", &r.at, r.name());
            }
            K::PixelFilter => {
                let name = r.string(0).unwrap_or_default();
                let kind = FilterKind::from_renderman_name(name)
                    .ok_or_else(|| r.error(format!("unknown filter \"{name}\"")))?;
                o.filter.kind = kind;
                o.filter.width = v(1);
                o.filter.height = Some(v(2));
                o.origin("hider.filter", &r.at, r.name());
            }
            K::Exposure => {
                if (v(0), v(1)) != (1.0, 1.0) {
                    let w = r.warning("exposure is not supported yet: gain 1 and gamma 1 are used");
                    warned.push(("exposure".to_string(), w));
                }
            }
            K::Quantize => {}
            K::Display => {
                let name = r.string(0).unwrap_or_default();
                let (extra, name) = match name.strip_prefix('+') {
                    Some(n) => (true, n),
                    None => (false, name),
                };
                let mode = r.string(2).unwrap_or_default();
                let source = aov_source(mode).map(|s| (s, None)).or_else(|| output_variable(mode));
                if let (true, Some((source, variable))) = (extra, source) {
                    // An output variable: a layer of the main output (docs/outputs.md).
                    let filter = r.param("filter").and_then(|p| p.strings()).and_then(|f| match f
                        .first()
                        .map(String::as_str)
                    {
                        Some("min") => Some(AovFilter::Min),
                        Some("max") => Some(AovFilter::Max),
                        Some("zmin") => Some(AovFilter::Zmin),
                        Some("nearest") => Some(AovFilter::Nearest),
                        _ => None,
                    });
                    let aov = match variable {
                        Some((name, ty)) => Aov::output(&name, ty),
                        None => Aov::new(source),
                    };
                    o.aovs.push(Aov { filter, ..aov });
                    return Ok(());
                }
                let d = Display {
                    name: name.to_string(),
                    driver: r.string(1).unwrap_or_default().to_string(),
                    mode: r.string(2).unwrap_or_default().to_string(),
                    extra,
                    at: r.at.clone(),
                };
                if !extra {
                    o.displays.clear();
                }
                o.displays.push(d);
            }
            K::Hider => {
                let name = r.string(0).unwrap_or_default();
                o.method = match name {
                    "hidden" | "stochastic" => HiderMethod::Stochastic,
                    "raytrace" => HiderMethod::RayTrace,
                    other => {
                        return Err(r.error(format!(
                            "unknown hider \"{other}\" (hidden, stochastic or raytrace)"
                        )));
                    }
                };
                if let Some(j) = r.param("jitter").and_then(|p| {
                    p.floats()
                        .map(<[f32]>::to_vec)
                        .or_else(|| p.ints().map(|i| i.iter().map(|&k| k as f32).collect()))
                }) {
                    o.jitter = j.first().is_some_and(|&x| x != 0.0);
                }
                if let Some(p) = r.param("depthfilter") {
                    o.depth_filter = match p.strings().and_then(|s| s.first()).map(String::as_str) {
                        Some("min") => DepthFilter::Min,
                        Some("max") => DepthFilter::Max,
                        Some("average") => DepthFilter::Average,
                        Some("midpoint") => DepthFilter::Midpoint,
                        _ => {
                            return Err(r.param_error(
                                p,
                                "must be \"min\", \"max\", \"average\" or \"midpoint\"",
                            ));
                        }
                    };
                }
                o.origin("hider.method", &r.at, r.name());
            }
            K::Option => {
                let name = r.string(0).unwrap_or_default().to_string();
                for p in &r.params {
                    match (name.as_str(), p.name.as_str()) {
                        ("limits", "bucketsize") => {
                            let b: Vec<i32> = p.ints().map(<[i32]>::to_vec).unwrap_or_else(|| {
                                p.floats().unwrap_or(&[]).iter().map(|&f| f as i32).collect()
                            });
                            if b.len() != 2 || b.iter().any(|&k| k < 1) {
                                return Err(r.param_error(p, "must be two sizes of at least 1"));
                            }
                            o.bucket_size = Some((b[0] as u32, b[1] as u32));
                            o.origin("hider.bucket_size", &r.at, r.name());
                        }
                        ("limits", "gridsize") => {
                            let g = p
                                .ints()
                                .and_then(|v| v.first().copied())
                                .or_else(|| p.floats().and_then(|v| v.first()).map(|&f| f as i32));
                            match g {
                                Some(g) if g >= 1 => {
                                    o.max_grid_size = Some(g as u32);
                                    o.origin("hider.max_grid_size", &r.at, r.name());
                                }
                                _ => return Err(r.param_error(p, "must be one size of at least 1")),
                            }
                        }
                        ("searchpath", kind) if Kind::of(kind).is_some() => {
                            let Some(kind) = Kind::of(kind) else { continue };
                            let Some([value]) = p.strings() else {
                                return Err(r.param_error(p, "must be one string of directories"));
                            };
                            let reader = &self.reader;
                            o.search.set(kind, value, |d| reader.resolve_archive(d, &r.at));
                        }
                        ("statistics", _) | ("searchpath", _) => {}
                        _ => {
                            let w = Warning {
                                at: r.param_location(p),
                                message: format!(
                                    "Option: \"{name}\" \"{}\" is not supported: ignored",
                                    p.name
                                ),
                            };
                            warned.push((format!("option {name} {}", p.name), w));
                        }
                    }
                }
            }
            _ => {
                let w = r.warning("not supported: ignored");
                warned.push((format!("request {}", r.name()), w));
            }
        }
        Ok(())
    }
}

/// The beauty's modes: an extra `Display` of one of these writes the image itself.
const IMAGE_MODES: &[&str] = &["rgb", "rgba", "rgbz", "rgbaz", "a", "az", "r", "g", "b"];

/// An output variable's name and declared type.
type Variable = (String, Option<VariableType>);

/// A shader output variable a `Display` mode names (not one of [`aov_source`]'s, nor an
/// image mode): its name, and its type if the mode declares one (`"varying color glow"`).
fn output_variable(mode: &str) -> Option<(AovSource, Option<Variable>)> {
    let words: Vec<&str> = mode.split_whitespace().collect();
    let name = *words.last()?;
    let ident = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !ident || IMAGE_MODES.contains(&name) {
        return None;
    }
    let ty = words.iter().rev().skip(1).find_map(|w| match *w {
        "float" => Some(VariableType::Float),
        "color" => Some(VariableType::Color),
        "point" => Some(VariableType::Point),
        "vector" => Some(VariableType::Vector),
        "normal" => Some(VariableType::Normal),
        _ => None,
    });
    Some((AovSource::Output, Some((name.to_string(), ty))))
}

/// The AOV a `Display` mode names: RenderMan's variable names (`"N"`, `"P"`, `"Ci"`, `"Oi"`,
/// `"z"`, `"s"`, `"t"`, `"dPdtime"`, `"__ambient"`, `"__diffuse"`, `"__specular"`), the last
/// word of a declared one (`"varying normal N"`), and `"id"` / `"object_id"` and
/// `"material_id"`. The beauty's modes (`"rgba"`, `"rgb"`, `"rgbaz"`) are not AOVs.
pub(crate) fn aov_source(mode: &str) -> Option<AovSource> {
    let word = mode.split_whitespace().last().unwrap_or_default();
    Some(match word {
        "Ci" => AovSource::Ci,
        "Oi" => AovSource::Oi,
        "z" | "Z" => AovSource::Z,
        "N" => AovSource::N,
        "P" => AovSource::P,
        "s" => AovSource::S,
        "t" => AovSource::T,
        "dPdtime" => AovSource::DPdtime,
        "id" | "object_id" => AovSource::ObjectId,
        "material_id" => AovSource::MaterialId,
        "__ambient" => AovSource::Ambient,
        "__diffuse" => AovSource::Diffuse,
        "__specular" => AovSource::Specular,
        _ => return None,
    })
}
