//! Real roots of low-degree polynomials in `f64`: a cancellation-free quadratic and an
//! interval root isolator for degree up to 4 (the torus quartic).
//!
//! Invariants: roots are returned in ascending order, every returned root is finite, and no
//! function panics or loops without bound on any input (NaN coefficients give no roots).

/// At most four real roots, ascending.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Roots {
    values: [f64; 4],
    len: usize,
}

impl Roots {
    /// The roots found, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    /// Appends `x` unless it is not finite, there is no room, or it repeats the last root.
    fn push(&mut self, x: f64) {
        if !x.is_finite() || self.len == self.values.len() {
            return;
        }
        if self.len > 0 && self.values[self.len - 1] == x {
            return;
        }
        self.values[self.len] = x;
        self.len += 1;
    }
}

/// Real roots of `a x^2 + b x + c = 0`, ascending, without catastrophic cancellation: the
/// larger-magnitude root comes from `q = -(b + sign(b) sqrt(disc)) / 2` and the other from
/// `c / q`. A vanishing `a` degrades to the linear equation; a double root is reported once.
pub(crate) fn quadratic(a: f64, b: f64, c: f64) -> Roots {
    let mut roots = Roots::default();
    if a == 0.0 {
        if b != 0.0 {
            roots.push(-c / b);
        }
        return roots;
    }
    let disc = b * b - 4.0 * a * c;
    if disc.is_nan() || disc < 0.0 {
        return roots;
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    let (r0, r1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    let (lo, hi) = if r0 <= r1 { (r0, r1) } else { (r1, r0) };
    roots.push(lo);
    roots.push(hi);
    roots
}

/// `p(x)` and `p'(x)` for the coefficients `c[0] + c[1] x + c[2] x^2 + ...` (Horner).
fn eval(c: &[f64], x: f64) -> (f64, f64) {
    let mut p = 0.0;
    let mut dp = 0.0;
    for &k in c.iter().rev() {
        dp = dp * x + p;
        p = p * x + k;
    }
    (p, dp)
}

/// The root of `c` in `[a, b]`, where `p(a)` and `p(b)` have opposite signs: Newton steps
/// that stay inside the shrinking bracket, bisection otherwise.
fn refine(c: &[f64], mut a: f64, mut b: f64, fa: f64) -> f64 {
    let mut x = 0.5 * (a + b);
    let mut step_before = b - a;
    for _ in 0..200 {
        let (f, df) = eval(c, x);
        if f == 0.0 {
            return x;
        }
        if (f < 0.0) == (fa < 0.0) {
            a = x;
        } else {
            b = x;
        }
        let newton = if df != 0.0 { x - f / df } else { f64::NAN };
        let next = if newton > a && newton < b && (newton - x).abs() < 0.5 * step_before {
            newton
        } else {
            0.5 * (a + b)
        };
        step_before = (next - x).abs();
        if next == x || step_before <= 2.0 * f64::EPSILON * x.abs() || b - a <= f64::MIN_POSITIVE {
            return next;
        }
        x = next;
    }
    x
}

/// Real roots in `[lo, hi]` of the polynomial `c[0] + c[1] x + ... + c[n] x^n` (`n <= 4`)
/// at which it changes sign (or vanishes exactly at an end of a monotone piece), ascending.
///
/// The roots of the derivative split `[lo, hi]` into monotone pieces, each holding at most
/// one root, which is then bracketed and refined. Roots of even multiplicity (a ray grazing
/// a surface) have no sign change and may be missed.
pub(crate) fn roots_in(c: &[f64], lo: f64, hi: f64) -> Roots {
    let mut roots = Roots::default();
    if lo.is_nan() || hi.is_nan() || lo > hi || c.iter().any(|k| !k.is_finite()) {
        return roots;
    }
    match c.len() {
        0 | 1 => return roots,
        2 => {
            if c[1] != 0.0 {
                let x = -c[0] / c[1];
                if x >= lo && x <= hi {
                    roots.push(x);
                }
            }
            return roots;
        }
        3 => {
            for &x in quadratic(c[2], c[1], c[0]).as_slice() {
                if x >= lo && x <= hi {
                    roots.push(x);
                }
            }
            return roots;
        }
        _ => {}
    }
    let n = c.len().min(5);
    let mut derivative = [0.0; 4];
    for k in 1..n {
        derivative[k - 1] = c[k] * k as f64;
    }
    let critical = roots_in(&derivative[..n - 1], lo, hi);
    let mut breaks = [0.0; 6];
    let mut count = 0;
    breaks[count] = lo;
    count += 1;
    for &x in critical.as_slice() {
        if x > breaks[count - 1] && x < hi {
            breaks[count] = x;
            count += 1;
        }
    }
    breaks[count] = hi;
    count += 1;
    let c = &c[..n];
    for w in breaks[..count].windows(2) {
        let (a, b) = (w[0], w[1]);
        let (fa, _) = eval(c, a);
        let (fb, _) = eval(c, b);
        if fa == 0.0 {
            roots.push(a);
        } else if fb != 0.0 && (fa < 0.0) != (fb < 0.0) {
            roots.push(refine(c, a, b, fa));
        }
    }
    if eval(c, hi).0 == 0.0 {
        roots.push(hi);
    }
    roots
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_is_accurate_for_both_roots() {
        let r = quadratic(1.0, -1e8, 1.0);
        assert_eq!(r.as_slice().len(), 2);
        assert!((r.as_slice()[0] - 1e-8).abs() < 1e-20);
        assert!((r.as_slice()[1] - 1e8).abs() < 1e-6);
        assert_eq!(quadratic(1.0, 0.0, 1.0).as_slice(), &[] as &[f64]);
        assert_eq!(quadratic(0.0, 2.0, -4.0).as_slice(), &[2.0]);
        assert_eq!(quadratic(1.0, -2.0, 1.0).as_slice(), &[1.0]);
        assert_eq!(quadratic(f64::NAN, 1.0, 1.0).as_slice(), &[] as &[f64]);
    }

    #[test]
    fn quartic_roots_are_found_in_order() {
        // (x-1)(x-2)(x+3)(x-0.5) = x^4 - 0.5x^3 - 7x^2 + 9.5x - 3
        let c = [-3.0, 9.5, -7.0, -0.5, 1.0];
        let r = roots_in(&c, -10.0, 10.0);
        let expect = [-3.0, 0.5, 1.0, 2.0];
        assert_eq!(r.as_slice().len(), 4, "{r:?}");
        for (x, e) in r.as_slice().iter().zip(expect) {
            assert!((x - e).abs() < 1e-12, "{x} vs {e}");
        }
        let r = roots_in(&c, 0.75, 10.0);
        assert_eq!(r.as_slice().len(), 2);
        // Close roots: (x-1)(x-1.000001)(x^2+1).
        let (a, b) = (1.0, 1.000001);
        let c = [a * b, -(a + b), 1.0 + a * b, -(a + b), 1.0];
        let r = roots_in(&c, -5.0, 5.0);
        assert_eq!(r.as_slice().len(), 2, "{r:?}");
        assert!((r.as_slice()[0] - a).abs() < 1e-9 && (r.as_slice()[1] - b).abs() < 1e-9);
    }
}
