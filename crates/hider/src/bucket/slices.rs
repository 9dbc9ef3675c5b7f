//! A bucket's samples rearranged for the paths that scan them slice by slice (stage: hider):
//! path D by lens slice, path M by time slice, each sample with the values those paths would
//! otherwise recompute per test. Invariant: the values are exactly the ones computed from
//! [`BucketSamples`], so the rearrangement changes no test's arithmetic.

use crate::LensSetup;
use crate::samples::BucketSamples;

/// One sample as paths D and M read it: position less the lens's depth-independent shift
/// (`x - lx * Dof_b`, or `x` for a pinhole), lens shift at depth 1 (`lx * Dof_a`), time and
/// list index `pixel*NS + s` — exactly the values the paths would compute from
/// [`BucketSamples`] per test, computed once per bucket instead.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SliceSample {
    pub(super) x: f32,
    pub(super) y: f32,
    pub(super) ax: f32,
    pub(super) ay: f32,
    pub(super) t: f32,
    pub(super) n: u32,
}

/// A bucket's samples by time slice (`by_time[pixel*NS + tau]`, path M) and by lens slice
/// (`by_lens[pixel*NS + lambda]`, path D), so the paths read a pixel's sample of a slice
/// directly instead of through `BucketSamples::by_time` / `by_lens`. Pixel-major, as
/// [`BucketSamples`]: a micropolygon's scan takes the slices in turn over the same few
/// pixels, so it reads each pixel's records in order. Reused from bucket to bucket (no
/// allocation once grown); each is built only when a bucket reads it.
#[derive(Debug, Default, Clone)]
pub(crate) struct SliceSamples {
    pub(super) by_time: Vec<SliceSample>,
    pub(super) by_lens: Vec<SliceSample>,
}

impl SliceSamples {
    pub(super) fn build(
        &mut self,
        smp: &BucketSamples,
        lens: Option<LensSetup>,
        (time, static_lens): (bool, bool),
        ns: usize,
        p_count: usize,
    ) {
        let record = |slice_order: &[u32], slice: usize, pixel: usize| {
            let k = pixel * ns + slice_order[pixel * ns + slice] as usize;
            let n = k as u32;
            let t = if time { smp.t[k] } else { 0.0 };
            match &lens {
                Some(l) => {
                    let (lx, ly) = (smp.lx[k], smp.ly[k]);
                    SliceSample {
                        x: smp.x[k] - lx * l.x_b,
                        y: smp.y[k] - ly * l.y_b,
                        ax: lx * l.x_a,
                        ay: ly * l.y_a,
                        t,
                        n,
                    }
                }
                None => SliceSample { x: smp.x[k], y: smp.y[k], ax: 0.0, ay: 0.0, t, n },
            }
        };
        self.by_time.clear();
        if time {
            for pixel in 0..p_count {
                for tau in 0..ns {
                    self.by_time.push(record(&smp.by_time, tau, pixel));
                }
            }
        }
        self.by_lens.clear();
        if static_lens && lens.is_some() {
            for pixel in 0..p_count {
                for lambda in 0..ns {
                    self.by_lens.push(record(&smp.by_lens, lambda, pixel));
                }
            }
        }
    }
}
