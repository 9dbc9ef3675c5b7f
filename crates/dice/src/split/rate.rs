//! The dice decision (stage: dice): a patch's grid size from its projected row and column
//! lengths at the shading rate, RenderMan's target area of a micropolygon, with the flatness
//! rule's floor, crack-free dicing's multiples and the largest grid; or a split where the
//! grid would be too big. Invariant: one decision for every motion breakpoint.

use glam::Vec3;

use super::{Decision, GridFacts, MAX_SIDE, OFF_SCREEN_GROWTH, Patch, Splitter, TestGrid};
use crate::split::{MAX_SPLIT_DEPTH, TEST_N};

impl Splitter {
    /// False if the margin-grown raster bound of a breakpoint's test grid misses the bucket
    /// grid; true without a raster bound (some point not in front of the eye).
    fn may_be_on_screen(&self, f: &GridFacts<'_>) -> bool {
        f.raster.is_none_or(|(lo, hi)| {
            hi.x >= self.screen_lo.x
                && hi.y >= self.screen_lo.y
                && lo.x <= self.screen_hi.x
                && lo.y <= self.screen_hi.y
        })
    }

    /// Grid size from the mean projected row and column lengths, the largest over the
    /// breakpoints (so the grid is near the shading rate at every time), rounded to nearest:
    /// a grid's mean micropolygon area aims at the shading rate, RenderMan's definition
    /// (docs/geometry.md, "Dicing to the shading rate"); split if too big and allowed, else
    /// clamp.
    pub(super) fn dice_decision(
        &self,
        facts: &[GridFacts<'_>],
        patch: &Patch,
        at_limit: bool,
    ) -> Decision {
        // Only points that may become kept vertices count (all of them unless at the limit).
        let raster = |p: &Vec3| {
            (p.is_finite() && p.z >= self.near).then(|| self.camera.eye_to_raster(*p).extend(0.0))
        };
        let measure = |facts: &[GridFacts<'_>]| {
            facts.iter().map(|f| lengths(f.grid, raster)).fold(
                ((0.0_f32, 0.0_f32), (0.0_f32, 0.0_f32)),
                |(long, target), l| {
                    let t = l.target();
                    (
                        (long.0.max(l.longest.0), long.1.max(l.longest.1)),
                        (target.0.max(t.0), target.1.max(t.1)),
                    )
                },
            )
        };
        let mut lens = measure(facts);
        // A moving grid is seen near the times it is on screen. Breakpoints where it is off
        // screen (gone far to one side, or next to the eye plane, where perspective stretches
        // it without bound) may ask for at most `OFF_SCREEN_GROWTH` times the lengths of the
        // breakpoints where it may be on screen; a grid on screen at none of its breakpoints
        // (one sweeping across between them) is measured at all of them.
        let on_screen: Vec<GridFacts<'_>> =
            facts.iter().copied().filter(|f| self.may_be_on_screen(f)).collect();
        if !on_screen.is_empty() && on_screen.len() < facts.len() {
            let on = measure(&on_screen);
            let cap = |a: (f32, f32), b: (f32, f32)| {
                (a.0.min(OFF_SCREEN_GROWTH * b.0), a.1.min(OFF_SCREEN_GROWTH * b.1))
            };
            lens = (cap(lens.0, on.0), cap(lens.1, on.1));
        }
        // The longest row and column choose a split's direction, as they always did.
        let ((long_u, long_v), (len_u, len_v)) = lens;
        // The micropolygon side, grown for a blurred patch (exactly `step` with the motion
        // and focus factors off).
        let step = self.step * self.blur_step_scale(facts);
        // Micropolygons along a side, unrounded: the mean length over the side.
        let exact = |len: f32| (f64::from(len) / f64::from(step)).clamp(0.0, MAX_SIDE);
        let (xu, xv) = (exact(len_u), exact(len_v));
        // No row or column is diced into micropolygons longer on average than
        // `MAX_ELONGATION` sides: a patch whose rows differ much in length (a triangle diced as
        // a quad with a collapsed side, a cap's rows near its pole) would otherwise have
        // slivers along its longest ones.
        let elongation =
            |len: f32| (exact(len) / MAX_ELONGATION).ceil().clamp(1.0, MAX_SIDE) as u64;
        let (long_nu, long_nv) = (elongation(long_u), elongation(long_v));
        let (shade_u, shade_v) = nearest_area((xu, 1, long_nu), (xv, 1, long_nv));
        // The flatness rule, from the breakpoints the lengths came from.
        let measured = if !on_screen.is_empty() { &on_screen[..] } else { facts };
        let (flat_u, flat_v) = self.flat_counts(measured, patch, raster);
        let (flat_u, flat_v) = (flat_u.max(long_nu), flat_v.max(long_nv));
        let (nu, nv) = nearest_area((xu, 1, flat_u), (xv, 1, flat_v));
        // Crack-free dicing: a vertex at every polyline vertex of every side (edge.rs).
        let (nu_c, nv_c) = match &patch.sides {
            Some(sides) => {
                let (du, dv) = sides.floors(patch.u, patch.v);
                let floor = |d: u32| 1_u64 << d.min(40);
                nearest_area((xu, floor(du), flat_u), (xv, floor(dv), flat_v))
            }
            None => (nu, nv),
        };
        if nu_c.saturating_mul(nv_c) <= self.max_grid {
            let extra = (nu_c * nv_c).saturating_sub(shade_u * shade_v) as u32;
            return Decision::Dice { nu: nu_c as u32, nv: nv_c as u32, limited: at_limit, extra };
        }
        // Progress is judged on the rates' own counts: halving a patch halves its sides'
        // floors too. They are counted from the longest row and column, rounded up (the
        // rule before dicing to the mean), which never grow when a patch is halved: the
        // mean lengths may (a half may keep a patch's longer columns), and a half asking
        // for more than its parent would count as a stall, and two of them would dice the
        // grid clamped, off crack-free dicing's multiples.
        let up = |len: f32| ((f64::from(len) / f64::from(step)).ceil()).clamp(1.0, MAX_SIDE) as u64;
        let count = up(long_u).max(flat_u) * up(long_v).max(flat_v);
        let stalled = stalls(patch.parent_count, count) && patch.stalls + 1 >= MAX_STALLS;
        if !at_limit && patch.depth < MAX_SPLIT_DEPTH && !stalled {
            // Where the floors made the grid too big, halve the side they raised most.
            let along_u = if (nu_c, nv_c) == (nu, nv) { long_u >= long_v } else { nu_c >= nv_c };
            return Decision::Split { along_u, hither: false, count };
        }
        let (nu, nv) = clamp_grid(nu, nv, self.max_grid);
        let (su, sv) = clamp_grid(shade_u, shade_v, self.max_grid);
        let extra = (u64::from(nu) * u64::from(nv)).saturating_sub(u64::from(su) * u64::from(sv));
        Decision::Dice { nu, nv, limited: true, extra: extra as u32 }
    }
}

/// The grid `(nu, nv)` whose mean micropolygon area is nearest the shading rate's: each
/// side `(x, step, min)` has the unrounded count `x` (the side's length over the
/// micropolygon side), must be a multiple of `step` (crack-free dicing's `2^d`, 1 without)
/// and at least `min` (the flatness rule's count) and `step`. Of the multiples just below
/// and just above `x` along each side (so no side is further than one multiple from its
/// own nearest), the pair whose area `nu * nv` is nearest `x_u * x_v` in ratio wins, and of
/// equally near pairs the one nearer the patch's aspect, then the one with more along u.
/// Choosing both sides together halves the worst error of coarse multiples: a patch asking
/// for 21 by 21 micropolygons in multiples of 16 gets 32 x 16 (area 0.86 of the rate),
/// where rounding each side would give 16 x 16 (1.72). Clamped to [`MAX_SIDE`].
pub(super) fn nearest_area(u: (f64, u64, u64), v: (f64, u64, u64)) -> (u64, u64) {
    let candidates = |(x, step, min): (f64, u64, u64)| {
        let step = step.max(1);
        let least = min.max(1).div_ceil(step).saturating_mul(step);
        let below = ((x / step as f64).floor().min(MAX_SIDE) as u64).saturating_mul(step);
        let above = ((x / step as f64).ceil().min(MAX_SIDE) as u64).saturating_mul(step);
        [below.max(least).min(MAX_SIDE as u64), above.max(least).min(MAX_SIDE as u64)]
    };
    let (cu, cv) = (candidates(u), candidates(v));
    // The error of a pair: first in area, then in aspect, both as |ln(ratio)|.
    let error = |nu: u64, nv: u64| {
        let ratio = |n: u64, x: f64| (n as f64 / x.max(f64::MIN_POSITIVE)).ln();
        let (ru, rv) = (ratio(nu, u.0), ratio(nv, v.0));
        ((ru + rv).abs(), (ru - rv).abs())
    };
    let mut best = (cu[0], cv[0]);
    for &nu in &cu {
        for &nv in &cv {
            let (e, b) = (error(nu, nv), error(best.0, best.1));
            // Ties within rounding keep the earlier pair (fewer along v, then along u).
            let better = e.0 < b.0 - 1e-9
                || (e.0 <= b.0 + 1e-9 && (e.1 < b.1 - 1e-9 || (e.1 <= b.1 + 1e-9 && nu > best.0)));
            if better {
                best = (nu, nv);
            }
        }
    }
    best
}

/// [`lengths`] of every grid: the largest `len_u` and the largest `len_v`.
pub(super) fn max_lengths(
    facts: &[GridFacts<'_>],
    map: impl Fn(&Vec3) -> Option<Vec3>,
) -> (f32, f32) {
    facts
        .iter()
        .map(|f| lengths(f.grid, &map).longest)
        .fold((0.0_f32, 0.0_f32), |(mu, mv), (u, v)| (mu.max(u), mv.max(v)))
}

/// A test grid's projected row and column lengths ([`lengths`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Lengths {
    /// `(len_u, len_v)`: the longest row and the longest column.
    pub(super) longest: (f32, f32),
    /// `(len_u, len_v)`: the mean row length and the mean column length over the patch's
    /// parameter range, by the trapezoid rule over the `TEST_N` rows (columns) at parameter
    /// steps of `1 / (TEST_N - 1)`: the end rows weigh half as much as the inner ones.
    pub(super) mean: (f32, f32),
    /// The projected area: the summed areas of the `(TEST_N - 1)^2` quads between the test
    /// points (each its absolute shoelace area; quads with an unmapped corner skipped).
    pub(super) area: f32,
}

/// The most micropolygon sides along a grid's longest row or column, on average, that one
/// of its micropolygons may span there ([`Splitter::dice_decision`]).
pub(super) const MAX_ELONGATION: f64 = 2.0;
/// Bounds on the shear correction of [`Lengths::target`]: a micropolygon's sides are kept
/// between half and twice the shading rate's side.
pub(super) const SHEAR_RANGE: (f32, f32) = (0.25, 4.0);

impl Lengths {
    /// `(len_u, len_v)` to divide by the micropolygon side: the mean lengths scaled by
    /// `sqrt(s)`, `s = area / (mean_u * mean_v)` clamped to [`SHEAR_RANGE`], so that a grid
    /// of `len_u / side` by `len_v / side` micropolygons has the mean area `side^2` (its
    /// area over their number) with the sides in the patch's aspect. `s` is the sine of
    /// the angle between the rows and columns of a sheared parallelogram (a ground plane
    /// seen off to one side), and corrects too for rows and columns whose lengths vary
    /// together across the patch (a plane under perspective). A patch with no area
    /// measured (all its quads unmapped) keeps its mean lengths.
    pub(super) fn target(&self) -> (f32, f32) {
        let (u, v) = self.mean;
        let product = u * v;
        let s = if product > 0.0 && self.area > 0.0 {
            (self.area / product).clamp(SHEAR_RANGE.0, SHEAR_RANGE.1)
        } else {
            1.0
        };
        let k = s.sqrt();
        (u * k, v * k)
    }
}

/// The rows' and columns' lengths of the grid, each the sum of its segment lengths between
/// the images under `map` (segments with an unmapped end skipped).
pub(super) fn lengths(grid: &TestGrid, map: impl Fn(&Vec3) -> Option<Vec3>) -> Lengths {
    let mapped = grid.map(|row| row.map(|p| map(&p)));
    let seg = |a: Option<Vec3>, b: Option<Vec3>| match (a, b) {
        (Some(a), Some(b)) => a.distance(b),
        _ => 0.0,
    };
    let rows: [f32; TEST_N] =
        std::array::from_fn(|j| mapped[j].windows(2).map(|w| seg(w[0], w[1])).sum::<f32>());
    let columns: [f32; TEST_N] = std::array::from_fn(|i| {
        (0..TEST_N - 1).map(|j| seg(mapped[j][i], mapped[j + 1][i])).sum::<f32>()
    });
    let longest = |l: &[f32; TEST_N]| l.iter().copied().fold(0.0_f32, f32::max);
    let mean = |l: &[f32; TEST_N]| {
        let inner: f32 = l[1..TEST_N - 1].iter().sum();
        (inner + 0.5 * (l[0] + l[TEST_N - 1])) / (TEST_N - 1) as f32
    };
    let mut area = 0.0_f32;
    for j in 0..TEST_N - 1 {
        for i in 0..TEST_N - 1 {
            let quad = [mapped[j][i], mapped[j][i + 1], mapped[j + 1][i + 1], mapped[j + 1][i]];
            if let [Some(a), Some(b), Some(c), Some(d)] = quad {
                let cross = |p: Vec3, q: Vec3| p.x * q.y - q.x * p.y;
                area += 0.5 * (cross(a, b) + cross(b, c) + cross(c, d) + cross(d, a)).abs();
            }
        }
    }
    Lengths {
        longest: (longest(&rows), longest(&columns)),
        mean: (mean(&rows), mean(&columns)),
        area,
    }
}

/// Shrink an `nu x nv` grid proportionally to at most `max` micropolygons (each side >= 1).
pub(super) fn clamp_grid(nu: u64, nv: u64, max: u64) -> (u32, u32) {
    if nu * nv <= max {
        return (nu as u32, nv as u32);
    }
    let f = (max as f64 / (nu as f64 * nv as f64)).sqrt();
    let nu2 = ((nu as f64 * f).floor() as u64).clamp(1, max);
    let nv2 = ((nv as f64 * f).floor() as u64).clamp(1, max / nu2);
    (nu2 as u32, nv2 as u32)
}

/// A split makes no progress when a half still asks for at least this fraction
/// (numerator, denominator) of its parent's micropolygons; see [`stalls`].
pub(super) const STALL_RATIO: (u128, u128) = (1, 1);
/// Consecutive splits without progress after which a patch is diced (clamped to
/// `max_grid_size`) instead of split again, and counted as limited.
pub(super) const MAX_STALLS: u32 = 2;

/// True if a patch that would be diced into `count` micropolygons, split from a parent that
/// would have been diced into `parent_count`, made no progress: a half of a patch asks for
/// at least [`STALL_RATIO`] of its parent's micropolygons. Halving a patch reduces its
/// count wherever its projection is finite; it fails to only where the projected lengths
/// saturate (a field of view of 1e-30 degrees, a vertex at 1e30, so lengths of `inf`
/// pixels, counted as [`MAX_SIDE`]), where further splits would multiply the work for
/// nothing until the depth limit, 2^40 patches later.
pub(super) fn stalls(parent_count: u64, count: u64) -> bool {
    parent_count > 0
        && u128::from(count) * STALL_RATIO.1 >= u128::from(parent_count) * STALL_RATIO.0
}

/// Micropolygon side length in pixels at `shading_rate` pixels per micropolygon.
pub(super) fn step(shading_rate: f32) -> f32 {
    shading_rate.max(1e-6).sqrt()
}
