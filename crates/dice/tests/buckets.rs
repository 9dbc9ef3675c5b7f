//! Bucket lists against brute force, and determinism of the whole output.

mod common;

use common::*;
use reyes_dice::{CameraSetup, dice_scene, screen_bound};
use reyes_hider::Frame;
use reyes_scene::{Lens, Scene, Shape, Transform};

/// A small busy scene: sphere, torus, cone, a tilted square, partly off screen.
fn busy_scene(lens: Option<Lens>) -> Scene {
    let objects = vec![
        object(sphere(1.0), vec![Transform::Translate([-1.5, 0.3, 6.0])]),
        object(
            Shape::Torus {
                major_radius: 1.0,
                minor_radius: 0.3,
                phimin: 0.0,
                phimax: 360.0,
                thetamax: 300.0,
            },
            vec![
                Transform::Rotate { angle: 60.0, axis: [1.0, 0.2, 0.0] },
                Transform::Translate([1.5, -0.5, 7.0]),
            ],
        ),
        object(
            Shape::Cone { height: 1.5, radius: 0.7, thetamax: 360.0 },
            vec![
                Transform::Rotate { angle: -90.0, axis: [1.0, 0.0, 0.0] },
                Transform::Translate([3.5, 1.0, 5.0]),
            ],
        ),
        object(
            Shape::BilinearPatch {
                points: [
                    [-4.0, -2.0, 4.0],
                    [4.0, -2.0, 4.0],
                    [-4.0, -1.0, 12.0],
                    [4.0, -1.5, 12.0],
                ],
            },
            vec![],
        ),
    ];
    let mut s = scene(160, 120, camera([0.0, 0.5, -1.0], [0.0, 0.0, 6.0], 50.0, lens), objects);
    s.hider.bucket_size = (8, 8);
    s.hider.shading_rate = 2.0;
    s
}

/// Brute force: does the box `[lo, hi]` reach a pixel of bucket `b` (pixel x is reached iff
/// `lo.x < x + 1` and `hi.x >= x`)? Computed in extended-screen coordinates, as the frame does.
fn touches(frame: &Frame, b: usize, lo: [f32; 3], hi: [f32; 3]) -> bool {
    let e = frame.border as f32;
    let (left, top) = frame.bucket_origin(b);
    let (left, top) = (left as f32 + e, top as f32 + e);
    let (right, bottom) = (left + frame.bucket_w as f32, top + frame.bucket_h as f32);
    lo[0] + e < right && hi[0] + e >= left && lo[1] + e < bottom && hi[1] + e >= top
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
        // Lists are strictly increasing.
        for list in &d.buckets {
            assert!(list.windows(2).all(|w| w[0] < w[1]));
        }
        // Invert the lists: buckets of each micropolygon.
        let mut listed: Vec<Vec<usize>> = vec![Vec::new(); d.mpolys.len()];
        for (b, list) in d.buckets.iter().enumerate() {
            for &i in list {
                listed[i as usize].push(b);
            }
        }
        let mut entries = 0;
        for (i, mp) in d.mpolys.iter().enumerate() {
            let (lo, hi) = screen_bound(mp, setup.as_ref(), s.camera.hither, s.camera.yon);
            let expect: Vec<usize> =
                (0..frame.bucket_count()).filter(|&b| touches(&frame, b, lo, hi)).collect();
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
