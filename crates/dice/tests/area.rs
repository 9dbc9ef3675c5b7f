//! Dicing accuracy: projected areas of diced surfaces and micropolygon sizes.

mod common;

use common::*;
use reyes_dice::CameraSetup;
use reyes_scene::{Shape, Transform};

/// A 2x2 square at depth 5 facing the camera, covers 304.5 px on a side at fov 35, 640x480.
fn square_scene(shading_rate: f32, offset: [f32; 2]) -> reyes_scene::Scene {
    let [ox, oy] = offset;
    let pts = [
        [ox - 1.0, oy - 1.0, 5.0],
        [ox + 1.0, oy - 1.0, 5.0],
        [ox - 1.0, oy + 1.0, 5.0],
        [ox + 1.0, oy + 1.0, 5.0],
    ];
    let mut s =
        scene_ahead(640, 480, 35.0, vec![object(Shape::BilinearPatch { points: pts }, vec![])]);
    s.hider.shading_rate = shading_rate;
    s
}

#[test]
fn front_facing_square_area_matches_its_projection() {
    for (rate, offset) in [(1.0, [0.0, 0.0]), (0.5, [0.3, -0.2]), (4.0, [-0.5, 0.4])] {
        let s = square_scene(rate, offset);
        let (d, _) = dice(&s);
        let k = f64::from(CameraSetup::new(&s).pixels_per_unit());
        let side = 2.0 * k / 5.0;
        let expect = side * side;
        let total: f64 = d.mpolys.iter().map(|m| signed_area(m).abs()).sum();
        let err = (total - expect).abs() / expect;
        assert!(err < 0.005, "rate {rate}: area {total} vs {expect} ({:.3}%)", 100.0 * err);
        assert_eq!(d.stats.culled, 0, "all of the square is on screen");
    }
}

#[test]
fn micropolygon_size_follows_the_shading_rate() {
    for rate in [0.25_f32, 1.0, 4.0, 16.0] {
        let s = square_scene(rate, [0.0, 0.0]);
        let (d, _) = dice(&s);
        let total: f64 = d.mpolys.iter().map(|m| signed_area(m).abs()).sum();
        let mean = total / d.mpolys.len() as f64;
        let rate = f64::from(rate);
        assert!(mean > rate / 2.0 && mean < rate * 2.0, "rate {rate}: mean area {mean}");
        // Grids stay within max_grid_size.
        assert!(d.stats.micropolygons <= d.stats.grids * u64::from(s.hider.max_grid_size));
    }
}

/// Analytic area of the perspective projection of a sphere of radius `r` centred on the
/// view axis at distance `d`: a disk of radius `k * r / sqrt(d^2 - r^2)`.
fn sphere_disk_area(k: f64, r: f64, d: f64) -> f64 {
    let radius = k * r / (d * d - r * r).sqrt();
    std::f64::consts::PI * radius * radius
}

#[test]
fn sphere_projected_area_matches_the_analytic_disk() {
    // Poles along the view axis, and poles up/down.
    let orientations = [vec![], vec![Transform::Rotate { angle: 90.0, axis: [1.0, 0.0, 0.0] }]];
    for rotate in orientations {
        let mut transform = rotate.clone();
        transform.push(Transform::Translate([0.0, 0.0, 10.0]));
        let s = scene_ahead(640, 480, 35.0, vec![object(sphere(1.0), transform)]);
        let (d, _) = dice(&s);
        let k = f64::from(CameraSetup::new(&s).pixels_per_unit());
        let expect = sphere_disk_area(k, 1.0, 10.0);
        // The front half covers the disk with one orientation, the back half with the other.
        let positive: f64 = d.mpolys.iter().map(signed_area).filter(|a| *a > 0.0).sum();
        let negative: f64 = -d.mpolys.iter().map(signed_area).filter(|a| *a < 0.0).sum::<f64>();
        for (name, area) in [("positive", positive), ("negative", negative)] {
            let err = (area - expect).abs() / expect;
            assert!(err < 0.02, "{rotate:?} {name}: {area} vs {expect} ({:.3}%)", 100.0 * err);
        }
    }
}

#[test]
fn transforms_place_the_object() {
    // Scale, move to x = -4, rotate 90 degrees about y (glam: -x -> +z), then translate:
    // the unit sphere scaled to radius 0.5 lands centred at (2, 1, 12).
    let transform = vec![
        Transform::Scale([0.5, 0.5, 0.5]),
        Transform::Translate([-4.0, 0.0, 0.0]),
        Transform::Rotate { angle: 90.0, axis: [0.0, 1.0, 0.0] },
        Transform::Translate([2.0, 1.0, 8.0]),
    ];
    let s = scene_ahead(320, 240, 45.0, vec![object(sphere(1.0), transform)]);
    let (d, _) = dice(&s);
    let cam = CameraSetup::new(&s);
    let centre = cam.eye_to_raster(glam::Vec3::new(2.0, 1.0, 12.0));
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for mp in &d.mpolys {
        let (l, h) = mp.bound();
        for a in 0..3 {
            lo[a] = lo[a].min(l[a]);
            hi[a] = hi[a].max(h[a]);
        }
    }
    let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    assert!(
        (mid[0] - centre.x).abs() < 0.2 && (mid[1] - centre.y).abs() < 0.2,
        "{mid:?} vs {centre}"
    );
    // Depth range of the sphere: 12 -+ 0.5 (the centre is nearly on the view axis).
    assert!(lo[2] > 11.4 && lo[2] < 11.6 && hi[2] > 12.4 && hi[2] < 12.6, "{lo:?} {hi:?}");
}
