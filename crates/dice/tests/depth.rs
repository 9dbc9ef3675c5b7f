//! Geometry whose depth changes by orders of magnitude over the shutter: a sphere that comes
//! from far beyond the scene (4e9) to the foreground (16). Its micropolygons must be diced
//! as finely as its apparent size at each time asks (not to the far end's millionth of a
//! pixel everywhere), keep their end depths through `f32` rounding, and drop the part of
//! their motion beyond yon. Fuzz regression `render-shrunk-lens-huge-floor-slow`: before
//! these rules, a 32x24 render of such a scene diced 1.75 M micropolygons with their end
//! depths rounded to 0, and took minutes.

mod common;

use common::*;
use reyes_dice::Diced;
use reyes_scene::{Scene, Transform, TransformKey};

/// Depth of the sphere's centre at shutter open and close (the camera looks down +z from
/// the origin, so camera depth is world z).
const FAR: f64 = 4.294_967_296e9;
const NEAR: f64 = 16.0;
const RADIUS: f64 = 0.5;

/// A 64x48 scene of a sphere of radius 0.5 at x = 1 moving from depth `from` to `to`, with
/// yon at `yon`.
fn moving_sphere(from: f64, to: f64, yon: f32) -> Scene {
    let at = |z: f64| vec![Transform::Translate([1.0, 0.0, z as f32])];
    let key = |time: f32, z: f64| TransformKey { time, transform: at(z) };
    let sphere =
        object(sphere(RADIUS as f32), vec![]).with_motion(vec![key(0.0, from), key(1.0, to)]);
    let mut s = scene_ahead(64, 48, 40.0, vec![sphere]);
    s.camera.yon = yon;
    s
}

/// The centre's depth at normalised time `t` of the motion from `from` to `to`.
fn centre(from: f64, to: f64, t: f32) -> f64 {
    let t = f64::from(t);
    from * (1.0 - t) + to * t
}

/// Every vertex's depth at the start and at the end of its segment (`v + speed`) is the
/// sphere's at that time, within `rel` of it.
fn check_depths(d: &Diced, from: f64, to: f64, rel: f64) {
    assert!(!d.mpolys.is_empty());
    for mp in &d.mpolys {
        for (k, t) in [(0, mp.time[0]), (1, mp.time[1])] {
            let c = centre(from, to, t);
            let (lo, hi) = ((c - RADIUS) * (1.0 - rel), (c + RADIUS) * (1.0 + rel));
            for j in 0..4 {
                let z =
                    f64::from(mp.v[j][2]) + if k == 1 { f64::from(mp.speed[j][2]) } else { 0.0 };
                assert!(
                    (lo..=hi).contains(&z),
                    "vertex {j} at time {t}: depth {z}, the sphere is at {c} +- {RADIUS}"
                );
            }
        }
    }
}

#[test]
fn a_sphere_from_far_away_is_diced_for_its_size_when_near() {
    // The flatness rule's relative bound scales with the sphere's extent at each time: the
    // moving sphere is diced no finer than the same sphere standing at its near end.
    let (moving, _) = dice(&moving_sphere(FAR, NEAR, 1e30));
    let (still, _) = dice(&moving_sphere(NEAR, NEAR, 1e30));
    let (m, s) = (moving.stats.vertices, still.stats.vertices);
    println!("vertices diced: moving {m}, still {s}");
    assert!(m <= 2 * s, "moving {:?}\nstill {:?}", moving.stats, still.stats);
}

#[test]
fn end_depths_survive_rounding_over_a_great_depth_change() {
    // Each segment is cut where a vertex's depth changes by more than 1024 times, so the
    // end depth `z0 + (z1 - z0)` in f32 is within 1024 ulps (6e-5) of the true one; 1e-3
    // leaves room for the rounding of the cut times and the projection.
    let (d, _) = dice(&moving_sphere(FAR, NEAR, 1e30));
    check_depths(&d, FAR, NEAR, 1e-3);
    for mp in &d.mpolys {
        for j in 0..4 {
            let (z0, z1) = (mp.v[j][2], mp.v[j][2] + mp.speed[j][2]);
            assert!(z0.max(z1) <= 1025.0 * z0.min(z1), "vertex {j}: {z0} to {z1}");
        }
    }
}

#[test]
fn the_part_of_a_motion_beyond_yon_is_dropped() {
    // From depth 1000 to 10 with yon at 100: the nearest point of the sphere reaches yon at
    // t = (1000 - 0.5 - 100) / 990; no micropolygon exists before that, and each starts
    // with some vertex within yon.
    let (from, to, yon) = (1000.0, 10.0, 100.0_f32);
    let (d, _) = dice(&moving_sphere(from, to, yon));
    check_depths(&d, from, to, 1e-5);
    let first = (from - RADIUS - f64::from(yon)) / (from - to);
    for mp in &d.mpolys {
        assert!(f64::from(mp.time[0]) >= first - 1e-6, "starts at {} before {first}", mp.time[0]);
        let nearest = mp.v.iter().map(|v| v[2]).fold(f32::INFINITY, f32::min);
        assert!(nearest <= yon * (1.0 + 1e-5), "starts at depth {nearest} beyond yon");
    }
}
