//! One Catmull-Clark refinement of a local mesh with the DeRose-Kass-Truong 1998 semi-sharp
//! crease rules, its topology, the 1-ring of a face, and the limit positions of vertices
//! (stage: subdivision; invariant: every rule is linear in the points and chosen by topology
//! and sharpness alone, so varyings subdivide exactly like positions).

use glam::DVec3;
use std::collections::HashMap;

pub(crate) const SHARP_INF: f64 = f64::INFINITY;

/// Internal mesh: f64 points, faces, edge sharpness keyed by sorted vertex pair, vertex sharpness.
#[derive(Clone, Debug)]
pub(crate) struct Local {
    pub(crate) pts: Vec<DVec3>,
    pub(crate) faces: Vec<Vec<usize>>,
    pub(crate) crease: HashMap<(usize, usize), f64>,
    pub(crate) corner: Vec<f64>,
}

pub(crate) fn key(a: usize, b: usize) -> (usize, usize) {
    if a < b { (a, b) } else { (b, a) }
}

pub(crate) struct Topo {
    pub(crate) edges: Vec<(usize, usize)>,
    pub(crate) edge_faces: Vec<Vec<usize>>,
    pub(crate) edge_index: HashMap<(usize, usize), usize>,
    pub(crate) vert_edges: Vec<Vec<usize>>,
    pub(crate) vert_faces: Vec<Vec<usize>>,
}

impl Topo {
    pub(crate) fn new(m: &Local) -> Topo {
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
    pub(crate) fn sharp(&self, m: &Local, e: usize) -> f64 {
        if self.edge_faces[e].len() != 2 {
            SHARP_INF
        } else {
            m.crease.get(&self.edges[e]).copied().unwrap_or(0.0)
        }
    }
    pub(crate) fn other(&self, e: usize, v: usize) -> usize {
        let (a, b) = self.edges[e];
        if a == v { b } else { a }
    }
}

#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Rule {
    Smooth,
    Crease(usize, usize),
    Corner,
}

/// The vertex rule at sharpness threshold `th` (0 for this level, 1 for the next).
pub(crate) fn rule(m: &Local, t: &Topo, v: usize, th: f64) -> Rule {
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

pub(crate) fn refine(m: &Local) -> (Local, Vec<usize>) {
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
pub(crate) fn ring(m: &Local, t: &Topo, f: usize, start: usize) -> Local {
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

pub(crate) fn limit_point(m: &Local, t: &Topo, v: usize) -> DVec3 {
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
pub(crate) fn regular_vertex(m: &Local, t: &Topo, v: usize) -> bool {
    t.vert_faces[v].len() == 4
        && t.vert_edges[v].len() == 4
        && m.corner[v] == 0.0
        && t.vert_faces[v].iter().all(|&f| m.faces[f].len() == 4)
        && t.vert_edges[v].iter().all(|&e| t.sharp(m, e) == 0.0)
}

/// Vertices after `x` in the face holding the directed edge `y -> x`.
pub(crate) fn across(m: &Local, t: &Topo, x: usize, y: usize) -> Option<(usize, usize)> {
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
