//! The check primitives every section's rules are built from: finiteness, signs, intervals,
//! integer ranges, non-zero and parallel vectors and unit colours.
//!
//! Invariants: each primitive checks finiteness before any range test, reports at the path it
//! is given, and its message is the one the error catalogue shows (`must be > 0, got -1`).

use std::fmt;

use glam::DVec3;

use super::Issue;
use crate::model::{Rgb, V3};
pub(super) use crate::roll::dvec;

/// The outcome of one check: the first [`Issue`] found, if any.
pub(super) type Check = Result<(), Issue>;

pub(super) fn fail(path: impl Into<String>, message: impl Into<String>) -> Check {
    Err(Issue { path: path.into(), message: message.into() })
}

/// An interval of `f32`, each end open or closed; displays as `(0, 16]`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Interval {
    lo: f32,
    lo_closed: bool,
    hi: f32,
    hi_closed: bool,
}

impl Interval {
    /// `(lo, hi)`.
    pub(super) const fn open(lo: f32, hi: f32) -> Interval {
        Interval { lo, lo_closed: false, hi, hi_closed: false }
    }

    /// `(lo, hi]`.
    pub(super) const fn open_closed(lo: f32, hi: f32) -> Interval {
        Interval { lo, lo_closed: false, hi, hi_closed: true }
    }

    /// `[lo, hi)`.
    pub(super) const fn closed_open(lo: f32, hi: f32) -> Interval {
        Interval { lo, lo_closed: true, hi, hi_closed: false }
    }

    /// `[lo, hi]`.
    pub(super) const fn closed(lo: f32, hi: f32) -> Interval {
        Interval { lo, lo_closed: true, hi, hi_closed: true }
    }

    fn contains(self, v: f32) -> bool {
        let above = if self.lo_closed { v >= self.lo } else { v > self.lo };
        let below = if self.hi_closed { v <= self.hi } else { v < self.hi };
        above && below
    }
}

impl fmt::Display for Interval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let open = if self.lo_closed { '[' } else { '(' };
        let close = if self.hi_closed { ']' } else { ')' };
        write!(f, "{open}{}, {}{close}", self.lo, self.hi)
    }
}

/// Colours, opacities, reflectivities and glass tints: `[0, 1]`.
pub(super) const UNIT: Interval = Interval::closed(0.0, 1.0);
/// Gloss and blur cone half-angles, in degrees.
const SPREAD: Interval = Interval::closed_open(0.0, 90.0);
/// Sweep angles, in degrees.
const SWEEP: Interval = Interval::open_closed(0.0, 360.0);

/// `value` must be finite.
pub(super) fn finite(path: &str, value: f32) -> Check {
    if value.is_finite() { Ok(()) } else { fail(path, format!("must be finite, got {value}")) }
}

/// `check` on every component, each at `path[i]`. The path is written out only for a value
/// that fails (checks are pure functions of path and value, so the second call fails alike):
/// a mesh of a million points is checked without formatting a million paths.
pub(super) fn each(path: &str, values: &[f32], check: impl Fn(&str, f32) -> Check) -> Check {
    for (i, v) in values.iter().enumerate() {
        if check("", *v).is_err() {
            check(&format!("{path}[{i}]"), *v)?;
        }
    }
    Ok(())
}

/// Every component finite.
pub(super) fn finite_all(path: &str, values: &[f32]) -> Check {
    each(path, values, finite)
}

/// Every component of every item finite, item `i` at `path[i]`.
pub(super) fn finite_each<const N: usize>(path: &str, items: &[[f32; N]]) -> Check {
    for (i, item) in items.iter().enumerate() {
        if !item.iter().all(|v| v.is_finite()) {
            finite_all(&format!("{path}[{i}]"), item)?;
        }
    }
    Ok(())
}

/// Finite and `> 0`.
pub(super) fn positive(path: &str, value: f32) -> Check {
    finite(path, value)?;
    if value > 0.0 { Ok(()) } else { fail(path, format!("must be > 0, got {value}")) }
}

/// Finite and `>= 0`.
pub(super) fn non_negative(path: &str, value: f32) -> Check {
    finite(path, value)?;
    if value >= 0.0 { Ok(()) } else { fail(path, format!("must be >= 0, got {value}")) }
}

/// Finite and inside `interval`; `unit` follows the interval in the message (` degrees`).
pub(super) fn within(path: &str, value: f32, interval: Interval, unit: &str) -> Check {
    finite(path, value)?;
    if interval.contains(value) {
        Ok(())
    } else {
        fail(path, format!("must be in {interval}{unit}, got {value}"))
    }
}

/// `value > bound`, where `bound` is the (finite) value of the field `name`; `value` finite.
pub(super) fn above(path: &str, value: f32, name: &str, bound: f32) -> Check {
    if value > bound {
        Ok(())
    } else {
        fail(path, format!("must be > {name} ({bound}), got {value}"))
    }
}

/// Integer in `lo..=hi`.
pub(super) fn int_in(path: &str, value: u32, lo: u32, hi: u32) -> Check {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        fail(path, format!("must be in {lo}..={hi}, got {value}"))
    }
}

/// A cone half-angle (gloss, blur) in `[0, 90)` degrees.
pub(super) fn spread(path: &str, degrees: f32) -> Check {
    within(path, degrees, SPREAD, " degrees")
}

/// A sweep angle in `(0, 360]` degrees.
pub(super) fn sweep(path: &str, degrees: f32) -> Check {
    within(path, degrees, SWEEP, " degrees")
}

/// A colour or opacity: every channel finite and in `[0, 1]`.
pub(super) fn unit_rgb(path: &str, rgb: &Rgb) -> Check {
    each(path, rgb, |p, v| within(p, v, UNIT, ""))
}

/// A colour of light (an unlit surface's, an emission): every channel finite and >= 0,
/// unbounded above (values above 1 glow, and reach an EXR unclamped).
pub(super) fn light_rgb(path: &str, rgb: &Rgb) -> Check {
    each(path, rgb, non_negative)
}

/// Every component finite, and not all zero.
pub(super) fn nonzero_vector(path: &str, v: &V3) -> Check {
    finite_all(path, v)?;
    if v.iter().all(|&a| a == 0.0) {
        return fail(path, "must be non-zero");
    }
    Ok(())
}

/// Whether `a` and `b` are parallel (or either is zero), up to a relative `1e-6` of the
/// sine of the angle between them.
pub(super) fn parallel(a: DVec3, b: DVec3) -> bool {
    a.cross(b).length() <= 1e-6 * a.length() * b.length()
}
