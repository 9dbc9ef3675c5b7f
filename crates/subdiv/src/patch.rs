//! A limit patch: one quad of the once-subdivided mesh, its descent made once and shared, and
//! the owner rule that makes neighbours agree bit for bit on their shared edges and corners
//! (stage: subdivision).

use glam::{DVec3, Vec3};
use std::sync::Arc;

use crate::MAX_DEPTH;
use crate::eval::{bspline_eval, compose, descend, eval_local_from, grid};
use crate::level::{Local, Topo, refine, ring};

/// Levels of [`eval_local`]'s descent a patch keeps once made ([`Shared`]): below them a
/// point is within `2^-EAGER` of an irregular point (the extraordinary corner, a crease) and
/// is evaluated adaptively from the deepest kept quad.
pub(crate) const EAGER: usize = 8;
/// Most irregular quads kept per patch (a crease makes two per level along its edge).
pub(crate) const EAGER_NODES: usize = 256;

/// [`eval_local`]'s descent of one quad, made once: the regular quads as their B-spline
/// points, the irregular ones split to [`EAGER`] levels, then kept for adaptive evaluation.
#[derive(Debug)]
pub(crate) enum Node {
    /// A regular quad: its 16 B-spline points.
    Regular(Box<[DVec3; 16]>),
    /// An irregular quad, `depth` levels down, evaluated adaptively.
    Deep(Box<Local>, usize),
    /// An irregular quad's four children.
    Split(Box<[Node; 4]>),
}

impl Node {
    pub(crate) fn build(m: Local, depth: usize, budget: &mut usize) -> Node {
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
    pub(crate) fn eval(&self, mut u: f64, mut v: f64) -> [DVec3; 3] {
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
pub(crate) struct Shared {
    pub(crate) local: Local,
    pub(crate) tree: std::sync::OnceLock<Node>,
}

impl Shared {
    pub(crate) fn new(local: Local) -> Shared {
        Shared { local, tree: std::sync::OnceLock::new() }
    }

    pub(crate) fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        self.tree
            .get_or_init(|| Node::build(self.local.clone(), 0, &mut EAGER_NODES.clone()))
            .eval(u, v)
    }
}

/// One quad of the once-subdivided mesh as a parametric patch on a sub-rectangle of [0,1]^2.
#[derive(Clone, Debug)]
pub struct LimitPatch {
    pub(crate) local: Arc<Shared>,
    /// Level-0 face this quad came from.
    pub face: usize,
    /// Level-1 vertex ids of the quad's corners (canonical keys for shared edges).
    pub corners: [usize; 4],
    pub(crate) edge_owner: [Option<(Arc<Shared>, usize)>; 4],
    pub(crate) corner_pos: [Vec3; 4],
    pub(crate) rect: [f64; 4],
    pub(crate) fv: Arc<[Vec<f64>; 4]>,
}

/// Patch `(u, v)` on its edge `k` (0: v=0, 1: u=1, 2: v=1, 3: u=0) at edge parameter t.
pub(crate) fn on_edge(k: usize, t: f64) -> (f64, f64) {
    match k {
        0 => (t, 0.0),
        1 => (1.0, t),
        2 => (1.0 - t, 1.0),
        _ => (0.0, 1.0 - t),
    }
}

impl LimitPatch {
    pub(crate) fn eval_full(&self, u: f64, v: f64) -> [DVec3; 3] {
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

    pub(crate) fn sub(&self, r: [f64; 4]) -> LimitPatch {
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
