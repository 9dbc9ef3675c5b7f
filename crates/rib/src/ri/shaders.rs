//! RenderMan's standard shaders (Spec 3.2, Appendix A) as the scene model's materials and
//! lights, with the Specification's parameters and defaults.
//!
//! Invariants: a shader parameter is read only when its declared type is the one the standard
//! shader gives it (a float or a colour of the right size); anything else is a warning and the
//! default is kept. Unknown shaders are named once per name in a warning (an error with
//! `--strict`) and stand in as `plastic` on the primitive's `Cs` and `Os`.

use reyes_scene::{ColorSpace, Displacement, Light, Maps, Material, Scalar, TextureMap};

use crate::ri::state::SurfaceShader;
use crate::ri::xform::{Xform, point};
use crate::{Location, Param, Warning};

/// A float parameter of a shader, if given as one float.
pub(super) fn float(params: &[Param], name: &str) -> Option<f32> {
    params.iter().find(|p| p.name == name).and_then(|p| match p.floats() {
        Some([v]) => Some(*v),
        _ => None,
    })
}

/// A colour parameter of a shader, if given as three floats.
pub(super) fn color(params: &[Param], name: &str) -> Option<[f32; 3]> {
    params.iter().find(|p| p.name == name).and_then(|p| match p.floats() {
        Some([r, g, b]) => Some([*r, *g, *b]),
        _ => None,
    })
}

/// A point parameter of a shader, if given as three floats.
fn point_param(params: &[Param], name: &str) -> Option<[f32; 3]> {
    color(params, name)
}

/// Warnings for the parameters of `params` that a standard shader does not take, or takes in
/// another form.
pub(super) fn unused(
    shader: &str,
    params: &[Param],
    known: &[(&str, usize)],
    at: &Location,
    warnings: &mut Vec<Warning>,
) {
    for p in params {
        match known.iter().find(|(n, _)| *n == p.name) {
            None => warnings.push(Warning {
                at: at.at(p.at),
                message: format!("{shader}: unknown parameter \"{}\" ignored", p.name),
            }),
            Some((_, n)) if p.floats().map(<[f32]>::len) != Some(*n) => warnings.push(Warning {
                at: at.at(p.at),
                message: format!(
                    "{shader}: parameter \"{}\" must be {n} number{}; the default is used",
                    p.name,
                    if *n == 1 { "" } else { "s" }
                ),
            }),
            _ => {}
        }
    }
}

/// What a surface shader becomes.
pub(crate) enum SurfaceResult {
    /// A material.
    Material(Material),
    /// An unknown shader, standing in as plastic; the name is reported.
    Unknown(Material, String),
}

/// The material of `surface` on a primitive of colour `cs` and opacity `os`. Warnings about
/// parameters are pushed to `warnings` (once per shader request: `reported` remembers them).
pub(crate) fn material(
    surface: &SurfaceShader,
    cs: [f32; 3],
    os: [f32; 3],
    warnings: &mut Vec<Warning>,
    report: bool,
) -> SurfaceResult {
    let p = &surface.params;
    let f = |name: &str, default: f32| float(p, name).unwrap_or(default);
    let mut check = |shader: &str, known: &[(&str, usize)]| {
        if report && let Some(at) = &surface.at {
            unused(shader, p, known, at, warnings);
        }
    };
    let plastic = |p: &[Param]| Material::Plastic {
        color: cs,
        opacity: os,
        ka: float(p, "Ka").unwrap_or(1.0),
        kd: float(p, "Kd").unwrap_or(0.5),
        ks: float(p, "Ks").unwrap_or(0.5),
        roughness: float(p, "roughness").unwrap_or(0.1),
        specular_color: color(p, "specularcolor").unwrap_or([1.0; 3]),
    };
    match surface.name.as_deref() {
        None | Some("defaultsurface") => {
            // No shader: RenderMan's defaultsurface, a headlight at the eye.
            check("defaultsurface", &[("Ka", 1), ("Kd", 1)]);
            SurfaceResult::Material(Material::DefaultSurface {
                color: cs,
                opacity: os,
                ka: f("Ka", 0.2),
                kd: f("Kd", 0.8),
            })
        }
        Some(name @ ("metal" | "shinymetal")) => {
            let mut known = vec![("Ka", 1), ("Ks", 1), ("roughness", 1)];
            if name == "shinymetal" {
                known.extend([("Kr", 1), ("texturename", 1)]);
            }
            check(name, &known);
            SurfaceResult::Material(Material::Metal {
                color: cs,
                opacity: os,
                ka: f("Ka", 1.0),
                ks: f("Ks", 1.0),
                roughness: f("roughness", 0.1),
            })
        }
        Some("constant") => {
            check("constant", &[]);
            SurfaceResult::Material(Material::Constant { color: cs, opacity: os })
        }
        Some("matte") => {
            check("matte", &[("Ka", 1), ("Kd", 1)]);
            SurfaceResult::Material(Material::Matte {
                color: cs,
                opacity: os,
                ka: f("Ka", 1.0),
                kd: f("Kd", 1.0),
            })
        }
        Some("plastic") => {
            check(
                "plastic",
                &[("Ka", 1), ("Kd", 1), ("Ks", 1), ("roughness", 1), ("specularcolor", 3)],
            );
            SurfaceResult::Material(plastic(p))
        }
        Some("paintedplastic") => {
            // `texturename`, a string, is read by `lookdev`.
            let numbers: Vec<Param> =
                p.iter().filter(|q| q.name != "texturename").cloned().collect();
            if report && let Some(at) = &surface.at {
                unused(
                    "paintedplastic",
                    &numbers,
                    &[("Ka", 1), ("Kd", 1), ("Ks", 1), ("roughness", 1), ("specularcolor", 3)],
                    at,
                    warnings,
                );
            }
            SurfaceResult::Material(plastic(p))
        }
        Some(other) => SurfaceResult::Unknown(plastic(&[]), other.to_string()),
    }
}

/// A light source shader placed by the transformation `to_world` (current space to ours).
pub(crate) enum LightResult {
    /// A light.
    Light(Light),
    /// A shader we do not have; the name is reported.
    Unknown(String),
}

/// Input a light shader tolerates, as RenderMan renderers do: where, what is wrong, and what
/// was done instead (the caller warns, or refuses under `--strict`).
pub(crate) struct Tolerated {
    pub at: Location,
    pub what: String,
    pub done: String,
}

/// The `"from"` and `"to"` of a light in its own space, with the Specification's defaults;
/// when they are the same point (no direction), the default direction (0, 0, 1) from
/// `"from"`, noted in `tolerated`.
fn direction(
    shader: &str,
    params: &[Param],
    at: &Location,
    tolerated: &mut Vec<Tolerated>,
) -> ([f32; 3], [f32; 3]) {
    let from = point_param(params, "from").unwrap_or([0.0; 3]);
    let to = point_param(params, "to").unwrap_or([0.0, 0.0, 1.0]);
    if from != to {
        return (from, to);
    }
    let place = params.iter().find(|p| p.name == "to").map_or(at.clone(), |p| at.at(p.at));
    let [x, y, z] = from;
    tolerated.push(Tolerated {
        at: place,
        what: format!("{shader}: \"from\" and \"to\" are the same point ({x}, {y}, {z})"),
        done: "the Specification's default direction, from (0, 0, 0) toward (0, 0, 1), is used"
            .into(),
    });
    (from, [x, y, z + 1.0])
}

/// A spotlight's `"coneangle"` and `"conedeltaangle"` in degrees (the model's unit). The
/// Specification gives them in radians; exporters often write degrees, and no cone reaches
/// pi radians, so an angle above pi is read as degrees, noted in `tolerated`. A cone angle
/// read as degrees takes its delta with it: they come from one writer.
fn cone_angles(params: &[Param], at: &Location, tolerated: &mut Vec<Tolerated>) -> (f32, f32) {
    let mut degrees_seen = false;
    let mut angle = |name: &str, default: f32| -> f32 {
        let Some(p) = params.iter().find(|p| p.name == name) else { return default };
        let Some(v) = float(params, name) else { return default };
        let why = if v > std::f32::consts::PI {
            format!("spotlight: \"{name}\" {v} is more than pi radians")
        } else if degrees_seen {
            format!("spotlight: \"{name}\" {v} comes with a cone angle in degrees")
        } else {
            return v.to_degrees();
        };
        degrees_seen = true;
        tolerated.push(Tolerated {
            at: at.at(p.at),
            what: why,
            done: format!("read as {v} degrees"),
        });
        v
    };
    let cone = angle("coneangle", 30.0);
    let delta = angle("conedeltaangle", 5.0);
    (cone, delta)
}

/// The light of `LightSource name params` under `to_world` at shutter open; what it
/// tolerates goes to `tolerated`.
pub(crate) fn light(
    name: &str,
    params: &[Param],
    to_world: &Xform,
    at: &Location,
    warnings: &mut Vec<Warning>,
    tolerated: &mut Vec<Tolerated>,
) -> LightResult {
    let m = to_world.at(f32::NEG_INFINITY);
    let intensity = float(params, "intensity").unwrap_or(1.0);
    let lightcolor = color(params, "lightcolor").unwrap_or([1.0; 3]);
    match name {
        "ambientlight" => {
            unused(name, params, &[("intensity", 1), ("lightcolor", 3)], at, warnings);
            LightResult::Light(Light::Ambient { color: lightcolor, intensity })
        }
        "distantlight" => {
            unused(
                name,
                params,
                &[("intensity", 1), ("lightcolor", 3), ("from", 3), ("to", 3)],
                at,
                warnings,
            );
            let (from, to) = direction(name, params, at, tolerated);
            let (from, to) = (point(&m, from), point(&m, to));
            LightResult::Light(Light::Distant {
                from,
                to,
                color: lightcolor,
                intensity,
                shadows: false,
            })
        }
        "pointlight" => {
            unused(name, params, &[("intensity", 1), ("lightcolor", 3), ("from", 3)], at, warnings);
            let from = point(&m, point_param(params, "from").unwrap_or([0.0; 3]));
            LightResult::Light(Light::Point { from, color: lightcolor, intensity, shadows: false })
        }
        "spotlight" => {
            unused(
                name,
                params,
                &[
                    ("intensity", 1),
                    ("lightcolor", 3),
                    ("from", 3),
                    ("to", 3),
                    ("coneangle", 1),
                    ("conedeltaangle", 1),
                    ("beamdistribution", 1),
                ],
                at,
                warnings,
            );
            let (from, to) = direction(name, params, at, tolerated);
            let (from, to) = (point(&m, from), point(&m, to));
            // The Specification's angles are radians (defaults 30 and 5 degrees).
            let (cone_angle, cone_delta) = cone_angles(params, at, tolerated);
            LightResult::Light(Light::Spot {
                from,
                to,
                color: lightcolor,
                intensity,
                cone_angle,
                cone_delta,
                beam_distribution: float(params, "beamdistribution").unwrap_or(2.0),
                shadows: false,
            })
        }
        other => LightResult::Unknown(other.to_string()),
    }
}

/// A string parameter of a shader, if given as one string.
fn string<'p>(params: &'p [Param], name: &str) -> Option<&'p str> {
    params.iter().find(|p| p.name == name).and_then(|p| match p.strings() {
        Some([s]) => Some(s.as_str()),
        _ => None,
    })
}

/// Look development of a primitive from its shaders: `paintedplastic`'s `texturename` as a
/// colour map (sRGB, periodic, over the surface's `(u, v)` scaled by `TextureCoordinates`'
/// `repeat`), and the standard displacement
/// shader `bumpy` (`P += Km * texture(texturename) * normalize(N)`, the map read as linear
/// data) as true displacement with the block's `displacementbound`. `resolve` turns a
/// texture name into a file name (along the texture search path), given where and by which
/// request it is named. Other displacement shaders
/// are unknown: reported through `unknown`, and no displacement.
pub(crate) fn lookdev(
    surface: &SurfaceShader,
    displacement: &SurfaceShader,
    bound: Option<f32>,
    repeat: (f32, f32),
    resolve: impl Fn(&str, &Location, &str) -> String,
    warnings: &mut Vec<Warning>,
    report: bool,
) -> Result<(Maps, Option<Displacement>), String> {
    let map = |file: String, color_space| TextureMap {
        file,
        color_space,
        wrap: Default::default(),
        repeat,
        width: 1.0,
    };
    let mut maps = Maps::default();
    if surface.name.as_deref() == Some("paintedplastic")
        && let (Some(name), Some(at)) = (string(&surface.params, "texturename"), &surface.at)
        && !name.is_empty()
    {
        maps.color = Some(map(resolve(name, at, "Surface"), ColorSpace::Srgb));
    }
    let displace = match (displacement.name.as_deref(), &displacement.at) {
        (Some("bumpy"), Some(at)) => {
            if report {
                let numbers: Vec<Param> = displacement
                    .params
                    .iter()
                    .filter(|q| q.name != "texturename")
                    .cloned()
                    .collect();
                unused("bumpy", &numbers, &[("Km", 1)], at, warnings);
            }
            let km = float(&displacement.params, "Km").unwrap_or(1.0);
            match string(&displacement.params, "texturename").filter(|n| !n.is_empty()) {
                Some(name) => Some(Displacement {
                    source: Scalar::Texture(map(
                        resolve(name, at, "Displacement"),
                        ColorSpace::Linear,
                    )),
                    amount: km,
                    center: 0.0,
                    bound,
                }),
                None => {
                    if report {
                        warnings.push(Warning {
                            at: at.clone(),
                            message:
                                "bumpy: no \"texturename\": displaces by 0 (texture(\"\") is 0)"
                                    .into(),
                        });
                    }
                    None
                }
            }
        }
        (Some(other), _) => return Err(other.to_string()),
        (None, _) => None,
    };
    Ok((maps, displace))
}
