//! RenderMan's standard `spotlight` (RenderMan Interface Specification 3.2, Appendix A), set
//! up once and evaluated at shaded points; shared by the dicer's local illumination and the
//! ray-traced shading (reyes-shade), so both paths light a point bit for bit alike.
//!
//! Invariants: the axis is unit; angles are stored as cosines; the light arriving is finite
//! and non-negative for finite input, and nothing arrives outside the cone, at the light's
//! own position or where the fall-off is zero.

use glam::Vec3;
use reyes_scene::Light;

/// `d^2` below which a light is taken to sit on the shaded point and is ignored (the rule of
/// point lights).
const MIN_DIST2: f32 = 1e-20;

/// A spot light after setup: the Specification's
///
/// ```text
/// light spotlight(intensity, lightcolor, from, to, coneangle, conedeltaangle, beamdistribution)
///   A = (to - from) / length(to - from);
///   illuminate(from, A, coneangle) {
///     cosangle = L.A / length(L);
///     atten = pow(cosangle, beamdistribution) / (L.L);
///     atten *= smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle);
///     Cl = atten * intensity * lightcolor;
///   }
/// ```
///
/// with `L` from the light to the shaded point and the angles given in degrees. Beyond 90
/// degrees a cone reaches points behind the light (`cosangle < 0`), where `pow` of a negative
/// number is not defined for a general exponent; there `cosangle` is taken as 0 (so such
/// points get nothing unless `beamdistribution` is 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotLight {
    from: Vec3,
    /// Unit axis `A`, from `from` toward `to`.
    axis: Vec3,
    /// `intensity * color`.
    cl: Vec3,
    /// `cos(cone_angle)`: the edge of the cone.
    cos_outer: f32,
    /// `cos(cone_angle - cone_delta)`: the inner edge of the penumbra.
    cos_inner: f32,
    beam: f32,
}

impl SpotLight {
    /// The spot light at `from` aimed at `to` (angles in degrees), or `None` when
    /// `from == to` (no axis: it lights nothing).
    pub fn new(
        from: [f32; 3],
        to: [f32; 3],
        color: [f32; 3],
        intensity: f32,
        cone_angle: f32,
        cone_delta: f32,
        beam_distribution: f32,
    ) -> Option<SpotLight> {
        let from = Vec3::from(from);
        let axis = (Vec3::from(to) - from).try_normalize()?;
        Some(SpotLight {
            from,
            axis,
            cl: intensity * Vec3::from(color),
            cos_outer: cone_angle.to_radians().cos(),
            cos_inner: (cone_angle - cone_delta).to_radians().cos(),
            beam: beam_distribution,
        })
    }

    /// The spot light of a scene's `Light::Spot`, or `None` for any other light and for a
    /// spot light without an axis.
    pub fn of(light: &Light) -> Option<SpotLight> {
        let Light::Spot {
            from,
            to,
            color,
            intensity,
            cone_angle,
            cone_delta,
            beam_distribution,
            ..
        } = *light
        else {
            return None;
        };
        SpotLight::new(from, to, color, intensity, cone_angle, cone_delta, beam_distribution)
    }

    /// The light's position.
    pub fn from(&self) -> Vec3 {
        self.from
    }

    /// The unit vector from `p` toward the light and the colour `Cl` arriving at `p`, or
    /// `None` when nothing arrives (outside the cone, zero fall-off, or `p` at the light).
    #[inline]
    pub fn arriving(&self, p: Vec3) -> Option<(Vec3, Vec3)> {
        let d = self.from - p;
        let d2 = d.length_squared();
        if !d2.is_finite() || d2 <= MIN_DIST2 {
            return None;
        }
        let l = d / d2.sqrt();
        // L = p - from = -d, so L.A / |L| = -l.A.
        let cos_angle = -l.dot(self.axis);
        // illuminate(from, A, coneangle): only points inside the cone.
        if cos_angle.is_nan() || cos_angle < self.cos_outer {
            return None;
        }
        let atten = cos_angle.max(0.0).powf(self.beam) / d2
            * smoothstep(self.cos_outer, self.cos_inner, cos_angle);
        (atten > 0.0).then(|| (l, self.cl * atten))
    }
}

/// The Shading Language's `smoothstep(min, max, x)`: 0 below `min`, 1 from `max` on, and the
/// Hermite cubic `t^2 (3 - 2 t)`, `t = (x - min) / (max - min)`, in between (a step at
/// `min` when `min == max`).
#[inline]
pub fn smoothstep(min: f32, max: f32, x: f32) -> f32 {
    if x < min {
        0.0
    } else if x >= max {
        1.0
    } else {
        let t = (x - min) / (max - min);
        t * t * (3.0 - 2.0 * t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form in f64, from the Specification's formula, for a white light of
    /// `intensity` at the origin aimed down +z.
    fn closed_form(intensity: f64, beam: f64, cone: f64, delta: f64, p: [f64; 3]) -> f64 {
        let len = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        let cos_angle = p[2] / len;
        let (e0, e1) = (cone.to_radians().cos(), (cone - delta).to_radians().cos());
        if cos_angle < e0 {
            return 0.0;
        }
        let s = reyes_testkit::shading::smoothstep(e0, e1, cos_angle);
        intensity * cos_angle.powf(beam) / (len * len) * s
    }

    #[test]
    fn falloff_across_the_penumbra_is_the_specifications() {
        let (cone, delta, beam, intensity) = (30.0f32, 5.0f32, 2.0f32, 7.0f32);
        let spot = SpotLight::new(
            [0.0; 3],
            [0.0, 0.0, 3.0],
            [1.0, 0.5, 0.25],
            intensity,
            cone,
            delta,
            beam,
        )
        .expect("aimed");
        // Points at distance 4 at angles from the axis to past the cone's edge.
        for k in 0..=400 {
            let angle = f64::from(k) * 0.1; // 0 .. 40 degrees
            let (s, c) = angle.to_radians().sin_cos();
            let p = [4.0 * s, 0.0, 4.0 * c];
            let want = closed_form(7.0, 2.0, 30.0, 5.0, p);
            let got = spot.arriving(Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32));
            match got {
                None => assert!(want < 1e-6, "angle {angle}: nothing arrives, want {want}"),
                Some((l, cl)) => {
                    let tol = 2e-5 * want + 1e-6;
                    assert!((f64::from(cl.x) - want).abs() <= tol, "angle {angle}: {cl} vs {want}");
                    assert!((f64::from(cl.y) - 0.5 * want).abs() <= tol, "colour scales: {cl}");
                    let to_light = -Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32).normalize();
                    assert!((l - to_light).length() < 1e-6, "{l} toward the light");
                }
            }
        }
        // Inside the inner cone the penumbra factor is 1: inverse square times cos^beam.
        let (_, cl) = spot.arriving(Vec3::new(0.0, 0.0, 2.0)).expect("on the axis");
        assert!((cl.x - 7.0 / 4.0).abs() < 1e-6, "{cl}");
        // Half-way across the penumbra (in cosine) smoothstep is exactly 1/2.
        let mid = 0.5 * (30f32.to_radians().cos() + 25f32.to_radians().cos());
        let p = Vec3::new((1.0 - mid * mid).sqrt(), 0.0, mid);
        let (_, cl) = spot.arriving(p).expect("in the penumbra");
        assert!((cl.x - 7.0 * mid * mid * 0.5).abs() < 1e-5, "{cl} at the penumbra's middle");
    }

    #[test]
    fn edges_and_degenerate_cases() {
        // No axis: no light.
        assert!(SpotLight::new([1.0; 3], [1.0; 3], [1.0; 3], 1.0, 30.0, 5.0, 2.0).is_none());
        // A hard edge (no penumbra) is a step at the cone's edge.
        let hard = SpotLight::new([0.0; 3], [0.0, 0.0, 1.0], [1.0; 3], 1.0, 45.0, 0.0, 0.0)
            .expect("aimed");
        assert!(hard.arriving(Vec3::new(0.99, 0.0, 1.0)).is_some());
        assert!(hard.arriving(Vec3::new(1.01, 0.0, 1.0)).is_none());
        // At the light itself and behind a narrow cone: nothing, never NaN.
        assert!(hard.arriving(Vec3::ZERO).is_none());
        assert!(hard.arriving(Vec3::new(0.0, 0.0, -1.0)).is_none());
        // A cone of 180 degrees reaches behind the light; a positive beam exponent gives those
        // points nothing (cosangle taken as 0), a zero one lights them by distance alone.
        let wide = SpotLight::new([0.0; 3], [0.0, 0.0, 1.0], [1.0; 3], 1.0, 180.0, 0.0, 1.5)
            .expect("aimed");
        assert!(wide.arriving(Vec3::new(0.0, 1.0, -1.0)).is_none());
        let flat = SpotLight::new([0.0; 3], [0.0, 0.0, 1.0], [1.0; 3], 1.0, 180.0, 0.0, 0.0)
            .expect("aimed");
        let (_, cl) = flat.arriving(Vec3::new(0.0, 0.0, -2.0)).expect("behind, lit");
        assert!((cl.x - 0.25).abs() < 1e-6, "{cl}");
        assert_eq!(smoothstep(0.5, 0.5, 0.5), 1.0);
        assert_eq!(smoothstep(0.5, 0.5, 0.49), 0.0);
        assert_eq!(smoothstep(0.0, 1.0, 0.5), 0.5);
    }
}
