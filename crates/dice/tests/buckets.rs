//! Bucket lists against brute force, and determinism of the whole output.

mod common;

use common::*;
use reyes_dice::{CameraSetup, dice_scene, screen_bound};
use reyes_hider::Frame;
use reyes_scene::{Lens, Scene, Shape};

/// A small busy scene: sphere, torus, cone, a tilted square, partly off screen.
fn busy_scene(lens: Option<Lens>) -> Scene {
    let mut objects = sphere_torus_cone();
    objects.push(object(
        Shape::BilinearPatch {
            points: [[-4.0, -2.0, 4.0], [4.0, -2.0, 4.0], [-4.0, -1.0, 12.0], [4.0, -1.5, 12.0]],
        },
        vec![],
    ));
    small_buckets_scene(busy_camera(lens), objects)
}

#[test]
fn every_micropolygon_is_in_every_bucket_its_bound_touches() {
    let lens = Lens { focal_length: 0.2, f_stop: 4.0, focal_distance: 6.0 };
    for lens in [None, Some(lens)] {
        let s = busy_scene(lens);
        let (d, frame) = dice(&s);
        let cam = CameraSetup::new(&s);
        let setup = cam.lens();
        assert_eq!(setup.is_some(), lens.is_some());
        assert_eq!(d.buckets.len(), frame.bucket_count());
        assert!(d.mpolys.len() > 1000, "{}", d.mpolys.len());
        // Lists are strictly increasing; inverted, they give the buckets of each micropolygon.
        let listed = buckets_of_each(&d);
        let mut entries = 0;
        for (i, mp) in d.mpolys.iter().enumerate() {
            let (lo, hi) = screen_bound(mp, setup.as_ref(), s.camera.hither, s.camera.yon);
            let expect = touched_buckets(&frame, lo, hi);
            assert!(!expect.is_empty(), "micropolygon {i} touches no bucket but was kept");
            assert_eq!(listed[i], expect, "micropolygon {i}, bound {lo:?}..{hi:?}");
            entries += expect.len() as u64;
        }
        assert_eq!(d.stats.bucket_entries, entries);
        assert_eq!(d.stats.micropolygons, d.mpolys.len() as u64);
    }
}

#[test]
fn output_is_identical_across_calls() {
    let s = busy_scene(Some(Lens { focal_length: 0.2, f_stop: 4.0, focal_distance: 6.0 }));
    let frame = frame_of(&s);
    let a = dice_scene(&s, &frame).expect("dice");
    let b = dice_scene(&s, &frame).expect("dice");
    let bytes_a: &[u8] = bytemuck::cast_slice(&a.mpolys);
    let bytes_b: &[u8] = bytemuck::cast_slice(&b.mpolys);
    assert!(bytes_a == bytes_b, "micropolygons differ");
    assert_eq!(a.buckets, b.buckets);
    assert_eq!(a.stats, b.stats);
}

#[test]
fn a_frame_for_another_image_is_an_error() {
    let s = busy_scene(None);
    let frame = Frame::new(100, 120, 1, 8, 8);
    let e = dice_scene(&s, &frame).expect_err("mismatch");
    assert!(matches!(e, reyes_dice::DiceError::FrameMismatch { .. }), "{e}");
    let mut bad = frame_of(&s);
    bad.bucket_w = 0;
    assert!(dice_scene(&s, &bad).is_err());
    let mut s = busy_scene(None);
    s.camera.look_at = s.camera.eye;
    assert_eq!(
        dice_scene(&s, &frame_of(&s)).expect_err("degenerate"),
        reyes_dice::DiceError::EyeAtLookAt
    );
}
