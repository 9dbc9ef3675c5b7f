//! Arbitrary output variables at each sample: what the visible points of a sample give
//! besides the beauty (stage: hider, after `CSGResolve`; docs/outputs.md).
//!
//! Two ways of taking a value from a sample's visible points:
//! - **composited** ([`AovValue::Color`], [`AovValue::Opacity`], [`AovValue::Shaded`]): the
//!   points' values are composited front to back with exactly the weights the beauty used
//!   (the resolution is traced, [`reyes_csg::Trace`], and replayed), so `Ci` is the beauty bit
//!   for bit and shading components that add up to each point's colour add up to the beauty;
//! - **front** ([`AovValue::Depth`], [`AovValue::Velocity`], [`AovValue::Vertex`]): the value
//!   of the front-most visible point at the sample, opaque or not, interpolated at the sample
//!   with the Shepard weights of `lerpz` (or vertex 0's, for ids); a sample with no visible
//!   point takes the plan's background value.
//!
//! Invariant: with no plan the hider does exactly what it did without AOVs; with one, the
//! beauty is unchanged bit for bit (the traced resolution computes the same composite).

use reyes_csg::{LERP_DONE, Trace, VisPoint, lerpz, shepard_weights};

use crate::mpoly::{Micropolygon, flags};

/// One value the plan takes from each sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AovValue {
    /// The premultiplied colour, composited as the beauty (3 floats).
    Color,
    /// The opacity `1 - trans`, composited (3 floats; the glass hack does not tint it, as it
    /// does not tint alpha).
    Opacity,
    /// 3 floats of the per-vertex data at `offset`, premultiplied colour-like values
    /// (shading components), interpolated like the colour (Gouraud or vertex 0) and
    /// composited.
    Shaded {
        /// Offset in the per-vertex data.
        offset: usize,
    },
    /// Exact eye depth of the front point (1 float).
    Depth,
    /// Halfway between the front point's depth and the nearest depth of a point behind it
    /// at the sample, infinite where there is none ([`midpoint_depth`]; 1 float).
    MidDepth,
    /// Raster motion of the front point over the shutter, pixels per shutter interval, from
    /// its micropolygon's `speed` over its segment (2 floats).
    Velocity,
    /// `len` floats of the per-vertex data at `offset`, of the front point.
    Vertex {
        /// Offset in the per-vertex data.
        offset: usize,
        /// Floats.
        len: usize,
        /// Shepard-interpolate at the sample (else vertex 0's value, exact for ids).
        interpolate: bool,
    },
}

impl AovValue {
    /// Floats per sample.
    pub fn len(self) -> usize {
        match self {
            AovValue::Color | AovValue::Opacity | AovValue::Shaded { .. } => 3,
            AovValue::Depth | AovValue::MidDepth => 1,
            AovValue::Velocity => 2,
            AovValue::Vertex { len, .. } => len,
        }
    }

    /// True if no floats (never, but clippy asks with `len`).
    pub fn is_empty(self) -> bool {
        self.len() == 0
    }
}

/// What to take from each sample: the values, in order, and the per-vertex data's stride.
#[derive(Debug, Clone, PartialEq)]
pub struct AovPlan {
    /// Floats per micropolygon vertex in the data handed with the micropolygons.
    pub stride: usize,
    /// The values, concatenated per sample in this order.
    pub values: Vec<AovValue>,
    /// Per value, what a sample with no visible point gives (all its floats).
    pub background: Vec<f32>,
}

impl AovPlan {
    /// Floats per sample.
    pub fn channels(&self) -> usize {
        self.values.iter().map(|v| v.len()).sum()
    }
}

/// One compositing step of a sample ([`Trace`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Step {
    Add { point: u32, weight: [f32; 3], holdout: bool },
    Scale([f32; 3]),
    Zero,
}

/// The steps of one sample.
#[derive(Debug, Default, Clone)]
pub(crate) struct Steps(pub Vec<Step>);

impl Trace for Steps {
    #[inline]
    fn add(&mut self, point: u32, weight: [f32; 3], holdout: bool) {
        self.0.push(Step::Add { point, weight, holdout });
    }
    #[inline]
    fn scale(&mut self, factor: [f32; 3]) {
        self.0.push(Step::Scale(factor));
    }
    #[inline]
    fn zero(&mut self) {
        self.0.push(Step::Zero);
    }
}

/// What a sample's values are read from.
pub(crate) struct Sources<'a> {
    pub points: &'a [VisPoint],
    /// Micropolygon (index into `mpolys`) of each point.
    pub point_mp: &'a [u32],
    pub mpolys: &'a [Micropolygon],
    /// Per-vertex data, `4 * stride` floats per micropolygon.
    pub data: &'a [f32],
}

impl Sources<'_> {
    /// `len` floats at `offset` of point `point`'s vertex data, weighted by `w`.
    fn vertex(&self, plan: &AovPlan, point: u32, offset: usize, w: [f32; 4], out: &mut [f32]) {
        let m = self.point_mp[point as usize] as usize;
        let base = m * 4 * plan.stride + offset;
        out.fill(0.0);
        let len = out.len();
        for (k, wk) in w.iter().enumerate() {
            if *wk == 0.0 {
                continue;
            }
            let at = base + k * plan.stride;
            for (o, d) in out.iter_mut().zip(&self.data[at..at + len]) {
                *o += wk * d;
            }
        }
    }

    /// Fill `out` (the plan's channels) for one sample from its `steps` (and `mid`, its
    /// [`midpoint_depth`] when the plan takes it), and return the front point's depth
    /// (`+inf` if none).
    pub(crate) fn sample(&self, plan: &AovPlan, steps: &[Step], mid: f32, out: &mut [f32]) -> f32 {
        let front = steps.iter().find_map(|s| match s {
            Step::Add { point, .. } => Some(*point),
            _ => None,
        });
        let depth = front.map_or(f32::INFINITY, |f| {
            let p = &self.points[f as usize];
            if p.flags & LERP_DONE != 0 { p.minz } else { lerpz(&p.v) }
        });
        // The front point's bilinear weights, solved once for all its geometric values.
        let mut bilinear: Option<[f32; 4]> = None;
        let mut geometric = |f: u32| -> [f32; 4] {
            *bilinear.get_or_insert_with(|| bilinear_weights(&self.points[f as usize].v))
        };
        let mut at = 0;
        let mut bg = 0;
        for value in &plan.values {
            let n = value.len();
            let o = &mut out[at..at + n];
            match (*value, front) {
                (AovValue::Color | AovValue::Opacity | AovValue::Shaded { .. }, _) => {
                    self.composite(plan, *value, steps, o);
                }
                (_, None) => o.copy_from_slice(&plan.background[bg..bg + n]),
                (AovValue::Depth, Some(_)) => o[0] = depth,
                (AovValue::MidDepth, Some(_)) => o[0] = mid,
                (AovValue::Velocity, Some(f)) => {
                    let mp = &self.mpolys[self.point_mp[f as usize] as usize];
                    let span = mp.time[1] - mp.time[0];
                    o.fill(0.0);
                    if mp.has(flags::MOVING) && span > 0.0 {
                        let w = geometric(f);
                        for (k, wk) in w.iter().enumerate() {
                            o[0] += wk * (mp.speed[k][0] / span);
                            o[1] += wk * (mp.speed[k][1] / span);
                        }
                    }
                }
                (AovValue::Vertex { offset, interpolate, .. }, Some(f)) => {
                    let w = if interpolate { geometric(f) } else { [1.0, 0.0, 0.0, 0.0] };
                    self.vertex(plan, f, offset, w, o);
                }
            }
            at += n;
            bg += n;
        }
        depth
    }

    /// Composite `value` over the steps, as `resolve_sample` composites the colour.
    fn composite(&self, plan: &AovPlan, value: AovValue, steps: &[Step], out: &mut [f32]) {
        let mut acc = [0.0f32; 3];
        let mut v = [0.0f32; 3];
        for step in steps {
            match *step {
                Step::Add { holdout: true, .. } => {}
                Step::Add { point, weight, holdout: false } => {
                    let p = &self.points[point as usize];
                    match value {
                        AovValue::Color => v = p.color,
                        AovValue::Opacity => v = p.trans.map(|t| 1.0 - t),
                        AovValue::Shaded { offset } => {
                            let mp = &self.mpolys[self.point_mp[point as usize] as usize];
                            // As the colour: Gouraud's Shepard weights, or vertex 0.
                            let w = if mp.has(flags::GOURAUD) {
                                shepard_weights(&p.v)
                            } else {
                                [1.0, 0.0, 0.0, 0.0]
                            };
                            self.vertex(plan, point, offset, w, &mut v);
                        }
                        _ => {}
                    }
                    for k in 0..3 {
                        acc[k] += weight[k] * v[k];
                    }
                }
                Step::Scale(f) => {
                    if value != AovValue::Opacity {
                        for k in 0..3 {
                            acc[k] *= f[k];
                        }
                    }
                }
                Step::Zero => acc = [0.0; 3],
            }
        }
        out.copy_from_slice(&acc);
    }
}

pub use reyes_csg::bilinear_weights;

/// The points of one sample's list (from `head`, linked by `next`) at least this fraction of
/// the front depth behind it are another surface: nearer ones are the same surface seen
/// twice (neighbouring micropolygons overlapping along a shared edge, by 4e-4 pixel).
const SAME_SURFACE: f32 = 1e-4;

/// RenderMan's `depthfilter "midpoint"` at one sample: halfway between the nearest point of
/// its visible-point list (from `head`) and the nearest point that is another surface
/// ([`SAME_SURFACE`]), infinite if there is none (nothing behind casts a shadow on).
pub(crate) fn midpoint_depth(points: &[VisPoint], head: u32) -> f32 {
    let depth = |p: &VisPoint| if p.flags & LERP_DONE != 0 { p.minz } else { lerpz(&p.v) };
    let list = || {
        std::iter::successors(Some(head).filter(|&h| h != reyes_csg::NIL), |&k| {
            Some(points[k as usize].next).filter(|&n| n != reyes_csg::NIL)
        })
        .map(|k| depth(&points[k as usize]))
    };
    let front = list().fold(f32::INFINITY, f32::min);
    let behind = front + SAME_SURFACE * front.abs();
    let second = list().filter(|&z| z > behind).fold(f32::INFINITY, f32::min);
    if second.is_finite() { 0.5 * (front + second) } else { f32::INFINITY }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_weights_invert_the_bilinear_map() {
        // A skewed, non-parallelogram quad; for (u, v) on a grid, move the quad so B(u, v)
        // is at the origin and recover the weights (to f32 rounding of values near 10).
        let q = [[0.0, 0.0], [10.0, 1.0], [12.0, 9.0], [-1.0, 7.0]];
        for i in 0..=10 {
            for j in 0..=10 {
                let (u, v) = (f64::from(i) / 10.0, f64::from(j) / 10.0);
                let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
                let at = |a: usize| (0..4).map(|k| w[k] * q[k][a]).sum::<f64>();
                let (x, y) = (at(0), at(1));
                let quad = q.map(|p| [(p[0] - x) as f32, (p[1] - y) as f32, 1.0]);
                let got = bilinear_weights(&quad);
                for k in 0..4 {
                    assert!((f64::from(got[k]) - w[k]).abs() < 1e-5, "({u},{v}): {got:?} vs {w:?}");
                }
            }
        }
    }
}
