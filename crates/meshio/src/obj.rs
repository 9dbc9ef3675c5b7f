//! Wavefront OBJ through `tobj`, with OBJ's separate position/uv/normal indices welded into one
//! index space (`single_index`) and n-gons kept (`triangulate: false`).
//!
//! `tobj` reports an error kind without a line, and accepts what we must refuse (`l` lines and
//! faces of 1 or 2 vertices, non-finite numbers). So when `tobj` fails, or its result breaks an
//! invariant of [`MeshData`], [`locate`] scans the text once more with the same counting rules
//! (an index refers to the positions, uvs or normals defined above it) and names the first
//! offending line. Good files pay for one `tobj` pass and a finiteness check only.

use std::cell::RefCell;
use std::io::BufRead;
use std::path::{Path, PathBuf};

use crate::{Group, Material, MeshData, MeshError};

/// Reads OBJ text from `reader`; `bytes` is the same text if it is in memory, else the file
/// at `path` is read again to locate a fault.
pub(crate) fn read(
    path: &Path,
    reader: &mut impl BufRead,
    bytes: Option<&[u8]>,
) -> Result<MeshData, MeshError> {
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mtl_failure: RefCell<Option<(PathBuf, std::io::Error)>> = RefCell::new(None);
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: false,
        ignore_points: false,
        ignore_lines: false,
    };
    let loaded = tobj::load_obj_buf(reader, &options, |mtl| {
        let full = dir.join(mtl);
        match std::fs::read(&full) {
            Ok(text) => tobj::load_mtl_buf(&mut &text[..]),
            Err(e) => {
                mtl_failure.borrow_mut().get_or_insert((full, e));
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    });
    let (models, materials) = match loaded {
        Ok(x) => x,
        Err(e) => return Err(fault(path, bytes, &e.to_string())),
    };
    let materials = match materials {
        Ok(m) => m,
        Err(e) => {
            if let Some((mtl, source)) = mtl_failure.into_inner() {
                return Err(MeshError::Io { path: mtl, source });
            }
            let text = text_of(path, bytes)?;
            let line = find_line(&text, |kw, _| kw == "mtllib").unwrap_or(0);
            return Err(MeshError::Line {
                path: path.to_path_buf(),
                line,
                what: format!("material library: {e}"),
            });
        }
    };

    let mut mesh = MeshData::default();
    let has_normals = models.iter().all(|m| m.mesh.normals.len() == m.mesh.positions.len());
    let has_uvs = models.iter().all(|m| m.mesh.texcoords.len() / 2 == m.mesh.positions.len() / 3);
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for model in &models {
        let m = &model.mesh;
        let offset = mesh.points.len() as u32;
        mesh.points.extend(m.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        if has_normals {
            normals.extend(m.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]));
        }
        if has_uvs {
            uvs.extend(m.texcoords.chunks_exact(2).map(|t| [t[0], t[1]]));
        }
        let first_face = mesh.ends.len() as u32;
        mesh.indices.extend(m.indices.iter().map(|i| i + offset));
        let mut end = *mesh.ends.last().unwrap_or(&0);
        if m.face_arities.is_empty() {
            // tobj leaves the arities empty when every face is a triangle.
            for _ in 0..m.indices.len() / 3 {
                end += 3;
                mesh.ends.push(end);
            }
        } else {
            for &n in &m.face_arities {
                if n < 3 {
                    return Err(fault(path, bytes, "a face with fewer than 3 vertices"));
                }
                end += n;
                mesh.ends.push(end);
            }
        }
        let faces = first_face..mesh.ends.len() as u32;
        if !materials.is_empty() {
            let id = m.material_id.map(|i| i as u32);
            mesh.face_materials.extend(std::iter::repeat_n(id, faces.len()));
        }
        match mesh.groups.last_mut() {
            Some(g) if g.name == model.name && g.faces.end == faces.start => {
                g.faces.end = faces.end
            }
            _ if faces.is_empty() => {}
            _ => mesh.groups.push(Group { name: model.name.clone(), faces }),
        }
    }
    let finite = |v: &[f32]| v.iter().all(|x| x.is_finite());
    if !models
        .iter()
        .all(|m| finite(&m.mesh.positions) && finite(&m.mesh.normals) && finite(&m.mesh.texcoords))
    {
        return Err(fault(path, bytes, "a number is not finite"));
    }
    if has_normals && !normals.is_empty() {
        mesh.normals = Some(normals);
    }
    if has_uvs && !uvs.is_empty() {
        mesh.uvs = Some(uvs);
    }
    mesh.materials = materials
        .into_iter()
        .map(|m| Material {
            name: m.name,
            diffuse: m.diffuse,
            specular: m.specular,
            shininess: m.shininess,
            dissolve: m.dissolve,
            diffuse_texture: m
                .diffuse_texture
                .map(|t| path.parent().unwrap_or(Path::new("")).join(t)),
        })
        .collect();
    Ok(mesh)
}

/// The error for a file `tobj` rejected (or whose result breaks an invariant), at the line
/// [`locate`] finds, or without a line if it finds none (`fallback` says what `tobj` saw).
fn fault(path: &Path, bytes: Option<&[u8]>, fallback: &str) -> MeshError {
    let text = match text_of(path, bytes) {
        Ok(t) => t,
        Err(e) => return e,
    };
    match locate(&text) {
        Some((line, what)) => MeshError::Line { path: path.to_path_buf(), line, what },
        None => MeshError::File { path: path.to_path_buf(), what: fallback.to_string() },
    }
}

/// The text in memory, or read again from `path`.
fn text_of<'a>(
    path: &Path,
    bytes: Option<&'a [u8]>,
) -> Result<std::borrow::Cow<'a, [u8]>, MeshError> {
    match bytes {
        Some(b) => Ok(b.into()),
        None => std::fs::read(path)
            .map(Into::into)
            .map_err(|source| MeshError::Io { path: path.to_path_buf(), source }),
    }
}

/// The 1-based number of the first line whose keyword and rest satisfy `hit`.
fn find_line(bytes: &[u8], hit: impl Fn(&str, &str) -> bool) -> Option<usize> {
    bytes.split(|&b| b == b'\n').enumerate().find_map(|(i, raw)| {
        let text = std::str::from_utf8(raw).ok()?;
        let (kw, rest) = split_keyword(text);
        hit(kw, rest).then_some(i + 1)
    })
}

fn split_keyword(line: &str) -> (&str, &str) {
    let line = line.trim();
    match line.split_once(|c: char| c.is_ascii_whitespace()) {
        Some((kw, rest)) => (kw, rest.trim()),
        None => (line, ""),
    }
}

/// The first line of `bytes` that breaks a rule of [`MeshData`] or that `tobj` refuses, and
/// what is wrong with it.
pub(crate) fn locate(bytes: &[u8]) -> Option<(usize, String)> {
    // How many positions, uvs and normals the file defines (positive indices may refer
    // forward, as tobj allows), and how many the lines above define (negative indices count
    // back from there).
    let mut total = [0usize; 3];
    for raw in bytes.split(|&b| b == b'\n') {
        match raw.split(u8::is_ascii_whitespace).find(|w| !w.is_empty()) {
            Some(b"v") => total[0] += 1,
            Some(b"vt") => total[1] += 1,
            Some(b"vn") => total[2] += 1,
            _ => {}
        }
    }
    let (mut nv, mut nvt, mut nvn) = (0usize, 0usize, 0usize);
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = i + 1;
        let Ok(text) = std::str::from_utf8(raw) else {
            return Some((line, "the line is not UTF-8 text".into()));
        };
        let (kw, rest) = split_keyword(text);
        let bad = match kw {
            "v" => {
                nv += 1;
                numbers(rest, 3, "vertex position").or_else(|| {
                    let extra = rest.split_ascii_whitespace().count();
                    match extra {
                        3 | 6 => None,
                        4 if rest.split_ascii_whitespace().nth(3)?.parse::<f32>().ok()? == 0.0 => {
                            Some("vertex w is zero".into())
                        }
                        4 => None,
                        _ => Some(format!("vertex has {extra} numbers (3, 4 or 6 expected)")),
                    }
                })
            }
            "vt" => {
                nvt += 1;
                numbers(rest, 2, "texture coordinate")
            }
            "vn" => {
                nvn += 1;
                numbers(rest, 3, "normal")
            }
            "f" => face(rest, [nv, nvt, nvn], total),
            "l" => Some("line elements ('l') are not supported".into()),
            "usemtl" if rest.is_empty() => Some("usemtl without a material name".into()),
            "o" | "g" if rest.is_empty() => None,
            _ => None,
        };
        if let Some(what) = bad {
            return Some((line, what));
        }
    }
    None
}

/// Checks that `rest` starts with `n` finite numbers.
fn numbers(rest: &str, n: usize, what: &str) -> Option<String> {
    let mut words = rest.split_ascii_whitespace();
    for k in 0..n {
        match words.next().map(str::parse::<f32>) {
            Some(Ok(x)) if x.is_finite() => {}
            Some(Ok(_)) => return Some(format!("{what} is not finite")),
            Some(Err(_)) => return Some(format!("{what}: number {} is not a number", k + 1)),
            None => return Some(format!("{what} has {k} numbers ({n} expected)")),
        }
    }
    None
}

/// Checks one face's `v`, `v/vt`, `v//vn` or `v/vt/vn` corners: a positive index against the
/// file's `total` count, a negative one against the count `above` the face.
fn face(rest: &str, above: [usize; 3], total: [usize; 3]) -> Option<String> {
    let mut corners = 0;
    for word in rest.split_ascii_whitespace() {
        corners += 1;
        let mut parts = word.split('/');
        for (k, name) in ["position", "texture coordinate", "normal"].into_iter().enumerate() {
            let Some(part) = parts.next() else { break };
            if part.is_empty() && k > 0 {
                continue;
            }
            let Ok(index) = part.parse::<i64>() else {
                return Some(format!("face corner '{word}': '{part}' is not an index"));
            };
            // OBJ indices are 1-based; negative ones count back from the last defined.
            let (ok, count) = if index > 0 {
                (index as usize <= total[k], total[k])
            } else {
                (index < 0 && index.unsigned_abs() as usize <= above[k], above[k])
            };
            if !ok {
                let whence = if index > 0 { "in the file" } else { "above this line" };
                return Some(format!("face {name} index {index} out of range ({count} {whence})"));
            }
        }
        if parts.next().is_some() {
            return Some(format!("face corner '{word}' has more than 3 indices"));
        }
    }
    (corners < 3).then(|| format!("face has {corners} vertices (at least 3 needed)"))
}
