//! Rational tensor-product Bezier patches: evaluation with partial derivatives, sub-patches
//! by blossoming, and the control hull.
//!
//! Invariants: the net holds `(du + 1) * (dv + 1)` homogeneous points `(w p, w)`, u-major;
//! with positive weights the surface lies in the convex hull of the projected points
//! `p`, and so does every sub-patch (whose net is computed exactly, up to rounding).

use glam::{DVec3, DVec4};

use super::MAX_ORDER;

/// A rational Bezier patch of degree `du` in u and `dv` in v over `[0, 1]^2`.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierPatch {
    /// Degree in u.
    pub du: usize,
    /// Degree in v.
    pub dv: usize,
    /// Homogeneous control points `(w x, w y, w z, w)`, `net[j * (du + 1) + i]`.
    pub net: Vec<DVec4>,
}

/// A point of a patch with its first partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchEval {
    /// Position.
    pub p: DVec3,
    /// `dP/du`.
    pub dpdu: DVec3,
    /// `dP/dv`.
    pub dpdv: DVec3,
}

/// Bernstein polynomials of degree `n` at `t` and their derivatives, in `b[..=n]`, `d[..=n]`.
fn bernstein(
    n: usize,
    t: f64,
    b: &mut [f64; MAX_ORDER as usize],
    d: &mut [f64; MAX_ORDER as usize],
) {
    let s = 1.0 - t;
    b[0] = 1.0;
    d[0] = 0.0;
    for k in 1..=n {
        // Degree k - 1 is in b[..k]; the derivative of degree n is taken at k == n.
        if k == n {
            for i in 0..=n {
                let left = if i > 0 { b[i - 1] } else { 0.0 };
                let right = if i < n { b[i] } else { 0.0 };
                d[i] = n as f64 * (left - right);
            }
        }
        let mut prev = 0.0;
        for item in b.iter_mut().take(k) {
            let here = *item;
            *item = s * here + prev;
            prev = t * here;
        }
        b[k] = prev;
    }
}

impl BezierPatch {
    /// A patch from its degrees and net (`(du + 1) * (dv + 1)` points, degrees below
    /// [`MAX_ORDER`]).
    pub fn new(du: usize, dv: usize, net: Vec<DVec4>) -> BezierPatch {
        debug_assert_eq!(net.len(), (du + 1) * (dv + 1));
        BezierPatch { du, dv, net }
    }

    /// Control point `(i, j)`.
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> DVec4 {
        self.net[j * (self.du + 1) + i]
    }

    /// Position and partial derivatives at `(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> PatchEval {
        const N: usize = MAX_ORDER as usize;
        let (mut bu, mut du) = ([0.0; N], [0.0; N]);
        let (mut bv, mut dv) = ([0.0; N], [0.0; N]);
        bernstein(self.du, u, &mut bu, &mut du);
        bernstein(self.dv, v, &mut bv, &mut dv);
        let (mut a, mut au, mut av) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        for j in 0..=self.dv {
            let (mut row, mut row_u) = (DVec4::ZERO, DVec4::ZERO);
            for i in 0..=self.du {
                let h = self.at(i, j);
                row += h * bu[i];
                row_u += h * du[i];
            }
            a += row * bv[j];
            au += row_u * bv[j];
            av += row * dv[j];
        }
        let p = a.truncate() / a.w;
        PatchEval {
            p,
            dpdu: (au.truncate() - p * au.w) / a.w,
            dpdv: (av.truncate() - p * av.w) / a.w,
        }
    }

    /// The unit normal `dP/du x dP/dv` at `(u, v)`; where that vanishes (a collapsed edge or
    /// corner), the normal a little way into the patch, else the patch's average normal,
    /// else +z.
    pub fn normal(&self, u: f64, v: f64) -> DVec3 {
        let e = self.eval(u, v);
        if let Some(n) = e.dpdu.cross(e.dpdv).try_normalize() {
            return n;
        }
        let nudge = |t: f64| if t < 0.5 { t + 1e-3 } else { t - 1e-3 };
        let e = self.eval(nudge(u), nudge(v));
        e.dpdu.cross(e.dpdv).try_normalize().unwrap_or_else(|| self.average_normal())
    }

    /// The normal of the corners' diagonals (the vector area of their bilinear patch), or
    /// +z when that vanishes.
    pub fn average_normal(&self) -> DVec3 {
        let c = |i: usize, j: usize| {
            let h = self.at(i, j);
            h.truncate() / h.w
        };
        let (p0, p1, p2, p3) = (c(0, 0), c(self.du, 0), c(0, self.dv), c(self.du, self.dv));
        (p3 - p0).cross(p2 - p1).try_normalize().unwrap_or(DVec3::Z)
    }

    /// The projected control points `p = (w p) / w`: with positive weights the patch lies in
    /// their convex hull.
    pub fn hull(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.net.iter().map(|h| h.truncate() / h.w)
    }

    /// The same surface over `[u0, u1] x [v0, v1]`, reparametrised to `[0, 1]^2`.
    pub fn sub(&self, u: [f64; 2], v: [f64; 2]) -> BezierPatch {
        let (nu, nv) = (self.du + 1, self.dv + 1);
        // Along u, row by row.
        let mut rows = Vec::with_capacity(nu * nv);
        let mut poly = Vec::with_capacity(nu.max(nv));
        for j in 0..nv {
            poly.clear();
            poly.extend((0..nu).map(|i| self.at(i, j)));
            for k in 0..nu {
                rows.push(blossom_bezier(&poly, u, k));
            }
        }
        // Along v, column by column.
        let mut net = vec![DVec4::ZERO; nu * nv];
        for i in 0..nu {
            poly.clear();
            poly.extend((0..nv).map(|j| rows[j * nu + i]));
            for k in 0..nv {
                net[k * nu + i] = blossom_bezier(&poly, v, k);
            }
        }
        BezierPatch::new(self.du, self.dv, net)
    }
}

/// Control point `k` of the Bezier curve `poly` restricted to `[a, b]`: its blossom at
/// `(a, .., a, b, .., b)` with `k` copies of `b` (de Casteljau with varying parameters).
fn blossom_bezier(poly: &[DVec4], [a, b]: [f64; 2], k: usize) -> DVec4 {
    let n = poly.len() - 1;
    let mut d = [DVec4::ZERO; MAX_ORDER as usize];
    d[..=n].copy_from_slice(poly);
    for level in 0..n {
        let t = if level < k { b } else { a };
        for i in 0..n - level {
            d[i] = d[i] * (1.0 - t) + d[i + 1] * t;
        }
    }
    d[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binomial(n: usize, k: usize) -> f64 {
        (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
    }

    #[test]
    fn bernstein_values_and_derivatives() {
        const N: usize = MAX_ORDER as usize;
        for n in 1..N {
            for t in [0.0, 0.25, 0.6, 1.0] {
                let (mut b, mut d) = ([0.0; N], [0.0; N]);
                bernstein(n, t, &mut b, &mut d);
                for k in 0..=n {
                    let exact = binomial(n, k) * t.powi(k as i32) * (1.0 - t).powi((n - k) as i32);
                    assert!((b[k] - exact).abs() < 1e-12, "n {n} k {k} t {t}");
                    let h = 1e-6;
                    let f =
                        |t: f64| binomial(n, k) * t.powi(k as i32) * (1.0 - t).powi((n - k) as i32);
                    let fd = (f(t + h) - f(t - h)) / (2.0 * h);
                    assert!((d[k] - fd).abs() < 1e-4 * (1.0 + fd.abs()), "n {n} k {k} t {t}");
                }
            }
        }
    }

    #[test]
    fn sub_patch_is_the_same_surface() {
        let net: Vec<DVec4> = (0..12)
            .map(|k| {
                let (i, j) = ((k % 4) as f64, (k / 4) as f64);
                DVec4::new(i, j, (i * j).sin(), 1.0 + 0.3 * (k as f64).cos())
                    * DVec4::new(1.0, 1.0, 1.0, 1.0)
            })
            .map(|h| DVec4::new(h.x * h.w, h.y * h.w, h.z * h.w, h.w))
            .collect();
        let p = BezierPatch::new(3, 2, net);
        let s = p.sub([0.2, 0.7], [0.1, 0.5]);
        for (a, b) in [(0.0, 0.0), (0.3, 0.9), (1.0, 1.0), (0.5, 0.25)] {
            let want = p.eval(0.2 + 0.5 * a, 0.1 + 0.4 * b);
            let got = s.eval(a, b);
            assert!((want.p - got.p).length() < 1e-12, "({a}, {b})");
            assert!((want.dpdu * 0.5 - got.dpdu).length() < 1e-10);
            assert!((want.dpdv * 0.4 - got.dpdv).length() < 1e-10);
        }
    }
}
