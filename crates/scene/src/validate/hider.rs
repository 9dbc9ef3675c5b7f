//! The rules of the `hider` section, in field order (the method first, since it ties the
//! hider to the scene's solids).
//!
//! Invariant: reports at `hider.<field>` paths, as the source map spells them.

use super::primitives::{Check, fail, finite, int_in, positive};
use crate::model::{Hider, HiderMethod, Scene};

pub(super) fn hider(h: &Hider, scene: &Scene) -> Check {
    if h.method == HiderMethod::RayTrace && !scene.solids.is_empty() {
        return fail(
            "hider.method",
            "the ray-tracing hider does not evaluate CSG solids; use method: Stochastic",
        );
    }
    int_in("hider.pixel_samples[0]", h.pixel_samples.0, 1, 64)?;
    int_in("hider.pixel_samples[1]", h.pixel_samples.1, 1, 64)?;
    finite("hider.filter.width", h.filter.width)?;
    if !(h.filter.width > 0.0 && h.filter.width <= 16.0) {
        return fail(
            "hider.filter.width",
            format!("must be in (0, 16] pixels, got {}", h.filter.width),
        );
    }
    int_in("hider.bucket_size[0]", h.bucket_size.0, 1, 1024)?;
    int_in("hider.bucket_size[1]", h.bucket_size.1, 1, 1024)?;
    positive("hider.shading_rate", h.shading_rate)?;
    if h.max_grid_size < 1 {
        return fail("hider.max_grid_size", format!("must be >= 1, got {}", h.max_grid_size));
    }
    Ok(())
}
