//! The bilinear weights of the point of a micropolygon at a sample, shared by the hider's
//! AOVs and trims and by CSG's depth order (moved here from the hider for the latter).

use crate::shepard_weights;

/// The bilinear weights `[(1-u)(1-v), u(1-v), uv, (1-u)v]` of the point `(u, v)` of the
/// quadrilateral `v` (raster x, y relative to the sample, cyclic order) that lies at the
/// sample, `B(u, v) = 0`. Geometric values (N, P, s, t, motion) are interpolated with them, so
/// a value that is bilinear over the micropolygon (as its position is, up to the curvature of
/// the surface within it) is exact at the sample, which Shepard's weights are not.
///
/// Derivation: with `e = p1 - p0`, `f = p3 - p0`, `g = p0 - p1 + p2 - p3` and `h = -p0`,
/// `B(u, v) = 0` is `h = u e + v f + u v g`. Crossing with `e + v g` eliminates `u`:
/// `k2 v^2 + k1 v + k0 = 0` with `k2 = g x f`, `k1 = e x f + h x g`, `k0 = h x e`
/// (`a x b = a.x b.y - a.y b.x`); then `u = (h - v f) / (e + v g)` along the larger
/// component. The root in `[0, 1]` is taken (clamped for a sample on an edge); a degenerate or
/// non-convex quad with no usable root falls back to Shepard's weights.
pub fn bilinear_weights(v: &[[f32; 3]; 4]) -> [f32; 4] {
    let p = |k: usize| [f64::from(v[k][0]), f64::from(v[k][1])];
    let (p0, p1, p2, p3) = (p(0), p(1), p(2), p(3));
    let sub = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let e = sub(p1, p0);
    let f = sub(p3, p0);
    let g = [p0[0] - p1[0] + p2[0] - p3[0], p0[1] - p1[1] + p2[1] - p3[1]];
    let h = [-p0[0], -p0[1]];
    let (k2, k1, k0) = (cross(g, f), cross(e, f) + cross(h, g), cross(h, e));
    let scale = k1.abs().max(k0.abs()).max(k2.abs());
    let in_unit = |t: f64| (-1e-4..=1.0 + 1e-4).contains(&t);
    let v_root = if scale.is_nan() || scale <= 0.0 || !scale.is_finite() {
        None
    } else if k2.abs() <= 1e-9 * scale {
        (k1 != 0.0).then(|| -k0 / k1)
    } else {
        let disc = k1 * k1 - 4.0 * k0 * k2;
        if disc < 0.0 {
            None
        } else {
            let sq = disc.sqrt();
            // The numerically stable pair of roots.
            let q = -0.5 * (k1 + k1.signum() * sq);
            let (r1, r2) = (q / k2, if q != 0.0 { k0 / q } else { f64::NAN });
            [r1, r2].into_iter().find(|&r| in_unit(r))
        }
    };
    let Some(vv) = v_root.filter(|&t| in_unit(t)) else { return shepard_weights(v) };
    let vv = vv.clamp(0.0, 1.0);
    let den = [e[0] + vv * g[0], e[1] + vv * g[1]];
    let a = if den[0].abs() >= den[1].abs() { 0 } else { 1 };
    if den[a] == 0.0 {
        return shepard_weights(v);
    }
    let u = (h[a] - vv * f[a]) / den[a];
    if !in_unit(u) {
        return shepard_weights(v);
    }
    let u = u.clamp(0.0, 1.0);
    [(1.0 - u) * (1.0 - vv), u * (1.0 - vv), u * vv, (1.0 - u) * vv].map(|w| w as f32)
}
