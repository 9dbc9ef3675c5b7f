//! Rolling without slipping (Appendix B's `h` command and `spinangle`): every object's `roll`
//! becomes transform motion keys, so the engines, which read only `motion`, move it.
//!
//! Definition. Let `u` be `roll.up` normalised, `r` the radius, and for the path segment from
//! key `a` to key `b` let `d = p_b - p_a`, `h = d - u (u . d)` its part in the plane (validation
//! makes the part along `u` negligible), `s = |h|` the distance rolled, `axis = u x h / s` and
//! `theta = s / r` (radians) the whole turn of the segment. Its keys are at the scene times
//! `t_a + (t_b - t_a) j / steps`, `j = 1..=steps` (the last exactly `t_b`; a time that rounds
//! onto its neighbour in `f32` is dropped, so times strictly increase), plus one key at the
//! path's first time. At fraction `f = j / steps` the key's transform list is
//!
//! ```text
//! object.transform...,            the rest orientation, applied first (object space)
//! Rotate(done),                   the segments already finished, composed (left out if none)
//! Rotate(theta f, axis),          the current segment so far (left out at its end)
//! Translate(p_a + d f)            the centre
//! ```
//!
//! where `done = R_k ... R_2 R_1` is the product of the finished segments' turns (a later turn
//! is applied after, about the world-fixed axis through the centre), composed as a quaternion
//! in `f64` and written as one `Rotate` with angle in `[0, 180]` degrees. Keeping the finished
//! turns in one `Rotate` holds every key to a fixed number of transforms, however long the
//! path. The angular velocity is then `u x v / r` for centre velocity `v`, so the contact
//! point `c - r u` has velocity `v + (u x v / r) x (-r u) = v - v = 0`: the ball does not slip.
//!
//! The engines interpolate vertex positions linearly between keys (chords, not arcs), so each
//! step may turn the ball at most [`MAX_STEP_DEGREES`]; validation enforces it through `steps`.

use glam::{DQuat, DVec3};

use crate::model::{Roll, Transform, TransformKey, V3};

/// Most roll per generated step, in degrees: between keys a vertex moves on the chord of its
/// arc, which at 45 degrees passes at most `1 - cos(22.5 deg)` = 7.6 % of the radius inside.
pub(crate) const MAX_STEP_DEGREES: f64 = 45.0;
/// Largest `roll.steps`.
pub(crate) const MAX_STEPS: u32 = 1024;
/// Most transforms (over all generated keys) one `roll` may produce.
pub(crate) const MAX_TRANSFORMS: usize = 1 << 20;
/// Largest part of a path displacement along `up`, relative to its length, taken as rolling
/// in the plane.
pub(crate) const PLANE_TOLERANCE: f64 = 1e-4;

pub(crate) fn dvec(v: &V3) -> DVec3 {
    DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))
}

fn fvec(v: DVec3) -> V3 {
    [v.x as f32, v.y as f32, v.z as f32]
}

/// One path segment split against the plane normal `up` (unit): the displacement, its
/// signed part along `up`, and its part in the plane.
pub(crate) struct Segment {
    /// `p_b - p_a`.
    pub d: DVec3,
    /// `up . d`.
    pub rise: f64,
    /// `d - up (up . d)`.
    pub h: DVec3,
}

impl Segment {
    pub(crate) fn new(up: DVec3, a: &V3, b: &V3) -> Segment {
        let d = dvec(b) - dvec(a);
        let rise = up.dot(d);
        Segment { d, rise, h: d - up * rise }
    }

    /// The distance rolled.
    pub(crate) fn distance(&self) -> f64 {
        self.h.length()
    }
}

/// `roll.up` normalised (validation has made it finite and non-zero).
pub(crate) fn unit_up(roll: &Roll) -> DVec3 {
    dvec(&roll.up).try_normalize().unwrap_or(DVec3::Y)
}

/// Number of transform keys `roll` expands to, before any are dropped for rounding.
pub(crate) fn key_count(roll: &Roll) -> usize {
    let segments = roll.path.len().saturating_sub(1);
    segments.saturating_mul(roll.steps as usize).saturating_add(1)
}

/// A rotation as a `Rotate` step, or `None` for the identity.
fn rotate_step(q: DQuat) -> Option<Transform> {
    let q = if q.w < 0.0 { -q } else { q };
    let v = DVec3::new(q.x, q.y, q.z);
    let s = v.length();
    let angle = (2.0 * s.atan2(q.w)).to_degrees() as f32;
    if s == 0.0 || angle == 0.0 {
        return None;
    }
    Some(Transform::Rotate { angle, axis: fvec(v / s) })
}

/// The transform keys of an object with `roll` whose own (rest) transform list is `rest`.
/// `roll` must have passed validation.
pub(crate) fn expand(roll: &Roll, rest: &[Transform]) -> Vec<TransformKey> {
    let up = unit_up(roll);
    let radius = f64::from(roll.radius);
    let steps = roll.steps.max(1);
    let key = |time: f32, done: Option<&Transform>, current: Option<Transform>, centre: DVec3| {
        let mut transform = Vec::with_capacity(rest.len() + 3);
        transform.extend_from_slice(rest);
        transform.extend(done.cloned());
        transform.extend(current);
        transform.push(Transform::Translate(fvec(centre)));
        TransformKey { time, transform }
    };
    let Some(first) = roll.path.first() else {
        return Vec::new();
    };
    let mut keys = Vec::with_capacity(key_count(roll));
    let mut done = DQuat::IDENTITY;
    let mut done_step: Option<Transform> = None;
    keys.push(key(first.time, None, None, dvec(&first.position)));
    let mut last = first.time;
    for pair in roll.path.windows(2) {
        let [a, b] = pair else { continue };
        let seg = Segment::new(up, &a.position, &b.position);
        let distance = seg.distance();
        let axis = if distance > 0.0 { up.cross(seg.h / distance).try_normalize() } else { None };
        let theta = distance / radius;
        let (ta, tb) = (f64::from(a.time), f64::from(b.time));
        let pa = dvec(&a.position);
        for j in 1..steps {
            let f = f64::from(j) / f64::from(steps);
            let time = (ta + (tb - ta) * f) as f32;
            if !(time > last && time < b.time) {
                continue;
            }
            let current = axis.and_then(|axis| {
                let angle = (theta * f).to_degrees() as f32;
                (angle != 0.0).then(|| Transform::Rotate { angle, axis: fvec(axis) })
            });
            keys.push(key(time, done_step.as_ref(), current, pa + seg.d * f));
            last = time;
        }
        if let Some(axis) = axis {
            done = (DQuat::from_axis_angle(axis, theta) * done).normalize();
            done_step = rotate_step(done);
        }
        keys.push(key(b.time, done_step.as_ref(), None, dvec(&b.position)));
        last = b.time;
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::RollKey;

    fn roll(path: &[(f32, V3)], steps: u32) -> Roll {
        Roll {
            radius: 0.5,
            up: [0.0, 1.0, 0.0],
            path: path.iter().map(|&(time, position)| RollKey { time, position }).collect(),
            steps,
        }
    }

    #[test]
    fn keys_cover_every_step_of_every_segment() {
        let r = roll(&[(0.0, [0.0, 0.5, 0.0]), (0.5, [1.0, 0.5, 0.0]), (1.0, [1.0, 0.5, 1.0])], 4);
        let keys = expand(&r, &[]);
        assert_eq!(keys.len(), key_count(&r));
        let times: Vec<f32> = keys.iter().map(|k| k.time).collect();
        assert_eq!(times, [0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0]);
        // First key: just the centre. Mid first segment: the current turn. End of the first
        // segment: the finished turn. Mid second: finished + current.
        assert_eq!(keys[0].transform, [Transform::Translate([0.0, 0.5, 0.0])]);
        assert_eq!(keys[2].transform.len(), 2);
        assert_eq!(keys[4].transform.len(), 2);
        assert_eq!(keys[6].transform.len(), 3);
    }

    #[test]
    fn times_that_round_together_are_dropped() {
        let r = roll(&[(0.5, [0.0, 0.5, 0.0]), (0.500_000_06, [1.0, 0.5, 0.0])], 1024);
        let keys = expand(&r, &[]);
        assert!(keys.windows(2).all(|w| w[0].time < w[1].time));
        assert_eq!(keys.last().map(|k| k.time), Some(0.500_000_06));
    }

    #[test]
    fn a_still_segment_does_not_turn() {
        let r = roll(&[(0.0, [0.0, 0.5, 0.0]), (1.0, [0.0, 0.5, 0.0])], 2);
        for k in expand(&r, &[]) {
            assert_eq!(k.transform, [Transform::Translate([0.0, 0.5, 0.0])]);
        }
    }
}
