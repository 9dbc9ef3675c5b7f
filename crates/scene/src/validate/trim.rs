//! The rules of a NURBS patch's trim loops (`Shape::NuPatch::trim`): every loop has a curve,
//! and every curve is a valid rational NURBS curve whose control points lie within
//! [`REACH`] domain extents of the patch's drawn domain (so that flattening it to the
//! tolerance of `patches::trim` takes a bounded number of segments).
//!
//! Invariant: no check can panic.

use super::primitives::{Check, fail, finite, finite_each, int_in};
use crate::model::{TrimCurve, TrimLoop};
use crate::patches::MAX_ORDER;
use crate::patches::trim::REACH;

/// Loop `l` at `at` of a patch drawn over `domain` = `[umin, umax, vmin, vmax]` (`None`: not
/// known yet, and the reach of the control points is not checked).
pub(super) fn trim_loop(at: &str, l: &TrimLoop, domain: Option<[f32; 4]>) -> Check {
    if l.curves.is_empty() {
        return fail(format!("{at}.curves"), "a trim loop needs at least one curve");
    }
    for (i, c) in l.curves.iter().enumerate() {
        curve(&format!("{at}.curves[{i}]"), c, domain)?;
    }
    Ok(())
}

fn curve(at: &str, c: &TrimCurve, domain: Option<[f32; 4]>) -> Check {
    let field = |name: &str| format!("{at}.{name}");
    int_in(&field("order"), c.order, 2, MAX_ORDER)?;
    let n = c.points.len();
    if (n as u64) < u64::from(c.order) {
        return fail(
            field("points"),
            format!("must have at least order = {} points, got {n}", c.order),
        );
    }
    let want = n as u64 + u64::from(c.order);
    if c.knot.len() as u64 != want {
        return fail(
            field("knot"),
            format!("must have points + order = {want} knots, got {}", c.knot.len()),
        );
    }
    for (i, &k) in c.knot.iter().enumerate() {
        finite(&format!("{at}.knot[{i}]"), k)?;
    }
    for (i, w) in c.knot.windows(2).enumerate() {
        if w[1] < w[0] {
            return fail(
                format!("{at}.knot[{}]", i + 1),
                format!("must not decrease, got {} after {}", w[1], w[0]),
            );
        }
    }
    finite(&field("min"), c.min)?;
    finite(&field("max"), c.max)?;
    let (lo, hi) = (c.knot[c.order as usize - 1], c.knot[n]);
    if c.min < lo {
        return fail(
            field("min"),
            format!(
                "must be >= knot[{}] ({lo}), the start of the valid range, got {}",
                c.order - 1,
                c.min
            ),
        );
    }
    if c.max > hi {
        return fail(
            field("max"),
            format!("must be <= knot[{n}] ({hi}), the end of the valid range, got {}", c.max),
        );
    }
    if c.max <= c.min {
        return fail(field("max"), format!("must be > min ({}), got {}", c.min, c.max));
    }
    finite_each(&field("points"), &c.points)?;
    for (i, p) in c.points.iter().enumerate() {
        if p[2] <= 0.0 {
            return fail(
                format!("{at}.points[{i}][2]"),
                format!("the weight w must be > 0, got {}", p[2]),
            );
        }
    }
    let Some([u0, u1, v0, v1]) = domain else { return Ok(()) };
    let (du, dv) = (f64::from(u1) - f64::from(u0), f64::from(v1) - f64::from(v0));
    let reach = REACH * du.max(dv);
    let (ulo, uhi) = (f64::from(u0) - reach, f64::from(u1) + reach);
    let (vlo, vhi) = (f64::from(v0) - reach, f64::from(v1) + reach);
    for (i, p) in c.points.iter().enumerate() {
        let (u, v) = (f64::from(p[0]) / f64::from(p[2]), f64::from(p[1]) / f64::from(p[2]));
        if !(ulo..=uhi).contains(&u) || !(vlo..=vhi).contains(&v) {
            return fail(
                format!("{at}.points[{i}]"),
                format!(
                    "the point (u, v) = ({}, {}) is more than {REACH} domain extent outside \
                     the patch's drawn domain [{u0}, {u1}] x [{v0}, {v1}]",
                    p[0] / p[2],
                    p[1] / p[2]
                ),
            );
        }
    }
    Ok(())
}
