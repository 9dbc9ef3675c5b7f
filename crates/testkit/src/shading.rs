//! Closed forms of the Shading Language in f64, the analytic truth of shading tests.
//!
//! Invariant: written from the RenderMan Interface Specification, never from the renderer's
//! own (f32) code, so that a test compares two independent computations.

/// The Shading Language's `smoothstep(min, max, x)` in f64: 0 below `min`, 1 from `max` on,
/// `t^2 (3 - 2 t)` with `t = (x - min) / (max - min)` in between.
pub fn smoothstep(min: f64, max: f64, x: f64) -> f64 {
    if x < min {
        0.0
    } else if x >= max {
        1.0
    } else {
        let t = (x - min) / (max - min);
        t * t * (3.0 - 2.0 * t)
    }
}
