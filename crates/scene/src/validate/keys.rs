//! The rules every list of motion keys obeys (camera, area lights, transform and deformation
//! motion, a rolling ball's path): length, then key by key its time, then its contents.
//!
//! Invariant: the shutter passed in is already valid (finite, `close >= open`).

use super::primitives::{Check, fail, finite};
use crate::model::Shutter;

/// The rules every list of motion keys at `at` obeys: empty, or at least 2 keys; every
/// key's `time` finite and inside the (already valid) shutter; times strictly increasing,
/// unless the shutter is closed (`close == open`), when they all equal `open`.
/// `contents(i, key)` checks key `i`'s other fields, after its time.
pub(super) fn keys<K>(
    at: &str,
    keys: &[K],
    time: impl Fn(&K) -> f32,
    shutter: &Shutter,
    mut contents: impl FnMut(usize, &K) -> Check,
) -> Check {
    if keys.len() == 1 {
        return fail(at, "motion needs at least 2 keys (or none), got 1");
    }
    let (open, close) = (shutter.open, shutter.close);
    let mut previous: Option<f32> = None;
    for (i, key) in keys.iter().enumerate() {
        let t = time(key);
        let path = format!("{at}[{i}].time");
        finite(&path, t)?;
        if t < open || t > close {
            return fail(
                path,
                format!("motion key time {t} is outside the shutter [{open}, {close}]"),
            );
        }
        if let Some(before) = previous
            && close > open
            && t <= before
        {
            return fail(
                path,
                format!("keys must be in increasing time order, got {t} after {before}"),
            );
        }
        previous = Some(t);
        contents(i, key)?;
    }
    Ok(())
}
