//! Motion- and focus-aware dicing (RenderMan's `GeometricApproximation "motionfactor"` and
//! `"focusfactor"`): a patch blurred over `B` pixels is diced at the shading rate times
//! `1 + factor * B / 16` (docs/geometry.md), exactly, and not at all when nothing blurs.
//! The expected counts follow the dicing rule of docs/geometry.md ("Dicing to the shading
//! rate"): the grid nearest the (effective) rate in area.

mod common;

use common::*;
use reyes_scene::{Lens, Object, Scene, Shape, Transform, TransformKey};

/// Image side in pixels and field of view of the test camera (at the origin, down +z).
const SIDE: u32 = 200;
const FOV: f32 = 40.0;
/// Depth and half side of the test patch.
const DEPTH: f64 = 20.0;
const HALF: f64 = 0.6;

/// Raster pixels per camera-space unit at depth 1: half the image's side over tan(fov / 2).
fn pixels_per_unit() -> f64 {
    f64::from(SIDE) / 2.0 / (f64::from(FOV).to_radians() / 2.0).tan()
}

/// A flat square of side `2 HALF` facing the camera at depth `DEPTH`, centred at `x`, moving
/// through the x offsets `path` (one breakpoint each, evenly over the shutter; none: still).
fn square(x: f32, path: &[f32]) -> Object {
    let h = HALF as f32;
    let shape =
        Shape::BilinearPatch { points: [[-h, -h, 0.0], [h, -h, 0.0], [-h, h, 0.0], [h, h, 0.0]] };
    let at = |dx: f32| vec![Transform::Translate([x + dx, 0.0, DEPTH as f32])];
    let o = object(shape, at(0.0));
    if path.is_empty() {
        return o;
    }
    let last = (path.len() - 1).max(1) as f32;
    o.with_motion(
        path.iter()
            .enumerate()
            .map(|(k, &dx)| TransformKey { time: k as f32 / last, transform: at(dx) })
            .collect(),
    )
}

/// The scene of `objects` with the test camera through `lens`, at `shading_rate`, in grids
/// large enough that a patch is never split (so one decision gives the whole count).
fn scene_of(objects: Vec<Object>, lens: Option<Lens>, shading_rate: f32) -> Scene {
    let mut s = scene(SIDE, SIDE, camera_ahead(FOV, lens), objects);
    s.hider.shading_rate = shading_rate;
    s.hider.max_grid_size = 1 << 20;
    s
}

/// Micropolygons the documented rule asks for on a flat square whose side is `len` pixels
/// long, at `rate * (1 + blur / 16)` pixels per micropolygon, `blur` the factor-weighted
/// blur: the grid [`rate_grid`] gives its two equal sides (every row of a flat square facing
/// the camera is as long as its mean, and it has no shear), as `nu * nv`.
fn expected_count(len: f64, rate: f64, blur: f64) -> u64 {
    let q = len / (rate * (1.0 + blur / 16.0)).sqrt();
    let (nu, nv) = rate_grid(q, q);
    nu * nv
}

#[test]
fn a_patch_moving_b_pixels_is_diced_at_the_documented_rate() {
    let k = pixels_per_unit();
    let side = k * 2.0 * HALF / DEPTH;
    for rate in [1.0_f32, 2.0] {
        for factor in [0.0_f32, 0.5, 1.0, 3.0] {
            // Over two breakpoints, and there and back over three (the blur is the path,
            // twice the distance, not the displacement, which is 0).
            for (path, travel) in [
                (vec![], 0.0),
                (vec![0.0, 0.0], 0.0),
                (vec![0.0, 1.0], 1.0),
                (vec![0.0, 3.0], 3.0),
                (vec![0.0, 1.5, 0.0], 3.0),
            ] {
                let mut s = scene_of(vec![square(-1.5, &path)], None, rate);
                s.hider.motion_factor = factor;
                let (d, _) = dice(&s);
                let blur = k * travel / DEPTH;
                let n = expected_count(side, f64::from(rate), f64::from(factor) * blur);
                let what = format!("rate {rate}, motion factor {factor}, path {path:?}");
                // One micropolygon per motion segment of each diced quad.
                let segments = path.len().saturating_sub(1).max(1) as u64;
                assert_eq!(d.stats.grids, 1, "{what}: one grid");
                assert_eq!(
                    d.stats.micropolygons,
                    n * segments,
                    "{what}: {n} in {segments} segments expected"
                );
            }
        }
    }
}

#[test]
fn a_defocused_patch_is_diced_at_the_documented_rate() {
    let k = pixels_per_unit();
    let side = k * 2.0 * HALF / DEPTH;
    // Lens radius 0.5 * 1 / 2 = 0.25; focused at 8, 12 or 40, the square at 20 is blurred.
    for focal_distance in [8.0_f32, 12.0, 40.0] {
        let lens = Lens { focal_length: 1.0, f_stop: 2.0, focal_distance };
        for factor in [0.5_f32, 1.0, 2.0] {
            let mut s = scene_of(vec![square(0.0, &[])], Some(lens), 1.0);
            s.hider.focus_factor = factor;
            let (d, _) = dice(&s);
            // The circle of confusion's diameter: a point at depth z seen through the lens
            // at radius R moves by R k (1 / z - 1 / focal_distance) pixels.
            let coc = 2.0
                * f64::from(lens.radius())
                * k
                * (1.0 / DEPTH - 1.0 / f64::from(focal_distance)).abs();
            let n = expected_count(side, 1.0, f64::from(factor) * coc);
            let what = format!("focused at {focal_distance}, focus factor {factor}, coc {coc}");
            assert_eq!(d.stats.grids, 1, "{what}: one grid");
            assert_eq!(d.stats.micropolygons, n, "{what}: {n} expected");
        }
    }
}

#[test]
fn the_two_factors_add_their_blurs() {
    let k = pixels_per_unit();
    let side = k * 2.0 * HALF / DEPTH;
    let lens = Lens { focal_length: 1.0, f_stop: 2.0, focal_distance: 8.0 };
    let mut s = scene_of(vec![square(-1.5, &[0.0, 2.0])], Some(lens), 1.0);
    s.hider.motion_factor = 1.0;
    s.hider.focus_factor = 0.5;
    let (d, _) = dice(&s);
    let motion = k * 2.0 / DEPTH;
    let coc = 2.0 * f64::from(lens.radius()) * k * (1.0 / DEPTH - 1.0 / 8.0).abs();
    let n = expected_count(side, 1.0, motion + 0.5 * coc);
    assert_eq!(d.stats.micropolygons, n, "{n} expected");
}

/// Balls moving across the frame (or still), seen through `lens`, at the factors given, as
/// objects' own factors or the scene's.
fn balls(moving: bool, lens: Option<Lens>) -> Scene {
    let objects = (0..4)
        .map(|i| {
            let x = -3.0 + 2.0 * i as f32;
            let at = |dx: f32| vec![Transform::Translate([x + dx, 0.0, 10.0])];
            let o = object(sphere(0.8), at(0.0));
            if moving {
                o.with_motion(vec![
                    TransformKey { time: 0.0, transform: at(0.0) },
                    TransformKey { time: 1.0, transform: at(1.0) },
                ])
            } else {
                o
            }
        })
        .collect();
    scene(320, 240, camera_ahead(40.0, lens), objects)
}

#[test]
fn the_factors_coarsen_blurred_scenes_and_leave_sharp_ones_alone() {
    // Without blur (still, pinhole) the factors change nothing, micropolygon for micropolygon.
    let still = balls(false, None);
    let (base, _) = dice(&still);
    let mut factored = still.clone();
    factored.hider.motion_factor = 2.0;
    factored.hider.focus_factor = 2.0;
    let (same, _) = dice(&factored);
    assert_eq!(base.mpolys, same.mpolys, "a sharp scene is diced as without the factors");
    assert_eq!(base.stats, same.stats);

    // Moving balls: fewer micropolygons. Each ball moves 31 to 33 pixels (its far side to
    // its near side), so the rule asks for about 1 / (1 + 31 / 16), a third, of them; the
    // flatness rule and crack-free dicing's multiples of `2^d`, which the factor leaves
    // alone, keep more (8,192 of 19,200: at factor 1 these balls are at that floor already).
    let moving = balls(true, None);
    let (sharp, _) = dice(&moving);
    let mut coarse = moving.clone();
    coarse.hider.motion_factor = 1.0;
    let (blurred, _) = dice(&coarse);
    let ratio = blurred.stats.micropolygons as f64 / sharp.stats.micropolygons as f64;
    eprintln!(
        "moving: {} -> {} micropolygons ({ratio:.3})",
        sharp.stats.micropolygons, blurred.stats.micropolygons
    );
    assert!(ratio < 0.5, "motion factor 1 on 44 pixels of motion: {ratio:.3} of them");

    // An object's own factor replaces the scene's: 0 on every ball undoes the scene's 1.
    let mut own = coarse.clone();
    for o in &mut own.objects {
        o.motion_factor = Some(0.0);
    }
    let (undone, _) = dice(&own);
    assert_eq!(undone.mpolys, sharp.mpolys, "objects' own factor 0 wins over the scene's");

    // Defocused balls (focused at 4, they are at 10): fewer; the motion factor alone, on
    // still balls, changes nothing.
    let lens = Lens { focal_length: 1.0, f_stop: 2.0, focal_distance: 4.0 };
    let defocused = balls(false, Some(lens));
    let (sharp, _) = dice(&defocused);
    let mut only_motion = defocused.clone();
    only_motion.hider.motion_factor = 1.0;
    assert_eq!(dice(&only_motion).0.mpolys, sharp.mpolys, "no motion, no change");
    let mut coarse = defocused.clone();
    coarse.hider.focus_factor = 1.0;
    let (blurred, _) = dice(&coarse);
    eprintln!(
        "defocused: {} -> {} micropolygons",
        sharp.stats.micropolygons, blurred.stats.micropolygons
    );
    assert!(blurred.stats.micropolygons < sharp.stats.micropolygons);

    // A patch in the focal plane has no focus blur: the focus factor changes nothing.
    let lens = Lens { focal_length: 1.0, f_stop: 2.0, focal_distance: DEPTH as f32 };
    let in_focus = scene_of(vec![square(0.0, &[])], Some(lens), 1.0);
    let mut factored = in_focus.clone();
    factored.hider.focus_factor = 4.0;
    assert_eq!(dice(&in_focus).0.mpolys, dice(&factored).0.mpolys, "in focus, no change");
}
