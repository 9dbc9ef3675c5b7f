//! Mesh files in scenes: every [`Shape::MeshFile`] is read (through `reyes-meshio`) into the
//! [`Shape::Mesh`] or [`Shape::SubdivisionMesh`] it describes, before validation.
//!
//! Invariants: never panics; a relative `path` is joined to the scene file's folder; a
//! failure is one [`SceneError`] at the position of the object's `path` field whose message
//! is meshio's one-line error (naming the mesh file and its line or element), marked as
//! I/O ([`Failure::Io`]) when the file could not be read at all.

use std::path::{Path, PathBuf};

use reyes_meshio::MeshData;

use crate::SceneError;
use crate::locate::SourceMap;
use crate::model::{Faces, Scene, Shape, SubdivTag};

/// Why the mesh files of a scene could not be read.
#[derive(Debug)]
pub(crate) enum Failure {
    /// A mesh file is missing or unreadable (exit status 1).
    Io(SceneError),
    /// A mesh file is malformed, or the shape asks for what it lacks (exit status 2).
    Bad(SceneError),
}

/// Replaces every `MeshFile` shape of `scene` by the mesh its file holds. `text` is the scene
/// source (for error positions) and `file` the scene file (for relative paths and messages).
/// Returns the objects whose shapes were read, with the files they came from.
pub(crate) fn resolve(
    scene: &mut Scene,
    text: &str,
    file: &Path,
) -> Result<Vec<(usize, PathBuf)>, Failure> {
    let mut read = Vec::new();
    if !scene.objects.iter().any(|o| matches!(o.shape, Shape::MeshFile { .. })) {
        return Ok(read);
    }
    let dir = file.parent().filter(|d| !d.as_os_str().is_empty());
    for (i, object) in scene.objects.iter_mut().enumerate() {
        let Shape::MeshFile { path, subdivision, group } = &object.shape else { continue };
        let error = |field: &str, message: String| {
            let field = format!("objects[{i}].shape.{field}");
            let pos = SourceMap::scan(text).find(&field);
            SceneError {
                file: file.to_path_buf(),
                line: pos.map(|p| p.line),
                col: pos.map(|p| p.col),
                field,
                message,
            }
        };
        let full: PathBuf = match dir {
            Some(d) if Path::new(path).is_relative() => d.join(path),
            _ => PathBuf::from(path),
        };
        let mesh = match reyes_meshio::read(&full) {
            Ok(mesh) => mesh,
            Err(e) if e.is_io() => {
                return Err(Failure::Io(error("path", format!("cannot read the mesh file: {e}"))));
            }
            Err(e) => return Err(Failure::Bad(error("path", e.to_string()))),
        };
        let mesh = match group {
            None => mesh,
            Some(name) => select_group(mesh, name)
                .map_err(|m| Failure::Bad(error("group", format!("{}: {m}", full.display()))))?,
        };
        object.shape = if *subdivision { subdivision_shape(mesh) } else { mesh_shape(mesh) };
        read.push((i, full));
    }
    Ok(read)
}

/// The faces of `mesh`.
fn faces_of(mesh: &MeshData) -> Faces {
    let mut faces = Faces::with_capacity(mesh.face_count(), mesh.indices.len());
    for face in mesh.faces() {
        faces.push(face);
    }
    faces
}

/// A polygon mesh with the file's normals and uvs (as `st`), and the materials' diffuse
/// colours as point colours where that is exact (see [`point_colors`]).
fn mesh_shape(mesh: MeshData) -> Shape {
    let faces = faces_of(&mesh);
    let colors = point_colors(&mesh);
    Shape::Mesh { points: mesh.points, faces, colors, normals: mesh.normals, st: mesh.uvs }
}

/// A Catmull-Clark control mesh: the file's uvs become facevarying `st` (one per face
/// corner), its normals are dropped (the limit surface has its own), and the boundary is
/// interpolated, so that an open mesh is drawn to its edge.
fn subdivision_shape(mesh: MeshData) -> Shape {
    let faces = faces_of(&mesh);
    let st = mesh.uvs.as_ref().map(|uv| {
        mesh.indices.iter().map(|&i| uv.get(i as usize).copied().unwrap_or([0.0; 2])).collect()
    });
    let colors = point_colors(&mesh);
    Shape::SubdivisionMesh {
        points: mesh.points,
        faces,
        tags: vec![SubdivTag::InterpolateBoundary],
        colors,
        st,
    }
}

/// Per-point colours from the OBJ materials' diffuse colours (`Kd`), only when that loses
/// nothing: every face has a material with a `Kd`, and every point is used by faces of one
/// colour. Otherwise `None` (a mesh whose colour changes across an edge shared by its faces
/// needs per-face colours, which the scene model does not have).
fn point_colors(mesh: &MeshData) -> Option<Vec<[f32; 3]>> {
    if mesh.materials.is_empty() || mesh.face_materials.len() != mesh.face_count() {
        return None;
    }
    let mut colors: Vec<Option<[f32; 3]>> = vec![None; mesh.points.len()];
    for (f, face) in mesh.faces().enumerate() {
        let kd = mesh.face_materials[f]
            .and_then(|m| mesh.materials.get(m as usize))
            .and_then(|m| m.diffuse)?;
        for &i in face {
            let slot = colors.get_mut(i as usize)?;
            match slot {
                Some(c) if *c != kd => return None,
                _ => *slot = Some(kd),
            }
        }
    }
    // Points no face uses take white (they are never drawn).
    Some(colors.into_iter().map(|c| c.unwrap_or([1.0; 3])).collect())
}

/// The faces of the groups (or objects) named `name`, with only the points they use
/// (renumbered in their original order). An error lists the names the file has.
fn select_group(mesh: MeshData, name: &str) -> Result<MeshData, String> {
    let chosen: Vec<_> = mesh.groups.iter().filter(|g| g.name == name).cloned().collect();
    if chosen.is_empty() {
        let mut names: Vec<&str> = mesh.groups.iter().map(|g| g.name.as_str()).collect();
        names.dedup();
        return Err(if names.is_empty() {
            format!("no group or object named {name:?}: the file has no groups")
        } else {
            format!("no group or object named {name:?}; the file has: {}", names.join(", "))
        });
    }
    let keep: Vec<usize> =
        chosen.iter().flat_map(|g| g.faces.start as usize..g.faces.end as usize).collect();
    let mut used = vec![false; mesh.points.len()];
    for &f in &keep {
        for &i in mesh.face(f) {
            used[i as usize] = true;
        }
    }
    let mut renumber = vec![u32::MAX; mesh.points.len()];
    let mut next = 0u32;
    for (i, u) in used.iter().enumerate() {
        if *u {
            renumber[i] = next;
            next += 1;
        }
    }
    let pick = |v: &[[f32; 3]]| -> Vec<[f32; 3]> {
        v.iter().zip(&used).filter(|(_, u)| **u).map(|(p, _)| *p).collect()
    };
    let mut out = MeshData {
        points: pick(&mesh.points),
        normals: mesh.normals.as_deref().map(pick),
        uvs: mesh
            .uvs
            .as_ref()
            .map(|uv| uv.iter().zip(&used).filter(|(_, u)| **u).map(|(t, _)| *t).collect()),
        materials: mesh.materials.clone(),
        ..MeshData::default()
    };
    for &f in &keep {
        out.indices.extend(mesh.face(f).iter().map(|&i| renumber[i as usize]));
        out.ends.push(out.indices.len() as u32);
        if let Some(m) = mesh.face_materials.get(f) {
            out.face_materials.push(*m);
        }
    }
    if out.face_materials.len() != out.ends.len() {
        out.face_materials.clear();
    }
    Ok(out)
}
