//! The rules of the `hider` section, in field order (the method first, since it ties the
//! hider to the scene's solids).
//!
//! Invariant: reports at `hider.<field>` paths, as the source map spells them.

use super::primitives::{Check, Interval, UNIT, fail, int_in, non_negative, positive, within};
use crate::filter::{self, FilterProblem};
use crate::model::{Hider, HiderMethod, Scene};

/// Both full widths of the filter (x and y), in pixels.
const FILTER_WIDTH: Interval = Interval::open_closed(0.0, 16.0);

pub(super) fn hider(h: &Hider, scene: &Scene) -> Check {
    if h.method == HiderMethod::RayTrace && !scene.solids.is_empty() {
        return fail(
            "hider.method",
            "the ray-tracing hider does not evaluate CSG solids; use method: Stochastic",
        );
    }
    int_in("hider.pixel_samples[0]", h.pixel_samples.0, 1, 64)?;
    int_in("hider.pixel_samples[1]", h.pixel_samples.1, 1, 64)?;
    within("hider.filter.width", h.filter.width, FILTER_WIDTH, " pixels")?;
    if let Some(height) = h.filter.height {
        within("hider.filter.height", height, FILTER_WIDTH, " pixels")?;
    }
    filter_table(h)?;
    int_in("hider.bucket_size[0]", h.bucket_size.0, 1, 1024)?;
    int_in("hider.bucket_size[1]", h.bucket_size.1, 1, 1024)?;
    positive("hider.shading_rate", h.shading_rate)?;
    int_in("hider.adaptive.max_level", h.adaptive.max_level, 0, 4)?;
    non_negative("hider.adaptive.threshold", h.adaptive.threshold)?;
    if h.adaptive.max_level > 0 && h.method == HiderMethod::RayTrace {
        return fail(
            "hider.adaptive.max_level",
            "adaptive sampling is the stochastic hider's; use method: Stochastic or max_level: 0",
        );
    }
    if h.max_grid_size < 1 {
        return fail("hider.max_grid_size", format!("must be >= 1, got {}", h.max_grid_size));
    }
    non_negative("hider.flatness", h.flatness)?;
    within("hider.relative_flatness", h.relative_flatness, UNIT, "")?;
    non_negative("hider.motion_factor", h.motion_factor)?;
    non_negative("hider.focus_factor", h.focus_factor)?;
    Ok(())
}

/// The film's filter table over the hider's sample strata can be built: the very sum the film
/// divides by ([`filter::check`]) is finite and positive. A filter narrower than the strata are
/// apart (a 0.1 pixel Gaussian on 2x2 samples) weighs no stratum centre at all.
fn filter_table(h: &Hider) -> Check {
    let (nx, ny) = h.pixel_samples;
    match filter::check(h) {
        Ok(()) => Ok(()),
        Err(FilterProblem::Sum(0.0)) => fail(
            "hider.filter",
            format!(
                "the filter is zero at every centre of the {nx}x{ny} sample strata, so its \
                 weights sum to 0: make it wider or change pixel_samples"
            ),
        ),
        Err(FilterProblem::Sum(sum)) => fail(
            "hider.filter",
            format!(
                "the filter's weights on the {nx}x{ny} sample strata sum to {sum:?}, not to a \
                 positive number: make it wider or change pixel_samples"
            ),
        ),
        Err(problem) => fail("hider.filter", format!("the filter has no table: {problem}")),
    }
}
