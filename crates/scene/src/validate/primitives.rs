//! The check primitives every section's rules are built from: finiteness, signs, integer and
//! angle ranges, non-zero vectors and unit colours.
//!
//! Invariants: each primitive checks finiteness before any range test, reports at the path it
//! is given, and its message is the one the error catalogue shows (`must be > 0, got -1`).

use glam::DVec3;

use super::Issue;
use crate::model::{Rgb, V3};

/// The outcome of one check: the first [`Issue`] found, if any.
pub(super) type Check = Result<(), Issue>;

pub(super) fn fail(path: impl Into<String>, message: impl Into<String>) -> Check {
    Err(Issue { path: path.into(), message: message.into() })
}

/// Gloss and blur cone half-angles must be below this, in degrees.
const MAX_SPREAD: f32 = 90.0;

/// `value` must be finite.
pub(super) fn finite(path: &str, value: f32) -> Check {
    if value.is_finite() { Ok(()) } else { fail(path, format!("must be finite, got {value}")) }
}

/// Every component finite.
pub(super) fn finite_all(path: &str, values: &[f32]) -> Check {
    for (i, v) in values.iter().enumerate() {
        finite(&format!("{path}[{i}]"), *v)?;
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
    finite(path, degrees)?;
    if (0.0..MAX_SPREAD).contains(&degrees) {
        Ok(())
    } else {
        fail(path, format!("must be in [0, 90) degrees, got {degrees}"))
    }
}

/// Every component finite, and not all zero.
pub(super) fn nonzero_vector(path: &str, v: &V3) -> Check {
    finite_all(path, v)?;
    if v.iter().all(|&a| a == 0.0) {
        return fail(path, "must be non-zero");
    }
    Ok(())
}

/// A sweep angle in `(0, 360]` degrees.
pub(super) fn sweep(path: &str, degrees: f32) -> Check {
    finite(path, degrees)?;
    if degrees > 0.0 && degrees <= 360.0 {
        Ok(())
    } else {
        fail(path, format!("must be in (0, 360] degrees, got {degrees}"))
    }
}

/// A colour or opacity: every channel finite and in `[0, 1]`.
pub(super) fn unit_rgb(path: &str, rgb: &Rgb) -> Check {
    for (i, v) in rgb.iter().enumerate() {
        let p = format!("{path}[{i}]");
        finite(&p, *v)?;
        if !(0.0..=1.0).contains(v) {
            return fail(p, format!("must be in [0, 1], got {v}"));
        }
    }
    Ok(())
}

pub(super) fn dvec(v: &V3) -> DVec3 {
    DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))
}
