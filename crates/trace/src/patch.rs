//! Ray intersection with bilinear patches (`f64`) and triangles (`f32`, Moeller-Trumbore).
//!
//! Invariants: a patch is `P(u,v) = lerp(lerp(P0,P1,u), lerp(P2,P3,u), v)` with corners in
//! RenderMan order, exactly as the dicer evaluates it; its outward normal is
//! `dP/du x dP/dv` (the patch's average normal where that vanishes). A triangle `(a, b, c)`
//! is the dicer's degenerate patch `P0=a, P1=b, P2=P3=c`: `v` is the weight of `c` and
//! `u = w_b / (1 - v)`, with the flat normal `(b-a) x (c-a)`. Both return the nearest hit
//! with parameter `> 0` independently of any `t_max`.
//!
//! Patch method: the ray meets the u-isoline segment `A(u) -> B(u)` only where the two are
//! coplanar, `(A(u) - o) . ((B(u) - A(u)) x d) = 0`, a quadratic in `u`; `v` and `s` then
//! follow from the closest points of the two lines, and two Newton steps on
//! `P(u,v) - o - s d = 0` polish the result. Where a root's isoline is parallel to the ray
//! the same is done over v-isolines instead.

use std::cmp::Ordering;

use glam::{DVec3, Vec3};

use crate::placement::LocalRay;
use crate::poly::quadratic;
use crate::quadric::LocalHit;

/// Tolerance on `u`, `v` outside `[0, 1]` before clamping, so that shared edges do not
/// leak between neighbouring patches through rounding.
const EDGE: f64 = 1e-9;

#[inline]
fn lerp4(p: &[DVec3; 4], u: f64, v: f64) -> DVec3 {
    let bottom = p[0].lerp(p[1], u);
    let top = p[2].lerp(p[3], u);
    bottom.lerp(top, v)
}

/// `(dP/du, dP/dv)` at `(u, v)`.
#[inline]
fn partials(p: &[DVec3; 4], u: f64, v: f64) -> (DVec3, DVec3) {
    ((p[1] - p[0]).lerp(p[3] - p[2], v), (p[2] - p[0]).lerp(p[3] - p[1], u))
}

/// Outcome of one family of isolines.
enum Isolines {
    /// Candidates `(s, u, v)` (nearest first is not guaranteed), all well conditioned.
    Found([Option<(f64, f64, f64)>; 2]),
    /// Some root's isoline was parallel to the ray, or the equation vanished identically.
    Degenerate,
}

/// Candidates of the u-isoline family of patch `p`.
fn isolines(p: &[DVec3; 4], o: DVec3, d: DVec3) -> Isolines {
    let qa = p[0] - o;
    let qb = p[1] - p[0];
    let e0 = p[2] - p[0];
    let de = (p[3] - p[1]) - e0;
    let e0xd = e0.cross(d);
    let dexd = de.cross(d);
    let a = qb.dot(dexd);
    let b = qa.dot(dexd) + qb.dot(e0xd);
    let c = qa.dot(e0xd);
    if a == 0.0 && b == 0.0 {
        return Isolines::Degenerate;
    }
    let dd = d.length_squared();
    let mut out = [None, None];
    for (slot, &u) in out.iter_mut().zip(quadratic(a, b, c).as_slice()) {
        if !(-EDGE..=1.0 + EDGE).contains(&u) {
            continue;
        }
        let u = u.clamp(0.0, 1.0);
        let e = e0 + de * u;
        let w = qa + qb * u;
        let n = d.cross(e);
        let nn = n.length_squared();
        if nn.partial_cmp(&(1e-24 * dd * e.length_squared())) != Some(Ordering::Greater) {
            return Isolines::Degenerate;
        }
        let s = w.dot(e.cross(n)) / nn;
        let v = w.dot(d.cross(n)) / nn;
        if (-EDGE..=1.0 + EDGE).contains(&v) && s > 0.0 {
            *slot = Some((s, u, v.clamp(0.0, 1.0)));
        }
    }
    Isolines::Found(out)
}

/// Two Newton steps on `P(u,v) - o - s d = 0`, kept only if they reduce the residual.
fn polish(p: &[DVec3; 4], o: DVec3, d: DVec3, mut x: (f64, f64, f64)) -> (f64, f64, f64) {
    let residual = |(s, u, v): (f64, f64, f64)| lerp4(p, u, v) - o - d * s;
    let mut r = residual(x);
    for _ in 0..2 {
        let (pu, pv) = partials(p, x.1, x.2);
        let m = -d;
        let det = pu.dot(pv.cross(m));
        if det == 0.0 || !det.is_finite() {
            break;
        }
        // Solve [pu pv -d] (du, dv, ds) = -r by Cramer's rule.
        let rhs = -r;
        let du = rhs.dot(pv.cross(m)) / det;
        let dv = pu.dot(rhs.cross(m)) / det;
        let ds = pu.dot(pv.cross(rhs)) / det;
        let next = (x.0 + ds, (x.1 + du).clamp(0.0, 1.0), (x.2 + dv).clamp(0.0, 1.0));
        let r_next = residual(next);
        let improves =
            r_next.length_squared().partial_cmp(&r.length_squared()) == Some(Ordering::Less);
        if !improves || next.0.is_nan() || next.0 <= 0.0 {
            break;
        }
        x = next;
        r = r_next;
    }
    x
}

/// Is `n` zero (or NaN), so unusable as a normal?
fn degenerate(n: DVec3) -> bool {
    let l = n.length_squared();
    l.is_nan() || l == 0.0
}

/// The nearest hit with `s > 0` of the ray with the bilinear patch `p` (object space).
pub(crate) fn bilinear(p: &[DVec3; 4], ray: &LocalRay) -> Option<LocalHit> {
    let (o, d) = (ray.o, ray.d);
    let candidates = match isolines(p, o, d) {
        Isolines::Found(c) => c,
        Isolines::Degenerate => {
            // The transposed patch swaps the roles of u and v.
            let t = [p[0], p[2], p[1], p[3]];
            match isolines(&t, o, d) {
                Isolines::Found(c) => c.map(|c| c.map(|(s, v, u)| (s, u, v))),
                Isolines::Degenerate => return None,
            }
        }
    };
    let best = candidates.into_iter().flatten().min_by(|a, b| a.0.total_cmp(&b.0))?;
    let (s, u, v) = polish(p, o, d, best);
    let (pu, pv) = partials(p, u, v);
    let mut n = pu.cross(pv);
    if degenerate(n) {
        n = (p[3] - p[0]).cross(p[2] - p[1]);
        if degenerate(n) {
            n = DVec3::Z;
        }
    }
    Some(LocalHit { s, p: lerp4(p, u, v), n, u, v })
}

/// A triangle hit in `f32`: parameter, dicer `(u, v)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TriangleHit {
    /// Ray parameter (> 0).
    pub t: f32,
    /// Dicer `u`.
    pub u: f32,
    /// Dicer `v` (the weight of the third vertex).
    pub v: f32,
}

/// Moeller-Trumbore: the hit with `t > 0` of `origin + t dir` with triangle `(a, b, c)`.
#[inline]
pub(crate) fn triangle(tri: &[Vec3; 3], origin: Vec3, dir: Vec3) -> Option<TriangleHit> {
    let [a, b, c] = *tri;
    let e1 = b - a;
    let e2 = c - a;
    let pvec = dir.cross(e2);
    let det = e1.dot(pvec);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let tvec = origin - a;
    let wb = tvec.dot(pvec) * inv;
    if !(0.0..=1.0).contains(&wb) {
        return None;
    }
    let qvec = tvec.cross(e1);
    let wc = dir.dot(qvec) * inv;
    if !(wc >= 0.0 && wb + wc <= 1.0) {
        return None;
    }
    let t = e2.dot(qvec) * inv;
    if t.is_nan() || t <= 0.0 {
        return None;
    }
    let u = if wc < 1.0 { (wb / (1.0 - wc)).clamp(0.0, 1.0) } else { 0.0 };
    Some(TriangleHit { t, u, v: wc })
}

/// The triangle's flat normal `(b-a) x (c-a)` (not normalised).
#[inline]
pub(crate) fn triangle_normal(tri: &[Vec3; 3]) -> Vec3 {
    (tri[1] - tri[0]).cross(tri[2] - tri[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Patch corners from their coordinates, in RenderMan order.
    fn corners(c: [[f64; 3]; 4]) -> [DVec3; 4] {
        c.map(DVec3::from)
    }

    #[test]
    fn flat_square_patch_is_hit_at_the_right_uv() {
        let p = corners([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [2.0, 1.0, 0.0]]);
        let ray = LocalRay::world(Vec3::new(0.5, 0.25, 3.0), Vec3::new(0.0, 0.0, -1.0));
        let hit = bilinear(&p, &ray).expect("hit");
        assert!((hit.s - 3.0).abs() < 1e-12);
        assert!((hit.u - 0.25).abs() < 1e-12 && (hit.v - 0.25).abs() < 1e-12);
        assert!(hit.n.normalize().abs_diff_eq(DVec3::Z, 1e-12));
    }

    #[test]
    fn twisted_patch_hits_satisfy_the_patch_equation() {
        let p = corners([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [1.0, 1.0, 0.0]]);
        for i in 0..=10 {
            for j in 0..=10 {
                let (u, v) = (0.01 + 0.098 * i as f64, 0.01 + 0.098 * j as f64);
                let target = lerp4(&p, u, v);
                let origin = Vec3::new(0.3, -0.2, 5.0);
                let dir = (target.as_vec3() - origin).normalize();
                let Some(hit) = bilinear(&p, &LocalRay::world(origin, dir)) else {
                    panic!("({u},{v}) missed");
                };
                let on = lerp4(&p, hit.u, hit.v);
                let along = origin.as_dvec3() + dir.as_dvec3() * hit.s;
                assert!((on - along).length() < 1e-6, "({u},{v})");
            }
        }
    }
}
