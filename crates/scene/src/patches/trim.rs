//! Trim loops of a NURBS patch (`RiTrimCurve`) as the renderer tests them: each loop
//! flattened once into a closed polyline in the patch's `(u, v)`, within a proven distance
//! of the true curve ([`tolerance`]), and the even-odd test of a parameter point against all
//! loops ([`TrimRegion::removes`]), with the conservative test of a parameter rectangle the
//! dicer uses to drop whole micropolygons ([`TrimRegion::classify`]).
//!
//! Invariants: the shape has passed validation (every curve of order `2..=MAX_ORDER` with
//! `n + order` non-decreasing knots, `min < max` in its valid range, weights `> 0`, control
//! points within [`REACH`] domain extents of the drawn domain), so every rational Bezier
//! span has positive weights and lies in the convex hull of its projected control points;
//! arithmetic is in `f64`; nothing here panics or allocates without bound (a loop is
//! refined to at most [`MAX_POINTS`] points).

use glam::{DVec2, DVec3, DVec4};

use super::nurbs::{extract, spans_of};
use crate::model::{Shape, TrimCurve, TrimLoop};

/// How far outside the drawn domain a trim control point may lie, in domain extents
/// (validation's limit): far enough for any loop that trims across an edge, near enough
/// that flattening to [`tolerance`] takes a bounded number of segments.
pub const REACH: f64 = 1.0;

/// Most points a loop's polyline gets; refinement stops there (only absurd weights reach it).
pub const MAX_POINTS: usize = 1 << 20;

/// Deepest halving of one Bezier span.
const MAX_DEPTH: u32 = 40;

/// The flattening tolerance of a patch whose drawn domain is `[u0, u1] x [v0, v1]`: 2^-20 of
/// its larger extent. Derivation: the hider interpolates a sample's `(u, v)` in `f32`, which
/// rounds at 2^-24 of the coordinate's size, so a tighter polyline would be lost in that
/// rounding; and a patch spans at most about 2^12 raster pixels in a frame (4096), so the
/// polyline is off the curve by at most 2^-8 = 0.004 pixel there, far below a micropolygon
/// (>= 0.25 pixel at any useful shading rate) and below the 1/16-pixel spacing of 4 x 4
/// samples: the trimmed edge is the curve's to sampling precision.
pub fn tolerance(domain: [f64; 4]) -> f64 {
    let [u0, u1, v0, v1] = domain;
    (u1 - u0).abs().max((v1 - v0).abs()) * (2.0f64).powi(-20)
}

/// Where a parameter rectangle lies against the trimmed region.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coverage {
    /// Every point of it is kept.
    Kept,
    /// Every point of it is removed.
    Removed,
    /// A loop's polyline crosses it: each point must be tested.
    Boundary,
}

/// One loop's polyline, its bound, and its segments binned by height.
#[derive(Debug, Clone, PartialEq)]
struct Polyline {
    /// Closed: segment `k` joins point `k` to point `k + 1` (the last to the first).
    points: Vec<DVec2>,
    lo: DVec2,
    hi: DVec2,
    /// Bin `b` lists the segments whose height range meets `[lo.y + b h, lo.y + (b + 1) h]`
    /// (`h = bin_height`), by [`Polyline::bin`] of their ends, so every segment meeting a
    /// height lies in that height's bin.
    bins: Vec<Vec<u32>>,
    bin_height: f64,
}

impl Polyline {
    fn new(points: Vec<DVec2>) -> Polyline {
        let lo = points.iter().fold(DVec2::INFINITY, |a, p| a.min(*p));
        let hi = points.iter().fold(DVec2::NEG_INFINITY, |a, p| a.max(*p));
        let n = points.len();
        // About eight segments a bin on a round loop; at most 4096 bins.
        let count = (n / 8).clamp(1, 4096);
        let span = hi.y - lo.y;
        let bin_height = if span > 0.0 && span.is_finite() { span / count as f64 } else { 0.0 };
        let mut line = Polyline { points, lo, hi, bins: vec![Vec::new(); count], bin_height };
        for k in 0..n {
            let (a, b) = line.segment(k);
            let (first, last) = (line.bin(a.y.min(b.y)), line.bin(a.y.max(b.y)));
            for bin in &mut line.bins[first..=last] {
                bin.push(k as u32);
            }
        }
        line
    }

    /// The bin of height `y`, clamped to the bins (monotone in `y`).
    fn bin(&self, y: f64) -> usize {
        if self.bin_height <= 0.0 {
            return 0;
        }
        let b = ((y - self.lo.y) / self.bin_height).floor();
        if b.is_nan() || b < 0.0 { 0 } else { (b as usize).min(self.bins.len() - 1) }
    }

    /// Segment `k`'s ends.
    fn segment(&self, k: usize) -> (DVec2, DVec2) {
        let n = self.points.len();
        (self.points[k], self.points[(k + 1) % n])
    }
}

/// The trim loops of one patch, flattened.
#[derive(Debug, Clone, PartialEq)]
pub struct TrimRegion {
    loops: Vec<Polyline>,
    /// Keep the inside and remove the outside (`"trimcurve" "sense" "outside"`).
    outside: bool,
    tolerance: f64,
}

/// The drawn domain `[umin, umax, vmin, vmax]` of a `NuPatch`.
pub fn domain(shape: &Shape) -> Option<[f64; 4]> {
    match shape {
        Shape::NuPatch { umin, umax, vmin, vmax, .. } => {
            Some([*umin, *umax, *vmin, *vmax].map(f64::from))
        }
        _ => None,
    }
}

/// The parameter rectangle `[u0, u1, v0, v1]` each span of a valid `NuPatch` covers, in the
/// order of [`super::bezier_patches`] (v spans outer, u spans inner): span `k`'s own `(s, t)`
/// in `[0, 1]^2` is the patch's `(u0 + s (u1 - u0), v0 + t (v1 - v0))`. Empty for other
/// shapes.
pub fn span_domains(shape: &Shape) -> Vec<[f64; 4]> {
    let Shape::NuPatch { nu, uorder, uknot, umin, umax, nv, vorder, vknot, vmin, vmax, .. } = shape
    else {
        return Vec::new();
    };
    let direction = |knots: &[f32], order: u32, n: u32, lo: f32, hi: f32| {
        if knots.len() != n as usize + order as usize || order < 1 || n < order {
            return Vec::new();
        }
        let k: Vec<f64> = knots.iter().map(|&k| f64::from(k)).collect();
        spans_of(&k, order as usize, n as usize, f64::from(lo), f64::from(hi))
    };
    let us = direction(uknot, *uorder, *nu, *umin, *umax);
    let vs = direction(vknot, *vorder, *nv, *vmin, *vmax);
    let mut out = Vec::with_capacity(us.len() * vs.len());
    for (_, [v0, v1]) in &vs {
        for (_, [u0, u1]) in &us {
            out.push([*u0, *u1, *v0, *v1]);
        }
    }
    out
}

impl TrimRegion {
    /// The region of a valid `NuPatch`, or `None` when it has no trim loops (or is another
    /// shape).
    pub fn of(shape: &Shape) -> Option<TrimRegion> {
        let Shape::NuPatch { trim, trim_outside, .. } = shape else { return None };
        if trim.is_empty() {
            return None;
        }
        let tolerance = tolerance(domain(shape)?);
        Some(TrimRegion::new(trim, *trim_outside, tolerance))
    }

    /// The region of `loops` flattened to `tolerance`.
    pub fn new(loops: &[TrimLoop], outside: bool, tolerance: f64) -> TrimRegion {
        let loops = loops
            .iter()
            .map(|l| {
                let mut points = Vec::new();
                for c in &l.curves {
                    flatten_curve(c, tolerance, &mut points);
                }
                // The closing segment is implicit; drop a repeated first point.
                if points.len() > 1 && points.first() == points.last() {
                    points.pop();
                }
                Polyline::new(points)
            })
            .collect();
        TrimRegion { loops, outside, tolerance }
    }

    /// The flattening tolerance: the polylines are within it of the curves.
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// The number of polyline segments over all loops.
    pub fn segments(&self) -> usize {
        self.loops.iter().map(|l| l.points.len()).sum()
    }

    /// Whether the parameter point `(u, v)` is trimmed away: it lies inside an odd number of
    /// loops (the even-odd rule: a ray toward +u crosses the loops' polylines an odd number
    /// of times; orientation does not matter), or with `outside`, an even number.
    pub fn removes(&self, u: f64, v: f64) -> bool {
        let mut inside = false;
        for l in &self.loops {
            if l.points.len() < 2 || v < l.lo.y || v > l.hi.y || u > l.hi.x {
                continue;
            }
            // A segment that crosses height v has v in its height range, so in v's bin.
            for &k in &l.bins[l.bin(v)] {
                let (a, b) = l.segment(k as usize);
                // A vertex exactly at height v counts as above: each crossing counted once.
                if (a.y > v) != (b.y > v) {
                    let x = a.x + (v - a.y) * (b.x - a.x) / (b.y - a.y);
                    if x > u {
                        inside = !inside;
                    }
                }
            }
        }
        inside != self.outside
    }

    /// Where the rectangle `[u0, u1] x [v0, v1]` lies: `Boundary` if some polyline segment
    /// meets it (closed), else all of it on the side of its centre. Exact up to rounding in
    /// the segment test, which only ever answers `Boundary` in doubt: a segment is taken to
    /// miss only if its bound misses the rectangle or all four corners lie strictly on one
    /// side of its line by more than the rounding of the cross products.
    pub fn classify(&self, [u0, u1, v0, v1]: [f64; 4]) -> Coverage {
        for l in &self.loops {
            if l.points.len() < 2 || l.hi.x < u0 || l.lo.x > u1 || l.hi.y < v0 || l.lo.y > v1 {
                continue;
            }
            // A segment meeting the rectangle meets its height range: it is in those bins
            // (some more than once, which only repeats a test).
            let first = l.bin(v0);
            for bin in &l.bins[first..=l.bin(v1).max(first)] {
                for &k in bin {
                    let (a, b) = l.segment(k as usize);
                    if segment_meets_rect(a, b, [u0, u1, v0, v1]) {
                        return Coverage::Boundary;
                    }
                }
            }
        }
        if self.removes(0.5 * (u0 + u1), 0.5 * (v0 + v1)) {
            Coverage::Removed
        } else {
            Coverage::Kept
        }
    }
}

/// Whether segment `a b` meets the closed rectangle, conservatively.
fn segment_meets_rect(a: DVec2, b: DVec2, [u0, u1, v0, v1]: [f64; 4]) -> bool {
    if a.x.max(b.x) < u0 || a.x.min(b.x) > u1 || a.y.max(b.y) < v0 || a.y.min(b.y) > v1 {
        return false;
    }
    let d = b - a;
    let side = |p: DVec2| d.x * (p.y - a.y) - d.y * (p.x - a.x);
    let corners = [DVec2::new(u0, v0), DVec2::new(u1, v0), DVec2::new(u1, v1), DVec2::new(u0, v1)];
    // Rounding of each cross product: a few ulps of the magnitudes multiplied.
    let scale = d.abs().max_element()
        * (corners.iter().map(|c| (*c - a).abs().max_element())).fold(0.0, f64::max);
    let slack = 8.0 * f64::EPSILON * scale;
    let s = corners.map(side);
    !(s.iter().all(|&x| x > slack) || s.iter().all(|&x| x < -slack))
}

/// Append the polyline of one trim curve: the points of each of its rational Bezier spans
/// over `[min, max]`, flattened to `tolerance`, the first point of the curve included.
fn flatten_curve(c: &TrimCurve, tolerance: f64, out: &mut Vec<DVec2>) {
    let order = c.order as usize;
    let n = c.points.len();
    if order < 2 || c.knot.len() != n + order || n < order {
        return;
    }
    let knots: Vec<f64> = c.knot.iter().map(|&k| f64::from(k)).collect();
    let ctrl: Vec<DVec4> =
        c.points.iter().map(|p| DVec4::new(p[0].into(), p[1].into(), 0.0, p[2].into())).collect();
    let p = order - 1;
    for (s, ab) in spans_of(&knots, order, n, f64::from(c.min), f64::from(c.max)) {
        let span: Vec<DVec3> = extract(&knots, &ctrl, p, s, ab)
            .into_iter()
            .map(|q| DVec3::new(q.x, q.y, q.w))
            .collect();
        if out.is_empty() {
            out.push(project(span[0]));
        }
        flatten_span(&span, tolerance, 0, out);
    }
}

/// The point of a homogeneous `(u w, v w, w)`.
fn project(h: DVec3) -> DVec2 {
    DVec2::new(h.x / h.z, h.y / h.z)
}

/// Append the end of each chord of a rational Bezier span `ctrl` (homogeneous, weights
/// `> 0`) halved until every projected control point is within `tolerance` of its chord:
/// by the convex hull property the span then lies within `tolerance` of the chord, whose
/// ends are on the curve.
fn flatten_span(ctrl: &[DVec3], tolerance: f64, depth: u32, out: &mut Vec<DVec2>) {
    let pts: Vec<DVec2> = ctrl.iter().map(|&h| project(h)).collect();
    let (a, b) = (pts[0], pts[pts.len() - 1]);
    let flat = pts.iter().all(|&q| distance_to_segment(q, a, b) <= tolerance);
    if flat || depth >= MAX_DEPTH || out.len() >= MAX_POINTS || !b.is_finite() {
        out.push(b);
        return;
    }
    // de Casteljau at 1/2 on the homogeneous points.
    let m = ctrl.len();
    let mut work = ctrl.to_vec();
    let mut left = Vec::with_capacity(m);
    let mut right = Vec::with_capacity(m);
    left.push(work[0]);
    right.push(work[m - 1]);
    for r in 1..m {
        for k in 0..m - r {
            work[k] = 0.5 * (work[k] + work[k + 1]);
        }
        left.push(work[0]);
        right.push(work[m - 1 - r]);
    }
    right.reverse();
    flatten_span(&left, tolerance, depth + 1, out);
    flatten_span(&right, tolerance, depth + 1, out);
}

/// Distance from `q` to the segment `a b`.
fn distance_to_segment(q: DVec2, a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    let l2 = d.length_squared();
    let t = if l2 > 0.0 { ((q - a).dot(d) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (a + t * d - q).length()
}

impl TrimLoop {
    /// The exact circle of radius `r` about `(cu, cv)` in parameter space: one order-3
    /// rational curve of nine homogeneous points, the corners of the square about the circle
    /// at weight 1/sqrt 2 and the midpoints of its sides at weight 1, knots doubled at the
    /// quarters (four exact quarter arcs). A hole of area pi r^2, for tests and tools.
    pub fn circle(cu: f32, cv: f32, r: f32) -> TrimLoop {
        let w = std::f32::consts::FRAC_1_SQRT_2;
        let square =
            [(1., 0.), (1., 1.), (0., 1.), (-1., 1.), (-1., 0.), (-1., -1.), (0., -1.), (1., -1.)];
        let points = square
            .iter()
            .chain(std::iter::once(&(1., 0.)))
            .enumerate()
            .map(|(i, &(x, y))| {
                let wi = if i % 2 == 1 { w } else { 1.0 };
                [(cu + r * x) * wi, (cv + r * y) * wi, wi]
            })
            .collect();
        let knot = vec![0., 0., 0., 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1., 1., 1.];
        TrimLoop { curves: vec![TrimCurve { order: 3, knot, min: 0.0, max: 1.0, points }] }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_circle_is_flattened_within_the_tolerance_and_tests_by_its_radius() {
        let tol = 1e-6;
        let region = TrimRegion::new(&[TrimLoop::circle(0.5, 0.5, 0.25)], false, tol);
        let l = &region.loops[0];
        // Every vertex on the circle (rounding only) and every chord's middle within tol.
        for (i, p) in l.points.iter().enumerate() {
            let q = l.points[(i + 1) % l.points.len()];
            assert!(((*p - DVec2::splat(0.5)).length() - 0.25).abs() < 1e-6);
            let mid = 0.5 * (*p + q);
            assert!(0.25 - (mid - DVec2::splat(0.5)).length() <= tol * 1.01);
        }
        // The chord count a circle needs: pi / acos(1 - tol / r), within a factor of 2.
        let need = std::f64::consts::PI / (1.0 - tol / 0.25).acos();
        let got = l.points.len() as f64;
        eprintln!("circle of radius 0.25 at tolerance {tol}: {got} segments ({need:.0} needed)");
        assert!(got >= need * 0.99 && got <= 2.0 * need + 8.0, "{got} for {need}");
        assert!(region.removes(0.5, 0.5));
        assert!(region.removes(0.5 + 0.2499, 0.5));
        assert!(!region.removes(0.5 + 0.2501, 0.5));
        assert!(!region.removes(0.0, 0.0));
        let outside = TrimRegion::new(&[TrimLoop::circle(0.5, 0.5, 0.25)], true, tol);
        assert!(!outside.removes(0.5, 0.5) && outside.removes(0.0, 0.0));
    }

    /// The even-odd test over every segment, without bins.
    fn removes_brute(r: &TrimRegion, u: f64, v: f64) -> bool {
        let mut inside = false;
        for l in &r.loops {
            for k in 0..l.points.len() {
                let (a, b) = l.segment(k);
                if (a.y > v) != (b.y > v) && a.x + (v - a.y) * (b.x - a.x) / (b.y - a.y) > u {
                    inside = !inside;
                }
            }
        }
        inside != r.outside
    }

    #[test]
    fn binned_tests_equal_the_tests_over_every_segment() {
        // Two circles and a thin sliver loop, points on a grid that hits vertex heights.
        let sliver = TrimLoop {
            curves: vec![TrimCurve {
                order: 2,
                knot: vec![0.0, 0.0, 0.5, 1.0, 1.0],
                min: 0.0,
                max: 1.0,
                points: vec![[0.1, 0.1, 1.0], [0.9, 0.15, 1.0], [0.1, 0.2, 1.0]],
            }],
        };
        let region = TrimRegion::new(
            &[TrimLoop::circle(0.5, 0.5, 0.3), TrimLoop::circle(0.3, 0.6, 0.1), sliver],
            false,
            1e-5,
        );
        for i in 0..=200 {
            for j in 0..=200 {
                let (u, v) = (f64::from(i) / 200.0, f64::from(j) / 200.0);
                assert_eq!(region.removes(u, v), removes_brute(&region, u, v), "({u}, {v})");
            }
        }
        // Rectangles of every size along the grid: as classified over every segment.
        let brute = |rect: [f64; 4]| {
            let crossed = region.loops.iter().any(|l| {
                (0..l.points.len()).any(|k| {
                    let (a, b) = l.segment(k);
                    segment_meets_rect(a, b, rect)
                })
            });
            match (
                crossed,
                removes_brute(&region, 0.5 * (rect[0] + rect[1]), 0.5 * (rect[2] + rect[3])),
            ) {
                (true, _) => Coverage::Boundary,
                (false, true) => Coverage::Removed,
                (false, false) => Coverage::Kept,
            }
        };
        for i in 0..40 {
            for j in 0..40 {
                let (u, v) = (f64::from(i) / 40.0, f64::from(j) / 40.0);
                for size in [0.001, 0.013, 0.1] {
                    let rect = [u, u + size, v, v + size * 0.7];
                    assert_eq!(region.classify(rect), brute(rect), "{rect:?}");
                }
            }
        }
        for l in &region.loops {
            for k in 0..l.points.len() {
                let (a, b) = l.segment(k);
                let v = 0.5 * (a.y + b.y);
                assert_eq!(region.removes(a.x, v), removes_brute(&region, a.x, v));
                assert_eq!(region.removes(b.x, a.y), removes_brute(&region, b.x, a.y));
            }
        }
    }

    #[test]
    fn nested_loops_alternate_and_rectangles_classify() {
        let region = TrimRegion::new(
            &[TrimLoop::circle(0.5, 0.5, 0.4), TrimLoop::circle(0.5, 0.5, 0.2)],
            false,
            1e-6,
        );
        assert!(!region.removes(0.5, 0.5)); // inside both: kept (island)
        assert!(region.removes(0.5 + 0.3, 0.5)); // in the ring: removed
        assert!(!region.removes(0.02, 0.02));
        assert_eq!(region.classify([0.45, 0.55, 0.45, 0.55]), Coverage::Kept);
        assert_eq!(region.classify([0.78, 0.82, 0.49, 0.51]), Coverage::Removed);
        assert_eq!(region.classify([0.69, 0.71, 0.49, 0.51]), Coverage::Boundary);
        assert_eq!(region.classify([0.0, 0.01, 0.0, 0.01]), Coverage::Kept);
        // A rectangle enclosing a whole loop is a boundary one.
        assert_eq!(region.classify([0.0, 1.0, 0.0, 1.0]), Coverage::Boundary);
    }
}
