//! The rules of a [`Shape::SubdivisionMesh`]: a consistently oriented manifold control mesh
//! of polygons of three or more points, and tags that name its points, edges and faces.
//!
//! Invariant: every check is linear in the mesh's size (one hash of directed edges), so a
//! control mesh of a million faces validates in well under a second; no check can panic.

use std::collections::HashSet;

use super::primitives::{Check, fail, finite_each};
use crate::model::{Faces, Rgb, SubdivTag, V3};

/// The fields of a subdivision mesh, at `at` (the shape's path).
pub(super) fn subdivision_mesh(
    at: &str,
    points: &[V3],
    faces: &Faces,
    tags: &[SubdivTag],
    colors: Option<&[Rgb]>,
    st: Option<&[[f32; 2]]>,
) -> Check {
    let field = |name: &str| format!("{at}.{name}");
    finite_each(&field("points"), points)?;
    if faces.is_empty() {
        return fail(field("faces"), "must hold at least one face");
    }
    // Directed edges: in a consistently oriented manifold mesh each is used once (its
    // neighbour runs along it the other way).
    let mut directed: HashSet<(u32, u32)> = HashSet::with_capacity(faces.indices().len());
    for (f, face) in faces.iter().enumerate() {
        if face.len() < 3 {
            return fail(
                format!("{at}.faces[{f}]"),
                format!("a face must have 3 or more indices, got {}", face.len()),
            );
        }
        for (k, &index) in face.iter().enumerate() {
            if index as usize >= points.len() {
                return fail(
                    format!("{at}.faces[{f}][{k}]"),
                    format!("index {index} is out of range: the mesh has {} points", points.len()),
                );
            }
            if face[..k].contains(&index) {
                return fail(
                    format!("{at}.faces[{f}][{k}]"),
                    format!("point {index} appears twice in the face"),
                );
            }
        }
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            if !directed.insert((a, b)) {
                return fail(
                    format!("{at}.faces[{f}]"),
                    format!(
                        "edge ({a}, {b}) is run from point {a} to point {b} by an earlier face \
                         too: the mesh must be manifold and consistently oriented"
                    ),
                );
            }
        }
    }
    let is_edge = |a: u32, b: u32| directed.contains(&(a, b)) || directed.contains(&(b, a));
    for (t, tag) in tags.iter().enumerate() {
        let path = format!("{at}.tags[{t}]");
        let sharp = |s: f32| -> Check {
            if s.is_nan() || s < 0.0 {
                return fail(format!("{path}.sharpness"), format!("must be >= 0, got {s}"));
            }
            Ok(())
        };
        let in_range = |name: &str, list: &[u32], n: usize, what: &str| -> Check {
            for (i, &v) in list.iter().enumerate() {
                if v as usize >= n {
                    return fail(
                        format!("{path}.{name}[{i}]"),
                        format!("{what} {v} is out of range: the mesh has {n} {what}s"),
                    );
                }
            }
            Ok(())
        };
        match tag {
            SubdivTag::InterpolateBoundary => {}
            SubdivTag::Crease { vertices, sharpness } => {
                sharp(*sharpness)?;
                if vertices.len() < 2 {
                    return fail(
                        format!("{path}.vertices"),
                        format!("a crease needs at least 2 points, got {}", vertices.len()),
                    );
                }
                in_range("vertices", vertices, points.len(), "point")?;
                for (i, w) in vertices.windows(2).enumerate() {
                    if !is_edge(w[0], w[1]) {
                        return fail(
                            format!("{path}.vertices[{}]", i + 1),
                            format!("({}, {}) is not an edge of the mesh", w[0], w[1]),
                        );
                    }
                }
            }
            SubdivTag::Corner { vertices, sharpness } => {
                sharp(*sharpness)?;
                in_range("vertices", vertices, points.len(), "point")?;
            }
            SubdivTag::Hole { faces: holes } => in_range("faces", holes, faces.len(), "face")?,
        }
    }
    if let Some(colors) = colors {
        if colors.len() != points.len() {
            return fail(
                field("colors"),
                format!("must have one colour per point ({}), got {}", points.len(), colors.len()),
            );
        }
        finite_each(&field("colors"), colors)?;
    }
    if let Some(st) = st {
        let corners = faces.indices().len();
        if st.len() != corners {
            return fail(
                field("st"),
                format!("must have one (s, t) per face corner ({corners}), got {}", st.len()),
            );
        }
        finite_each(&field("st"), st)?;
    }
    Ok(())
}
