//! Moving area lights (Appendix B's moving lights): keys in scene time, normalised over the
//! shutter, offset and intensity interpolated; a moving light's shadow is its time average.
//!
//! A small ball light (radius 0.01) at height H = 4 moves along x from -2 to +2 while its
//! intensity goes from 1 to 3, keys at the shutter's ends (scene times 10 and 12). The
//! floor point at the origin receives `E(t) = I(t) cos / d^2 = I(t) H / d^3` with
//! `d^2 = x(t)^2 + H^2`. An opaque half-plane x < 0 at height 2 hides the light exactly
//! while x(t) < 0, i.e. for the first half of the shutter.

use glam::Vec3;
use reyes_sampling::Strata;
use reyes_shade::Shading;

use crate::common::{floor_point, patch, scene_with_shutter, simpson, tracer, white_floor};

const H: f64 = 4.0;

fn setup(occluder: bool, keys: &str) -> reyes_scene::Scene {
    let floor = white_floor(20.0);
    let wall = patch(
        Vec3::new(-30.0, 2.0, -30.0),
        Vec3::new(30.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 60.0),
        "material: Matte(color: (1.0, 1.0, 1.0))",
    );
    scene_with_shutter(
        &format!(
            "lights: [Area(shape: Sphere(center: (0.0, {H:?}, 0.0), radius: 0.01), motion: [{keys}])], \
         objects: [{floor}{}]",
            if occluder { format!(", {wall}") } else { String::new() }
        ),
        10.0,
        12.0,
    )
}

const KEYS: &str = "(time: 10.0, offset: (-2.0, 0.0, 0.0), intensity: 1.0), \
                    (time: 12.0, offset: (2.0, 0.0, 0.0), intensity: 3.0)";

fn irradiance(t: f64) -> f64 {
    let x = -2.0 + 4.0 * t;
    let i = 1.0 + 2.0 * t;
    i * H / (x * x + H * H).powf(1.5)
}

#[test]
fn light_moves_and_dims_with_normalised_time() {
    let s = setup(false, KEYS);
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    for time in [0.0f32, 0.25, 0.5, 0.9, 1.0] {
        let at = floor_point(0, 0.0, 0.0, time);
        let got = f64::from(shading.shade_surface(&at, &mut Strata::new(0, 0, 0, 1)).0[0]);
        let want = irradiance(f64::from(time));
        // One light point, anywhere on a disk of radius rho = 0.01 through the light's
        // centre: E = I y / d^3 (y the point's height) changes by at most
        // rho / H + 3 rho / d <= 0.01 / 4 + 0.03 / 4 = 1% relative.
        assert!((got - want).abs() <= 0.01 * want, "time {time}: {got} vs {want}");
    }
    // Keys inside the shutter are held outside them: keys at scene times 10.5 and 11.5
    // (normalised 0.25 and 0.75) give the first key's light at normalised time 0.1.
    let s = setup(
        false,
        "(time: 10.5, offset: (-2.0, 0.0, 0.0), intensity: 1.0), \
         (time: 11.5, offset: (2.0, 0.0, 0.0), intensity: 3.0)",
    );
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    let got = f64::from(
        shading.shade_surface(&floor_point(0, 0.0, 0.0, 0.1), &mut Strata::new(0, 0, 0, 1)).0[0],
    );
    assert!((got - irradiance(0.0)).abs() <= 0.01 * got, "held: {got}");
}

#[test]
fn moving_lights_shadow_is_the_time_average() {
    let s = setup(true, KEYS);
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    // N stratified shading times (i + 1/2) / N, as a hider's time strata would give; the
    // integrand is smooth except for the jump at t = 1/2, which falls on a stratum
    // boundary (N even), so the midpoint rule's error is O(1/N^2) ~ 1e-5 relative here.
    let n = 256;
    let mut sum = 0.0;
    for i in 0..n {
        let time = (i as f32 + 0.5) / n as f32;
        let mut strata = Strata::new(1, 2, i, n);
        sum += f64::from(shading.shade_surface(&floor_point(0, 0.0, 0.0, time), &mut strata).0[0]);
    }
    let got = sum / f64::from(n);
    let want = simpson(irradiance, 0.5, 1.0, 1000);
    let all = simpson(irradiance, 0.0, 1.0, 1000);
    eprintln!("moving light: time-averaged {got:.6}, expected {want:.6} (unshadowed {all:.6})");
    // The light's radius 0.01 makes a penumbra only while |x| < 0.01, 0.25% of the shutter
    // (one or two of the 256 strata, each worth under 1/256 of the mean): allow 1%.
    assert!((got - want).abs() <= 0.01 * want, "{got} vs {want}");
}
