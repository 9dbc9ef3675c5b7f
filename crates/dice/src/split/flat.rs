//! The flatness rule of the split and dice decisions: how finely a patch must be diced for
//! its flat micropolygons to lie within a distance in pixels of the true surface, measured
//! on the decisions' own test grids (docs/geometry.md).

use glam::{Vec2, Vec3};
use reyes_hider::LensSetup;

use std::sync::Arc;

use super::{GridFacts, MARGIN_FRACTION as MARGIN, MAX_SIDE, Patch, Splitter, TEST_N, TestGrid};
use crate::csg::OperandBounds;

impl Splitter {
    /// Micropolygons per side `(nu, nv)` that the flatness rule asks for over the test grids
    /// of `facts` (`(1, 1)` with the rule off), for points mapped to raster by `map`.
    ///
    /// A row of the diced grid is a polyline through points of the surface; between two of
    /// them, `H` apart in the patch's parameter, the surface curve bulges from its chord by
    /// at most `|f''| H^2 / 8` pixels, with `f''` its second derivative in raster. The test
    /// points, `h = 1 / (TEST_N - 1)` apart, measure it: for three consecutive points
    /// `a, b, c`, the distance `d` of `b` from the chord `ac` is `|f''| h^2 / 2` (the normal
    /// part, as a bend; a curve whose image folds back on itself at a silhouette, so that
    /// `b - a` and `c - b` point apart, is measured by half the whole second difference,
    /// `|a - 2b + c| / 2 = |f''| h^2 / 2`, and the fold is then never missed, whichever side
    /// of a test point it falls). A straight image (a plane's rows under perspective,
    /// bunched up but straight) has no normal part and counts for nothing, rightly: its
    /// flat micropolygons are exact. So `n` micropolygons along the row keep the error
    /// within `tol` when `d (TEST_N - 1)^2 / (4 n^2) <= tol`, where `tol` is the smaller of
    /// the absolute bound and the relative one times the primitive's extent at that
    /// breakpoint ([`Patch::extent`], extent.rs). With a lens, a point seen from lens position `l` (`|l| <= 1`)
    /// moves by `l * coc(z)`: the bend is measured at the lens's centre and around its rim,
    /// and the largest counts. The estimate is multiplied by [`FLAT_SAFETY`]
    /// (an 8-point sampling of a full circle underestimates its curvature by 7%).
    pub(super) fn flat_counts(
        &self,
        facts: &[GridFacts<'_>],
        patch: &Patch,
        map: impl Fn(&Vec3) -> Option<Vec3>,
    ) -> (u64, u64) {
        if self.flatness <= 0.0 && self.relative_flatness <= 0.0 {
            return (1, 1);
        }
        // Micropolygons along a row for a bend of `bend` pixels within `tol` pixels.
        let need = |bend: f32, tol: f64| {
            let n = (TEST_N - 1) as f64 * (FLAT_SAFETY * f64::from(bend) / (4.0 * tol)).sqrt();
            if n.is_finite() { n.ceil().clamp(1.0, MAX_SIDE) as u64 } else { MAX_SIDE as u64 }
        };
        // The csg rule's bends in space are measured as pixels at their depth.
        let csg = self.csg_depth.as_ref().is_some_and(|c| c.near_another(facts));
        let k = self.camera.raster_scale().abs().max_element();
        let perspective = self.camera.projection() == reyes_scene::Projection::Perspective;
        let px = |z: f32| if perspective { k / z } else { k };
        let (mut nu, mut nv) = (1, 1);
        for f in facts {
            let b = bends(f.grid, &map, self.lens.as_ref());
            // The primitive's extent at this breakpoint: the patch is part of a surface
            // whose silhouette the relative bound is about (its own extent would tighten
            // the bound split by split); the patch's own where the primitive's is unknown.
            let extent =
                Some(patch.extent.at(f.pose)).filter(|e| e.is_finite()).unwrap_or(b.extent);
            // Below a millionth of a pixel nothing is measurable (and a point has no extent).
            let tol = f64::from(self.flat_tolerance(extent).max(1e-6));
            (nu, nv) = (nu.max(need(b.u, tol)), nv.max(need(b.v, tol)));
            if csg {
                // The bend in space, as pixels at its depth, within a tenth of the tolerance.
                let tol = tol * f64::from(CSG_DEPTH_FRACTION);
                let (u, v) = bends_in_space(f.grid, self.near, px);
                (nu, nv) = (nu.max(need(u, tol)), nv.max(need(v, tol)));
            }
        }
        (nu, nv)
    }

    /// The same decisions for an operand of a CSG solid: the flatness rule also bounds the
    /// micropolygons' distance from the surface in space (as pixels at its depth), not only
    /// across the screen, within [`CSG_DEPTH_FRACTION`] of the flatness bound (issue #36).
    /// Where two operands cross, the solid's outline is the projection of their crossing
    /// curve, which the facets' errors across their surfaces move by about those errors over
    /// the sine of the angle between the surfaces; the screen-space rule bounds nothing of
    /// the kind where a surface faces the eye, and at an operand's own silhouette its
    /// micropolygons, a pixel on screen, are many pixels long in depth, and their sag is
    /// too (the notch of `Difference(a, b)` was 0.2 of a pixel's coverage off).
    ///
    /// `operand`: the bounds of the scene's operands, and this object's tree and index; the
    /// rule holds for the patches whose bound meets another operand's of the same tree (the
    /// edges of every patch of the operand take the tighter tolerance).
    pub fn with_csg_depth(&self, operand: Option<(Arc<OperandBounds>, u16, u32)>) -> Splitter {
        let csg_depth = operand.map(|(bounds, tree, object)| CsgDepth { bounds, tree, object });
        Splitter { csg_depth, ..self.clone() }
    }

    /// The same decisions for a displaced surface whose points move up to `reach` in
    /// camera space (RenderMan's displacement bound): bounds, depth ranges and side-plane
    /// tests take in the cube of half-side `reach` about every test and hull point.
    pub fn with_displacement(&self, reach: f32) -> Splitter {
        Splitter { displace: reach, ..self.clone() }
    }

    /// The same decisions at another shading rate (an object's own `shading_rate`).
    pub fn with_shading_rate(&self, shading_rate: f32) -> Splitter {
        Splitter { step: super::step(shading_rate), ..self.clone() }
    }
}

/// What [`Splitter::with_csg_depth`] needs to know.
#[derive(Debug, Clone)]
pub(crate) struct CsgDepth {
    bounds: Arc<OperandBounds>,
    tree: u16,
    object: u32,
}

impl CsgDepth {
    /// Whether the patch seen in `facts` may come near another operand of its tree: its test
    /// points' camera-space bound, grown by a quarter of its extent (as the split decisions'
    /// margin: test points do not bound a curved surface), meets that operand's bound.
    fn near_another(&self, facts: &[GridFacts<'_>]) -> bool {
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for f in facts {
            if !f.all_finite {
                return true;
            }
            (lo, hi) = (lo.min(f.lo), hi.max(f.hi));
        }
        let grow = Vec3::splat(MARGIN * (hi - lo).max_element());
        self.bounds.meet_another(self.tree, self.object, lo - grow, hi + grow)
    }
}

/// The fraction of the flatness bound to which [`Splitter::with_csg_depth`] holds a CSG
/// operand's error in space: at the default 0.05 pixel, 0.005, which moves a crossing at 30
/// degrees by 0.01 pixel, a third of a pixel's sampling error at 256 samples along a pixel
/// of outline (about 0.006 in coverage; docs/geometry.md).
pub(crate) const CSG_DEPTH_FRACTION: f32 = 0.1;

/// The largest bends in space along rows (u) and columns (v) of a test grid, as pixels at
/// the bent point's depth (`px(z)`): the distance of the middle point of three from the
/// chord of the outer two (half the whole second difference where the three fold back);
/// points nearer than `near` are skipped.
fn bends_in_space(grid: &TestGrid, near: f32, px: impl Fn(f32) -> f32) -> (f32, f32) {
    let bend = |a: Vec3, b: Vec3, c: Vec3| {
        if !(a.is_finite() && b.is_finite() && c.is_finite()) || b.z < near {
            return 0.0;
        }
        let (ab, bc, ac) = (b - a, c - b, c - a);
        let d = if ab.dot(bc) <= 0.0 || ac.length_squared() <= 0.0 {
            0.5 * (a - 2.0 * b + c).length()
        } else {
            ab.cross(ac).length() / ac.length()
        };
        let d = d * px(b.z);
        if d.is_finite() { d } else { f32::INFINITY }
    };
    let (mut u, mut v) = (0.0_f32, 0.0_f32);
    for j in 0..TEST_N {
        for i in 0..TEST_N {
            if i + 2 < TEST_N {
                u = u.max(bend(grid[j][i], grid[j][i + 1], grid[j][i + 2]));
            }
            if j + 2 < TEST_N {
                v = v.max(bend(grid[j][i], grid[j + 1][i], grid[j + 2][i]));
            }
        }
    }
    (u, v)
}

/// Factor on the measured bends of [`Splitter::flat_counts`].
const FLAT_SAFETY: f64 = 1.25;

/// Eight points of the lens's rim (unit radius) at which [`bends`] measures a defocused bend.
const LENS_RIM: [[f32; 2]; 8] = [
    [1.0, 0.0],
    [std::f32::consts::FRAC_1_SQRT_2, std::f32::consts::FRAC_1_SQRT_2],
    [0.0, 1.0],
    [-std::f32::consts::FRAC_1_SQRT_2, std::f32::consts::FRAC_1_SQRT_2],
    [-1.0, 0.0],
    [-std::f32::consts::FRAC_1_SQRT_2, -std::f32::consts::FRAC_1_SQRT_2],
    [0.0, -1.0],
    [std::f32::consts::FRAC_1_SQRT_2, -std::f32::consts::FRAC_1_SQRT_2],
];

/// What [`bends`] measures of a test grid.
struct Bends {
    /// Largest bend `d` along a row (u) and along a column (v), in pixels.
    u: f32,
    v: f32,
    /// Raster extent of the mapped points (the larger side of their bound; infinite when
    /// none maps).
    extent: f32,
}

/// The bends of a test grid in raster (see [`Splitter::flat_counts`]): points mapped by
/// `map`, triples with an unmapped point skipped; with a `lens`, the largest bend over the
/// lens's centre and [`LENS_RIM`].
fn bends(grid: &TestGrid, map: impl Fn(&Vec3) -> Option<Vec3>, lens: Option<&LensSetup>) -> Bends {
    let mapped = grid.map(|row| row.map(|p| map(&p).map(|r| (Vec2::new(r.x, r.y), p.z))));
    // The bend of three raster points (see `Splitter::flat_counts`).
    let bend3 = |a: Vec2, b: Vec2, c: Vec2| {
        let (ab, bc, ac) = (b - a, c - b, c - a);
        if ab.dot(bc) <= 0.0 || ac.length_squared() <= 0.0 {
            0.5 * (a - 2.0 * b + c).length()
        } else {
            ab.perp_dot(ac).abs() / ac.length()
        }
    };
    let bend = |a: Option<(Vec2, f32)>, b: Option<(Vec2, f32)>, c: Option<(Vec2, f32)>| {
        let (Some((a, za)), Some((b, zb)), Some((c, zc))) = (a, b, c) else {
            return 0.0;
        };
        let mut d = bend3(a, b, c);
        if let Some(l) = lens {
            // Seen from lens position `q` each point moves by `q * coc(z)`: the bend at the
            // lens's centre and at eight points of its rim (a plane stays straight at every
            // one, so a defocused plane is not diced finer for nothing).
            let shift = |p: Vec2, z: f32, q: Vec2| {
                let (cx, cy) = l.coc(z);
                p + Vec2::new(q.x * cx, q.y * cy)
            };
            for q in LENS_RIM {
                let q = Vec2::from(q);
                d = d.max(bend3(shift(a, za, q), shift(b, zb, q), shift(c, zc, q)));
            }
        }
        if d.is_finite() { d } else { f32::INFINITY }
    };
    let mut out = Bends { u: 0.0, v: 0.0, extent: f32::INFINITY };
    let (mut lo, mut hi) = (Vec2::INFINITY, Vec2::NEG_INFINITY);
    for j in 0..TEST_N {
        for i in 0..TEST_N {
            if let Some((r, _)) = mapped[j][i] {
                lo = lo.min(r);
                hi = hi.max(r);
            }
            if i + 2 < TEST_N {
                out.u = out.u.max(bend(mapped[j][i], mapped[j][i + 1], mapped[j][i + 2]));
            }
            if j + 2 < TEST_N {
                out.v = out.v.max(bend(mapped[j][i], mapped[j + 1][i], mapped[j + 2][i]));
            }
        }
    }
    if lo.x <= hi.x {
        out.extent = (hi - lo).max_element();
    }
    out
}
