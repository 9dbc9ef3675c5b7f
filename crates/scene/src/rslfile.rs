//! A RON scene's shading-language surfaces (issue #30): every object whose material is
//! `Shader(name, params, ...)` gets its compiled surface shader and parameter values as its
//! [`ObjectShaders`], found along the scene's `shader_path` and compiled once per source.
//!
//! Invariants: the search runs over `shader_path` in order, each folder relative to the
//! scene file's, `@` standing for the built-in standard shaders; an empty path is the scene's
//! folder, then `@`. A parameter value must fit the parameter's declared type (a number for a
//! float, a number or triple for a colour, point, vector or normal, a string for a string, a
//! list of the array's length or a matrix's 16); every other case is an error naming the
//! field. A RON scene's "shader" space is its world space.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use reyes_sl::exec::{Num, Value};
use reyes_sl::{BaseType, CheckedShader, ShaderKind};

use crate::model::{Material, ObjectShaders, Scene, ShaderInstance, ShaderParam};

/// A failure: the field's path and what is wrong.
pub(crate) type Failure = (String, String);

/// Compiles and binds every `Shader` material of `scene` (read from `file`).
pub(crate) fn resolve(scene: &mut Scene, file: &Path) -> Result<(), Failure> {
    let base = file.parent().map(Path::to_path_buf).unwrap_or_default();
    let path: Vec<Option<PathBuf>> = if scene.shader_path.is_empty() {
        vec![Some(base.clone()), None]
    } else {
        scene.shader_path.iter().map(|d| if d == "@" { None } else { Some(base.join(d)) }).collect()
    };
    let dirs: Vec<PathBuf> = path.iter().flatten().cloned().collect();
    let mut compiled: HashMap<String, Arc<CheckedShader>> = HashMap::new();
    for (i, object) in scene.objects.iter_mut().enumerate() {
        let Material::Shader { name, params, .. } = &object.material else { continue };
        let field = format!("objects[{i}].material");
        let (text, shown, includes) =
            find(name, &path, &dirs).map_err(|m| (field.clone(), m))?.ok_or_else(|| {
                let searched: Vec<String> = path
                    .iter()
                    .map(|d| d.as_ref().map_or("@".into(), |d| d.display().to_string()))
                    .collect();
                let message = format!(
                    "no shader \"{name}\": no {name}.sl along the shader path ({})",
                    searched.join(", ")
                );
                (field.clone(), message)
            })?;
        let shader = match compiled.get(&text) {
            Some(s) => s.clone(),
            None => {
                let s = reyes_sl::compile_str(&shown, &text, &includes)
                    .map_err(|e| (field.clone(), e.to_string()))?;
                let s = Arc::new(s);
                compiled.insert(text, s.clone());
                s
            }
        };
        if shader.kind != ShaderKind::Surface {
            let message = format!("shader \"{name}\" ({shown}) is not a surface shader");
            return Err((field, message));
        }
        let mut values = Vec::new();
        for (pname, v) in params {
            let at = format!("{field}.params");
            let Some(p) = shader.param(pname) else {
                return Err((at, format!("shader \"{name}\" has no parameter \"{pname}\"")));
            };
            let value = bind(p.ty, v)
                .ok_or_else(|| (at, format!("\"{pname}\": {} does not fit a {}", show(v), p.ty)))?;
            values.push((pname.clone(), value));
        }
        let instance = ShaderInstance {
            shader,
            params: values,
            shader_to_world: reyes_sl::exec::space::IDENTITY,
            file: shown,
        };
        let shaders = ObjectShaders { surface: Some(instance), ..ObjectShaders::default() };
        object.shaders = Some(Arc::new(shaders));
    }
    Ok(())
}

/// The source of shader `name` along `path` (`None`: the built-in shaders), shown as, and
/// the folders its `#include`s search: its own, then `dirs`.
fn find(
    name: &str,
    path: &[Option<PathBuf>],
    dirs: &[PathBuf],
) -> Result<Option<(String, String, Vec<PathBuf>)>, String> {
    for entry in path {
        match entry {
            None => {
                if let Some(text) = reyes_sl::shaders::standard(name) {
                    return Ok(Some((text.to_string(), format!("{name}.sl (built in)"), vec![])));
                }
            }
            Some(dir) => {
                let file = dir.join(format!("{name}.sl"));
                if !file.is_file() {
                    continue;
                }
                let bytes = std::fs::read(&file).map_err(|e| format!("{}: {e}", file.display()))?;
                let mut includes = vec![dir.clone()];
                includes.extend(dirs.iter().filter(|d| *d != dir).cloned());
                let text = String::from_utf8_lossy(&bytes).into_owned();
                return Ok(Some((text, file.display().to_string(), includes)));
            }
        }
    }
    Ok(None)
}

/// The value `v` as a parameter of type `ty`, if it fits.
fn bind(ty: reyes_sl::Type, v: &ShaderParam) -> Option<Value> {
    let scalar = |x: f32| Value::Num(Num::scalar(x));
    match (ty.array, ty.base, v) {
        (Some(n), BaseType::Float, ShaderParam::List(xs)) if xs.len() == n as usize => {
            Some(Value::Array(xs.iter().map(|&x| scalar(x)).collect()))
        }
        (Some(_), _, _) => None,
        (None, BaseType::Float, ShaderParam::Float(x)) => Some(scalar(*x)),
        (None, BaseType::String, ShaderParam::Str(s)) => Some(Value::Str(s.clone())),
        (None, BaseType::Matrix, ShaderParam::List(xs)) if xs.len() == 16 => {
            Some(Value::Num(Num::uniform(xs)))
        }
        (None, BaseType::Color | BaseType::Point | BaseType::Vector | BaseType::Normal, v) => {
            match v {
                ShaderParam::Float(x) => Some(Value::Num(Num::uniform(&[*x; 3]))),
                ShaderParam::Triple((a, b, c)) => Some(Value::Num(Num::uniform(&[*a, *b, *c]))),
                _ => None,
            }
        }
        _ => None,
    }
}

fn show(v: &ShaderParam) -> String {
    match v {
        ShaderParam::Float(_) => "a number".into(),
        ShaderParam::Triple(_) => "a triple".into(),
        ShaderParam::Str(_) => "a string".into(),
        ShaderParam::List(xs) => format!("a list of {}", xs.len()),
    }
}
