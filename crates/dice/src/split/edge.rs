//! Crack-free dicing: the shared edges of split patches.
//!
//! Two grids that meet along a patch boundary are diced independently, at their own rates.
//! Where one puts more vertices along the boundary than the other, the other's straight
//! micropolygon edges cut across the first one's curved boundary, and samples fall through
//! the crack between them (the T-junction problem of every bucketed REYES dicer).
//!
//! The fix here: every side of a patch is part of an [`Edge`], made once, when the patch the
//! edge splits (or the root patch) is split, and shared (by reference) by every patch on
//! either side of it, down the whole split tree. An edge fixes its own polyline when it is
//! made: its range is halved wherever the curve strays from the chord by more than the
//! geometric accuracy the grids are diced to (the flatness bound, [`Splitter::edge_tolerance`]),
//! from its own geometry alone, so it does not matter which patch asks. A diced grid
//! then
//! - puts its boundary vertices *on* the polyline of each of its sides (linear in object
//!   space between the polyline's vertices; lines stay lines under the camera projection),
//!   not on the surface;
//! - has, along each side, a vertex at every polyline vertex of that side: its count along
//!   the side is a multiple of `2^d`, `d` the deepest halving of the polyline within the
//!   patch's range (a patch's range is itself a dyadic piece of the edge's), see
//!   [`Edge::floor`].
//!
//! So both grids along a boundary trace the same polyline, and their union has no crack, up
//! to the rounding of the points the finer grid adds between polyline vertices (a few
//! 1e-5 pixels off the line), which [`OVERLAP`] closes. Corners are points of the edges too:
//! a split takes the new edge's ends from the polylines of the sides it crosses, so the four
//! patches about a corner agree on it bit for bit. Motion: an edge holds its polyline's
//! points at every breakpoint, decided once for all of them (the largest stray over the
//! breakpoints), so the grids of all times still match vertex for vertex. A straight edge
//! (every edge of a bilinear patch or mesh face) stays one piece, and asks nothing of the
//! grids.
//!
//! Invariants: `t` is strictly increasing and holds the edge's two ends; every vertex
//! parameter is a dyadic point of the edge's range; `points` holds `t.len()` points per
//! breakpoint; [`Edge::at`] at a vertex parameter is that vertex's point exactly.

use glam::{Vec2, Vec3};

use super::Splitter;
use crate::motion::Pose;

/// Most halvings of an edge's range.
pub(crate) const EDGE_LIMIT: u32 = 16;
/// Points along a piece (ends included) at which its distance from its chord is measured:
/// the three inside ones see a piece that bends one way, or both ways, and a full circle
/// (a closed sweep's seam seen end on, whose ends coincide).
const EDGE_TEST: usize = 5;
/// Raster pixels by which a grid's boundary vertices are pushed out of the grid, so that
/// two grids along a shared edge overlap by a sliver rather than leave one of rounding
/// width (about 1e-4 pixel at raster coordinates of a thousand pixels, where `f32` steps
/// by 6e-5). An outline on a patch boundary moves out by as much, so it is kept below
/// 0.0005 pixel (issue #36: at 1e-3 it was 5 standard errors of a 256-sample edge), four
/// times that rounding.
pub(crate) const OVERLAP: f32 = 4.0e-4;
/// Raster length above which a piece of a subdivision surface's edge is also halved where its chord's point for a parameter
/// slides along the curve from the curve's point for it (see `Piece::strays`); shorter pieces
/// are judged by their distance from the chord alone (a paraboloid's apex, where the curve's
/// speed is unbounded, would otherwise be halved to the limit).
const ALONG_PIECE: f32 = 1.0;
/// Beyond this many halvings below a patch's range the floor is not honoured (the grid
/// would be too large to dice anyway; the patch is split further or clamped).
const MAX_FLOOR: u32 = 30;

/// Which line of parameter space an edge lies on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Line {
    /// `v` fixed, the edge running along `u`.
    AlongU(f32),
    /// `u` fixed, the edge running along `v`.
    AlongV(f32),
}

impl Line {
    /// The parameter point at `t` along the line.
    #[inline]
    fn uv(self, t: f32) -> (f32, f32) {
        match self {
            Line::AlongU(v) => (t, v),
            Line::AlongV(u) => (u, t),
        }
    }
}

/// One edge's polyline (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Edge {
    /// Parameters along the edge of the polyline's vertices, increasing, ends included.
    t: Vec<f32>,
    /// Object-space points: vertex `k` at breakpoint `b` is `points[b * t.len() + k]`.
    points: Vec<Vec3>,
}

impl Edge {
    /// The edge along `line` over `range`, with its end points `ends[b]` at every
    /// breakpoint `b` (of `poses`), its polyline fixed by `splitter`: no piece strays from
    /// the curve by more than `tol[b]` raster pixels at its test points at breakpoint `b`.
    pub fn new(
        splitter: &Splitter,
        poses: &[Pose<'_>],
        line: Line,
        range: [f32; 2],
        ends: &[[Vec3; 2]],
        tol: &[f32],
    ) -> Edge {
        let mut t = vec![range[0]];
        let mut per_pose: Vec<Vec<Vec3>> = ends.iter().map(|e| vec![e[0]]).collect();
        let first: Vec<Vec3> = ends.iter().map(|e| e[0]).collect();
        let last: Vec<Vec3> = ends.iter().map(|e| e[1]).collect();
        let mut fits = Vec::new();
        let mut piece =
            Piece { splitter, poses, line, tol, t: &mut t, points: &mut per_pose, fits: &mut fits };
        piece.halve(range, &first, &last, 0);
        t.push(range[1]);
        for (p, e) in per_pose.iter_mut().zip(ends) {
            p.push(e[1]);
        }
        for (pose, points) in poses.iter().zip(&mut per_pose) {
            straddle(pose, line, &t, points, &fits);
        }
        Edge { t, points: per_pose.concat() }
    }

    /// The same polyline run the other way, for a patch whose side goes along the edge of
    /// `[0, 1]` in the opposite direction (neighbouring faces of a mesh wind opposite ways
    /// along the edge they share): parameter `t` becomes `1 - t`, exact for the dyadic
    /// parameters of a root edge, so the vertices and [`Edge::floor`]s are the same ones.
    pub fn reversed(&self) -> Edge {
        let n = self.t.len();
        let t = self.t.iter().rev().map(|&t| 1.0 - t).collect();
        let points = self.points.chunks(n.max(1)).flat_map(|c| c.iter().rev().copied()).collect();
        Edge { t, points }
    }

    /// The point of the polyline at parameter `t` at breakpoint `b`: a vertex's point
    /// exactly at its parameter, linear in between, the nearer end outside the range.
    pub fn at(&self, b: usize, t: f32) -> Vec3 {
        let n = self.t.len();
        let points = &self.points[b * n..(b + 1) * n];
        let k = self.t.partition_point(|&p| p < t);
        if k >= n {
            return points[n - 1];
        }
        if self.t[k] == t || k == 0 {
            return points[k];
        }
        let (t0, t1) = (self.t[k - 1], self.t[k]);
        crate::motion::lerp(points[k - 1], points[k], (t - t0) / (t1 - t0))
    }

    /// The least `d` such that a grid with a multiple of `2^d` micropolygons along `range`
    /// (a dyadic piece of the edge's range) has a vertex at every polyline vertex inside it;
    /// capped at `MAX_FLOOR`.
    pub fn floor(&self, range: [f32; 2]) -> u32 {
        let lo = self.t.partition_point(|&p| p <= range[0]);
        let hi = self.t.partition_point(|&p| p < range[1]);
        let (a, w) = (f64::from(range[0]), f64::from(range[1]) - f64::from(range[0]));
        let mut d = 0;
        for &p in self.t.get(lo..hi).unwrap_or(&[]) {
            let x = (f64::from(p) - a) / w;
            let mut level = 0;
            let mut scaled = x;
            while scaled.fract() != 0.0 && level < MAX_FLOOR {
                scaled *= 2.0;
                level += 1;
            }
            d = d.max(level);
        }
        d
    }
}

/// The recursion that fixes an edge's polyline: vertices are appended in order.
struct Piece<'a, 'p> {
    splitter: &'a Splitter,
    poses: &'a [Pose<'p>],
    line: Line,
    /// Per breakpoint.
    tol: &'a [f32],
    t: &'a mut Vec<f32>,
    points: &'a mut Vec<Vec<Vec3>>,
    /// Per piece, in order: within the tolerance of the curve (not left long for being off
    /// screen or at the halving limit), so its sag may move its ends ([`straddle`]).
    fits: &'a mut Vec<bool>,
}

/// Move an edge's inside vertices (`points`, on the curve at the parameters `t` of `line`)
/// outward so that each chord straddles the curve instead of cutting inside it (issue #36).
/// A chord whose ends lie on a curve of curvature `k` misses it by `k L^2 / 8` at its middle
/// and by `k L^2 / 12`, two thirds of that, on average: every convex outline drawn by chords
/// is that much inside the true one. Moved by two thirds of its sag, a chord is as much
/// outside the curve near its ends as inside it near its middle, and covers the true area
/// to second order. Each piece of the polyline gives a third of its sag (the part across its
/// chord, measured at its middle parameter) to each of its inside ends, so that a chord
/// between two moved vertices moves by two thirds of the sag when its neighbours bend alike.
/// The edge's two ends are corners other edges share, and stay where they are. Pieces left
/// long (off screen, or at the halving limit) move nothing. No vertex moves by more than
/// two thirds of the tolerance, and no vertex is added: the grids are the same size.
fn straddle(pose: &Pose<'_>, line: Line, t: &[f32], points: &mut [Vec3], fits: &[bool]) {
    let n = t.len();
    if n <= 2 || fits.len() + 1 != n {
        return;
    }
    let sag: Vec<Vec3> = (0..n - 1)
        .map(|k| {
            if !fits[k] {
                return Vec3::ZERO;
            }
            let (u, v) = line.uv(0.5 * (t[k] + t[k + 1]));
            let (a, b, m) = (points[k], points[k + 1], pose.surface.position(u, v));
            let s = m - 0.5 * (a + b);
            let c = b - a;
            let c2 = c.length_squared();
            let across = if c2 > 0.0 { s - c * (s.dot(c) / c2) } else { Vec3::ZERO };
            // A straight edge's sag is rounding: it moves nothing, bit for bit.
            let rounding = 16.0 * f32::EPSILON * a.abs().max(b.abs()).max(m.abs()).max_element();
            if across.is_finite() && across.length() > rounding { across } else { Vec3::ZERO }
        })
        .collect();
    for k in 1..n - 1 {
        points[k] += (sag[k - 1] + sag[k]) / 3.0;
    }
}

impl Piece<'_, '_> {
    /// Halve the piece `range` (its end points `a`, `b` per breakpoint) if it is long, and
    /// append the vertices strictly inside it.
    fn halve(&mut self, range: [f32; 2], a: &[Vec3], b: &[Vec3], level: u32) {
        let mid = 0.5 * (range[0] + range[1]);
        if level >= EDGE_LIMIT || mid <= range[0] || mid >= range[1] {
            self.fits.push(false);
            return;
        }
        match self.strays(range, a, b) {
            Stray::Within => return self.fits.push(true),
            Stray::Unseen => return self.fits.push(false),
            Stray::Beyond => {}
        }

        let (u, v) = self.line.uv(mid);
        let m: Vec<Vec3> = self.poses.iter().map(|pose| pose.surface.position(u, v)).collect();
        self.halve([range[0], mid], a, &m, level + 1);
        self.t.push(mid);
        for (p, q) in self.points.iter_mut().zip(&m) {
            p.push(*q);
        }
        self.halve([mid, range[1]], &m, b, level + 1);
    }

    /// Whether the piece strays from its chord by more than `tol[b]` in raster at one of its
    /// `EDGE_TEST` points at some breakpoint (points not in front of the eye skipped), unless
    /// it is in a pinhole camera's view and its raster bound, grown by its own size, is off
    /// the screen at every breakpoint (it is never seen, so its shape does not matter).
    fn strays(&self, range: [f32; 2], a: &[Vec3], b: &[Vec3]) -> Stray {
        let sp = self.splitter;
        let (mut lo, mut hi) = (Vec2::INFINITY, Vec2::NEG_INFINITY);
        // Some breakpoint's stray is over its tolerance.
        let mut beyond = false;
        let mut all_seen = true;
        // Camera-space point and its raster position, for a point in front of the eye.
        let seen = |pose: &Pose<'_>, p: Vec3| {
            let c = sp.to_camera(pose, p);
            (c.is_finite() && c.z >= sp.near)
                .then(|| (c, sp.camera.eye_to_raster(c)))
                .filter(|(_, r)| r.is_finite())
        };
        // Pixels per camera-space unit at depth z, across the view (the larger axis).
        let k = sp.camera.raster_scale().abs().max_element();
        let perspective = sp.camera.projection() == reyes_scene::Projection::Perspective;
        let px = |z: f32| if perspective { k / z } else { k };
        for (k, pose) in self.poses.iter().enumerate() {
            let mut stray = 0.0_f32;
            let subdiv = matches!(pose.surface, crate::shapes::Surface::Subdiv(_));
            let (ea, eb) = (seen(pose, a[k]), seen(pose, b[k]));
            // The chord in camera space, even where an end is behind the eye: the part of
            // a piece that is in front must still follow the surface.
            let (ca, cb) = (sp.to_camera(pose, a[k]), sp.to_camera(pose, b[k]));
            let chord = (ca.is_finite() && cb.is_finite()).then_some((ca, cb));
            for e in [ea, eb] {
                match e {
                    Some((_, r)) => {
                        lo = lo.min(r);
                        hi = hi.max(r);
                    }
                    None => all_seen = false,
                }
            }
            for i in 1..EDGE_TEST - 1 {
                let f = i as f32 / (EDGE_TEST - 1) as f32;
                let (u, v) = self.line.uv(range[0] + (range[1] - range[0]) * f);
                let Some((c, r)) = seen(pose, pose.surface.position(u, v)) else {
                    all_seen = false;
                    continue;
                };
                lo = lo.min(r);
                hi = hi.max(r);
                // How far the chord is from the curve: across the screen, and in depth
                // (a chord seen end on is straight on screen but may cut deep under the
                // surface), the latter as pixels at the point's depth.
                if let (Some((_, ra)), Some((_, rb))) = (ea, eb) {
                    stray = stray.max(distance_to_segment(r, ra, rb));
                }
                // And along it: a grid puts its boundary vertex at parameter `t` at the
                // chord's point for `t` ([`Edge::at`], linear in the parameter), next to
                // its inside vertices on the surface at their parameters, so the curve
                // must also be near that point, not just near the chord. Where the
                // curve's speed varies (along an edge out of a Catmull-Clark
                // extraordinary vertex) the chord's point slides along the curve away
                // from the surface point, skewing the grids' boundary cells and opening
                // gaps between grids that take different vertices of the polyline.
                if let Some((ca, cb)) = chord {
                    // Only on subdivision surfaces for now: elsewhere the edges' speed
                    // varies smoothly enough that the across test has always sufficed, and
                    // pathological placements (fuzz regressions far-camera and
                    // camera-swing) halve for seconds under the along test.
                    let long = match (ea, eb) {
                        (Some((_, ra)), Some((_, rb))) => {
                            subdiv && (rb - ra).length() > ALONG_PIECE
                        }
                        _ => false,
                    };
                    let along = if long { (c - ca.lerp(cb, f)).length() } else { 0.0 };
                    stray = stray.max(distance_to_segment(c, ca, cb).max(along) * px(c.z));
                }
            }
            // (`f32::max` never keeps a NaN: `stray` is a number.)
            beyond |= stray > self.tol.get(k).copied().unwrap_or(f32::INFINITY);
        }
        // No exemption for short pieces: the grids along the edge are diced to the same
        // flatness bound (flat.rs), so a piece that strays more than it would leave the grids'
        // boundary coarser than their insides (a small sphere at 1/512 of its extent).
        if !beyond {
            return Stray::Within;
        }
        if all_seen && sp.lens.is_none() {
            let grow = (hi - lo).max_element() + super::MARGIN_PIXELS;
            let off = hi.x + grow < sp.screen_lo.x
                || hi.y + grow < sp.screen_lo.y
                || lo.x - grow > sp.screen_hi.x
                || lo.y - grow > sp.screen_hi.y;
            if off {
                return Stray::Unseen;
            }
        }
        Stray::Beyond
    }
}

/// What [`Piece::strays`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stray {
    /// Within the tolerance of the curve everywhere it was tested.
    Within,
    /// Beyond it, but never seen.
    Unseen,
    /// Beyond it: halve.
    Beyond,
}

/// Distance from `p` to the segment `a b` (to `a` when the segment is a point).
fn distance_to_segment<V: Point>(p: V, a: V, b: V) -> f32 {
    let d = b - a;
    let len2 = d.dot(d);
    let f = if len2 > 0.0 { ((p - a).dot(d) / len2).clamp(0.0, 1.0) } else { 0.0 };
    let e = p - (a + d * f);
    e.dot(e).sqrt()
}

/// What [`distance_to_segment`] needs of a point: 2-D raster or 3-D camera space.
trait Point:
    Copy
    + std::ops::Sub<Output = Self>
    + std::ops::Add<Output = Self>
    + std::ops::Mul<f32, Output = Self>
{
    fn dot(self, other: Self) -> f32;
}

impl Point for Vec2 {
    fn dot(self, other: Vec2) -> f32 {
        Vec2::dot(self, other)
    }
}

impl Point for Vec3 {
    fn dot(self, other: Vec3) -> f32 {
        Vec3::dot(self, other)
    }
}

/// The four sides of a patch, each a shared [`Edge`] (see the module documentation):
/// `bottom` and `top` run along `u` at `v0` and `v1`, `left` and `right` along `v` at `u0`
/// and `u1`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Sides {
    pub bottom: std::sync::Arc<Edge>,
    pub top: std::sync::Arc<Edge>,
    pub left: std::sync::Arc<Edge>,
    pub right: std::sync::Arc<Edge>,
}

impl Sides {
    /// The object-space point of a patch's boundary vertex at `(u, v)` at breakpoint `b`, on
    /// the side it lies on (`i`, `j` its grid indices of `nu`, `nv`), or `None` inside.
    #[inline]
    pub fn boundary(
        &self,
        b: usize,
        (u, v): (f32, f32),
        (i, j): (usize, usize),
        (nu, nv): (usize, usize),
    ) -> Option<Vec3> {
        if j == 0 {
            Some(self.bottom.at(b, u))
        } else if j == nv {
            Some(self.top.at(b, u))
        } else if i == 0 {
            Some(self.left.at(b, v))
        } else if i == nu {
            Some(self.right.at(b, v))
        } else {
            None
        }
    }

    /// `(du, dv)`: a grid of the patch `u` x `v` must have a multiple of `2^du`
    /// micropolygons along `u` and of `2^dv` along `v` ([`Edge::floor`]).
    pub fn floors(&self, u: [f32; 2], v: [f32; 2]) -> (u32, u32) {
        (self.bottom.floor(u).max(self.top.floor(u)), self.left.floor(v).max(self.right.floor(v)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge(t: Vec<f32>) -> Edge {
        let points = t.iter().map(|&t| Vec3::new(t, t * t, 0.0)).collect();
        Edge { t, points }
    }

    #[test]
    fn a_vertex_is_exact_and_between_is_linear() {
        let e = edge(vec![0.0, 0.25, 0.5, 1.0]);
        assert_eq!(e.at(0, 0.25), Vec3::new(0.25, 0.0625, 0.0));
        assert_eq!(e.at(0, 1.0), Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(e.at(0, 0.0), Vec3::ZERO);
        // Halfway between 0.5 (0.25) and 1 (1): 0.625.
        assert_eq!(e.at(0, 0.75), Vec3::new(0.75, 0.625, 0.0));
        assert_eq!(e.at(0, -1.0), Vec3::ZERO);
        assert_eq!(e.at(0, 2.0), Vec3::new(1.0, 1.0, 0.0));
    }

    #[test]
    fn a_reversed_edge_has_the_same_points_the_other_way() {
        let e = edge(vec![0.0, 0.125, 0.25, 0.5, 1.0]);
        let r = e.reversed();
        for t in [0.0, 0.125, 0.25, 0.5, 1.0] {
            assert_eq!(r.at(0, 1.0 - t), e.at(0, t), "t = {t}");
        }
        // Between vertices, the same chord (to the rounding of the interpolation).
        assert!((r.at(0, 0.7) - e.at(0, 0.3)).length() < 1e-6);
        assert_eq!(r.floor([0.0, 1.0]), 3);
        assert_eq!(r.floor([0.5, 1.0]), 2);
        assert_eq!(r.reversed(), e);
    }

    #[test]
    fn floors_count_the_deepest_halving_inside_a_range() {
        let e = edge(vec![0.0, 0.125, 0.25, 0.5, 1.0]);
        // 0.125 is 1/8 of [0, 1]: 3 halvings; 0.5 of [0.5, 1] is its end: none inside.
        assert_eq!(e.floor([0.0, 1.0]), 3);
        assert_eq!(e.floor([0.5, 1.0]), 0);
        assert_eq!(e.floor([0.0, 0.5]), 2);
        assert_eq!(e.floor([0.0, 0.25]), 1);
        assert_eq!(e.floor([0.25, 0.5]), 0);
    }
}
