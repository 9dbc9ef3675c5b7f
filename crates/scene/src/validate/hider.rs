//! The rules of the `hider` section, in field order (the method first, since it ties the
//! hider to the scene's solids).
//!
//! Invariant: reports at `hider.<field>` paths, as the source map spells them.

use super::primitives::{Check, Interval, fail, int_in, positive, within};
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
    int_in("hider.bucket_size[0]", h.bucket_size.0, 1, 1024)?;
    int_in("hider.bucket_size[1]", h.bucket_size.1, 1, 1024)?;
    positive("hider.shading_rate", h.shading_rate)?;
    if h.max_grid_size < 1 {
        return fail("hider.max_grid_size", format!("must be >= 1, got {}", h.max_grid_size));
    }
    Ok(())
}
