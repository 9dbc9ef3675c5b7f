//! Cancelling a render ([`reyes_render::cancel`]). Its own test binary: the request is
//! process-wide and never cleared, so it must not reach the other render tests.

use std::sync::atomic::{AtomicUsize, Ordering};

use reyes_render::{RenderError, RenderOptions, cancel, render};
use reyes_testkit::fixtures::parse;

/// A 64x48 sphere in 16x16 buckets (4 x 3 buckets) with the given hider `method`, and
/// shadows (ray-traced vertex shading) when `shadows`.
fn scene(method: &str, shadows: bool) -> reyes_scene::Scene {
    let light = if shadows {
        "Distant(from: (0.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), intensity: 1.0, shadows: true)"
    } else {
        "Ambient(intensity: 1.0)"
    };
    parse(&format!(
        "Scene(
  image: (width: 64, height: 48),
  camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), fov: 40.0, hither: 0.1, yon: 100.0),
  hider: (method: {method}, pixel_samples: (2, 2), bucket_size: (16, 16)),
  lights: [{light}],
  objects: [(name: \"ball\", shape: Sphere(radius: 1.0), material: Matte(color: (1.0, 0.5, 0.2)))],
)"
    ))
}

/// One test, in order: a request made from the third bucket's callback stops the frame there
/// (one worker, so exactly three buckets finish); after that every render, of either hider,
/// is cancelled at its first bucket.
#[test]
fn a_cancel_request_stops_the_render_between_buckets() {
    let finished = AtomicUsize::new(0);
    let tick = || {
        if finished.fetch_add(1, Ordering::SeqCst) + 1 == 3 {
            cancel::request();
        }
    };
    let opts = RenderOptions { threads: Some(1), on_bucket: Some(&tick), ..Default::default() };
    let r = render(&scene("Stochastic", false), &opts);
    assert!(matches!(r, Err(RenderError::Cancelled)), "{:?}", r.err());
    assert_eq!(finished.load(Ordering::SeqCst), 3);
    assert!(cancel::requested());

    for (method, shadows) in [("Stochastic", false), ("Stochastic", true), ("RayTrace", false)] {
        finished.store(0, Ordering::SeqCst);
        let r = render(&scene(method, shadows), &opts);
        assert!(matches!(r, Err(RenderError::Cancelled)), "{method} {shadows}: {:?}", r.err());
        assert_eq!(finished.load(Ordering::SeqCst), 0, "{method} {shadows}");
    }
}
