//! The shutter's time density (patent FIGS. 13-16) and the warp that maps stratified uniform
//! numbers to sample times that follow it.
//!
//! Invariant: [`ShutterShape::warp`] is monotonic from [0, 1] onto [0, 1], so every time
//! stratum keeps equal probability; [`ShutterShape::density`] integrates to 1.

/// Time density of the shutter (patent FIGS. 13-16). Stratified uniform times `u` are
/// mapped through the inverse of the shape's cumulative distribution, so every time stratum
/// keeps equal probability and sample times follow the density.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ShutterShape {
    /// Uniform density on [0, 1): the shutter is fully open throughout (FIGS. 13-15).
    #[default]
    Uniform,
    /// Trapezoidal density (FIG. 16: overlapping intervals weighting the middle): rises
    /// linearly over `[0, r]`, is `1/(1-r)` on `[r, 1-r]`, falls linearly over `[1-r, 1]`.
    Gradual {
        /// Ramp fraction `r`, in (0, 0.5].
        ramp: f32,
    },
}

impl ShutterShape {
    /// Inverse cumulative distribution: the time whose CDF value is `u` in [0, 1].
    pub fn warp(&self, u: f32) -> f32 {
        match *self {
            ShutterShape::Uniform => u,
            ShutterShape::Gradual { ramp: r } => {
                let (u, r) = (u as f64, r as f64);
                let k = 2.0 * r * (1.0 - r);
                let u1 = r / (2.0 * (1.0 - r)); // CDF at t = r
                let t = if u < u1 {
                    (u * k).sqrt()
                } else if u > 1.0 - u1 {
                    1.0 - ((1.0 - u) * k).sqrt()
                } else {
                    r + (u - u1) * (1.0 - r)
                };
                (t as f32).clamp(0.0, 1.0)
            }
        }
    }

    /// Probability density at time `t` (for tests and documentation).
    pub fn density(&self, t: f32) -> f32 {
        match *self {
            ShutterShape::Uniform => 1.0,
            ShutterShape::Gradual { ramp: r } => {
                let edge = t.min(1.0 - t);
                if edge < r { edge / (r * (1.0 - r)) } else { 1.0 / (1.0 - r) }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_warp_is_monotonic_onto_the_shutter_and_follows_the_density() {
        for shape in [ShutterShape::Uniform, ShutterShape::Gradual { ramp: 0.25 }] {
            assert_eq!(shape.warp(0.0), 0.0);
            assert_eq!(shape.warp(1.0), 1.0);
            let n = 10_000;
            let mut last = 0.0;
            let mut integral = 0.0f64;
            for k in 1..=n {
                let u = k as f32 / n as f32;
                let t = shape.warp(u);
                assert!(t >= last, "{shape:?}: warp({u}) = {t} < {last}");
                // The CDF's increment over [last, t] is the density's integral there (1/n).
                integral += f64::from(shape.density(0.5 * (last + t))) * f64::from(t - last);
                last = t;
            }
            // Midpoint rule over steps of about 1/n: error of order 1/n.
            assert!((integral - 1.0).abs() < 1e-3, "{shape:?}: {integral}");
        }
    }
}
