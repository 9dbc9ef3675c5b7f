//! reyes-scene: the scene model, RON parsing and validation.
//!
//! Stage: first in the pipeline. Produces an immutable, validated [`Scene`] that every later
//! stage borrows. Invariants: [`parse`] and [`load`] never panic, on any input; every error
//! displays as one line naming the file, the position and the field path when known.
#![deny(missing_docs)]

pub mod animate;
pub mod blobby;
pub mod closure;
pub mod curves;
mod error;
pub mod filter;
mod locate;
mod meshfile;
pub mod model;
/// The shading-language compiler and grid machine whose shaders the model holds (re-exported
/// so that front ends and stages name the same crate through the scene).
pub use reyes_sl as sl;
pub mod patches;
mod roll;
mod rslfile;
pub mod subdiv;
mod syntax;
mod validate;
pub mod view;
pub mod xform;

use std::path::Path;

pub use closure::{Closure, closed_alone, closure};
pub use error::{LoadError, SceneError};
pub use model::*;
pub use validate::Issue;
pub use xform::{normal_matrix, object_to_world, transform_matrix};

/// Parses and validates the RON scene `text`. `file` is used only in error messages.
///
/// After validation every object's `roll` is expanded into its `motion` keys (see
/// [`Roll`]); `roll` itself is kept, so a `Scene` written back out reads back the same.
///
/// Relative texture file names are resolved against `file`'s folder ([`resolve_textures`]).
///
/// A leading byte-order mark is ignored. Errors carry the line and column of the offending
/// text and the path of the offending field, e.g.
/// `scenes/x.ron:12:30: objects[0].shape.radius: must be > 0, got -1`.
///
/// A [`Shape::MeshFile`] is read here, relative to `file`'s folder, into the mesh it holds;
/// a mesh file that cannot be read is an error of this function too (use [`parse_files`] to
/// tell it apart as I/O).
pub fn parse(text: &str, file: &Path) -> Result<Scene, SceneError> {
    parse_files(text, file).map_err(|e| match e {
        LoadError::Scene(e) | LoadError::MeshIo(e) => e,
        LoadError::Io { path, source } => SceneError {
            file: path,
            line: None,
            col: None,
            field: String::new(),
            message: source.to_string(),
        },
    })
}

/// [`parse`], telling a mesh file that cannot be read ([`LoadError::MeshIo`], exit status 1)
/// from a bad scene or a malformed mesh file ([`LoadError::Scene`], exit status 2).
pub fn parse_files(text: &str, file: &Path) -> Result<Scene, LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut scene: Scene = match ron::Options::default().from_str(text) {
        Ok(scene) => scene,
        Err(err) => return Err(syntax::from_ron(text, file, &err).into()),
    };
    let read = match meshfile::resolve(&mut scene, text, file) {
        Ok(read) => read,
        Err(meshfile::Failure::Io(e)) => return Err(LoadError::MeshIo(e)),
        Err(meshfile::Failure::Bad(e)) => return Err(e.into()),
    };
    match validate(scene).and_then(|mut scene| {
        rslfile::resolve(&mut scene, file)
            .map(|()| scene)
            .map_err(|(path, message)| Issue { path, message })
    }) {
        Ok(scene) => Ok(resolve_textures(scene, file)),
        Err(mut issue) => {
            // A fault of a mesh read from a file names the file.
            for (i, mesh) in &read {
                let shape = format!("objects[{i}].shape");
                if issue.path == shape || issue.path.starts_with(&format!("{shape}.")) {
                    issue.message =
                        format!("{} (in the mesh read from {})", issue.message, mesh.display());
                }
            }
            let pos = locate::SourceMap::scan(text).find(&issue.path);
            Err(SceneError {
                file: file.to_path_buf(),
                line: pos.map(|p| p.line),
                col: pos.map(|p| p.col),
                field: issue.path,
                message: issue.message,
            }
            .into())
        }
    }
}

/// Validates a scene built in code or by another front-end (RIB) exactly as [`parse`] validates
/// a RON file, and completes it as [`parse`] does (rolls expanded into motion keys). The error
/// names the path of the offending value; the caller maps it to a position in its own source.
pub fn validate(scene: Scene) -> Result<Scene, Issue> {
    match validate::check(&scene) {
        None => Ok(expand_rolls(scene)),
        Some(issue) => Err(issue),
    }
}

/// Validates trim loops on their own (`RiTrimCurve`, before any patch takes them): every rule
/// of [`Shape::NuPatch`]'s `trim` but the one that needs the patch's domain, which `domain`
/// supplies when given. Paths start at `trim`, e.g. `trim[0].curves[1].knot[3]`.
pub fn validate_trim(loops: &[TrimLoop], domain: Option<[f32; 4]>) -> Result<(), Issue> {
    validate::trim_loops(loops, domain)
}

/// The scene with every relative texture file name joined to the folder of `file`, the
/// scene file it was read from (a name already absolute, or a scene read from standard input,
/// keeps its name).
pub fn resolve_textures(mut scene: Scene, file: &Path) -> Scene {
    let Some(dir) = file.parent().filter(|d| !d.as_os_str().is_empty()) else {
        return scene;
    };
    for map in scene.texture_maps_mut() {
        if Path::new(&map.file).is_relative() {
            map.file = dir.join(&map.file).to_string_lossy().into_owned();
        }
    }
    scene
}

/// Replaces the `motion` of every object with a `roll` by the keys the roll expands to.
fn expand_rolls(mut scene: Scene) -> Scene {
    for object in &mut scene.objects {
        if let Some(r) = &object.roll {
            object.motion = roll::expand(r, &object.transform);
        }
    }
    scene
}

/// Reads the scene file at `path` as text (errors as [`load`]'s).
pub fn read_text(path: &Path) -> Result<String, LoadError> {
    let bytes =
        std::fs::read(path).map_err(|source| LoadError::Io { path: path.to_path_buf(), source })?;
    String::from_utf8(bytes).map_err(|e| {
        let bytes = e.as_bytes();
        let valid = std::str::from_utf8(&bytes[..e.utf8_error().valid_up_to()]).unwrap_or("");
        syntax::invalid_utf8(path, valid).into()
    })
}

/// Reads, parses and validates the scene file at `path`.
///
/// A file that cannot be read is [`LoadError::Io`] (exit code 1), a mesh file it names that
/// cannot be read [`LoadError::MeshIo`] (exit code 1); a file that is not UTF-8 or not a
/// valid scene, or a malformed mesh file, is [`LoadError::Scene`] (exit code 2).
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let bytes =
        std::fs::read(path).map_err(|source| LoadError::Io { path: path.to_path_buf(), source })?;
    match std::str::from_utf8(&bytes) {
        Ok(text) => parse_files(text, path),
        Err(e) => {
            let valid = bytes.get(..e.valid_up_to()).and_then(|b| std::str::from_utf8(b).ok());
            Err(syntax::invalid_utf8(path, valid.unwrap_or("")).into())
        }
    }
}
