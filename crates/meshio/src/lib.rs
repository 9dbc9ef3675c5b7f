//! Mesh files (issue #15 point 2): polygon meshes read from Wavefront OBJ (through `tobj`) and
//! PLY (ASCII and binary of either byte order, our own reader), into one plain [`MeshData`].
//!
//! Invariants of every mesh returned: each face has at least 3 vertices; every index is below
//! `points.len()`; every coordinate, normal and uv is finite; `normals` and `uvs`, where
//! present, hold one entry per point; `ends` is non-decreasing and ends at `indices.len()`;
//! the groups' face ranges are in order and cover only faces that exist. Errors are one line
//! naming the file and the line (OBJ, ASCII PLY, any PLY header) or the element (binary PLY).
//!
//! ```
//! use std::path::Path;
//! use reyes_meshio::{Format, read_bytes};
//!
//! let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng quad\nf 1 2 3 4\n";
//! let mesh = read_bytes(Path::new("quad.obj"), obj.as_bytes(), Format::Obj).unwrap();
//! assert_eq!(mesh.face(0), &[0, 1, 2, 3]);
//! assert_eq!(mesh.groups[0].name, "quad");
//!
//! let bad = "v 0 0 0\nv 1 0 0\nf 1 2 3\n";
//! let e = read_bytes(Path::new("bad.obj"), bad.as_bytes(), Format::Obj).unwrap_err();
//! assert_eq!(e.to_string(), "bad.obj:3: face position index 3 out of range (2 in the file)");
//! ```

use std::ops::Range;
use std::path::{Path, PathBuf};

mod obj;
mod ply;
mod write;

pub use write::{write_obj, write_ply_binary};

/// A polygon mesh read from a file: points with optional per-point normals and uvs, and
/// n-gon faces stored flat as in `reyes_scene::Faces`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions.
    pub points: Vec<[f32; 3]>,
    /// One normal per point, where the file gives them for every vertex used.
    pub normals: Option<Vec<[f32; 3]>>,
    /// One texture coordinate per point, where the file gives them for every vertex used.
    pub uvs: Option<Vec<[f32; 2]>>,
    /// Every face's point indices, face after face.
    pub indices: Vec<u32>,
    /// Where each face ends in `indices` (one past its last index): face `i` is
    /// `indices[ends[i - 1]..ends[i]]` (from 0 for the first).
    pub ends: Vec<u32>,
    /// Named runs of faces (OBJ `g` and `o`), in file order; empty for PLY.
    pub groups: Vec<Group>,
    /// The materials of the file's material libraries (OBJ `mtllib`); empty for PLY.
    pub materials: Vec<Material>,
    /// Each face's index into `materials` (`None`: no `usemtl`, or a name no library
    /// defines); empty when `materials` is.
    pub face_materials: Vec<Option<u32>>,
}

/// A named run of faces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Group {
    /// The group's or object's name as written.
    pub name: String,
    /// Its faces (indices into the faces of [`MeshData`]).
    pub faces: Range<u32>,
}

/// A material of an OBJ material library (`.mtl`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Material {
    /// `newmtl` name.
    pub name: String,
    /// Diffuse colour (`Kd`).
    pub diffuse: Option<[f32; 3]>,
    /// Specular colour (`Ks`).
    pub specular: Option<[f32; 3]>,
    /// Specular exponent (`Ns`).
    pub shininess: Option<f32>,
    /// Opacity (`d`, 1 opaque).
    pub dissolve: Option<f32>,
    /// Diffuse texture (`map_Kd`), resolved against the OBJ file's folder.
    pub diffuse_texture: Option<PathBuf>,
}

/// Why a mesh file could not be read. Display is one line.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The file (or a material library it names) could not be read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The system's error.
        source: std::io::Error,
    },
    /// A text line is malformed (OBJ, ASCII PLY, a PLY header).
    #[error("{}:{line}: {what}", path.display())]
    Line {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        what: String,
    },
    /// An element of a binary PLY file is malformed.
    #[error("{}: element {index} ({element}): {what}", path.display())]
    Element {
        /// The file.
        path: PathBuf,
        /// The element's kind as the header names it (`vertex`, `face`).
        element: String,
        /// 0-based index among elements of that kind.
        index: usize,
        /// What is wrong.
        what: String,
    },
    /// The file as a whole is wrong: unknown format, or a fault without a position.
    #[error("{}: {what}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
}

impl MeshError {
    /// True for I/O errors (missing or unreadable files), which the CLI reports with exit
    /// status 1, against 2 for a malformed file.
    pub fn is_io(&self) -> bool {
        matches!(self, MeshError::Io { .. })
    }
}

/// The file formats read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ.
    Obj,
    /// Stanford PLY.
    Ply,
}

impl Format {
    /// The format a path names by its extension (`.obj`, `.ply`, any case).
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Some(Format::Obj),
            "ply" => Some(Format::Ply),
            _ => None,
        }
    }
}

/// Reads a mesh file, choosing the format from the extension (or, without a known one,
/// from a PLY file's `ply` magic line).
pub fn read(path: impl AsRef<Path>) -> Result<MeshData, MeshError> {
    let path = path.as_ref();
    if Format::from_path(path) == Some(Format::Obj) {
        // OBJ streams through a buffer, so the text is not held beside what tobj builds
        // (a third of the peak for a million faces); a faulty file is read again to find
        // the line.
        let file = std::fs::File::open(path).map_err(|source| io(path, source))?;
        return obj::read(path, &mut std::io::BufReader::with_capacity(1 << 16, file), None);
    }
    let bytes = std::fs::read(path).map_err(|source| io(path, source))?;
    let format = match Format::from_path(path) {
        Some(f) => f,
        None if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") => Format::Ply,
        None => {
            return Err(MeshError::File {
                path: path.to_path_buf(),
                what: "unknown mesh format (expected a .obj or .ply file)".into(),
            });
        }
    };
    read_bytes(path, &bytes, format)
}

/// Reads a mesh held in memory; `path` names it in errors and is the folder OBJ material
/// libraries are found relative to.
pub fn read_bytes(path: &Path, bytes: &[u8], format: Format) -> Result<MeshData, MeshError> {
    match format {
        Format::Obj => obj::read(path, &mut &bytes[..], Some(bytes)),
        Format::Ply => ply::read(path, bytes),
    }
}

fn io(path: &Path, source: std::io::Error) -> MeshError {
    MeshError::Io { path: path.to_path_buf(), source }
}

impl MeshData {
    /// The number of faces.
    pub fn face_count(&self) -> usize {
        self.ends.len()
    }

    /// Face `i`'s point indices.
    ///
    /// # Panics
    ///
    /// If `i >= face_count()`.
    pub fn face(&self, i: usize) -> &[u32] {
        let start = if i == 0 { 0 } else { self.ends[i - 1] as usize };
        &self.indices[start..self.ends[i] as usize]
    }

    /// Every face's point indices, in order.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.face_count()).map(move |i| self.face(i))
    }
}
