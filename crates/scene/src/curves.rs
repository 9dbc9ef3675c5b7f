//! RenderMan curves (`RiCurves`), shared by validation, the dicer and the ray engine: the
//! segment and primitive-variable counts, every segment as a cubic Bezier with its width,
//! normals, colour and opacity, and the ribbon a segment sweeps.
//!
//! Invariants: a segment's own parameter `t` runs over `[0, 1]`; segments are listed curve
//! after curve in RenderMan's order; a cubic segment in the Bezier basis keeps its control
//! points exactly, other bases are converted by `B = Mb^-1 M G` (as patch meshes are); every
//! primitive variable of a segment is held in the same Bezier form, so one evaluation serves
//! them all. A linear segment is the Bezier cubic of its straight line (exact), whose width
//! direction turns between the mitres at its two ends, so the ribbons of a polyline meet
//! without gap or overlap at its corners. Evaluation never panics and gives finite values
//! for finite input: degenerate tangents and sides fall back to fixed directions.

use glam::Vec3;

use crate::model::{Basis, CurveType, Primvar, Shape, Wrap};
use crate::patches;

/// Segments of one curve of `n` control points, RenderMan's rule: linear `n - 1`
/// nonperiodic and `n` periodic; cubic `(n - 4) / step + 1` nonperiodic and `n / step`
/// periodic. `Err` says why the count is invalid.
pub fn segment_count(kind: CurveType, wrap: Wrap, n: u32, step: u32) -> Result<u32, String> {
    match (kind, wrap) {
        (CurveType::Linear, Wrap::Nonperiodic) if n < 2 => {
            Err(format!("a linear curve needs at least 2 points, got {n}"))
        }
        (CurveType::Linear, Wrap::Nonperiodic) => Ok(n - 1),
        (CurveType::Linear, Wrap::Periodic) if n < 3 => {
            Err(format!("a periodic linear curve needs at least 3 points, got {n}"))
        }
        (CurveType::Linear, Wrap::Periodic) => Ok(n),
        (CurveType::Cubic, _) if step == 0 => Err("the step must be at least 1".into()),
        (CurveType::Cubic, Wrap::Nonperiodic) => {
            if n < 4 || !(n - 4).is_multiple_of(step) {
                Err(format!(
                    "a nonperiodic cubic curve needs 4 + a multiple of the step ({step}) points, got {n}"
                ))
            } else {
                Ok((n - 4) / step + 1)
            }
        }
        (CurveType::Cubic, Wrap::Periodic) => {
            if n < 4 || !n.is_multiple_of(step) {
                Err(format!(
                    "a periodic cubic curve needs a multiple of the step ({step}) points, at least 4, got {n}"
                ))
            } else {
                Ok(n / step)
            }
        }
    }
}

/// Varying values of a curve of `segments` segments: one per segment end, `segments + 1`
/// nonperiodic, `segments` periodic (the last end is the first).
pub fn varying_count(wrap: Wrap, segments: u32) -> u32 {
    match wrap {
        Wrap::Nonperiodic => segments + 1,
        Wrap::Periodic => segments,
    }
}

/// The step of a curves shape: the given one, else the basis's standard step (1 for an
/// explicit matrix without one, which validation refuses).
pub fn step(kind: CurveType, basis: &Basis, given: Option<u32>) -> u32 {
    match kind {
        CurveType::Linear => 1,
        CurveType::Cubic => patches::step(basis, given).unwrap_or(0),
    }
}

/// Where one curve's data lie.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CurveSpan {
    /// Index of its first control point.
    pub first: usize,
    /// Its control points.
    pub points: usize,
    /// Its segments.
    pub segments: usize,
    /// Index of its first varying value.
    pub first_varying: usize,
}

/// Every curve's span, in order; `Err((curve, why))` for a curve whose count is invalid.
/// Empty for any other shape.
pub fn spans(shape: &Shape) -> Result<Vec<CurveSpan>, (usize, String)> {
    let Shape::Curves { kind, wrap, nvertices, basis, step: given, .. } = shape else {
        return Ok(Vec::new());
    };
    let step = step(*kind, basis, *given);
    let mut out = Vec::with_capacity(nvertices.len());
    let (mut first, mut first_varying) = (0usize, 0usize);
    for (c, &n) in nvertices.iter().enumerate() {
        let segments = segment_count(*kind, *wrap, n, step).map_err(|e| (c, e))?;
        out.push(CurveSpan {
            first,
            points: n as usize,
            segments: segments as usize,
            first_varying,
        });
        first += n as usize;
        first_varying += varying_count(*wrap, segments) as usize;
    }
    Ok(out)
}

/// The counts a curves shape's primitive variables must have, per storage class:
/// `(uniform, varying, vertex)`.
pub fn primvar_counts(spans: &[CurveSpan], wrap: Wrap) -> (usize, usize, usize) {
    let varying = spans.iter().map(|s| varying_count(wrap, s.segments as u32) as usize).sum();
    let vertex = spans.iter().map(|s| s.points).sum();
    (spans.len(), varying, vertex)
}

/// How a ribbon turns: toward its normals, or toward the camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Facing {
    /// The curve's normals (`N`).
    Normals,
    /// A perspective camera at this point (object space).
    Eye(Vec3),
    /// An orthographic camera looking along this direction (object space).
    Along(Vec3),
}

/// One segment of a curve as a cubic Bezier, with its primitive variables in the same form.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// Bezier control points of the centre line (object space).
    pub p: [Vec3; 4],
    /// Bezier coefficients of the width.
    pub width: [f32; 4],
    /// Bezier coefficients of the normal (`N`), when the curve has normals.
    pub normal: Option<[Vec3; 4]>,
    /// Bezier coefficients of the colour (`Cs`); `None`: white.
    pub color: Option<[Vec3; 4]>,
    /// Bezier coefficients of the opacity (`Os`); `None`: opaque.
    pub opacity: Option<[Vec3; 4]>,
    /// A linear segment's width directions turn between these tangents, the mitres of its
    /// two ends; `None` for a cubic segment, which takes its own derivative.
    pub mitre: Option<[Vec3; 2]>,
}

/// Bernstein weights of degree 3 at `t`.
#[inline]
fn bernstein(t: f32) -> [f32; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
}

#[inline]
fn mix<T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>>(
    c: &[T; 4],
    b: [f32; 4],
) -> T {
    c[0] * b[0] + c[1] * b[1] + c[2] * b[2] + c[3] * b[3]
}

/// Any unit vector perpendicular to the unit vector `t`.
fn perpendicular(t: Vec3) -> Vec3 {
    let other = if t.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    t.cross(other).try_normalize().unwrap_or(Vec3::Z)
}

impl Segment {
    /// Centre-line point at `t`.
    #[inline]
    pub fn center(&self, t: f32) -> Vec3 {
        mix(&self.p, bernstein(t))
    }

    /// Unit tangent at `t` (the mitre-turned one on a linear segment).
    pub fn tangent(&self, t: f32) -> Vec3 {
        let d = match &self.mitre {
            Some([a, b]) => a.lerp(*b, t),
            None => {
                let s = 1.0 - t;
                let p = &self.p;
                (p[1] - p[0]) * (s * s) + (p[2] - p[1]) * (2.0 * s * t) + (p[3] - p[2]) * (t * t)
            }
        };
        d.try_normalize().or_else(|| (self.p[3] - self.p[0]).try_normalize()).unwrap_or(Vec3::X)
    }

    /// Width at `t` (never negative).
    #[inline]
    pub fn width_at(&self, t: f32) -> f32 {
        mix(&self.width, bernstein(t)).max(0.0)
    }

    /// The largest width anywhere on the segment (a bound: the Bezier coefficients hold it).
    pub fn max_width(&self) -> f32 {
        self.width.iter().copied().fold(0.0, f32::max)
    }

    /// Colour at `t`.
    pub fn color_at(&self, t: f32) -> Vec3 {
        self.color.as_ref().map_or(Vec3::ONE, |c| mix(c, bernstein(t)))
    }

    /// Opacity at `t`.
    pub fn opacity_at(&self, t: f32) -> Vec3 {
        self.opacity
            .as_ref()
            .map_or(Vec3::ONE, |c| mix(c, bernstein(t)).clamp(Vec3::ZERO, Vec3::ONE))
    }

    /// The unit direction across the ribbon at `t` and the ribbon's unit normal there, for a
    /// ribbon facing `facing`. The normal of a camera-facing ribbon points toward the camera;
    /// `side = tangent x normal`, so `dP/du x dP/dv` (`side x tangent`) points along it.
    pub fn frame(&self, t: f32, facing: Facing) -> (Vec3, Vec3) {
        let tangent = self.tangent(t);
        // `toward`: a vector whose part across the tangent is the normal's direction.
        let toward = match facing {
            Facing::Normals => self.normal.as_ref().map_or(Vec3::Z, |n| mix(n, bernstein(t))),
            Facing::Eye(eye) => eye - self.center(t),
            Facing::Along(dir) => -dir,
        };
        let normal = (toward - tangent * toward.dot(tangent))
            .try_normalize()
            .unwrap_or_else(|| perpendicular(tangent));
        (tangent.cross(normal), normal)
    }

    /// The ribbon's point at `(u, t)`, `u` across it in `[0, 1]` (0.5 on the centre line),
    /// and its unit normal.
    pub fn ribbon(&self, u: f32, t: f32, facing: Facing) -> (Vec3, Vec3) {
        let (side, normal) = self.frame(t, facing);
        (self.center(t) + side * ((u - 0.5) * self.width_at(t)), normal)
    }

    /// The part `[t0, t1]` of the segment, as a segment of its own (de Casteljau on every
    /// coefficient; the mitres are lerped).
    pub fn sub(&self, t0: f32, t1: f32) -> Segment {
        Segment {
            p: sub_bezier(&self.p, t0, t1),
            width: sub_bezier(&self.width, t0, t1),
            normal: self.normal.as_ref().map(|n| sub_bezier(n, t0, t1)),
            color: self.color.as_ref().map(|c| sub_bezier(c, t0, t1)),
            opacity: self.opacity.as_ref().map(|c| sub_bezier(c, t0, t1)),
            mitre: self.mitre.map(|[a, b]| [a.lerp(b, t0), a.lerp(b, t1)]),
        }
    }
}

/// The Bezier coefficients of the part `[t0, t1]` of the cubic with coefficients `c`.
fn sub_bezier<T>(c: &[T; 4], t0: f32, t1: f32) -> [T; 4]
where
    T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
{
    // The blossom at (a, b, c): nested lerps.
    let lerp = |a: T, b: T, t: f32| a * (1.0 - t) + b * t;
    let blossom = |x: [f32; 3]| {
        let l1 = [lerp(c[0], c[1], x[0]), lerp(c[1], c[2], x[0]), lerp(c[2], c[3], x[0])];
        let l2 = [lerp(l1[0], l1[1], x[1]), lerp(l1[1], l1[2], x[1])];
        lerp(l2[0], l2[1], x[2])
    };
    [blossom([t0, t0, t0]), blossom([t0, t0, t1]), blossom([t0, t1, t1]), blossom([t1, t1, t1])]
}

/// `K = Mb^-1 M` of `basis` in single precision.
fn conversion(basis: &Basis) -> [[f32; 4]; 4] {
    basis.bezier_conversion().map(|row| row.map(|x| x as f32))
}

/// `K G`: four values in the basis to Bezier coefficients.
fn to_bezier<T>(k: &[[f32; 4]; 4], g: [T; 4]) -> [T; 4]
where
    T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
{
    std::array::from_fn(|r| g[0] * k[r][0] + g[1] * k[r][1] + g[2] * k[r][2] + g[3] * k[r][3])
}

/// The Bezier form of the line from `a` to `b`.
fn line<T>(a: T, b: T) -> [T; 4]
where
    T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
{
    let third = 1.0 / 3.0;
    [a, a * (1.0 - third) + b * third, a * third + b * (1.0 - third), b]
}

/// A primitive variable of a curves shape, resolved for one segment: its Bezier
/// coefficients, from the values of its class.
fn segment_values<T>(
    var: &Primvar<T>,
    curve: usize,
    span: &CurveSpan,
    segment: usize,
    cubic: Option<(&[[f32; 4]; 4], [usize; 4])>,
    wrap: Wrap,
) -> Option<[T; 4]>
where
    T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
{
    let varying = |k: usize| {
        let count = varying_count(wrap, span.segments as u32) as usize;
        span.first_varying + k % count.max(1)
    };
    Some(match var {
        Primvar::Constant(v) => [*v; 4],
        Primvar::Uniform(v) => [*v.get(curve)?; 4],
        Primvar::Varying(v) => line(*v.get(varying(segment))?, *v.get(varying(segment + 1))?),
        Primvar::Vertex(v) => match cubic {
            Some((k, idx)) => {
                let g = [v.get(idx[0])?, v.get(idx[1])?, v.get(idx[2])?, v.get(idx[3])?];
                to_bezier(k, g.map(|x| *x))
            }
            None => {
                // Linear: vertices are the segment ends.
                let at = |j: usize| span.first + (segment + j) % span.points.max(1);
                line(*v.get(at(0))?, *v.get(at(1))?)
            }
        },
    })
}

/// Every segment of a curves shape, curve after curve, with its control points replaced by
/// `positions` when given (a deformation key; a missing point keeps the shape's own).
/// Empty for any other shape, and for a shape validation would refuse.
pub fn segments(shape: &Shape, positions: Option<&[Vec3]>) -> Vec<Segment> {
    let Shape::Curves { kind, wrap, points, basis, width, normals, colors, opacities, .. } = shape
    else {
        return Vec::new();
    };
    let Ok(spans) = spans(shape) else { return Vec::new() };
    let step = match shape {
        Shape::Curves { step, .. } => self::step(*kind, basis, *step) as usize,
        _ => 1,
    };
    let point = |i: usize| -> Vec3 {
        positions
            .and_then(|p| p.get(i).copied())
            .or_else(|| points.get(i).map(|p| Vec3::from(*p)))
            .unwrap_or(Vec3::ZERO)
    };
    let k = conversion(basis);
    let total: usize = spans.iter().map(|s| s.segments).sum();
    let mut out = Vec::with_capacity(total);
    for (c, span) in spans.iter().enumerate() {
        let n = span.points;
        let at = |j: usize| span.first + j % n.max(1);
        for s in 0..span.segments {
            let cubic_idx = match kind {
                CurveType::Cubic => Some([0, 1, 2, 3].map(|j| at(s * step + j))),
                CurveType::Linear => None,
            };
            let cubic = cubic_idx.map(|idx| (&k, idx));
            let (p, mitre) = match cubic_idx {
                Some(idx) => (to_bezier(&k, idx.map(point)), None),
                None => {
                    let (a, b) = (point(at(s)), point(at(s + 1)));
                    (line(a, b), Some(mitres(span, s, *wrap, &point)))
                }
            };
            let value = |var: &Primvar<f32>| segment_values(var, c, span, s, cubic, *wrap);
            out.push(Segment {
                p,
                width: value(width).unwrap_or([1.0; 4]),
                normal: normals.as_ref().and_then(|n| vec3_values(n, c, span, s, cubic, *wrap)),
                color: colors.as_ref().and_then(|v| vec3_values(v, c, span, s, cubic, *wrap)),
                opacity: opacities.as_ref().and_then(|v| vec3_values(v, c, span, s, cubic, *wrap)),
                mitre,
            });
        }
    }
    out
}

/// [`segment_values`] of a 3-vector primitive variable, without copying its array.
fn vec3_values(
    var: &Primvar<[f32; 3]>,
    curve: usize,
    span: &CurveSpan,
    segment: usize,
    cubic: Option<(&[[f32; 4]; 4], [usize; 4])>,
    wrap: Wrap,
) -> Option<[Vec3; 4]> {
    let varying = |k: usize| {
        let count = varying_count(wrap, span.segments as u32) as usize;
        span.first_varying + k % count.max(1)
    };
    let get = |v: &[[f32; 3]], i: usize| v.get(i).map(|x| Vec3::from(*x));
    Some(match var {
        Primvar::Constant(v) => [Vec3::from(*v); 4],
        Primvar::Uniform(v) => [get(v, curve)?; 4],
        Primvar::Varying(v) => line(get(v, varying(segment))?, get(v, varying(segment + 1))?),
        Primvar::Vertex(v) => match cubic {
            Some((k, idx)) => {
                let g = [get(v, idx[0])?, get(v, idx[1])?, get(v, idx[2])?, get(v, idx[3])?];
                to_bezier(k, g)
            }
            None => {
                let at = |j: usize| span.first + (segment + j) % span.points.max(1);
                line(get(v, at(0))?, get(v, at(1))?)
            }
        },
    })
}

/// The mitred tangents at the two ends of linear segment `s` of the curve `span`: at an
/// inner vertex (or any vertex of a periodic curve) the sum of the unit directions of the
/// two segments meeting there, at an end of an open curve the segment's own direction.
fn mitres(span: &CurveSpan, s: usize, wrap: Wrap, point: &impl Fn(usize) -> Vec3) -> [Vec3; 2] {
    let n = span.points;
    let at = |j: isize| span.first + j.rem_euclid(n.max(1) as isize) as usize;
    let dir = |j: isize| (point(at(j + 1)) - point(at(j))).normalize_or_zero();
    let own = dir(s as isize);
    let periodic = wrap == Wrap::Periodic;
    let start = if s > 0 || periodic { dir(s as isize - 1) + own } else { own };
    let end = if s + 1 < span.segments || periodic { own + dir(s as isize + 1) } else { own };
    [start, end]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curves(kind: CurveType, wrap: Wrap, nvertices: Vec<u32>, points: Vec<[f32; 3]>) -> Shape {
        Shape::Curves {
            kind,
            wrap,
            nvertices,
            points,
            basis: Basis::Bezier,
            step: None,
            width: Primvar::Constant(0.5),
            normals: None,
            colors: None,
            opacities: None,
        }
    }

    #[test]
    fn counts_follow_renderman() {
        use CurveType::*;
        use Wrap::*;
        assert_eq!(segment_count(Linear, Nonperiodic, 5, 1), Ok(4));
        assert_eq!(segment_count(Linear, Periodic, 5, 1), Ok(5));
        assert_eq!(segment_count(Cubic, Nonperiodic, 7, 3), Ok(2));
        assert_eq!(segment_count(Cubic, Nonperiodic, 7, 1), Ok(4));
        assert_eq!(segment_count(Cubic, Periodic, 6, 1), Ok(6));
        assert_eq!(segment_count(Cubic, Periodic, 6, 2), Ok(3));
        assert!(segment_count(Cubic, Nonperiodic, 6, 3).is_err());
        assert!(segment_count(Cubic, Nonperiodic, 3, 1).is_err());
        assert!(segment_count(Linear, Nonperiodic, 1, 1).is_err());
        assert_eq!(varying_count(Nonperiodic, 4), 5);
        assert_eq!(varying_count(Periodic, 4), 4);
    }

    #[test]
    fn bezier_segments_keep_their_points_and_bsplines_join() {
        let pts = vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 1.0, 0.0], [3.0, 0.0, 0.0]];
        let s = segments(&curves(CurveType::Cubic, Wrap::Nonperiodic, vec![4], pts.clone()), None);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].p.map(|p| p.to_array()), [pts[0], pts[1], pts[2], pts[3]]);
        // A B-spline of 6 points: 3 segments meeting end to end.
        let mut shape = curves(
            CurveType::Cubic,
            Wrap::Nonperiodic,
            vec![6],
            vec![
                [0.0; 3],
                [1.0, 2.0, 0.0],
                [2.0, 0.0, 1.0],
                [3.0, 2.0, 0.0],
                [4.0, 0.0, 0.0],
                [5.0, 1.0, 0.0],
            ],
        );
        if let Shape::Curves { basis, .. } = &mut shape {
            *basis = Basis::BSpline;
        }
        let s = segments(&shape, None);
        assert_eq!(s.len(), 3);
        for w in s.windows(2) {
            assert!(w[0].center(1.0).distance(w[1].center(0.0)) < 1e-5);
            assert!(w[0].tangent(1.0).distance(w[1].tangent(0.0)) < 1e-5);
        }
    }

    #[test]
    fn linear_ribbons_meet_at_their_corners() {
        let shape = curves(
            CurveType::Linear,
            Wrap::Nonperiodic,
            vec![3],
            vec![[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
        );
        let s = segments(&shape, None);
        let facing = Facing::Along(Vec3::Z);
        for u in [0.0, 1.0] {
            let (a, _) = s[0].ribbon(u, 1.0, facing);
            let (b, _) = s[1].ribbon(u, 0.0, facing);
            assert!(a.distance(b) < 1e-6, "{a} {b}");
        }
    }

    #[test]
    fn a_camera_facing_ribbon_is_across_the_view_and_its_normal_faces_the_eye() {
        let shape = curves(
            CurveType::Linear,
            Wrap::Nonperiodic,
            vec![2],
            vec![[0.0, 0.0, 5.0], [0.0, 1.0, 5.0]],
        );
        let s = &segments(&shape, None)[0];
        let (side, normal) = s.frame(0.5, Facing::Eye(Vec3::ZERO));
        assert!(side.dot(Vec3::Y).abs() < 1e-6 && side.dot(Vec3::new(0.0, 0.5, 5.0)).abs() < 1e-5);
        assert!(normal.dot(-Vec3::Z) > 0.99);
        let (p0, _) = s.ribbon(0.0, 0.5, Facing::Eye(Vec3::ZERO));
        let (p1, _) = s.ribbon(1.0, 0.5, Facing::Eye(Vec3::ZERO));
        assert!((p0.distance(p1) - 0.5).abs() < 1e-6);
        // dP/du x dP/dv points along the normal.
        assert!((p1 - p0).cross(s.tangent(0.5)).dot(normal) > 0.0);
    }

    #[test]
    fn sub_segments_are_the_same_curve() {
        let shape = curves(
            CurveType::Cubic,
            Wrap::Nonperiodic,
            vec![4],
            vec![[0.0; 3], [1.0, 3.0, 0.0], [2.0, -1.0, 1.0], [3.0, 0.0, 0.0]],
        );
        let s = &segments(&shape, None)[0];
        let part = s.sub(0.25, 0.75);
        for k in 0..=10 {
            let t = k as f32 / 10.0;
            assert!(part.center(t).distance(s.center(0.25 + 0.5 * t)) < 1e-5);
        }
    }
}
