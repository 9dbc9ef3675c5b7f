//! Recursion limits: `max_depth` stops the bounces, `min_weight` prunes faint paths.

use glam::Vec3;
use reyes_sampling::Strata;
use reyes_shade::{RayCounts, Shading};
use reyes_trace::Ray;

use crate::common::{patch, scene, tracer};

/// Two facing mirrors at z = 0 and z = 1, each glowing 0.1 and reflecting half; a ray
/// from between them along +z. Bounce k adds 0.1 * 0.5^k.
fn corridor(max_depth: u32, min_weight: f32) -> (f32, RayCounts) {
    let mirror = |z: f32| {
        patch(
            Vec3::new(-10.0, -10.0, z),
            Vec3::new(20.0, 0.0, 0.0),
            Vec3::new(0.0, 20.0, 0.0),
            "material: Constant(color: (0.1, 0.1, 0.1)), reflect: Some((color: (0.5, 0.5, 0.5)))",
        )
    };
    let mut s = scene(&format!("objects: [{}, {}]", mirror(0.0), mirror(1.0)));
    // Set after parsing: validation requires max_depth >= 1 with reflecting objects.
    s.raytrace.max_depth = max_depth;
    s.raytrace.min_weight = min_weight;
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    let mut counts = RayCounts::default();
    let ray = Ray::new(Vec3::new(0.0, 0.0, 0.5), Vec3::Z, 0.0);
    let got = shading.trace_counted(&ray, f32::INFINITY, &mut Strata::new(0, 0, 0, 1), &mut counts);
    (got.rgba[0], counts)
}

fn series(terms: u32) -> f32 {
    (0..terms).map(|k| 0.1 * 0.5f32.powi(k as i32)).sum()
}

#[test]
fn max_depth_stops_the_bounces() {
    for depth in [0, 1, 2, 5, 12] {
        let (got, counts) = corridor(depth, 0.0);
        let want = series(depth + 1);
        assert!((got - want).abs() < 1e-6, "max_depth {depth}: {got} vs {want}");
        assert_eq!(counts.reflection, u64::from(depth), "one reflected ray per bounce");
    }
}

#[test]
fn min_weight_prunes_faint_paths() {
    // Path weights 0.5, 0.25, 0.125: with min_weight 0.2 the third bounce is not traced.
    let (got, counts) = corridor(12, 0.2);
    assert!((got - series(3)).abs() < 1e-6, "{got}");
    assert_eq!(counts.reflection, 2);
    // Exactly at the threshold the ray is traced.
    let (got, _) = corridor(12, 0.25);
    assert!((got - series(3)).abs() < 1e-6, "{got}");
}
