//! NURBS spans as rational Bezier patches: each non-empty knot span of `[umin, umax] x
//! [vmin, vmax]` by blossoming, first along u (each row of control points) then along v.
//!
//! Invariants: the shape has passed validation (knot vectors of `n + order` non-decreasing
//! values, `umin < umax` inside the valid range, `nu * nv` points with `w > 0`), so every
//! denominator of de Boor's algorithm on a non-empty span is positive.

use glam::{DVec3, DVec4};

use super::{BezierPatch, MAX_ORDER};
use crate::model::Shape;

/// The Bezier pieces of one direction: for each non-empty span `[U_s, U_s+1]` meeting
/// `[lo, hi]`, its index `s` and the clipped interval `[a, b]`.
pub(super) fn spans_of(
    knots: &[f64],
    order: usize,
    n: usize,
    lo: f64,
    hi: f64,
) -> Vec<(usize, [f64; 2])> {
    let p = order - 1;
    let mut out = Vec::new();
    for s in p..n {
        let (k0, k1) = (knots[s], knots[s + 1]);
        let (a, b) = (k0.max(lo), k1.min(hi));
        if k0 < k1 && a < b {
            out.push((s, [a, b]));
        }
    }
    out
}

/// The blossom of the B-spline of degree `p` with `knots` and control points `ctrl` on
/// span `s` (`U_s < U_s+1`) at the parameters `ts` (`p` of them).
fn blossom(knots: &[f64], ctrl: &[DVec4], p: usize, s: usize, ts: &[f64]) -> DVec4 {
    let mut d = [DVec4::ZERO; MAX_ORDER as usize];
    d[..=p].copy_from_slice(&ctrl[s - p..=s]);
    for (r, &t) in ts.iter().enumerate().map(|(r, t)| (r + 1, t)) {
        for k in (r..=p).rev() {
            let j = s - p + k;
            let alpha = (t - knots[j]) / (knots[j + p + 1 - r] - knots[j]);
            d[k] = d[k - 1] * (1.0 - alpha) + d[k] * alpha;
        }
    }
    d[p]
}

/// The Bezier control points over `[a, b]` of span `s`: blossoms at `a^(p-k) b^k`.
pub(super) fn extract(
    knots: &[f64],
    ctrl: &[DVec4],
    p: usize,
    s: usize,
    [a, b]: [f64; 2],
) -> Vec<DVec4> {
    let mut ts = vec![0.0; p];
    (0..=p)
        .map(|k| {
            for (i, t) in ts.iter_mut().enumerate() {
                *t = if i < p - k { a } else { b };
            }
            blossom(knots, ctrl, p, s, &ts)
        })
        .collect()
}

/// The numbers of non-empty u and v spans [`spans`] gives, `(0, 0)` for other shapes.
pub(super) fn span_counts(shape: &Shape) -> (usize, usize) {
    let Shape::NuPatch { nu, uorder, uknot, umin, umax, nv, vorder, vknot, vmin, vmax, .. } = shape
    else {
        return (0, 0);
    };
    let count = |knots: &[f32], order: u32, n: u32, lo: f32, hi: f32| {
        if knots.len() != n as usize + order as usize || order < 1 {
            return 0;
        }
        let k: Vec<f64> = knots.iter().map(|&k| f64::from(k)).collect();
        spans_of(&k, order as usize, n as usize, f64::from(lo), f64::from(hi)).len()
    };
    (count(uknot, *uorder, *nu, *umin, *umax), count(vknot, *vorder, *nv, *vmin, *vmax))
}

/// Every span of a valid `NuPatch` as a rational Bezier patch (v spans outer, u inner).
pub(super) fn spans(shape: &Shape, positions: Option<&[DVec3]>) -> Vec<BezierPatch> {
    let Shape::NuPatch {
        nu, uorder, uknot, umin, umax, nv, vorder, vknot, vmin, vmax, points, ..
    } = shape
    else {
        return Vec::new();
    };
    let (nu, nv, ou, ov) = (*nu as usize, *nv as usize, *uorder as usize, *vorder as usize);
    let orders = 2..=MAX_ORDER as usize;
    if points.len() != nu * nv
        || uknot.len() != nu + ou
        || vknot.len() != nv + ov
        || !orders.contains(&ou)
        || !orders.contains(&ov)
        || nu < ou
        || nv < ov
    {
        return Vec::new();
    }
    let uk: Vec<f64> = uknot.iter().map(|&k| f64::from(k)).collect();
    let vk: Vec<f64> = vknot.iter().map(|&k| f64::from(k)).collect();
    let homogeneous: Vec<DVec4> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let h = DVec4::from(p.map(f64::from));
            match positions.and_then(|q| q.get(i)) {
                Some(q) => (*q * h.w).extend(h.w),
                None => h,
            }
        })
        .collect();
    let (pu, pv) = (ou - 1, ov - 1);
    let uspans = spans_of(&uk, ou, nu, f64::from(*umin), f64::from(*umax));
    let vspans = spans_of(&vk, ov, nv, f64::from(*vmin), f64::from(*vmax));
    // Along u: every row's Bezier points for every u span, rows[u span][row][k].
    let rows: Vec<Vec<Vec<DVec4>>> = uspans
        .iter()
        .map(|&(s, ab)| {
            (0..nv).map(|j| extract(&uk, &homogeneous[j * nu..(j + 1) * nu], pu, s, ab)).collect()
        })
        .collect();
    let mut out = Vec::with_capacity(uspans.len() * vspans.len());
    for &(t, ab) in &vspans {
        for row in &rows {
            let mut net = vec![DVec4::ZERO; (pu + 1) * (pv + 1)];
            for i in 0..=pu {
                let column: Vec<DVec4> = row.iter().map(|r| r[i]).collect();
                for (k, q) in extract(&vk, &column, pv, t, ab).into_iter().enumerate() {
                    net[k * (pu + 1) + i] = q;
                }
            }
            out.push(BezierPatch::new(pu, pv, net));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Cox-de Boor basis function `N_{i,p}(t)` (half-open spans, the last span closed).
    fn basis(knots: &[f64], i: usize, p: usize, t: f64) -> f64 {
        if p == 0 {
            let last = knots[knots.len() - 1];
            let inside = knots[i] <= t && t < knots[i + 1];
            let at_end = t == last && knots[i] < knots[i + 1] && knots[i + 1] == last;
            return if inside || at_end { 1.0 } else { 0.0 };
        }
        let mut out = 0.0;
        let d0 = knots[i + p] - knots[i];
        if d0 > 0.0 {
            out += (t - knots[i]) / d0 * basis(knots, i, p - 1, t);
        }
        let d1 = knots[i + p + 1] - knots[i + 1];
        if d1 > 0.0 {
            out += (knots[i + p + 1] - t) / d1 * basis(knots, i + 1, p - 1, t);
        }
        out
    }

    #[test]
    fn spans_equal_the_cox_de_boor_surface() {
        // Order 3 by order 4, a repeated interior knot, a clipped range, uneven weights.
        let (nu, nv, ou, ov) = (5usize, 5usize, 3usize, 4usize);
        let uknot = [0.0, 0.0, 0.0, 0.4, 0.4, 1.0, 1.0, 1.0];
        let vknot = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
        let points: Vec<[f32; 4]> = (0..nu * nv)
            .map(|k| {
                let (i, j) = ((k % nu) as f32, (k / nu) as f32);
                let w = 1.0 + 0.5 * ((k * 7 % 5) as f32) / 5.0;
                [i * w, j * w, (i - j).sin() * w, w]
            })
            .collect();
        let shape = Shape::NuPatch {
            nu: nu as u32,
            uorder: ou as u32,
            uknot: uknot.map(|k| k as f32).to_vec(),
            umin: 0.1,
            umax: 0.9,
            nv: nv as u32,
            vorder: ov as u32,
            vknot: vknot.map(|k| k as f32).to_vec(),
            vmin: 0.0,
            vmax: 1.0,
            points: points.clone(),
            trim: Vec::new(),
            trim_outside: false,
        };
        let patches = spans(&shape, None);
        // u spans [0.1, 0.4], [0.4, 0.9]; v spans [0, 0.5], [0.5, 1].
        assert_eq!(patches.len(), 4);
        let ranges = [[0.1, 0.4], [0.4, 0.9]];
        let vranges = [[0.0, 0.5], [0.5, 1.0]];
        for (k, patch) in patches.iter().enumerate() {
            let (ur, vr) = (ranges[k % 2], vranges[k / 2]);
            for (a, b) in [(0.0, 0.0), (0.5, 0.5), (1.0, 0.3), (0.2, 1.0)] {
                let (u, v) = (ur[0] + a * (ur[1] - ur[0]), vr[0] + b * (vr[1] - vr[0]));
                let mut h = DVec4::ZERO;
                for j in 0..nv {
                    for i in 0..nu {
                        let w = basis(&uknot, i, ou - 1, u) * basis(&vknot, j, ov - 1, v);
                        h += DVec4::from(points[j * nu + i].map(f64::from)) * w;
                    }
                }
                let want = h.truncate() / h.w;
                let got = patch.eval(a, b).p;
                assert!((want - got).length() < 1e-6, "span {k} ({a}, {b}): {want} vs {got}");
            }
        }
    }
}
