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

use glam::{DVec3, Vec3};
use std::collections::HashMap;
use std::fmt;
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

/// Invalid input, naming the face, vertex or tag index.
#[derive(Clone, Debug, PartialEq)]
pub enum SubdivError {
    /// A face with fewer than 3 vertices.
    FaceTooSmall {
        /// Face index.
        face: usize,
        /// Its count.
        count: usize,
    },
    /// `face_counts` does not sum to `faces.len()`.
    FaceCountSum {
        /// The sum of the counts.
        expected: usize,
        /// `faces.len()`.
        got: usize,
    },
    /// A vertex index out of range in a face.
    VertexIndex {
        /// Face index.
        face: usize,
        /// The bad index.
        index: usize,
    },
    /// Facevarying data of the wrong length.
    FacevaryingLength {
        /// `faces.len() * facevarying_width`.
        expected: usize,
        /// What was given.
        got: usize,
    },
    /// Vertex varying data of the wrong length.
    VaryingLength {
        /// `points.len() * width`.
        expected: usize,
        /// What was given.
        got: usize,
    },
    /// A face uses a vertex twice.
    RepeatedVertex {
        /// Face index.
        face: usize,
        /// The vertex.
        vertex: usize,
    },
    /// A non-finite control point.
    NonFinitePoint {
        /// Vertex index.
        vertex: usize,
    },
    /// An edge used twice in the same direction or by more than two faces.
    NonManifoldEdge {
        /// Face where it was found.
        face: usize,
        /// Edge end points.
        a: usize,
        /// Edge end points.
        b: usize,
    },
    /// A tag naming a vertex or face out of range, a bad sharpness, or a crease step that is not an edge.
    BadTag {
        /// Tag index.
        tag: usize,
        /// What is wrong.
        what: String,
    },
}

impl fmt::Display for SubdivError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::FaceTooSmall { face, count } => {
                write!(f, "face {face}: {count} vertices, need at least 3")
            }
            Self::FaceCountSum { expected, got } => {
                write!(f, "face counts sum to {expected} but {got} face indices given")
            }
            Self::VertexIndex { face, index } => {
                write!(f, "face {face}: vertex index {index} out of range")
            }
            Self::RepeatedVertex { face, vertex } => {
                write!(f, "face {face}: vertex {vertex} used twice")
            }
            Self::FacevaryingLength { expected, got } => {
                write!(f, "facevarying: {got} floats, expected {expected}")
            }
            Self::VaryingLength { expected, got } => {
                write!(f, "vertex varying: {got} floats, expected {expected}")
            }
            Self::NonFinitePoint { vertex } => write!(f, "vertex {vertex}: non-finite point"),
            Self::NonManifoldEdge { face, a, b } => {
                write!(f, "face {face}: edge {a}-{b} is non-manifold or inconsistently oriented")
            }
            Self::BadTag { tag, what } => write!(f, "tag {tag}: {what}"),
        }
    }
}

impl std::error::Error for SubdivError {}

const SHARP_INF: f64 = f64::INFINITY;

/// Internal mesh: f64 points, faces, edge sharpness keyed by sorted vertex pair, vertex sharpness.
#[derive(Clone, Debug)]
struct Local {
    pts: Vec<DVec3>,
    faces: Vec<Vec<usize>>,
    crease: HashMap<(usize, usize), f64>,
    corner: Vec<f64>,
}

fn key(a: usize, b: usize) -> (usize, usize) {
    if a < b { (a, b) } else { (b, a) }
}

struct Topo {
    edges: Vec<(usize, usize)>,
    edge_faces: Vec<Vec<usize>>,
    edge_index: HashMap<(usize, usize), usize>,
    vert_edges: Vec<Vec<usize>>,
    vert_faces: Vec<Vec<usize>>,
}

impl Topo {
    fn new(m: &Local) -> Topo {
        let mut t = Topo {
            edges: Vec::new(),
            edge_faces: Vec::new(),
            edge_index: HashMap::new(),
            vert_edges: vec![Vec::new(); m.pts.len()],
            vert_faces: vec![Vec::new(); m.pts.len()],
        };
        for (fi, f) in m.faces.iter().enumerate() {
            for i in 0..f.len() {
                let (a, b) = (f[i], f[(i + 1) % f.len()]);
                t.vert_faces[a].push(fi);
                let k = key(a, b);
                let e = match t.edge_index.get(&k) {
                    Some(&e) => e,
                    None => {
                        let e = t.edges.len();
                        t.edges.push(k);
                        t.edge_faces.push(Vec::new());
                        t.edge_index.insert(k, e);
                        t.vert_edges[a].push(e);
                        t.vert_edges[b].push(e);
                        e
                    }
                };
                t.edge_faces[e].push(fi);
            }
        }
        t
    }
    fn sharp(&self, m: &Local, e: usize) -> f64 {
        if self.edge_faces[e].len() != 2 {
            SHARP_INF
        } else {
            m.crease.get(&self.edges[e]).copied().unwrap_or(0.0)
        }
    }
    fn other(&self, e: usize, v: usize) -> usize {
        let (a, b) = self.edges[e];
        if a == v { b } else { a }
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Rule {
    Smooth,
    Crease(usize, usize),
    Corner,
}

/// The vertex rule at sharpness threshold `th` (0 for this level, 1 for the next).
fn rule(m: &Local, t: &Topo, v: usize, th: f64) -> Rule {
    let sharp: Vec<usize> =
        t.vert_edges[v].iter().copied().filter(|&e| t.sharp(m, e) > th).collect();
    let lone = t.vert_faces[v].len() == 1 && sharp.len() == 2;
    if m.corner[v] > th || sharp.len() > 2 || lone {
        Rule::Corner
    } else if sharp.len() == 2 {
        Rule::Crease(t.other(sharp[0], v), t.other(sharp[1], v))
    } else {
        Rule::Smooth
    }
}

fn refine(m: &Local) -> (Local, Vec<usize>) {
    let t = Topo::new(m);
    let nv = m.pts.len();
    let ne = t.edges.len();
    let fp: Vec<DVec3> = m
        .faces
        .iter()
        .map(|f| f.iter().map(|&i| m.pts[i]).sum::<DVec3>() / f.len() as f64)
        .collect();
    let mut pts = vec![DVec3::ZERO; nv + ne + m.faces.len()];
    for (e, &(a, b)) in t.edges.iter().enumerate() {
        let mid = (m.pts[a] + m.pts[b]) * 0.5;
        let s = t.sharp(m, e);
        pts[nv + e] = if s >= 1.0 {
            mid
        } else {
            let ef = &t.edge_faces[e];
            let smooth = (m.pts[a] + m.pts[b] + fp[ef[0]] + fp[ef[1]]) * 0.25;
            smooth.lerp(mid, s.max(0.0))
        };
    }
    #[allow(clippy::needless_range_loop)] // v indexes points, topology and sharpness alike
    for v in 0..nv {
        let p = m.pts[v];
        let n = t.vert_edges[v].len();
        let at = |r: Rule| -> DVec3 {
            match r {
                Rule::Corner => p,
                Rule::Crease(a, b) => (p * 6.0 + m.pts[a] + m.pts[b]) / 8.0,
                Rule::Smooth => {
                    let k = t.vert_faces[v].len();
                    if k == 0 || n < 3 || k != n {
                        return p;
                    }
                    let q = t.vert_faces[v].iter().map(|&f| fp[f]).sum::<DVec3>() / k as f64;
                    let r = t.vert_edges[v]
                        .iter()
                        .map(|&e| (p + m.pts[t.other(e, v)]) * 0.5)
                        .sum::<DVec3>()
                        / n as f64;
                    let nf = n as f64;
                    (q + r * 2.0 + p * (nf - 3.0)) / nf
                }
            }
        };
        let r0 = rule(m, &t, v, 0.0);
        let r1 = rule(m, &t, v, 1.0);
        pts[v] = if r0 == r1 || r0 == Rule::Smooth {
            at(r0)
        } else {
            // Transition: blend by the mean sharpness of what made this level sharp.
            let mut ss: Vec<f64> =
                t.vert_edges[v].iter().map(|&e| t.sharp(m, e)).filter(|&s| s > 0.0).collect();
            if m.corner[v] > 0.0 {
                ss.push(m.corner[v]);
            }
            let w = ss.iter().map(|s| s.min(1.0)).sum::<f64>() / ss.len().max(1) as f64;
            at(r1).lerp(at(r0), w)
        };
    }
    for (f, p) in fp.iter().enumerate() {
        pts[nv + ne + f] = *p;
    }
    let mut faces = Vec::new();
    let mut offset = Vec::new();
    for (fi, f) in m.faces.iter().enumerate() {
        offset.push(faces.len());
        let l = f.len();
        for i in 0..l {
            let en = t.edge_index[&key(f[i], f[(i + 1) % l])];
            let ep = t.edge_index[&key(f[(i + l - 1) % l], f[i])];
            faces.push(vec![f[i], nv + en, nv + ne + fi, nv + ep]);
        }
    }
    let mut crease = HashMap::new();
    for (&(a, b), &s) in &m.crease {
        let Some(&e) = t.edge_index.get(&(a, b)) else {
            continue;
        };
        if s <= 0.0 || t.edge_faces[e].len() != 2 {
            continue;
        }
        for v in [a, b] {
            // Chaikin: the child next to v mixes in the other crease edge at v.
            let others: Vec<f64> = t.vert_edges[v]
                .iter()
                .filter(|&&o| o != e)
                .map(|&o| m.crease.get(&t.edges[o]).copied().unwrap_or(0.0))
                .filter(|&s| s > 0.0)
                .collect();
            let so = if others.len() == 1 { others[0] } else { s };
            let c = (0.75 * s + 0.25 * so - 1.0).max(0.0);
            if c > 0.0 {
                crease.insert(key(v, nv + e), c);
            }
        }
    }
    let mut corner = vec![0.0; pts.len()];
    for (c, s) in corner.iter_mut().zip(&m.corner) {
        *c = (s - 1.0).max(0.0);
    }
    (Local { pts, faces, crease, corner }, offset)
}

/// The sub-mesh of `m`: face `f` first (rotated to start at its corner `start`) and every face
/// touching one of its vertices, renumbered.
fn ring(m: &Local, t: &Topo, f: usize, start: usize) -> Local {
    let face = &m.faces[f];
    let mut fs = vec![f];
    for &v in face {
        for &g in &t.vert_faces[v] {
            if !fs.contains(&g) {
                fs.push(g);
            }
        }
    }
    let mut map = HashMap::new();
    let mut pts = Vec::new();
    let mut corner = Vec::new();
    let mut faces = Vec::new();
    for (k, &g) in fs.iter().enumerate() {
        let src = &m.faces[g];
        let n = src.len();
        let rot = if k == 0 { start } else { 0 };
        let nf = (0..n)
            .map(|i| {
                let v = src[(i + rot) % n];
                *map.entry(v).or_insert_with(|| {
                    pts.push(m.pts[v]);
                    corner.push(m.corner[v]);
                    pts.len() - 1
                })
            })
            .collect();
        faces.push(nf);
    }
    let crease = m
        .crease
        .iter()
        .filter_map(|(&(a, b), &s)| Some((key(*map.get(&a)?, *map.get(&b)?), s)))
        .collect();
    Local { pts, faces, crease, corner }
}

fn limit_point(m: &Local, t: &Topo, v: usize) -> DVec3 {
    let p = m.pts[v];
    match rule(m, t, v, 0.0) {
        Rule::Corner => p,
        Rule::Crease(a, b) => (m.pts[a] + p * 4.0 + m.pts[b]) / 6.0,
        Rule::Smooth => {
            // Halstead et al. 1993 on a quad mesh: (n^2 v + 4 sum e_i + sum f_i) / (n (n + 5)).
            let n = t.vert_edges[v].len() as f64;
            let es: DVec3 = t.vert_edges[v].iter().map(|&e| m.pts[t.other(e, v)]).sum();
            let mut fs = DVec3::ZERO;
            for &f in &t.vert_faces[v] {
                let face = &m.faces[f];
                let i = face.iter().position(|&x| x == v).unwrap_or(0);
                fs += m.pts[face[(i + 2) % face.len()]];
            }
            (p * n * n + es * 4.0 + fs) / (n * (n + 5.0))
        }
    }
}

/// Regular corner: interior valence-4 quad vertex, no sharpness at it or its edges.
fn regular_vertex(m: &Local, t: &Topo, v: usize) -> bool {
    t.vert_faces[v].len() == 4
        && t.vert_edges[v].len() == 4
        && m.corner[v] == 0.0
        && t.vert_faces[v].iter().all(|&f| m.faces[f].len() == 4)
        && t.vert_edges[v].iter().all(|&e| t.sharp(m, e) == 0.0)
}

/// Vertices after `x` in the face holding the directed edge `y -> x`.
fn across(m: &Local, t: &Topo, x: usize, y: usize) -> Option<(usize, usize)> {
    for &f in &t.vert_faces[x] {
        let face = &m.faces[f];
        let n = face.len();
        for i in 0..n {
            if face[i] == y && face[(i + 1) % n] == x {
                return Some((face[(i + 2) % n], face[(i + 3) % n]));
            }
        }
    }
    None
}

/// The 16 B-spline control points (index 4 j + i, i along u) of face 0 if it is regular.
fn grid(m: &Local, t: &Topo) -> Option<[DVec3; 16]> {
    let f = &m.faces[0];
    if f.len() != 4 || !f.iter().all(|&v| regular_vertex(m, t, v)) {
        return None;
    }
    let (p0, p1, p2, p3) = (f[0], f[1], f[2], f[3]);
    let mut g = [0usize; 16];
    let s = |g: &mut [usize; 16], i: usize, j: usize, v: usize| g[4 * j + i] = v;
    s(&mut g, 1, 1, p0);
    s(&mut g, 2, 1, p1);
    s(&mut g, 2, 2, p2);
    s(&mut g, 1, 2, p3);
    let (a, b) = across(m, t, p0, p1)?;
    s(&mut g, 1, 0, a);
    s(&mut g, 2, 0, b);
    let (a, b) = across(m, t, p1, p2)?;
    s(&mut g, 3, 1, a);
    s(&mut g, 3, 2, b);
    let (a, b) = across(m, t, p2, p3)?;
    s(&mut g, 2, 3, a);
    s(&mut g, 1, 3, b);
    let (a, b) = across(m, t, p3, p0)?;
    s(&mut g, 0, 2, a);
    s(&mut g, 0, 1, b);
    let (_, b) = across(m, t, p0, g[1])?;
    s(&mut g, 0, 0, b);
    let (a, _) = across(m, t, g[2], p1)?;
    s(&mut g, 3, 0, a);
    let (_, b) = across(m, t, p2, g[14])?;
    s(&mut g, 3, 3, b);
    let (a, _) = across(m, t, g[13], p3)?;
    s(&mut g, 0, 3, a);
    Some(g.map(|i| m.pts[i]))
}

fn basis(t: f64) -> ([f64; 4], [f64; 4]) {
    let s = 1.0 - t;
    (
        [
            s * s * s / 6.0,
            (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
            (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
            t * t * t / 6.0,
        ],
        [
            -s * s / 2.0,
            (3.0 * t * t - 4.0 * t) / 2.0,
            (-3.0 * t * t + 2.0 * t + 1.0) / 2.0,
            t * t / 2.0,
        ],
    )
}

fn bspline_eval(g: &[DVec3; 16], u: f64, v: f64) -> [DVec3; 3] {
    let (bu, du) = basis(u);
    let (bv, dv) = basis(v);
    let mut r = [DVec3::ZERO; 3];
    for j in 0..4 {
        for i in 0..4 {
            let p = g[4 * j + i];
            r[0] += p * (bu[i] * bv[j]);
            r[1] += p * (du[i] * bv[j]);
            r[2] += p * (bu[i] * dv[j]);
        }
    }
    r
}

/// Adaptive evaluation of face 0 of `m` at (u, v) in [0,1]^2: (P, dP/du, dP/dv).
fn eval_local(m0: &Local, u: f64, v: f64) -> [DVec3; 3] {
    eval_local_from(m0, u, v, 0)
}

/// [`eval_local`] of a quad that is already `start` levels down.
fn eval_local_from(m0: &Local, mut u: f64, mut v: f64, start: usize) -> [DVec3; 3] {
    let mut m = m0.clone();
    // d(u', v') / d(u, v), columns: jac[0] = (du'/du, dv'/du), jac[1] = (du'/dv, dv'/dv).
    let mut jac = [[1.0, 0.0], [0.0, 1.0]];
    for depth in start..=MAX_DEPTH {
        let t = Topo::new(&m);
        let r = if let Some(g) = grid(&m, &t) {
            Some(bspline_eval(&g, u, v))
        } else if depth == MAX_DEPTH {
            let f = &m.faces[0];
            let l: Vec<DVec3> = f.iter().map(|&x| limit_point(&m, &t, x)).collect();
            let p = l[0] * ((1.0 - u) * (1.0 - v))
                + l[1] * (u * (1.0 - v))
                + l[2] * (u * v)
                + l[3] * ((1.0 - u) * v);
            let du = (l[1] - l[0]) * (1.0 - v) + (l[2] - l[3]) * v;
            let dv = (l[3] - l[0]) * (1.0 - u) + (l[2] - l[1]) * u;
            Some([p, du, dv])
        } else {
            None
        };
        if let Some([p, du, dv]) = r {
            let pu = du * jac[0][0] + dv * jac[0][1];
            let pv = du * jac[1][0] + dv * jac[1][1];
            return [p, pu, pv];
        }
        let (c, nu, nv) = descend(u, v, &mut jac);
        let (child, off) = refine(&m);
        let ct = Topo::new(&child);
        m = ring(&child, &ct, off[0] + c, 0);
        u = nu;
        v = nv;
    }
    [DVec3::ZERO; 3]
}

/// The child quad holding `(u, v)` and the point in its own parameters (children are
/// numbered and turned as `refine` makes them), composing `jac` with the step.
#[inline]
fn descend(u: f64, v: f64, jac: &mut [[f64; 2]; 2]) -> (usize, f64, f64) {
    let (c, nu, nv, a) = if u < 0.5 && v < 0.5 {
        (0, 2.0 * u, 2.0 * v, [[2.0, 0.0], [0.0, 2.0]])
    } else if v < 0.5 {
        (1, 2.0 * v, 2.0 * (1.0 - u), [[0.0, -2.0], [2.0, 0.0]])
    } else if u >= 0.5 {
        (2, 2.0 * (1.0 - u), 2.0 * (1.0 - v), [[-2.0, 0.0], [0.0, -2.0]])
    } else {
        (3, 2.0 * (1.0 - v), 2.0 * u, [[0.0, 2.0], [-2.0, 0.0]])
    };
    // a[k] = d(u', v')/d(parent k); compose with jac.
    let j = *jac;
    *jac = [
        [a[0][0] * j[0][0] + a[1][0] * j[0][1], a[0][1] * j[0][0] + a[1][1] * j[0][1]],
        [a[0][0] * j[1][0] + a[1][0] * j[1][1], a[0][1] * j[1][0] + a[1][1] * j[1][1]],
    ];
    (c, nu, nv)
}

/// `(P, dP/du, dP/dv)` from derivatives in a child's parameters and the chain's `jac`.
#[inline]
fn compose([p, du, dv]: [DVec3; 3], jac: &[[f64; 2]; 2]) -> [DVec3; 3] {
    [p, du * jac[0][0] + dv * jac[0][1], du * jac[1][0] + dv * jac[1][1]]
}

/// Levels of [`eval_local`]'s descent a patch keeps once made ([`Shared`]): below them a
/// point is within `2^-EAGER` of an irregular point (the extraordinary corner, a crease) and
/// is evaluated adaptively from the deepest kept quad.
const EAGER: usize = 8;
/// Most irregular quads kept per patch (a crease makes two per level along its edge).
const EAGER_NODES: usize = 256;

/// [`eval_local`]'s descent of one quad, made once: the regular quads as their B-spline
/// points, the irregular ones split to [`EAGER`] levels, then kept for adaptive evaluation.
#[derive(Debug)]
enum Node {
    /// A regular quad: its 16 B-spline points.
    Regular(Box<[DVec3; 16]>),
    /// An irregular quad, `depth` levels down, evaluated adaptively.
    Deep(Box<Local>, usize),
    /// An irregular quad's four children.
    Split(Box<[Node; 4]>),
}

impl Node {
    fn build(m: Local, depth: usize, budget: &mut usize) -> Node {
        let t = Topo::new(&m);
        if let Some(g) = grid(&m, &t) {
            return Node::Regular(Box::new(g));
        }
        if depth >= EAGER || *budget == 0 {
            return Node::Deep(Box::new(m), depth);
        }
        *budget -= 1;
        let (child, off) = refine(&m);
        let ct = Topo::new(&child);
        let kids: [Local; 4] = std::array::from_fn(|c| ring(&child, &ct, off[0] + c, 0));
        Node::Split(Box::new(kids.map(|k| Node::build(k, depth + 1, budget))))
    }

    /// What [`eval_local`] gives at `(u, v)`, bit for bit (the same arithmetic in the same
    /// order, only the refinements are not redone).
    fn eval(&self, mut u: f64, mut v: f64) -> [DVec3; 3] {
        let mut node = self;
        let mut jac = [[1.0, 0.0], [0.0, 1.0]];
        loop {
            match node {
                Node::Regular(g) => return compose(bspline_eval(g, u, v), &jac),
                Node::Deep(m, depth) => return compose(eval_local_from(m, u, v, *depth), &jac),
                Node::Split(kids) => {
                    let (c, nu, nv) = descend(u, v, &mut jac);
                    node = &kids[c];
                    (u, v) = (nu, nv);
                }
            }
        }
    }
}

/// A patch's 1-ring with its descent, made on first use and shared by the patch, its parts
/// and the neighbours it owns edges for.
#[derive(Debug)]
struct Shared {
    local: Local,
    tree: std::sync::OnceLock<Node>,
}

impl Shared {
    fn new(local: Local) -> Shared {
        Shared { local, tree: std::sync::OnceLock::new() }
    }

    fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        self.tree
            .get_or_init(|| Node::build(self.local.clone(), 0, &mut EAGER_NODES.clone()))
            .eval(u, v)
    }
}

/// One quad of the once-subdivided mesh as a parametric patch on a sub-rectangle of [0,1]^2.
#[derive(Clone, Debug)]
pub struct LimitPatch {
    local: Arc<Shared>,
    /// Level-0 face this quad came from.
    pub face: usize,
    /// Level-1 vertex ids of the quad's corners (canonical keys for shared edges).
    pub corners: [usize; 4],
    edge_owner: [Option<(Arc<Shared>, usize)>; 4],
    corner_pos: [Vec3; 4],
    rect: [f64; 4],
    fv: Arc<[Vec<f64>; 4]>,
}

/// Patch `(u, v)` on its edge `k` (0: v=0, 1: u=1, 2: v=1, 3: u=0) at edge parameter t.
fn on_edge(k: usize, t: f64) -> (f64, f64) {
    match k {
        0 => (t, 0.0),
        1 => (1.0, t),
        2 => (1.0 - t, 1.0),
        _ => (0.0, 1.0 - t),
    }
}

impl LimitPatch {
    fn eval_full(&self, u: f64, v: f64) -> [DVec3; 3] {
        let mut r = self.local.eval(u, v);
        let corner =
            [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].iter().position(|&c| c == (u, v));
        if let Some(c) = corner {
            r[0] = self.corner_pos[c].as_dvec3();
            return r;
        }
        let edge = if v == 0.0 {
            Some((0, u))
        } else if u == 1.0 {
            Some((1, v))
        } else if v == 1.0 {
            Some((2, 1.0 - u))
        } else if u == 0.0 {
            Some((3, 1.0 - v))
        } else {
            None
        };
        if let Some((k, t)) = edge
            && let Some((owner, ok)) = &self.edge_owner[k]
        {
            {
                let (a, b) = (self.corners[k], self.corners[(k + 1) % 4]);
                let tc = if a < b { t } else { 1.0 - t };
                // The owner runs lo -> hi, so its own edge parameter is tc.
                let (ou, ov) = on_edge(*ok, tc);
                r[0] = owner.eval(ou, ov)[0];
            }
        }
        r
    }

    /// Limit position and derivatives at `(u, v)` in [0,1]^2 of this (sub-)patch.
    pub fn eval(&self, u: f32, v: f32) -> (Vec3, Vec3, Vec3) {
        let [u0, u1, v0, v1] = self.rect;
        let (su, sv) = (u1 - u0, v1 - v0);
        let pu = if u == 0.0 {
            u0
        } else if u == 1.0 {
            u1
        } else {
            u0 + su * u as f64
        };
        let pv = if v == 0.0 {
            v0
        } else if v == 1.0 {
            v1
        } else {
            v0 + sv * v as f64
        };
        let [p, du, dv] = self.eval_full(pu.clamp(0.0, 1.0), pv.clamp(0.0, 1.0));
        (p.as_vec3(), (du * su).as_vec3(), (dv * sv).as_vec3())
    }

    /// Facevarying data at `(u, v)`: bilinear in the level-1 quad, whose corners carry the
    /// level-0 face's bilinear values (corner, edge midpoint, face centre, edge midpoint).
    pub fn eval_facevarying(&self, u: f32, v: f32) -> Vec<f32> {
        let [u0, u1, v0, v1] = self.rect;
        let (u, v) = (u0 + (u1 - u0) * u as f64, v0 + (v1 - v0) * v as f64);
        let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
        (0..self.fv[0].len())
            .map(|i| (0..4).map(|k| w[k] * self.fv[k][i]).sum::<f64>() as f32)
            .collect()
    }

    /// The 16 bicubic B-spline control points (index `4 j + i`, `i` along u) when the whole
    /// quad is regular (and this is not a split sub-patch).
    pub fn bspline(&self) -> Option<[Vec3; 16]> {
        if self.rect != [0.0, 1.0, 0.0, 1.0] {
            return None;
        }
        let t = Topo::new(&self.local.local);
        grid(&self.local.local, &t).map(|g| g.map(|p| p.as_vec3()))
    }

    /// A conservative box: the hull of the 1-ring control points at the deepest level whose
    /// child quad contains the whole parameter rectangle (every rule is a convex combination).
    pub fn bound(&self) -> (Vec3, Vec3) {
        let mut m = self.local.local.clone();
        let [mut u0, mut u1, mut v0, mut v1] = self.rect;
        for _ in 0..MAX_DEPTH {
            let c = if u1 <= 0.5 && v1 <= 0.5 {
                0
            } else if u0 >= 0.5 && v1 <= 0.5 {
                1
            } else if u0 >= 0.5 && v0 >= 0.5 {
                2
            } else if u1 <= 0.5 && v0 >= 0.5 {
                3
            } else {
                break;
            };
            let map = |u: f64, v: f64| match c {
                0 => (2.0 * u, 2.0 * v),
                1 => (2.0 * v, 2.0 * (1.0 - u)),
                2 => (2.0 * (1.0 - u), 2.0 * (1.0 - v)),
                _ => (2.0 * (1.0 - v), 2.0 * u),
            };
            let (a, b) = map(u0, v0);
            let (cc, d) = map(u1, v1);
            (u0, u1, v0, v1) = (a.min(cc), a.max(cc), b.min(d), b.max(d));
            let (child, off) = refine(&m);
            let ct = Topo::new(&child);
            m = ring(&child, &ct, off[0] + c, 0);
        }
        let lo = m.pts.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
        let hi = m.pts.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
        // Round outward by one f32 ulp-ish margin so the f32 box stays conservative.
        let pad = (hi - lo).max_element() * 1e-6 + 1e-30;
        ((lo - pad).as_vec3(), (hi + pad).as_vec3())
    }

    fn sub(&self, r: [f64; 4]) -> LimitPatch {
        LimitPatch { rect: r, edge_owner: Default::default(), ..self.clone() }
    }

    /// The part `[u0, u1] x [v0, v1]` of this patch (parameters of this patch), as a patch of
    /// its own, for [`LimitPatch::bound`]; like the halves of [`LimitPatch::split_u`], it
    /// evaluates its own points, without edge routing.
    pub fn part(&self, u: [f64; 2], v: [f64; 2]) -> LimitPatch {
        let [u0, u1, v0, v1] = self.rect;
        let (su, sv) = (u1 - u0, v1 - v0);
        self.sub([u0 + su * u[0], u0 + su * u[1], v0 + sv * v[0], v0 + sv * v[1]])
    }

    /// Whether two handles are of the same patch of the same mesh (shared refinement data,
    /// same face, same parameter rectangle).
    pub fn same(&self, other: &LimitPatch) -> bool {
        Arc::ptr_eq(&self.local, &other.local)
            && self.corners == other.corners
            && self.rect == other.rect
    }

    /// Split at u = 1/2 of this patch's rectangle. Sub-patches evaluate their own points
    /// (no edge routing), so the dicer must keep shared edges on the unsplit patches' grids.
    pub fn split_u(&self) -> (LimitPatch, LimitPatch) {
        let [u0, u1, v0, v1] = self.rect;
        let m = 0.5 * (u0 + u1);
        (self.sub([u0, m, v0, v1]), self.sub([m, u1, v0, v1]))
    }

    /// Split at v = 1/2 of this patch's rectangle.
    pub fn split_v(&self) -> (LimitPatch, LimitPatch) {
        let [u0, u1, v0, v1] = self.rect;
        let m = 0.5 * (v0 + v1);
        (self.sub([u0, u1, v0, m]), self.sub([u0, u1, m, v1]))
    }
}

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
