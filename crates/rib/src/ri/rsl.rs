//! Shaders written in the RenderMan Shading Language (issue #30): a `Surface`,
//! `Displacement`, `LightSource`, `Atmosphere` or `Imager` naming a shader that is not one of
//! the built-in standard ones is looked up as `NAME.sl` along `Option "searchpath" "shader"`
//! (default: the folder of the RIB file naming it), compiled when the scene loads, and its
//! request's parameters bound by the shader's declared types.
//!
//! Invariants: a source is compiled once per load (the table is keyed by the file's text, so
//! two names of one file, or one file read twice, share one `Arc`); a compile error stops the
//! load with the compiler's one-line `file:line:col: message`; a parameter the shader does
//! not declare, or a value that does not fit its type, is a warning and the default is kept;
//! a name with no source anywhere is `None` (the caller keeps its stand-in and warning). The
//! Specification's standard shaders that have no native form (`fog`, `depthcue`, ...) come
//! from the compiler's own copies (`reyes_scene::sl::shaders`) when no file of that name is found.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use glam::DMat4;
use reyes_scene::sl::exec::Num;
use reyes_scene::sl::{BaseType, CheckedShader, ShaderKind};
use reyes_scene::{PrimitiveValue, ShaderInstance, ShaderValue};

use super::frame::Machine;
use super::search::{Kind, Lookup};
use super::state::SurfaceShader;
use crate::{Class, Location, Param, RibError, Warning};

/// Surface shaders the renderer has natively (`shaders.rs`).
pub(super) const NATIVE_SURFACES: &[&str] =
    &["defaultsurface", "metal", "shinymetal", "constant", "matte", "plastic", "paintedplastic"];
/// Native surfaces that read lights, and whose built-in shading-language copy needs no
/// texture: under a light shader they run as that copy.
const LIT_SURFACES: &[&str] = &["matte", "metal", "plastic"];
/// Displacement shaders the renderer has natively.
pub(super) const NATIVE_DISPLACEMENTS: &[&str] = &["bumpy"];
/// Light shaders the renderer has natively.
pub(super) const NATIVE_LIGHTS: &[&str] =
    &["ambientlight", "distantlight", "pointlight", "spotlight"];

/// The shaders compiled during one load, by source text.
#[derive(Default)]
pub(crate) struct ShaderTable {
    by_text: HashMap<String, Arc<CheckedShader>>,
}

/// A DMat4 (column vectors) as the shading language's matrix (row vectors, row by row).
pub(super) fn sl_matrix(m: &DMat4) -> [f32; 16] {
    m.to_cols_array().map(|x| x as f32)
}

impl Machine {
    /// True if `name.sl` is a file on the shader search path (not a built-in shader).
    fn on_path(&self, name: &str, at: &Location) -> bool {
        let file = format!("{name}.sl");
        let reader = &self.reader;
        matches!(
            self.frame_options.search.find(Kind::Shader, &file, |n| reader.resolve_archive(n, at)),
            Lookup::Unsearched(p) | Lookup::Found(p) if p.is_file()
        )
    }

    /// The shader `name` of `kind` named at `at` by `request`, compiled, with its file's name;
    /// `None` when no source is found.
    fn compiled(
        &mut self,
        name: &str,
        kind: ShaderKind,
        at: &Location,
        request: &'static str,
    ) -> Result<Option<(Arc<CheckedShader>, String)>, RibError> {
        let file = format!("{name}.sl");
        let reader = &self.reader;
        let found = match self
            .frame_options
            .search
            .find(Kind::Shader, &file, |n| reader.resolve_archive(n, at))
        {
            Lookup::Unsearched(p) | Lookup::Found(p) if p.is_file() => Some(p),
            _ => None,
        };
        let builtin = found.is_none();
        let (text, shown, dir) = match &found {
            // Bytes that are not UTF-8 (a Latin-1 comment) read as U+FFFD, as the compiler
            // reads an #include; `#include` looks in the shader's folder, then along the
            // shader search path.
            Some(path) => match std::fs::read(path) {
                Ok(bytes) => {
                    let text = String::from_utf8_lossy(&bytes).into_owned();
                    let mut dirs = vec![path.parent().map(PathBuf::from).unwrap_or_default()];
                    for d in self.frame_options.search.dirs(Kind::Shader) {
                        if !dirs.contains(&d) {
                            dirs.push(d);
                        }
                    }
                    (text, path.display().to_string(), dirs)
                }
                Err(e) => {
                    return Err(RibError::Shader {
                        at: at.clone(),
                        message: format!("{}: cannot read: {e}", path.display()),
                    });
                }
            },
            None => match reyes_scene::sl::shaders::standard(name) {
                Some(text) => (text.to_string(), format!("{name}.sl (built in)"), Vec::new()),
                None => return Ok(None),
            },
        };
        let shader = match self.sl.by_text.get(&text) {
            Some(s) => s.clone(),
            None => {
                let s = reyes_scene::sl::compile_str(&shown, &text, &dir)
                    .map_err(|e| RibError::Shader { at: at.clone(), message: e.to_string() })?;
                let s = Arc::new(s);
                self.sl.by_text.insert(text, s.clone());
                s
            }
        };
        if shader.kind != kind && builtin {
            // A standard shader of another type (`Surface "fog"`) names no shader of this
            // one: unknown, as before shaders were compiled.
            return Ok(None);
        }
        if shader.kind != kind {
            return Err(RibError::Request {
                at: at.clone(),
                request,
                message: format!(
                    "shader \"{name}\" ({shown}) is a {} shader, not a {} shader",
                    kind_name(shader.kind),
                    kind_name(kind)
                ),
            });
        }
        Ok(Some((shader, shown)))
    }

    /// The instance of the shader `s` (of `kind`, set by `request`) placed by `to_world` (its
    /// "shader" space), if it names a shading-language shader with a source.
    pub(super) fn sl_instance(
        &mut self,
        s: &SurfaceShader,
        kind: ShaderKind,
        request: &'static str,
        to_world: &DMat4,
    ) -> Result<Option<ShaderInstance>, RibError> {
        let (Some(name), Some(at)) = (&s.name, &s.at) else { return Ok(None) };
        let Some((shader, file)) = self.compiled(name, kind, at, request)? else {
            return Ok(None);
        };
        // The shader declares its parameters: the reader's warnings that a parameter of the
        // request is not declared are answered (those it lacks get a warning of their own).
        let declared: Vec<Location> =
            s.params.iter().filter(|p| p.decl.is_none()).map(|p| at.at(p.at)).collect();
        self.warnings
            .retain(|w| !(declared.contains(&w.at) && w.message.contains("is not declared")));
        let mut warnings = Vec::new();
        let params = bind(&shader, &s.params, at, &mut warnings);
        for w in warnings {
            let key = format!("sl param {w}");
            self.warn_once(key, w);
        }
        self.note_maps(&params, at);
        Ok(Some(ShaderInstance { shader, params, shader_to_world: sl_matrix(to_world), file }))
    }
}

impl Machine {
    /// Records the texture maps an instance's string parameters name (issue #32): each value
    /// that is a file along the texture search path (or beside the RIB file without one).
    fn note_maps(&mut self, params: &[(String, reyes_scene::ShaderValue)], at: &Location) {
        use reyes_scene::ShaderValue as V;
        let mut names = Vec::new();
        for (_, v) in params {
            match v {
                V::Str(s) => names.push(s.clone()),
                V::Array(xs) => names.extend(xs.iter().filter_map(|x| match x {
                    V::Str(s) => Some(s.clone()),
                    _ => None,
                })),
                V::Num(_) => {}
            }
        }
        let Some(b) = &self.build else { return };
        let known = |n: &str| b.shaders.maps.iter().any(|(m, _)| m == n);
        let names: Vec<String> = names.into_iter().filter(|n| !n.is_empty() && !known(n)).collect();
        for name in names {
            let found = self
                .frame_options
                .search
                .find(Kind::Texture, &name, |n| self.reader.resolve_archive(n, at));
            let path = match found {
                Lookup::Unsearched(p) | Lookup::Found(p) | Lookup::Missing(p, _) => p,
            };
            // A map the file itself writes before this frame renders (a depth output of an
            // earlier frame, a `Make*` request) is known though it does not exist yet.
            let beside = self.reader.resolve_archive(&name, at);
            let made = self.multipass.made.iter().find(|m| **m == path || **m == beside).cloned();
            let path = made.unwrap_or(path);
            if path.is_file() || self.multipass.made.contains(&path) {
                if let Some(b) = &mut self.build
                    && !b.shaders.maps.iter().any(|(m, _)| *m == name)
                {
                    b.shaders.maps.push((name, path));
                }
            } else if looks_like_a_map(&name) {
                let w = Warning {
                    at: at.clone(),
                    message: format!(
                        "texture \"{name}\" is not found (along the texture search path, or beside the RIB file): its lookups read 0"
                    ),
                };
                self.warn_once(format!("missing map {name}"), w);
            }
        }
    }
}

/// True if a shader parameter's string value names a texture file by its extension (then a
/// missing file is worth a warning; other strings may be anything).
fn looks_like_a_map(name: &str) -> bool {
    let ext = std::path::Path::new(name).extension().and_then(|e| e.to_str()).unwrap_or("");
    let ext = ext.to_ascii_lowercase();
    ["tex", "tx", "tdl", "env", "shd", "sm", "zfile", "tif", "tiff", "png", "jpg", "jpeg", "exr"]
        .contains(&ext.as_str())
}

fn kind_name(k: ShaderKind) -> &'static str {
    match k {
        ShaderKind::Surface => "surface",
        ShaderKind::Displacement => "displacement",
        ShaderKind::Light => "light",
        ShaderKind::Volume => "volume",
        ShaderKind::Imager => "imager",
    }
}

/// Floats per element of a parameter type (0: a string).
fn width(b: BaseType) -> usize {
    match b {
        BaseType::Float => 1,
        BaseType::Color | BaseType::Point | BaseType::Vector | BaseType::Normal => 3,
        BaseType::Matrix => 16,
        _ => 0,
    }
}

/// The value of `p` for a parameter of type `ty`, if it fits (numbers for numbers, strings
/// for strings, an array's full length; one number for a triple is broadcast).
fn value_of(ty: reyes_scene::sl::Type, p: &Param) -> Option<ShaderValue> {
    let w = width(ty.base);
    let count = ty.array.map_or(1, |n| n.max(1) as usize);
    if w == 0 {
        let s = p.strings()?;
        return match ty.array {
            None if s.len() == 1 => Some(ShaderValue::Str(s[0].clone())),
            Some(_) if s.len() == count => {
                Some(ShaderValue::Array(s.iter().map(|x| ShaderValue::Str(x.clone())).collect()))
            }
            _ => None,
        };
    }
    let floats: Vec<f32> = match (p.floats(), p.ints()) {
        (Some(f), _) => f.to_vec(),
        (None, Some(i)) => i.iter().map(|&x| x as f32).collect(),
        _ => return None,
    };
    let one = |c: &[f32]| ShaderValue::Num(Num::uniform(c));
    match ty.array {
        None if floats.len() == w => Some(one(&floats)),
        None if floats.len() == 1 && w == 3 => Some(one(&[floats[0]; 3])),
        Some(_) if floats.len() == w * count => {
            Some(ShaderValue::Array(floats.chunks(w).map(one).collect()))
        }
        _ => None,
    }
}

/// The shader's parameter values from a request's parameters: each by the parameter's
/// declared type; the others are warnings.
pub(super) fn bind(
    shader: &CheckedShader,
    params: &[Param],
    at: &Location,
    warnings: &mut Vec<Warning>,
) -> Vec<(String, ShaderValue)> {
    let mut out = Vec::new();
    for p in params {
        let here = at.at(p.at);
        let Some(var) = shader.param(&p.name) else {
            warnings.push(Warning {
                at: here,
                message: format!(
                    "shader \"{}\" has no parameter \"{}\": ignored",
                    shader.name, p.name
                ),
            });
            continue;
        };
        match value_of(var.ty, p) {
            Some(v) => out.push((p.name.clone(), v)),
            None => warnings.push(Warning {
                at: here,
                message: format!(
                    "shader \"{}\": parameter \"{}\" is declared {}; the value given does not fit: the default is used",
                    shader.name, p.name, var.ty
                ),
            }),
        }
    }
    out
}

/// The primitive variables of a primitive's request that name parameters of `shader`:
/// constant and uniform ones as one value, varying and vertex ones given at the four corners
/// of a parametric shape as corners; others are reported and left out.
pub(super) fn primitive_values(
    shader: &CheckedShader,
    params: &[Param],
    at: &Location,
    warnings: &mut Vec<Warning>,
) -> Vec<(String, PrimitiveValue)> {
    let mut out = Vec::new();
    for p in params {
        let Some(var) = shader.param(&p.name) else { continue };
        let class = p.decl.map_or(Class::Uniform, |d| d.class);
        let w = width(var.ty.base);
        let value = match class {
            Class::Constant | Class::Uniform => value_of(var.ty, p).map(PrimitiveValue::Uniform),
            Class::Varying | Class::Vertex
                if var.ty.array.is_none()
                    && w > 0
                    && w <= 3
                    && var.detail == reyes_scene::sl::Detail::Varying =>
            {
                match p.floats() {
                    Some(f) if f.len() == 4 * w => {
                        Some(PrimitiveValue::Corners { width: w, data: f.to_vec() })
                    }
                    _ => None,
                }
            }
            _ => None,
        };
        match value {
            Some(v) => out.push((p.name.clone(), v)),
            None => warnings.push(Warning {
                at: at.at(p.at),
                message: format!(
                    "primitive variable \"{}\" is not bound to shader \"{}\" (only constant and uniform values, or varying and vertex values at the four corners of a parametric shape for a varying parameter, are): ignored",
                    p.name, shader.name
                ),
            }),
        }
    }
    out
}

impl Machine {
    /// The shading-language shaders of a primitive made by `r` under the attributes `a`,
    /// placed by `to_world`: `None` when every shader it names is native (or unknown).
    pub(super) fn object_shaders(
        &mut self,
        a: &super::state::Attributes,
        r: &crate::Request,
        to_world: &DMat4,
    ) -> Result<Option<Arc<reyes_scene::ObjectShaders>>, RibError> {
        // A standard name is native unless the user's NAME.sl is on the search path, which
        // then comes first, as a RenderMan renderer's search finds it.
        let native = |m: &Machine, s: &SurfaceShader, list: &[&str]| {
            s.name.as_deref().is_none_or(|n| list.contains(&n) && !m.on_path(n, &r.at))
        };
        let mut o = reyes_scene::ObjectShaders::default();
        // Under a light shader, the standard surfaces that read lights run as the built-in
        // shading-language copies, so that the light shader lights them (the native models
        // see only the native lights).
        let under_shader = self
            .build
            .as_ref()
            .is_some_and(|b| b.shader_light_slots.iter().any(|s| a.lights_on.contains(s)));
        let lit = a.surface.name.as_deref().is_some_and(|n| LIT_SURFACES.contains(&n));
        if !native(self, &a.surface, NATIVE_SURFACES) || (under_shader && lit) {
            o.surface = self.sl_instance(&a.surface, ShaderKind::Surface, "Surface", to_world)?;
        }
        if !native(self, &a.displacement, NATIVE_DISPLACEMENTS) {
            o.displacement = self.sl_instance(
                &a.displacement,
                ShaderKind::Displacement,
                "Displacement",
                to_world,
            )?;
        }
        if a.atmosphere.name.is_some() {
            o.atmosphere =
                self.sl_instance(&a.atmosphere, ShaderKind::Volume, "Atmosphere", to_world)?;
            if o.atmosphere.is_none()
                && let (Some(name), Some(at)) = (&a.atmosphere.name, &a.atmosphere.at)
            {
                if self.options.strict {
                    return Err(RibError::Request {
                        at: at.clone(),
                        request: "Atmosphere",
                        message: format!("unknown volume shader \"{name}\" (--strict)"),
                    });
                }
                let w = Warning {
                    at: at.clone(),
                    message: format!(
                        "Atmosphere: unknown shader \"{name}\" (no {name}.sl): ignored"
                    ),
                };
                self.warn_once(format!("atmosphere {name}"), w);
            }
        }
        if o.is_empty() {
            return Ok(None);
        }
        o.displacement_bound = a.displacement_bound.unwrap_or(0.0);
        if let (Some(d), None) = (&o.displacement, a.displacement_bound)
            && let Some(at) = &a.displacement.at
        {
            let w = Warning {
                at: at.clone(),
                message: format!(
                    "Displacement: shader \"{}\" without Attribute \"displacementbound\": its bound is taken as 0, so displaced points may be cut at bucket edges (and are counted as escaped)",
                    d.name()
                ),
            };
            self.warn_once(format!("sl displacement bound {at}"), w);
        }
        let mut warnings = Vec::new();
        for s in [&o.surface, &o.displacement].into_iter().flatten() {
            for (name, v) in primitive_values(&s.shader, &r.params, &r.at, &mut warnings) {
                if !o.primitive.iter().any(|(n, _)| *n == name) {
                    o.primitive.push((name, v));
                }
            }
        }
        for w in warnings {
            let key = format!("sl primvar {w}");
            self.warn_once(key, w);
        }
        Ok(Some(Arc::new(o)))
    }

    /// `LightSource` of a shading-language light shader: true if `name` is one (then the
    /// light is added, as a placeholder light of the model that lights nothing natively, and
    /// switched on like any light).
    pub(super) fn sl_light(
        &mut self,
        r: &crate::Request,
        name: &str,
        handle: &str,
    ) -> Result<bool, RibError> {
        if NATIVE_LIGHTS.contains(&name) && !self.on_path(name, &r.at) {
            return Ok(false);
        }
        let s = SurfaceShader::of(r);
        let to_world = self.to_world().at(f32::NEG_INFINITY);
        let Some(instance) = self.sl_instance(&s, ShaderKind::Light, "LightSource", &to_world)?
        else {
            return Ok(false);
        };
        let Some(b) = &mut self.build else {
            let w = r.warning(format!(
                "light shader \"{name}\" before WorldBegin: shading-language lights are placed inside the world only; ignored"
            ));
            self.warnings.push(w);
            return Ok(true);
        };
        let index = b.light_count() as u32;
        let placeholder = reyes_scene::Light::Ambient { color: [0.0; 3], intensity: 0.0 };
        let slot = b.add_light(handle.to_string(), placeholder, r.at.clone());
        b.shaders.lights.push((index, instance));
        b.shader_light_slots.push(slot);
        if !self.attributes.lights_on.contains(&slot) {
            self.attributes.lights_on.push(slot);
        }
        Ok(true)
    }

    /// `Imager` of a shading-language imager shader: true if it names one with a source.
    pub(super) fn sl_imager(&mut self, r: &crate::Request) -> Result<bool, RibError> {
        let s = SurfaceShader::of(r);
        let Some(instance) =
            self.sl_instance(&s, ShaderKind::Imager, "Imager", &DMat4::IDENTITY)?
        else {
            return Ok(false);
        };
        self.frame_options.imager = Some(instance);
        Ok(true)
    }
}
