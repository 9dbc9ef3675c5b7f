//! The eye plane, hither and yon, and culling of geometry that cannot be seen.

mod common;

use common::*;
use reyes_dice::CameraSetup;
use reyes_hider::flags;
use reyes_scene::{Shape, Transform};

/// A wall in the plane x = 1 from z = -5 (behind the eye) to z = 20, y in [-1, 1], seen
/// with a wide lens and hither = 1 so that the hither cut is on screen.
fn wall_scene() -> reyes_scene::Scene {
    let pts = [[1.0, -1.0, -5.0], [1.0, -1.0, 20.0], [1.0, 1.0, -5.0], [1.0, 1.0, 20.0]];
    let mut cam = camera_ahead(120.0, None);
    cam.hither = 1.0;
    cam.yon = 15.0;
    scene(320, 240, cam, vec![object(Shape::BilinearPatch { points: pts }, vec![])])
}

#[test]
fn a_patch_crossing_the_eye_plane_keeps_its_visible_part() {
    let s = wall_scene();
    let (d, frame) = dice(&s);
    let hither = s.camera.hither;
    let yon = s.camera.yon;
    assert!(d.stats.hither_splits > 0, "{:?}", d.stats);
    assert!(!d.mpolys.is_empty());
    for mp in &d.mpolys {
        for v in &mp.v {
            assert!(v[2] > 0.0 && v[2] >= 0.5 * hither, "vertex {v:?}");
            assert!(v.iter().all(|c| c.is_finite()));
        }
        let outside = mp.v.iter().any(|v| v[2] < hither || v[2] > yon);
        assert_eq!(mp.has(flags::HITHER_YON_CROSSING), outside, "{:?}", mp.v);
        assert!(!mp.v.iter().all(|v| v[2] < hither) && !mp.v.iter().all(|v| v[2] > yon));
    }
    assert!(d.stats.crossing > 0);
    // Coverage: every pixel centre whose ray meets the wall well inside [hither, yon] lies
    // in some micropolygon.
    let cam = CameraSetup::new(&s);
    let k = cam.pixels_per_unit();
    let mut checked = 0;
    for py in 0..240 {
        for px in 0..320 {
            let (x, y) = (px as f32 + 0.5, py as f32 + 0.5);
            let dx = (x - 160.0) / k;
            let dy = -(y - 120.0) / k;
            if dx <= 0.0 {
                continue;
            }
            let z = 1.0 / dx;
            let wy = z * dy;
            if z < hither * 1.02 || z > yon * 0.98 || wy.abs() > 0.98 {
                continue;
            }
            checked += 1;
            assert!(
                covered(&d, &frame, x, y),
                "pixel ({px}, {py}) sees the wall at z = {z} but no micropolygon covers it"
            );
        }
    }
    assert!(checked > 2000, "{checked}");
}

#[test]
fn geometry_behind_the_camera_produces_nothing() {
    let objects = vec![
        object(sphere(1.0), vec![Transform::Translate([0.0, 0.0, -10.0])]),
        object(sphere(50.0), vec![Transform::Translate([0.0, 0.0, -200.0])]),
        object(
            Shape::BilinearPatch {
                points: [
                    [-5.0, -5.0, -1.0],
                    [5.0, -5.0, -1.0],
                    [-5.0, 5.0, -3.0],
                    [5.0, 5.0, -3.0],
                ],
            },
            vec![],
        ),
    ];
    let s = scene_ahead(320, 240, 45.0, objects);
    let (d, _) = dice(&s);
    assert!(d.mpolys.is_empty());
    assert_eq!(d.stats.grids, 0, "{:?}", d.stats);
    assert_eq!(d.stats.patches_culled, 3);
    assert!(d.buckets.iter().all(Vec::is_empty));
}

#[test]
fn geometry_off_screen_or_beyond_yon_produces_nothing() {
    let objects = vec![
        // Far to the side.
        object(sphere(1.0), vec![Transform::Translate([40.0, 0.0, 10.0])]),
        // Beyond yon.
        object(sphere(1.0), vec![Transform::Translate([0.0, 0.0, 2000.0])]),
        // Beside the eye, outside the frustum, partly behind it.
        object(sphere(1.0), vec![Transform::Translate([0.0, -6.0, 0.0])]),
    ];
    let s = scene_ahead(320, 240, 45.0, objects);
    let (d, _) = dice(&s);
    assert!(d.mpolys.is_empty(), "{:?}", d.stats);
    assert_eq!(d.stats.grids, 0, "{:?}", d.stats);
}

#[test]
fn sphere_around_the_eye_is_cut_at_hither() {
    // The eye is inside a sphere: everything in front is visible, nothing is projected
    // from behind the eye.
    let s = scene_ahead(64, 48, 60.0, vec![object(sphere(3.0), vec![])]);
    let (d, _) = dice(&s);
    assert!(!d.mpolys.is_empty());
    assert!(d.mpolys.iter().all(|m| m.v.iter().all(|v| v[2] >= 0.05 && v[0].is_finite())));
    // Every pixel centre is covered (the sphere surrounds the view).
    let frame = frame_of(&s);
    for py in 0..48 {
        for px in 0..64 {
            let (x, y) = (px as f32 + 0.5, py as f32 + 0.5);
            assert!(covered(&d, &frame, x, y), "({px}, {py})");
        }
    }
}

/// A square facing the camera, moving from depth 2 straight through the eye to depth -2
/// over the shutter (camera-space z = 2 - 4t at every vertex): every micropolygon keeps the
/// part of the shutter during which it is at least hither / 2 deep, `t` in
/// `[0, (2 - hither / 2) / 4]`, ending exactly there at depth hither / 2 and at its true
/// position (the perspective image of the linearly moving point), with no vertex nearer.
/// (Before, the dicer dropped every micropolygon whose vertices came nearer than hither / 2
/// at either end of its segment: the whole square.)
#[test]
fn a_patch_moving_through_the_eye_keeps_its_part_in_front() {
    let pts = [[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [-0.5, 0.5, 0.0], [0.5, 0.5, 0.0]];
    let mut o = object(Shape::BilinearPatch { points: pts }, vec![]);
    o.motion = vec![
        reyes_scene::TransformKey {
            time: 0.0,
            transform: vec![Transform::Translate([0.0, 0.0, 2.0])],
        },
        reyes_scene::TransformKey {
            time: 1.0,
            transform: vec![Transform::Translate([0.0, 0.0, -2.0])],
        },
    ];
    let mut cam = camera_ahead(90.0, None);
    cam.shutter = reyes_scene::Shutter { open: 0.0, close: 1.0, ..reyes_scene::Shutter::default() };
    let s = scene(64, 64, cam, vec![o]);
    let near = 0.5 * s.camera.hither;
    let end = (2.0 - near) / 4.0;
    let (d, _) = dice(&s);
    assert!(!d.mpolys.is_empty(), "{:?}", d.stats);
    let cam = CameraSetup::new(&s);
    for mp in &d.mpolys {
        assert!(mp.has(flags::MOVING));
        assert_eq!(mp.time[0], 0.0);
        assert!((mp.time[1] - end).abs() < 1e-5, "time {:?}, expected [0, {end}]", mp.time);
        for (v, s) in mp.v.iter().zip(&mp.speed) {
            assert_eq!(v[2], 2.0, "depth at open");
            let z1 = v[2] + s[2];
            // (`v + speed` rounds: the stored end is `near`, the sum within an ulp of 2.)
            assert!((z1 - near).abs() < 1e-6, "depth {z1} at the end");
            // The end position is the projection of the point at depth `near`: the point's
            // camera x, y do not change (it moves along z), so raster scales by 2 / near
            // about the centre.
            let centre = cam.raster_centre();
            for a in 0..2 {
                let c = [centre.x, centre.y][a];
                let want = c + (v[a] - c) * 2.0 / near;
                let got = v[a] + s[a];
                assert!((got - want).abs() <= 1e-3 * want.abs().max(1.0), "{got} vs {want}");
            }
        }
    }
}
