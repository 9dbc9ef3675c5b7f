//! Settings of the distributed ray tracing: [`RayTrace`].
//!
//! Invariant: `Default` is what an absent `raytrace` section (or field) gives.

use serde::{Deserialize, Serialize};

/// Distributed ray tracing (patent FIGS. 19-22, Appendix B): limits and cost.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RayTrace {
    /// Deepest chain of secondary rays (reflection and refraction bounces) followed from a
    /// shaded point; at least 1 when any object reflects or refracts.
    pub max_depth: u32,
    /// A secondary ray whose weight (the product of the reflection or transmission colours
    /// along its path, largest channel) falls below this is not traced.
    pub min_weight: f32,
    /// Rays per effect (each shadowing light, glossy reflection, refraction) per grid
    /// vertex when the stochastic hider shades vertices (>= 1).
    pub vertex_rays: u32,
}

impl Default for RayTrace {
    fn default() -> Self {
        RayTrace { max_depth: 4, min_weight: 0.01, vertex_rays: 1 }
    }
}
