//! Transformations of the RI state machine: the current transformation as motion keys, the
//! RIB matrix convention, and the matrices of RenderMan's transformation requests.
//!
//! Invariants: matrices are `f64` and act on column vectors (`p' = M p`); RIB writes matrices
//! for row vectors (`p' = p M`, the translation in the last row), so a RIB matrix is the
//! transpose of ours. Concatenation follows the Specification: a request's transformation is
//! applied to points *before* everything already in the current transformation, `CTM' = CTM M`.
//! A transformation with several keys is piecewise linear in time between its keys (matrices
//! interpolated entry by entry, as Aqsis and Pixie do) and held outside them.

use glam::{DMat4, DVec3, DVec4};
use reyes_scene::Transform;

/// A transformation over the shutter: one matrix, or matrices at increasing times.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Xform {
    /// `(time, matrix)`; one key means "the same at every time" (its time is unused).
    pub keys: Vec<(f32, DMat4)>,
}

impl Default for Xform {
    fn default() -> Self {
        Xform::still(DMat4::IDENTITY)
    }
}

impl Xform {
    /// The same matrix at every time.
    pub fn still(m: DMat4) -> Xform {
        Xform { keys: vec![(0.0, m)] }
    }

    /// True if the transformation changes over the shutter.
    pub fn moving(&self) -> bool {
        self.keys.len() > 1
    }

    /// The matrix at `time`.
    pub fn at(&self, time: f32) -> DMat4 {
        let k = &self.keys;
        if k.len() == 1 || time <= k[0].0 {
            return k[0].1;
        }
        for w in k.windows(2) {
            let ((t0, m0), (t1, m1)) = (w[0], w[1]);
            if time <= t1 {
                let f = if t1 > t0 { f64::from((time - t0) / (t1 - t0)) } else { 1.0 };
                return lerp(&m0, &m1, f);
            }
        }
        k[k.len() - 1].1
    }

    /// `self M`: `m` applied first, at every key.
    pub fn then_apply(&self, m: &DMat4) -> Xform {
        Xform { keys: self.keys.iter().map(|(t, k)| (*t, *k * *m)).collect() }
    }

    /// `self M(t)` for a transformation given at `times` (a motion block): keywise when the
    /// times agree, else on the union of both sets of times.
    pub fn then_apply_keys(&self, times: &[f32], ms: &[DMat4]) -> Xform {
        let other = Xform { keys: times.iter().copied().zip(ms.iter().copied()).collect() };
        self.compose(&other)
    }

    /// `self other` at every time of either.
    pub fn compose(&self, other: &Xform) -> Xform {
        match (self.moving(), other.moving()) {
            (false, false) => Xform::still(self.keys[0].1 * other.keys[0].1),
            (false, true) => {
                Xform { keys: other.keys.iter().map(|(t, m)| (*t, self.keys[0].1 * *m)).collect() }
            }
            (true, false) => self.then_apply(&other.keys[0].1),
            (true, true) => {
                let mut times: Vec<f32> =
                    self.keys.iter().chain(&other.keys).map(|(t, _)| *t).collect();
                times.sort_by(f32::total_cmp);
                times.dedup();
                Xform { keys: times.iter().map(|&t| (t, self.at(t) * other.at(t))).collect() }
            }
        }
    }

    /// The key times (empty for a still transformation).
    #[cfg(test)]
    pub fn times(&self) -> Vec<f32> {
        if self.moving() { self.keys.iter().map(|(t, _)| *t).collect() } else { Vec::new() }
    }
}

/// Entrywise `a + (b - a) f`.
fn lerp(a: &DMat4, b: &DMat4, f: f64) -> DMat4 {
    DMat4::from_cols_array(&std::array::from_fn(|i| {
        let (x, y) = (a.to_cols_array()[i], b.to_cols_array()[i]);
        x + (y - x) * f
    }))
}

/// Our matrix of a RIB matrix (16 numbers, row-major, for row vectors).
pub(crate) fn from_rib(m: &[f32]) -> DMat4 {
    // Read column-major, a row-major row-vector matrix becomes its transpose: ours.
    DMat4::from_cols_array(&std::array::from_fn(|i| f64::from(m[i])))
}

/// How far a RIB matrix is from an affine one: its projective terms (its 4th, 8th, 12th and
/// 16th numbers, the last row of our matrix) against (0, 0, 0, 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Projective {
    /// Exactly (0, 0, 0, 1).
    Affine,
    /// Within [`SNAP`] of it, relative to the matrix's scale: exporters' rounding noise
    /// (1e-10 to 1e-26 in the zeros), to be snapped.
    Near([f32; 4]),
    /// A projective matrix (`Perspective`, or a homogeneous scale): kept as given.
    Far,
}

/// How close to (0, 0, 0, 1) the projective terms must be, times the matrix's scale (its
/// largest entry, at least 1), to be taken as it.
pub(crate) const SNAP: f32 = 1e-6;

/// Classifies the projective terms of the RIB matrix `m` (16 numbers).
pub(crate) fn projective(m: &[f32]) -> Projective {
    let terms = [m[3], m[7], m[11], m[15]];
    if terms == [0.0, 0.0, 0.0, 1.0] {
        return Projective::Affine;
    }
    let scale = m.iter().fold(1.0f32, |a, x| a.max(x.abs()));
    let off = [terms[0], terms[1], terms[2], terms[3] - 1.0];
    if off.iter().all(|d| d.abs() <= SNAP * scale) {
        Projective::Near(terms)
    } else {
        Projective::Far
    }
}

/// A number for a message: as written for ordinary magnitudes (`0`, `1`, `0.25`), in
/// exponent form for tiny and huge ones (`1e-10`, `-2.5e-17`), never a run of zeros.
pub(crate) fn show(x: f32) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e7).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `m` with its projective terms set to (0, 0, 0, 1).
pub(crate) fn snapped(m: &[f32]) -> Vec<f32> {
    let mut m = m.to_vec();
    (m[3], m[7], m[11], m[15]) = (0.0, 0.0, 0.0, 1.0);
    m
}

/// `Translate dx dy dz`.
pub(crate) fn translate(d: [f32; 3]) -> DMat4 {
    DMat4::from_translation(dvec(d))
}

/// `Scale sx sy sz`.
pub(crate) fn scale(s: [f32; 3]) -> DMat4 {
    DMat4::from_scale(dvec(s))
}

/// `Rotate angle dx dy dz`: the rotation by `angle` degrees about the axis, the matrix of
/// Aqsis and Pixie (the right-hand rule's matrix, which in RenderMan's left-handed camera space
/// turns clockwise seen down the axis toward the origin). A zero axis gives the identity.
pub(crate) fn rotate(angle: f32, axis: [f32; 3]) -> DMat4 {
    match dvec(axis).try_normalize() {
        Some(a) => DMat4::from_axis_angle(a, f64::from(angle).to_radians()),
        None => DMat4::IDENTITY,
    }
}

/// `Skew angle dx1 dy1 dz1 dx2 dy2 dz2` (Spec 3.2, 4.3): shears so that the vector `a2`
/// (made perpendicular to `a1`) turns by `angle` degrees toward `a1`. None when the angle
/// cannot be reached (the shear would be infinite) or the vectors are parallel.
pub(crate) fn skew(angle: f32, a1: [f32; 3], a2: [f32; 3]) -> Option<DMat4> {
    let d1 = dvec(a1).try_normalize()?;
    let a2 = dvec(a2);
    // The part of a2 perpendicular to d1.
    let perp = (a2 - d1 * a2.dot(d1)).try_normalize()?;
    let d2 = perp;
    // The angle between a2 and its perpendicular part, then turned by `angle`.
    let par = a2.dot(d1);
    let per = a2.dot(d2);
    let base = par.atan2(per);
    let target = base + f64::from(angle).to_radians();
    if target.abs() >= std::f64::consts::FRAC_PI_2 - 1e-12 {
        return None;
    }
    // Points move along d1 in proportion to their component along d2.
    let k = target.tan() - base.tan();
    // M = I + k d1 d2^T (column vectors).
    let cols = [d2.x * k, d2.y * k, d2.z * k];
    let mut m = DMat4::IDENTITY;
    for (c, kc) in cols.iter().enumerate() {
        let col = m.col_mut(c);
        *col += DVec4::new(d1.x * kc, d1.y * kc, d1.z * kc, 0.0);
    }
    Some(m)
}

/// `Perspective fov` (Spec 3.2, 4.3): `x' = x / (z tan(fov/2))`, `y' = y / (z tan(fov/2))`,
/// `z' = (z - 1) / z`: the matrix `[f 0 0 0; 0 f 0 0; 0 0 1 1; 0 0 -1 0]` of the Specification
/// (written for row vectors, `f = 1 / tan(fov/2)`), with its homogeneous divide by `z`. None
/// for a fov outside (0, 180).
pub(crate) fn perspective(fov: f32) -> Option<DMat4> {
    if !(fov > 0.0 && fov < 180.0) {
        return None;
    }
    let f = 1.0 / (0.5 * f64::from(fov)).to_radians().tan();
    Some(DMat4::from_cols(
        DVec4::new(f, 0.0, 0.0, 0.0),
        DVec4::new(0.0, f, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 1.0, 1.0),
        DVec4::new(0.0, 0.0, -1.0, 0.0),
    ))
}

fn dvec(v: [f32; 3]) -> DVec3 {
    DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))
}

/// The model's transform list of one matrix.
pub(crate) fn to_model(m: &DMat4) -> Vec<Transform> {
    let rows = m.transpose().to_cols_array_2d().map(|r| r.map(|x| x as f32));
    vec![Transform::Matrix(rows)]
}

/// Where `p` goes under `m` (with the homogeneous divide).
pub(crate) fn point(m: &DMat4, p: [f32; 3]) -> [f32; 3] {
    let q = m.project_point3(dvec(p));
    [q.x as f32, q.y as f32, q.z as f32]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rib_matrices_are_transposed_and_concatenate_object_side_first() {
        // RIB: translation in the last row.
        let m = from_rib(&[1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 5., 6., 7., 1.]);
        assert_eq!(m.transform_point3(DVec3::ZERO), DVec3::new(5.0, 6.0, 7.0));
        // Translate then Rotate 90 about z: the rotation is applied to points first.
        let ctm = Xform::default().then_apply(&translate([1.0, 0.0, 0.0]));
        let ctm = ctm.then_apply(&rotate(90.0, [0.0, 0.0, 1.0]));
        let p = ctm.at(0.0).transform_point3(DVec3::X);
        assert!((p - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-12, "{p}");
    }

    #[test]
    fn the_model_matrix_acts_as_ours() {
        let m = translate([1.0, 2.0, 3.0]) * rotate(30.0, [1.0, 1.0, 0.0]);
        let model = reyes_scene::object_to_world(&to_model(&m)).as_dmat4();
        let p = DVec3::new(0.3, -0.7, 2.0);
        assert!((model.transform_point3(p) - m.transform_point3(p)).length() < 1e-5);
    }

    #[test]
    fn motion_keys_interpolate_and_compose() {
        let a = Xform { keys: vec![(0.0, translate([0.0; 3])), (1.0, translate([2.0, 0.0, 0.0]))] };
        let mid = a.at(0.5).transform_point3(DVec3::ZERO);
        assert!((mid - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-12);
        let b = Xform { keys: vec![(0.5, scale([1.0; 3])), (1.0, scale([2.0; 3]))] };
        let c = a.compose(&b);
        assert_eq!(c.times(), vec![0.0, 0.5, 1.0]);
        let p = c.at(1.0).transform_point3(DVec3::X);
        assert!((p - DVec3::new(4.0, 0.0, 0.0)).length() < 1e-12, "{p}");
    }

    #[test]
    fn projective_terms_near_the_affine_ones_are_told_apart_from_projective_ones() {
        let mut m = [0.0f32; 16];
        (m[0], m[5], m[10], m[15]) = (1.0, 1.0, 1.0, 1.0);
        assert_eq!(projective(&m), Projective::Affine);
        m[3] = 1e-20;
        m[15] = 1.0 + 1e-7;
        assert_eq!(projective(&m), Projective::Near([1e-20, 0.0, 0.0, 1.0 + 1e-7]));
        // Relative to the matrix's scale: 1e-4 is noise beside a translation of 1000.
        m[12] = 1000.0;
        m[7] = 1e-4;
        assert!(matches!(projective(&m), Projective::Near(_)));
        m[12] = 10.0;
        assert_eq!(projective(&m), Projective::Far);
        let s = snapped(&m);
        assert_eq!((s[3], s[7], s[11], s[15], s[12]), (0.0, 0.0, 0.0, 1.0, 10.0));
        // Perspective's matrix stays projective.
        let p = perspective(90.0).unwrap().to_cols_array().map(|x| x as f32);
        assert_eq!(projective(&p), Projective::Far);
    }

    #[test]
    fn skew_turns_the_second_axis_toward_the_first() {
        // Skew 45 degrees: y toward x. The point (0, 1, 0) moves to (1, 1, 0).
        let m = skew(45.0, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]).unwrap();
        let p = m.transform_point3(DVec3::Y);
        assert!((p - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-12, "{p}");
        assert!(skew(90.0, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]).is_none());
        assert!(skew(10.0, [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]).is_none());
    }
}
