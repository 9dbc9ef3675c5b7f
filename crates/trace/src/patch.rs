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

/// The hit with `t > 0` of `origin + t dir` with triangle `(a, b, c)`, from either side:
/// Woop, Benthin and Wald's watertight test ("Watertight Ray/Triangle Intersection", JCGT
/// 2(1), 2013). The vertices are moved to the ray's origin and sheared so that the ray runs
/// along the new `z` axis; the edge functions are then 2D cross products of the sheared
/// vertices. Two triangles sharing an edge compute that edge's function from the same
/// sheared vertices with the operands swapped, so they get the same magnitude with opposite
/// signs, bit for bit: a ray through the edge is inside one of them (both, when the function
/// is exactly 0), never outside both, and a ray through a shared vertex is inside one of the
/// triangles around it. An edge function that rounds to 0 is recomputed in f64, where the
/// products are exact. Moeller-Trumbore, used before, let about 8% of the rays aimed at
/// shared edges and vertices slip through (`rays_through_shared_edges_...`).
#[inline]
pub(crate) fn triangle(tri: &[Vec3; 3], origin: Vec3, dir: Vec3) -> Option<TriangleHit> {
    let d = dir.to_array();
    let ad = dir.abs();
    // The ray's dominant axis becomes z; x and y keep the handedness (swapped if it points
    // down z), which only fixes the edge functions' common sign.
    let kz = if ad.x >= ad.y && ad.x >= ad.z {
        0
    } else if ad.y >= ad.z {
        1
    } else {
        2
    };
    if d[kz] == 0.0 || !dir.is_finite() {
        return None;
    }
    let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
    if d[kz] < 0.0 {
        std::mem::swap(&mut kx, &mut ky);
    }
    let (sx, sy, sz) = (d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
    let rel = tri.map(|p| (p - origin).to_array());
    let [a, b, c] = rel.map(|p| [p[kx] - sx * p[kz], p[ky] - sy * p[kz]]);
    let edge = |p: [f32; 2], q: [f32; 2]| {
        let e = p[0] * q[1] - p[1] * q[0];
        if e != 0.0 {
            return e;
        }
        let (p, q) = (p.map(f64::from), q.map(f64::from));
        (p[0] * q[1] - p[1] * q[0]) as f32
    };
    // Weights (unnormalised) of a, b and c: each the function of the opposite edge.
    let (wa, wb, wc) = (edge(c, b), edge(a, c), edge(b, a));
    if (wa < 0.0 || wb < 0.0 || wc < 0.0) && (wa > 0.0 || wb > 0.0 || wc > 0.0) {
        return None;
    }
    let det = wa + wb + wc;
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let [za, zb, zc] = rel.map(|p| sz * p[kz]);
    let inv = 1.0 / det;
    let t = (wa * za + wb * zb + wc * zc) * inv;
    if t.is_nan() || t <= 0.0 {
        return None;
    }
    let (wb, wc) = ((wb * inv).clamp(0.0, 1.0), (wc * inv).clamp(0.0, 1.0));
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

    /// Rays aimed at points of the shared edges and vertices of a bumpy triangulated grid
    /// (the worst case for a watertight test: the aim point is within an ulp of the edge,
    /// on either side of it after rounding) must each hit some triangle: the grid covers every
    /// point they aim at, and a ray that misses both triangles of an edge sees through the
    /// surface. Moeller-Trumbore lets about 1 in 100 of them through; the test is exact, so
    /// the expectation is none, whatever the ray's origin or direction.
    #[test]
    fn rays_through_shared_edges_and_vertices_never_slip_through() {
        let n = 8;
        let z = |i: usize, j: usize| 0.3 * ((i * 7 + j * 13) % 5) as f32 - 0.6;
        let at = |i: usize, j: usize| {
            Vec3::new(i as f32 * 0.37 - 1.3, j as f32 * 0.41 - 1.7, z(i, j) + 4.0)
        };
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
        let mut rng = reyes_sampling::rng::SplitMix64::from_state(17);
        let mut slipped = 0;
        let trials = 20_000;
        for k in 0..trials {
            // An interior grid edge (horizontal, vertical or the quads' diagonal) or vertex.
            let i = 1 + (rng.next_u64() % (n as u64 - 2)) as usize;
            let j = 1 + (rng.next_u64() % (n as u64 - 2)) as usize;
            let t = rng.next_f32();
            let target = match k % 4 {
                0 => at(i, j).lerp(at(i + 1, j), t),
                1 => at(i, j).lerp(at(i, j + 1), t),
                2 => at(i, j).lerp(at(i + 1, j + 1), t),
                _ => at(i, j),
            };
            let origin = Vec3::new(
                rng.next_f32() * 6.0 - 3.0,
                rng.next_f32() * 6.0 - 3.0,
                rng.next_f32() * 2.0 - 9.0,
            );
            let dir = (target - origin) * (0.5 + rng.next_f32());
            if !tris.iter().any(|tri| triangle(tri, origin, dir).is_some()) {
                slipped += 1;
            }
        }
        assert_eq!(slipped, 0, "{slipped} of {trials} rays slipped through shared edges");
    }

    /// The hit's parameter and weights agree with the plane and barycentric coordinates,
    /// from either winding and from either side.
    #[test]
    fn triangle_hits_give_the_ray_parameter_and_the_dicer_uv() {
        let (a, b, c) =
            (Vec3::new(0.0, 0.0, 2.0), Vec3::new(2.0, 0.0, 2.0), Vec3::new(0.0, 2.0, 2.0));
        let origin = Vec3::new(0.5, 0.25, 0.0);
        for dir in [Vec3::Z, Vec3::Z * 3.0] {
            let h = triangle(&[a, b, c], origin, dir).expect("hit");
            assert!((h.t * dir.z - 2.0).abs() < 1e-6, "{h:?}");
            // Weights: b 0.25, c 0.125; u = wb / (1 - wc), v = wc.
            assert!((h.v - 0.125).abs() < 1e-6 && (h.u - 0.25 / 0.875).abs() < 1e-6, "{h:?}");
        }
        assert!(triangle(&[a, c, b], origin, Vec3::Z).is_some(), "the other winding");
        assert!(triangle(&[a, b, c], origin + Vec3::Z * 3.0, -Vec3::Z).is_some(), "from behind");
        assert!(triangle(&[a, b, c], origin, -Vec3::Z).is_none(), "behind the origin");
        assert!(triangle(&[a, b, c], Vec3::new(1.5, 1.5, 0.0), Vec3::Z).is_none(), "outside");
        assert!(triangle(&[a, b, c], origin, Vec3::X).is_none(), "parallel");
        assert!(triangle(&[a, b, c], origin, Vec3::NAN).is_none(), "NaN");
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
