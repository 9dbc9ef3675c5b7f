//! Every kind of light against shadow geometry: a point light's hard shadow, a rectangle
//! light's straight penumbra, a sphere light's round one.
//!
//! Setup as in `penumbra.rs`: the floor y = 0, an opaque occluder at height `HO = 5`, the
//! light at height `H = 10`; lit fractions are the floor's shading with the occluder over
//! its shading without, from the same strata.

use glam::Vec3;
use reyes_shade::Shading;

use crate::common::{floor_point, patch, scene, shade_mean, tracer};

const H: f32 = 10.0;
const HO: f32 = 5.0;

fn floor() -> String {
    patch(
        Vec3::new(-20.0, 0.0, -20.0),
        Vec3::new(40.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 40.0),
        "material: Matte(color: (1.0, 1.0, 1.0), ka: 0.0)",
    )
}

/// Lit fraction at floor point `(x, 0, z)` between scenes with and without `occluder`
/// under `light`, over `n` stratified members of one set.
fn fraction(light: &str, occluder: &str, x: f32, z: f32, n: u32) -> f32 {
    let with = scene(&format!("lights: [{light}], objects: [{}, {occluder}]", floor()));
    let without = scene(&format!("lights: [{light}], objects: [{}]", floor()));
    let (tw, to) = (tracer(&with), tracer(&without));
    let (sw, so) = (Shading::new(&with, &tw), Shading::new(&without, &to));
    let at = floor_point(0, x, z, 0.0);
    shade_mean(&sw, &at, n, 3).x / shade_mean(&so, &at, n, 3).x
}

fn disk_occluder(radius: f32) -> String {
    format!(
        "(shape: Disk(radius: {radius:?}), \
          transform: [Rotate(angle: 90.0, axis: (1.0, 0.0, 0.0)), Translate((0.0, {HO:?}, 0.0))], \
          material: Matte(color: (1.0, 1.0, 1.0)))"
    )
}

#[test]
fn a_point_light_casts_a_hard_shadow_of_the_projected_size() {
    // Similar triangles: the occluder's rim at radius 2 and height 5, seen from the light
    // at height 10, lands at radius 2 * 10 / (10 - 5) = 4. No penumbra: every floor point
    // is either fully lit or fully dark, whatever the strata.
    let light = format!("Point(from: (0.0, {H:?}, 0.0), intensity: 100.0, shadows: true)");
    let occ = disk_occluder(2.0);
    for r in [0.0, 2.0, 3.9, 3.99] {
        assert_eq!(fraction(&light, &occ, r, 0.0, 16), 0.0, "r {r} is in the shadow");
    }
    for r in [4.01, 4.1, 6.0] {
        assert_eq!(fraction(&light, &occ, r, 0.0, 16), 1.0, "r {r} is lit");
    }
    // Without `shadows` the same light shines through.
    let unshadowed = format!("Point(from: (0.0, {H:?}, 0.0), intensity: 100.0)");
    assert_eq!(fraction(&unshadowed, &occ, 0.0, 0.0, 16), 1.0);
}

#[test]
fn a_rectangle_light_gives_a_straight_penumbra_across_an_edge() {
    // A 2 x 2 square light centred on the axis and an occluding half-plane x < 0 at
    // height 5 (a large patch whose edge is the z axis). Across the edge, the penumbra on
    // the floor runs from x = -a h / (H - h) to +a h / (H - h) with a = 1 (the light's
    // half-width): -1 to 1. At x = 0 exactly half the light is hidden, and the weights
    // (cos cos / d^2) are symmetric about the edge's plane, so the fraction is 1/2.
    let light = format!(
        "Area(shape: Rectangle(corner: (-1.0, {H:?}, -1.0), edge_u: (2.0, 0.0, 0.0), \
              edge_v: (0.0, 0.0, 2.0)), intensity: 100.0)"
    );
    let occ = patch(
        Vec3::new(-30.0, HO, -30.0),
        Vec3::new(30.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 60.0),
        "material: Matte(color: (1.0, 1.0, 1.0))",
    );
    let n = 1024;
    for x in [-3.0, -1.5, -1.02] {
        assert_eq!(fraction(&light, &occ, x, 0.0, n), 0.0, "x {x} is in the umbra");
    }
    for x in [1.02, 1.5, 3.0] {
        assert!((fraction(&light, &occ, x, 0.0, n) - 1.0).abs() < 1e-6, "x {x} is lit");
    }
    // Tolerance: 32 x 32 strata, the edge's image a straight line across the light cuts
    // at most 2 x 32 strata, each adding variance <= 1/4 / n^2: sd <= sqrt(64 / 4) / 1024
    // = 0.004; four of them.
    let mid = fraction(&light, &occ, 0.0, 0.0, n);
    assert!((mid - 0.5).abs() < 0.016, "x 0: {mid}");
    let mut last = 0.0;
    for k in 0..=8 {
        let x = -1.0 + 2.0 * k as f32 / 8.0;
        let f = fraction(&light, &occ, x, 0.0, n);
        assert!(f >= last - 0.016, "the lit fraction grows across the penumbra: {f} at {x}");
        last = f;
    }
}

#[test]
fn a_sphere_light_casts_the_penumbra_of_its_silhouette() {
    // A ball light of radius 1 at height 10 over an occluding disk of radius 2: seen from
    // a floor point near the axis its silhouette is (nearly) a horizontal unit disk, so the
    // umbra and penumbra radii are those of the unit disk light: 3 and 5. Points off axis
    // see the silhouette tilted by at most atan(5 / 10), which moves the outer radius by
    // well under the 0.2 margins used here.
    let light =
        format!("Area(shape: Sphere(center: (0.0, {H:?}, 0.0), radius: 1.0), intensity: 100.0)");
    let occ = disk_occluder(2.0);
    for r in [0.0, 2.0, 2.8] {
        assert_eq!(fraction(&light, &occ, r, 0.0, 256), 0.0, "r {r} is in the umbra");
    }
    for r in [5.2, 6.0] {
        assert!((fraction(&light, &occ, r, 0.0, 256) - 1.0).abs() < 1e-6, "r {r} is lit");
    }
    let mid = fraction(&light, &occ, 4.0, 0.0, 1024);
    assert!((0.3..0.7).contains(&mid), "r 4, mid-penumbra: {mid}");
}
