//! Derivatives from the grid: differences between neighbouring points along u (the row) and
//! v (the column), divided by `du`/`dv` at the point: centred inside, one-sided at the edges
//! and next to inactive points (a point whose both neighbours are inactive, or a grid one
//! point wide, or `du` 0, has derivative 0). A uniform value has derivative 0.

use super::GridContext;
use super::geom::{cross, length, scale};
use super::value::{Mask, Num};

impl GridContext<'_> {
    /// `Du(x)` (`along_v` false) or `Dv(x)`.
    pub(crate) fn deriv(&self, x: &Num, along_v: bool, mask: &Mask) -> Num {
        let n = self.n;
        if !x.varying {
            return Num::zeros(x.w, false, n);
        }
        let d = self.global_num(if along_v { "dv" } else { "du" });
        let (stride, count) = if along_v { (self.nu, self.nv) } else { (1, self.nu) };
        let mut out = Num::zeros(x.w, true, n);
        for i in mask.iter() {
            let k = if along_v { i / self.nu } else { i % self.nu };
            let prev = k > 0 && mask.on[i - stride];
            let next = k + 1 < count && mask.on[i + stride];
            let (a, b, steps) = match (prev, next) {
                (true, true) => (i - stride, i + stride, 2.0),
                (false, true) => (i, i + stride, 1.0),
                (true, false) => (i - stride, i, 1.0),
                (false, false) => continue,
            };
            let h = d.f(i) * steps;
            if h == 0.0 {
                continue;
            }
            let (xa, xb) = (x.lane(a), x.lane(b));
            for (c, o) in out.lane_mut(i).iter_mut().enumerate() {
                *o = (xb[c] - xa[c]) / h;
            }
        }
        out
    }

    /// `Deriv(num, den)`: `Du(num)/Du(den) + Dv(num)/Dv(den)`, a term dropped where its
    /// denominator is 0.
    pub(crate) fn deriv_by(&self, num: &Num, den: &Num, mask: &Mask) -> Num {
        let n = self.n;
        let (nu, nv) = (self.deriv(num, false, mask), self.deriv(num, true, mask));
        let (du, dv) = (self.deriv(den, false, mask), self.deriv(den, true, mask));
        super::value::map_n(n, mask, &[&nu, &nv, &du, &dv], num.w, |l, o| {
            for (c, oc) in o.iter_mut().enumerate() {
                let t = |x: &[f32], d: &[f32]| if d[0] != 0.0 { x[c] / d[0] } else { 0.0 };
                *oc = t(l[0], l[2]) + t(l[1], l[3]);
            }
        })
    }

    /// `area(p)`: `length(Du(p) du ^ Dv(p) dv)`, the area of the micropolygon at each point.
    pub(crate) fn area(&self, p: &Num, mask: &Mask) -> Num {
        let (pu, pv) = (self.deriv(p, false, mask), self.deriv(p, true, mask));
        let (du, dv) = (self.global_num("du"), self.global_num("dv"));
        super::value::map_n(self.n, mask, &[&pu, &pv, &du, &dv], 1, |l, o| {
            let a = scale([l[0][0], l[0][1], l[0][2]], l[2][0]);
            let b = scale([l[1][0], l[1][1], l[1][2]], l[3][0]);
            o[0] = length(cross(a, b));
        })
    }

    /// `calculatenormal(p)`: `Du(p) ^ Dv(p)`.
    pub(crate) fn calculatenormal(&self, p: &Num, mask: &Mask) -> Num {
        let (pu, pv) = (self.deriv(p, false, mask), self.deriv(p, true, mask));
        super::value::map_n(self.n, mask, &[&pu, &pv], 3, |l, o| {
            o.copy_from_slice(&cross([l[0][0], l[0][1], l[0][2]], [l[1][0], l[1][1], l[1][2]]));
        })
    }
}
