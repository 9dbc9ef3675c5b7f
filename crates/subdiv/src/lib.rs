//! Catmull-Clark subdivision surfaces (issue #15, point 1): validation of a control mesh with
//! RenderMan tags, refinement with the DeRose-Kass-Truong 1998 semi-sharp crease rules, and
//! one [`LimitPatch`] per quad of the once-subdivided mesh.
//!
//! Evaluation is by local adaptive subdivision: a patch keeps its face and the faces around
//! its four corners (the 1-ring, which is all its limit surface depends on); at each level the
//! child quad holding `(u, v)` is kept, until its corners are regular (valence 4, interior,
//! no sharpness at the corners or on their edges), where the surface is exactly the uniform
//! bicubic B-spline patch of the 16 points around it. Points that never become regular
//! (the extraordinary corner itself, points on a sharp crease) stop at depth [`MAX_DEPTH`] and
//! use the limit-position masks of the four sub-patch corners (Halstead et al. 1993 for smooth
//! vertices, 1-4-1 for creases, the point for corners), bilinearly; at depth 12 the sub-patch
//! is 2^-12 wide, so the interpolation error, of the order of the square of that width times
//! the curvature (6e-8 of the patch's size), is at f32 rounding for positions, and the
//! derivatives there are finite differences of limit positions (relative error about 2^-12,
//! a normal off by 0.014 degrees at most). Every level costs a refinement of the 1-ring, and
//! points on an infinitely sharp crease descend all the way, so the depth is no deeper.
//!
//! Shared edges: a point with `u` or `v` exactly 0 or 1 is evaluated by the *owner* of that edge
//! (the adjacent patch whose edge runs from the lower to the higher level-1 vertex id), at the
//! canonical parameter, so both neighbours return bit-identical positions whenever `1 - t` is
//! exact in f64 (all f32 parameters above 2^-29). Corners use a per-vertex canonical owner.
//!
//! Arithmetic is f64 inside; only the results are rounded to f32.

use glam::Vec3;
use std::collections::HashMap;
use std::sync::Arc;

/// Depth at which adaptive evaluation stops and falls back to limit masks.
pub const MAX_DEPTH: usize = 12;

/// A RenderMan subdivision tag.
#[derive(Clone, Debug, PartialEq)]
pub enum Tag {
    /// Boundary edges infinitely sharp, boundary vertices with one face are corners.
    /// Without it, quads touching the boundary after one step are not drawn.
    InterpolateBoundary,
    /// A chain of edges `vertices[i]-vertices[i+1]` with a sharpness (`f32::INFINITY` allowed).
    Crease {
        /// The vertex chain.
        vertices: Vec<usize>,
        /// Sharpness, >= 0.
        sharpness: f32,
    },
    /// Vertex sharpness for each listed vertex.
    Corner {
        /// The vertices.
        vertices: Vec<usize>,
        /// Sharpness, >= 0.
        sharpness: f32,
    },
    /// Faces not drawn (they still shape their neighbours).
    Hole {
        /// The faces.
        faces: Vec<usize>,
    },
}

/// A control mesh: n-gons of any valence, consistently oriented, manifold.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Control points.
    pub points: Vec<Vec3>,
    /// Number of vertices of each face (>= 3).
    pub face_counts: Vec<usize>,
    /// Vertex indices of all faces, concatenated.
    pub faces: Vec<usize>,
    /// Tags.
    pub tags: Vec<Tag>,
    /// Floats per face-vertex of facevarying data (e.g. 2 for `st`); 0 for none.
    pub facevarying_width: usize,
    /// Facevarying data, `facevarying_width` floats per entry of `faces`. Interpolated
    /// bilinearly per face (RenderMan's default facevarying interpolation; our choice here).
    pub facevarying: Vec<f32>,
}

mod error;
mod eval;
mod level;
mod patch;

pub use error::SubdivError;
pub use patch::LimitPatch;

use eval::eval_local;
use level::{Local, Topo, key, refine, ring};
use patch::Shared;

/// Validate `mesh` and build its limit patches: one per drawn quad of the once-subdivided mesh
/// (not a hole, and, without `interpolateboundary`, not touching the boundary).
pub fn limit_patches(mesh: &Mesh) -> Result<Vec<LimitPatch>, SubdivError> {
    let np = mesh.points.len();
    let sum: usize = mesh.face_counts.iter().sum();
    if sum != mesh.faces.len() {
        return Err(SubdivError::FaceCountSum { expected: sum, got: mesh.faces.len() });
    }
    let fw = mesh.facevarying_width;
    if mesh.facevarying.len() != mesh.faces.len() * fw {
        return Err(SubdivError::FacevaryingLength {
            expected: mesh.faces.len() * fw,
            got: mesh.facevarying.len(),
        });
    }
    if let Some(vertex) = mesh.points.iter().position(|p| !p.is_finite()) {
        return Err(SubdivError::NonFinitePoint { vertex });
    }
    let mut faces = Vec::new();
    let mut starts = Vec::new();
    let mut directed = HashMap::new();
    let mut at = 0;
    for (fi, &c) in mesh.face_counts.iter().enumerate() {
        if c < 3 {
            return Err(SubdivError::FaceTooSmall { face: fi, count: c });
        }
        let f = &mesh.faces[at..at + c];
        starts.push(at);
        at += c;
        for (i, &v) in f.iter().enumerate() {
            if v >= np {
                return Err(SubdivError::VertexIndex { face: fi, index: v });
            }
            if f[..i].contains(&v) {
                return Err(SubdivError::RepeatedVertex { face: fi, vertex: v });
            }
        }
        for i in 0..c {
            let (a, b) = (f[i], f[(i + 1) % c]);
            if directed.insert((a, b), fi).is_some() {
                return Err(SubdivError::NonManifoldEdge { face: fi, a, b });
            }
        }
        faces.push(f.to_vec());
    }
    let mut m = Local {
        pts: mesh.points.iter().map(|p| p.as_dvec3()).collect(),
        faces,
        crease: HashMap::new(),
        corner: vec![0.0; np],
    };
    let mut hole = vec![false; m.faces.len()];
    let mut interp = false;
    let bad = |tag: usize, what: String| SubdivError::BadTag { tag, what };
    for (ti, tag) in mesh.tags.iter().enumerate() {
        match tag {
            Tag::InterpolateBoundary => interp = true,
            Tag::Crease { vertices, sharpness } | Tag::Corner { vertices, sharpness } => {
                let s = *sharpness as f64;
                if s.is_nan() || s < 0.0 {
                    return Err(bad(ti, format!("sharpness {sharpness} is not >= 0")));
                }
                if let Some(&v) = vertices.iter().find(|&&v| v >= np) {
                    return Err(bad(ti, format!("vertex {v} out of range")));
                }
                if matches!(tag, Tag::Corner { .. }) {
                    for &v in vertices {
                        m.corner[v] = s;
                    }
                    continue;
                }
                if vertices.len() < 2 {
                    return Err(bad(ti, "crease needs at least 2 vertices".into()));
                }
                for w in vertices.windows(2) {
                    let (a, b) = (w[0], w[1]);
                    if !directed.contains_key(&(a, b)) && !directed.contains_key(&(b, a)) {
                        return Err(bad(ti, format!("{a}-{b} is not an edge")));
                    }
                    m.crease.insert(key(a, b), s);
                }
            }
            Tag::Hole { faces } => {
                for &f in faces {
                    if f >= hole.len() {
                        return Err(bad(ti, format!("face {f} out of range")));
                    }
                    hole[f] = true;
                }
            }
        }
    }
    let (m1, off) = refine(&m);
    let t1 = Topo::new(&m1);
    let boundary: Vec<bool> = (0..m1.pts.len())
        .map(|v| t1.vert_edges[v].iter().any(|&e| t1.edge_faces[e].len() != 2))
        .collect();
    let mut drawn = Vec::new();
    for (f0, &o) in off.iter().enumerate() {
        if hole[f0] {
            continue;
        }
        for i in 0..m.faces[f0].len() {
            let q = o + i;
            if !interp && m1.faces[q].iter().any(|&v| boundary[v]) {
                continue;
            }
            drawn.push((f0, q));
        }
    }
    let locals: Vec<Arc<Shared>> =
        drawn.iter().map(|&(_, q)| Arc::new(Shared::new(ring(&m1, &t1, q, 0)))).collect();
    let mut owner_of = HashMap::new();
    let mut corner_owner: HashMap<usize, usize> = HashMap::new();
    for (pi, &(_, q)) in drawn.iter().enumerate() {
        let f = &m1.faces[q];
        for k in 0..4 {
            let (a, b) = (f[k], f[(k + 1) % 4]);
            if a < b {
                owner_of.insert((a, b), (pi, k));
            }
            corner_owner.entry(f[k]).or_insert(pi);
        }
    }
    let mut out = Vec::new();
    for (pi, &(f0, q)) in drawn.iter().enumerate() {
        let f = &m1.faces[q];
        let corners = [f[0], f[1], f[2], f[3]];
        let mut edge_owner: [Option<(Arc<Shared>, usize)>; 4] = Default::default();
        for k in 0..4 {
            if let Some(&(po, ko)) = owner_of.get(&key(f[k], f[(k + 1) % 4])) {
                edge_owner[k] = Some((locals[po].clone(), ko));
            }
        }
        let mut corner_pos = [Vec3::ZERO; 4];
        for k in 0..4 {
            let po = corner_owner[&f[k]];
            let kc = m1.faces[drawn[po].1].iter().position(|&x| x == f[k]).unwrap_or(0);
            let (u, v) = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)][kc];
            corner_pos[k] = eval_local(&locals[po].local, u, v)[0].as_vec3();
        }
        // Facevarying corners: level-0 face f0, child at its corner i = q - off[f0].
        let (start, n) = (starts[f0], mesh.face_counts[f0]);
        let i = q - off[f0];
        let val = |c: usize, k: usize| mesh.facevarying[(start + c % n) * fw + k] as f64;
        let fv: [Vec<f64>; 4] = [
            (0..fw).map(|k| val(i, k)).collect(),
            (0..fw).map(|k| 0.5 * (val(i, k) + val(i + 1, k))).collect(),
            (0..fw).map(|k| (0..n).map(|c| val(c, k)).sum::<f64>() / n as f64).collect(),
            (0..fw).map(|k| 0.5 * (val(i + n - 1, k) + val(i, k))).collect(),
        ];
        out.push(LimitPatch {
            fv: Arc::new(fv),
            local: locals[pi].clone(),
            face: f0,
            corners,
            edge_owner,
            corner_pos,
            rect: [0.0, 1.0, 0.0, 1.0],
        });
    }
    Ok(out)
}

/// Vertex varyings (`Cs`, `N`, ...), `width` floats per control point, subdivide exactly like
/// the points (every rule is linear in the data and chosen by topology and sharpness only).
/// Returns one patch list per group of 3 floats (the last group zero-padded); patch `k` of
/// each group matches patch `k` of [`limit_patches`], and its `eval(u, v).0` holds the group's
/// values (`.1`, `.2` their derivatives).
pub fn varying_patches(
    mesh: &Mesh,
    width: usize,
    data: &[f32],
) -> Result<Vec<Vec<LimitPatch>>, SubdivError> {
    if data.len() != mesh.points.len() * width {
        return Err(SubdivError::VaryingLength {
            expected: mesh.points.len() * width,
            got: data.len(),
        });
    }
    (0..width.div_ceil(3))
        .map(|g| {
            let mut m = mesh.clone();
            for (i, p) in m.points.iter_mut().enumerate() {
                let at = |c: usize| {
                    if 3 * g + c < width { data[i * width + 3 * g + c] } else { 0.0 }
                };
                *p = Vec3::new(at(0), at(1), at(2));
            }
            limit_patches(&m)
        })
        .collect()
}

#[cfg(test)]
mod tests;
