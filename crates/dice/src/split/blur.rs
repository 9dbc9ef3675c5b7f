//! Motion- and focus-aware dicing, RenderMan's `GeometricApproximation "motionfactor"` and
//! `"focusfactor"`: a patch blurred over many pixels, by its motion over the shutter or by
//! the lens, is diced (and so shaded, at its vertices) at a coarser rate (docs/geometry.md).
//!
//! The rule: a patch whose blur is `B_m` pixels of motion and `B_f` pixels of defocus is
//! diced at the effective shading rate `shading_rate * (1 + (motion_factor * B_m +
//! focus_factor * B_f) / 16)`, so its micropolygon side grows by the square root of that
//! factor. With both factors 0 (the default) the factor is exactly 1 and every decision is
//! the shading rate's alone.
//!
//! Both blurs are measured on the decision's own test grids, and both are the least blur of
//! any point of the patch, so that no part of it is diced more coarsely than its own blur
//! allows: `B_m` is the shortest raster path of a test point through the breakpoints (the
//! raster displacement from one breakpoint to the next, summed: micropolygons move
//! linearly in raster between breakpoints), and `B_f` the diameter of the smallest circle
//! of confusion over the patch's depth range (0 when the range holds the focal plane). One
//! factor holds for all breakpoints, since the decision it scales is one for all of them.

use super::{GridFacts, Splitter, TEST_N};

/// The blur, in pixels, that one unit of a factor turns into one more shading rate: a
/// factor of 1 doubles the shading rate of a patch blurred over 16 pixels.
pub(crate) const BLUR_PIXELS: f32 = 16.0;

impl Splitter {
    /// The same decisions with motion- and focus-aware dicing: `motion` and `focus` are the
    /// factors on the patch's motion and defocus blur (>= 0; 0 is off), see the module doc.
    pub fn with_blur_factors(&self, motion: f32, focus: f32) -> Splitter {
        Splitter { motion_factor: motion, focus_factor: focus, ..self.clone() }
    }

    /// The factor on the micropolygon side length for a patch with the test grids of `facts`
    /// (one per breakpoint that counts, in time order): `sqrt(1 + (motion_factor * B_m +
    /// focus_factor * B_f) / 16)`, exactly 1 with both factors 0.
    pub(super) fn blur_step_scale(&self, facts: &[GridFacts<'_>]) -> f32 {
        if self.motion_factor <= 0.0 && self.focus_factor <= 0.0 {
            return 1.0;
        }
        let mut blur = 0.0_f32;
        if self.motion_factor > 0.0 {
            blur += self.motion_factor * self.motion_blur(facts);
        }
        if self.focus_factor > 0.0 {
            blur += self.focus_factor * self.focus_blur(facts);
        }
        let scale = (1.0 + blur / BLUR_PIXELS).sqrt();
        if scale.is_finite() && scale >= 1.0 { scale } else { 1.0 }
    }

    /// `B_m`: the shortest raster path, in pixels, of any test point through the breakpoints
    /// of `facts` (0 with one breakpoint, or when no point is in front of `near` at every
    /// breakpoint).
    pub(super) fn motion_blur(&self, facts: &[GridFacts<'_>]) -> f32 {
        if facts.len() < 2 {
            return 0.0;
        }
        let mut least = f32::INFINITY;
        for j in 0..TEST_N {
            for i in 0..TEST_N {
                let mut path = 0.0_f32;
                let mut last = None;
                let mut kept = true;
                for f in facts {
                    let p = f.grid[j][i];
                    if !(p.is_finite() && p.z >= self.near) {
                        kept = false;
                        break;
                    }
                    let r = self.camera.eye_to_raster(p);
                    if let Some(q) = last {
                        path += r.distance(q);
                    }
                    last = Some(r);
                }
                if kept {
                    least = least.min(path);
                }
            }
        }
        if least.is_finite() { least } else { 0.0 }
    }

    /// `B_f`: the diameter in pixels of the smallest circle of confusion over the depth range
    /// of `facts` (their test and hull points at every breakpoint, clamped to hither and
    /// yon), along the axis where it is smaller; 0 without a lens or when the range holds
    /// the focal plane. The lens moves a point at depth `z` by `l * coc(z)` for lens
    /// positions `|l| <= 1`, so the diameter is `2 |coc(z)|`, monotone in `1 / z` on each
    /// side of the focal plane: an end of the range holds the smallest.
    pub(super) fn focus_blur(&self, facts: &[GridFacts<'_>]) -> f32 {
        let Some(lens) = &self.lens else {
            return 0.0;
        };
        let zmin = facts.iter().map(|f| f.lo.z).fold(f32::INFINITY, f32::min);
        let zmax = facts.iter().map(|f| f.hi.z).fold(f32::NEG_INFINITY, f32::max);
        if !(zmin.is_finite() && zmax.is_finite()) {
            return 0.0;
        }
        let near = zmin.clamp(self.hither, self.yon);
        let far = zmax.clamp(near, self.yon);
        let (x1, y1) = lens.coc(near);
        let (x2, y2) = lens.coc(far);
        let least = |a: f32, b: f32| if a * b <= 0.0 { 0.0 } else { a.abs().min(b.abs()) };
        let diameter = 2.0 * least(x1, x2).min(least(y1, y2));
        if diameter.is_finite() { diameter } else { 0.0 }
    }
}
