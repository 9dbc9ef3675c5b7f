//! Evaluation of a quad of a local mesh: the uniform bicubic B-spline where its corners are
//! regular, adaptive descent to [`crate::MAX_DEPTH`] levels elsewhere, and the chain rule that
//! carries derivatives back up (stage: subdivision; invariant: f64 inside, the same
//! arithmetic in the same order wherever a point is evaluated).

use glam::DVec3;

use crate::MAX_DEPTH;
use crate::level::{Local, Topo, across, limit_point, refine, regular_vertex, ring};

/// The 16 B-spline control points (index 4 j + i, i along u) of face 0 if it is regular.
pub(crate) fn grid(m: &Local, t: &Topo) -> Option<[DVec3; 16]> {
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

pub(crate) fn basis(t: f64) -> ([f64; 4], [f64; 4]) {
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

pub(crate) fn bspline_eval(g: &[DVec3; 16], u: f64, v: f64) -> [DVec3; 3] {
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
pub(crate) fn eval_local(m0: &Local, u: f64, v: f64) -> [DVec3; 3] {
    eval_local_from(m0, u, v, 0)
}

/// [`eval_local`] of a quad that is already `start` levels down.
pub(crate) fn eval_local_from(m0: &Local, mut u: f64, mut v: f64, start: usize) -> [DVec3; 3] {
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
pub(crate) fn descend(u: f64, v: f64, jac: &mut [[f64; 2]; 2]) -> (usize, f64, f64) {
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
pub(crate) fn compose([p, du, dv]: [DVec3; 3], jac: &[[f64; 2]; 2]) -> [DVec3; 3] {
    [p, du * jac[0][0] + dv * jac[0][1], du * jac[1][0] + dv * jac[1][1]]
}
