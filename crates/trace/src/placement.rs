//! Object placement over the shutter: the object-to-world matrix at a ray's time, and the
//! ray carried into object space.
//!
//! Invariants: key times are normalised to `[0, 1]` over the shutter and strictly increase
//! (a closed shutter keeps only the first key); a `Frame` always holds a finite, invertible
//! matrix and its inverse. Between two keys the matrix is interpolated element-wise; for an
//! affine matrix `lerp(M0, M1, s) p == lerp(M0 p, M1 p, s)`, so every point of the surface
//! moves exactly as a diced vertex whose world positions are lerped between the keys (for
//! translations this is the translation lerp, for rotations the chord between the two key
//! positions, never the arc). For a projective `Matrix` key the two differ by the
//! homogeneous divide; the element-wise form is used.
//!
//! A projective matrix maps lines to lines but not linearly in the parameter: world
//! `t` and object `s` are related by `s = t a / (a + t b)` (a Moebius map that increases
//! with `t`), where `a`, `b` are the `w` of the object-space homogeneous origin and
//! direction. Only the part of the ray before it crosses the plane the matrix sends to
//! infinity is traced.

use glam::{DMat4, DVec3, DVec4, Vec3};

/// One object-to-world matrix at a normalised time.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MatrixKey {
    /// Normalised time in `[0, 1]`.
    pub time: f32,
    /// Object to world.
    pub matrix: DMat4,
}

/// A finite, invertible object-to-world matrix and its inverse.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Frame {
    to_world: DMat4,
    to_object: DMat4,
    projective: bool,
}

/// Is the bottom row of `m` other than `(0, 0, 0, 1)`?
pub(crate) fn is_projective(m: &DMat4) -> bool {
    m.row(3) != DVec4::W
}

impl Frame {
    /// The frame of `to_world`, or `None` when it is not finite or not invertible.
    pub fn new(to_world: DMat4) -> Option<Frame> {
        if !to_world.is_finite() {
            return None;
        }
        let to_object = to_world.try_inverse()?;
        Some(Frame { to_world, to_object, projective: is_projective(&to_world) })
    }

    /// The ray `origin + t dir` in object space, or `None` when its origin maps to infinity.
    pub fn localise(&self, origin: Vec3, dir: Vec3) -> Option<LocalRay> {
        let a = self.to_object * origin.as_dvec3().extend(1.0);
        let b = self.to_object * dir.as_dvec3().extend(0.0);
        if !self.projective {
            return Some(LocalRay { o: a.truncate(), d: b.truncate(), aw: 1.0, bw: 0.0 });
        }
        if a.w == 0.0 || !a.is_finite() || !b.is_finite() {
            return None;
        }
        let o = a.truncate() / a.w;
        let d = (b.truncate() * a.w - a.truncate() * b.w) / (a.w * a.w);
        Some(LocalRay { o, d, aw: a.w, bw: b.w })
    }

    /// World-space outward normal of the surface whose object-space point is `p` with outward
    /// normal `n`: the tangent plane `(n, -n.p)` carried by the inverse transpose, oriented by
    /// the sign of the world point's homogeneous `w`. Not normalised.
    pub fn normal_to_world(&self, p: DVec3, n: DVec3) -> DVec3 {
        if !self.projective {
            // The upper 3x3 of the inverse, transposed.
            let m = &self.to_object;
            return DVec3::new(
                m.x_axis.x * n.x + m.x_axis.y * n.y + m.x_axis.z * n.z,
                m.y_axis.x * n.x + m.y_axis.y * n.y + m.y_axis.z * n.z,
                m.z_axis.x * n.x + m.z_axis.y * n.y + m.z_axis.z * n.z,
            );
        }
        let plane = self.to_object.transpose() * n.extend(-n.dot(p));
        let w = (self.to_world * p.extend(1.0)).w;
        if w < 0.0 { -plane.truncate() } else { plane.truncate() }
    }
}

/// A ray in object space: `o + s d`, with the map back to world `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LocalRay {
    /// Origin.
    pub o: DVec3,
    /// Direction (not normalised).
    pub d: DVec3,
    /// Homogeneous `w` of the origin (1 for affine frames).
    aw: f64,
    /// Homogeneous `w` of the direction (0 for affine frames).
    bw: f64,
}

impl LocalRay {
    /// A world-space ray used as is.
    pub fn world(origin: Vec3, dir: Vec3) -> LocalRay {
        LocalRay { o: origin.as_dvec3(), d: dir.as_dvec3(), aw: 1.0, bw: 0.0 }
    }

    /// The world ray parameter of object parameter `s` (NaN or infinite past the pole).
    #[inline]
    pub fn world_t(&self, s: f64) -> f64 {
        if self.bw == 0.0 { s } else { s * self.aw / (self.aw - s * self.bw) }
    }
}

/// How an object sits in the world over the shutter.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Placement {
    /// Object space is world space (static affine transforms are baked into the points).
    Identity,
    /// One matrix for the whole shutter.
    Static(Box<Frame>),
    /// Two or more keys; the frame is built at each ray's time.
    Moving(Vec<MatrixKey>),
    /// A singular or non-finite matrix: the object is flattened and cannot be hit.
    Degenerate,
}

/// Keys bracketing normalised time `time`: `(i, j, w)` with the value `lerp(key[i], key[j], w)`.
/// Held before the first key and after the last; a non-finite time is taken as 0.
pub(crate) fn bracket(
    times: impl ExactSizeIterator<Item = f32> + Clone,
    time: f32,
) -> (usize, usize, f32) {
    let time = if time.is_finite() { time } else { 0.0 };
    let n = times.len();
    let mut previous: Option<(usize, f32)> = None;
    for (i, t) in times.enumerate() {
        if time <= t {
            return match previous {
                None => (i, i, 0.0),
                Some((j, tj)) => {
                    let w = if t > tj { (time - tj) / (t - tj) } else { 0.0 };
                    (j, i, w.clamp(0.0, 1.0))
                }
            };
        }
        previous = Some((i, t));
    }
    let last = n.saturating_sub(1);
    (last, last, 0.0)
}

impl Placement {
    /// The placement of keys `(normalised time, object-to-world)`: identity, static, moving
    /// or degenerate. Keys that all hold the same matrix are one static key.
    pub fn from_keys(keys: Vec<MatrixKey>) -> Placement {
        let still = keys.windows(2).all(|w| w[0].matrix == w[1].matrix);
        match keys.first() {
            None => Placement::Identity,
            Some(only) if still => {
                if only.matrix == DMat4::IDENTITY {
                    Placement::Identity
                } else {
                    match Frame::new(only.matrix) {
                        Some(frame) => Placement::Static(Box::new(frame)),
                        None => Placement::Degenerate,
                    }
                }
            }
            Some(_) => Placement::Moving(keys),
        }
    }

    /// The object-to-world matrix at normalised `time` (identity for `Identity`).
    pub fn matrix_at(&self, time: f32) -> Option<DMat4> {
        match self {
            Placement::Identity => Some(DMat4::IDENTITY),
            Placement::Static(frame) => Some(frame.to_world),
            Placement::Moving(keys) => {
                let (i, j, w) = bracket(keys.iter().map(|k| k.time), time);
                let (a, b) = (keys.get(i)?, keys.get(j)?);
                let w = f64::from(w);
                Some(a.matrix * (1.0 - w) + b.matrix * w)
            }
            Placement::Degenerate => None,
        }
    }

    /// Every key matrix (one for static placements, none for degenerate ones).
    pub fn key_matrices(&self) -> Vec<DMat4> {
        match self {
            Placement::Identity => vec![DMat4::IDENTITY],
            Placement::Static(frame) => vec![frame.to_world],
            Placement::Moving(keys) => keys.iter().map(|k| k.matrix).collect(),
            Placement::Degenerate => vec![],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bracket_holds_and_interpolates() {
        let times = [0.0_f32, 0.5, 1.0];
        assert_eq!(bracket(times.iter().copied(), -1.0), (0, 0, 0.0));
        assert_eq!(bracket(times.iter().copied(), 0.0), (0, 0, 0.0));
        assert_eq!(bracket(times.iter().copied(), 0.25), (0, 1, 0.5));
        assert_eq!(bracket(times.iter().copied(), 0.75), (1, 2, 0.5));
        assert_eq!(bracket(times.iter().copied(), 2.0), (2, 2, 0.0));
        assert_eq!(bracket(times.iter().copied(), f32::NAN), (0, 0, 0.0));
        let late = [0.2_f32, 0.6];
        assert_eq!(bracket(late.iter().copied(), 0.1), (0, 0, 0.0));
        assert_eq!(bracket(late.iter().copied(), 0.9), (1, 1, 0.0));
    }

    #[test]
    fn projective_parameter_map_matches_world_points() {
        // A perspective-like matrix: w = 1 + z/4.
        let m = DMat4::from_cols_array_2d(&[
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.25],
            [0.5, 0.0, 0.0, 1.0],
        ]);
        let frame = Frame::new(m).expect("invertible");
        let (o, d) = (Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.3, -0.1, 0.4));
        let local = frame.localise(o, d).expect("finite");
        for s in [0.0, 0.2, 1.0, 3.0] {
            let p_obj = local.o + local.d * s;
            let world = m.project_point3(p_obj);
            let t = local.world_t(s);
            let on_ray = o.as_dvec3() + d.as_dvec3() * t;
            assert!((world - on_ray).length() < 1e-9, "s {s}: {world} vs {on_ray}");
        }
    }
}
