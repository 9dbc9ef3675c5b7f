//! Projections and screen windows (RenderMan's `Projection` and `ScreenWindow`) in the dicer:
//! the default window computes exactly what the renderer computed before windows existed, an
//! explicit window maps its corners to the image's, an orthographic camera ignores depth and
//! the lens, and primary rays hold what the hider draws.

mod common;

use common::*;
use glam::{Vec2, Vec3};
use reyes_dice::{CameraSetup, Viewer};
use reyes_scene::{Camera, Lens, Projection, Scene, Transform};
use reyes_testkit::random::Uniform;

/// A scene of `objects` seen by `camera` on a `w x h` image.
fn seen_by(camera: Camera, w: u32, h: u32, objects: Vec<reyes_scene::Object>) -> Scene {
    scene(w, h, camera, objects)
}

/// A camera at the origin looking down +z (fov 40) with `projection` and `window`.
fn ahead(projection: Projection, window: Option<[f32; 4]>) -> Camera {
    Camera { projection, screen_window: window, ..camera_ahead(40.0, None) }
}

/// The default window's raster mapping is, bit for bit, the formula the renderer used before
/// screen windows and projections existed: `w/2 + k x/z`, `h/2 - k y/z`, with
/// `k = (min(w, h)/2) / tan(fov/2)`.
#[test]
fn the_default_window_is_bit_identical_to_the_old_projection() {
    let mut uniform = Uniform::new(0x5c4e);
    for _ in 0..200 {
        let mut r = |lo: f32, hi: f32| uniform.range(lo, hi);
        let (w, h) = (r(1.0, 3000.0) as u32, r(1.0, 3000.0) as u32);
        let fov = r(1.0, 170.0);
        let s = seen_by(camera_ahead(fov, None), w, h, vec![]);
        let cam = CameraSetup::new(&s);
        let (wf, hf) = (w as f32, h as f32);
        let k = 0.5 * wf.min(hf) / (0.5 * fov.to_radians()).tan();
        assert_eq!(cam.pixels_per_unit().to_bits(), k.to_bits());
        assert_eq!(cam.raster_scale(), Vec2::splat(k));
        for _ in 0..20 {
            let z = r(0.1, 100.0);
            let p = Vec3::new(r(-2.0, 2.0) * z, r(-2.0, 2.0) * z, z);
            let old = Vec2::new(0.5 * wf + k * p.x / p.z, 0.5 * hf - k * p.y / p.z);
            let new = cam.eye_to_raster(p);
            assert_eq!((new.x.to_bits(), new.y.to_bits()), (old.x.to_bits(), old.y.to_bits()));
            // The pinhole primary ray, as it was computed.
            let raster = Vec2::new(r(0.0, wf), r(0.0, hf));
            let (o, d) = cam.primary_ray(raster, (0.3, -0.2));
            assert_eq!(o, Vec3::ZERO);
            let want = Vec3::new((raster.x - 0.5 * wf) / k, (0.5 * hf - raster.y) / k, 1.0);
            assert_eq!(d, want);
        }
        assert_eq!(cam.viewer(), Viewer::Eye(Vec3::ZERO));
    }
}

/// Writing RenderMan's default window explicitly gives the same projection, up to rounding.
#[test]
fn an_explicit_default_window_matches_the_default() {
    for (w, h) in [(640u32, 480u32), (200, 400), (64, 64), (1920, 1080)] {
        let a = w as f32 / h as f32;
        let window = if a >= 1.0 { [-a, a, -1.0, 1.0] } else { [-1.0, 1.0, -1.0 / a, 1.0 / a] };
        for projection in [Projection::Perspective, Projection::Orthographic] {
            let default = CameraSetup::new(&seen_by(ahead(projection, None), w, h, vec![]));
            let explicit =
                CameraSetup::new(&seen_by(ahead(projection, Some(window)), w, h, vec![]));
            for p in [Vec3::new(0.3, -0.7, 2.0), Vec3::new(-5.0, 4.0, 30.0), Vec3::Z] {
                let (x, y) = (default.eye_to_raster(p), explicit.eye_to_raster(p));
                assert!((x - y).abs().max_element() < 1e-3, "{w}x{h} {projection:?}: {x} vs {y}");
            }
        }
    }
}

/// An explicit window's corners are the image's corners, in either projection.
#[test]
fn the_screen_window_fills_the_image() {
    let (w, h) = (300u32, 120u32);
    let [l, r, b, t] = [-0.7f32, 1.9, -0.4, 0.25];
    let tan = (20f32).to_radians().tan();
    for projection in [Projection::Perspective, Projection::Orthographic] {
        let cam = CameraSetup::new(&seen_by(ahead(projection, Some([l, r, b, t])), w, h, vec![]));
        // A camera-space point at depth 3 whose screen position is (sx, sy).
        let at = |sx: f32, sy: f32| match projection {
            Projection::Perspective => Vec3::new(sx * tan * 3.0, sy * tan * 3.0, 3.0),
            Projection::Orthographic => Vec3::new(sx, sy, 3.0),
        };
        for (sx, sy, want) in [
            (l, t, Vec2::ZERO),
            (r, t, Vec2::new(w as f32, 0.0)),
            (l, b, Vec2::new(0.0, h as f32)),
            (r, b, Vec2::new(w as f32, h as f32)),
            (0.5 * (l + r), 0.5 * (b + t), Vec2::new(0.5 * w as f32, 0.5 * h as f32)),
        ] {
            let got = cam.eye_to_raster(at(sx, sy));
            assert!((got - want).abs().max_element() < 1e-3, "{projection:?} ({sx}, {sy}): {got}");
        }
    }
}

/// Orthographic: raster position does not depend on depth, the lens is ignored, points are
/// seen along the view direction, and primary rays leave the eye plane along it holding the
/// point the hider draws.
#[test]
fn orthographic_ignores_depth_and_the_lens() {
    let lens = Some(Lens { focal_length: 1.0, f_stop: 2.0, focal_distance: 5.0 });
    let mut camera = Camera {
        projection: Projection::Orthographic,
        screen_window: Some([-2.0, 3.0, -1.5, 1.0]),
        ..camera([1.0, 2.0, -3.0], [2.0, 2.5, 4.0], 40.0, lens)
    };
    camera.up = [0.2, 1.0, 0.1];
    let s = seen_by(camera, 200, 100, vec![]);
    let cam = CameraSetup::new(&s);
    assert!(cam.lens().is_none(), "no depth of field under an orthographic projection");
    assert_eq!(cam.projection(), Projection::Orthographic);
    let to_world = cam.world_to_camera().inverse();
    let forward = to_world.transform_vector3(Vec3::Z);
    let mut uniform = Uniform::new(0x5c4e);
    for _ in 0..200 {
        let mut r = |lo: f32, hi: f32| uniform.range(lo, hi);
        let p = Vec3::new(r(-2.0, 3.0), r(-1.5, 1.0), r(0.5, 50.0));
        let raster = cam.eye_to_raster(p);
        let deeper = cam.eye_to_raster(Vec3::new(p.x, p.y, p.z * 3.0 + 1.0));
        assert_eq!(raster, deeper, "depth does not move a point");
        let (o, d) = cam.primary_ray(raster, (r(-1.0, 1.0), r(-1.0, 1.0)));
        assert!((d - forward).length() < 1e-6, "rays are parallel to the view: {d}");
        let m = cam.world_to_camera();
        assert!(m.transform_point3(o).z.abs() < 1e-4, "from the eye plane");
        let on_ray = o + d * p.z;
        let p_world = to_world.transform_point3(p);
        assert!((on_ray - p_world).length() < 1e-4 * (1.0 + p.z), "{on_ray} vs {p_world}");
        // Seen along the view direction, whatever the point.
        let from = cam.viewer().seen_from(p_world);
        assert!(((p_world - from).normalize() - forward).length() < 1e-4);
    }
}

/// The diced area of a sphere under an orthographic camera is the disk `pi (k r)^2` at any
/// distance, `k` the pixels per unit: the silhouette does not shrink with depth.
#[test]
fn an_orthographic_sphere_projects_to_a_disk_of_its_radius() {
    for z in [2.0f32, 20.0, 200.0] {
        let s = seen_by(
            Camera { yon: 1000.0, ..ahead(Projection::Orthographic, None) },
            160,
            120,
            vec![object(sphere(0.6), vec![Transform::Translate([0.1, -0.2, z])])],
        );
        let (d, _) = dice(&s);
        let k = f64::from(CameraSetup::new(&s).pixels_per_unit());
        assert_eq!(k, 60.0, "an orthographic default window spans 2 units across 120 pixels");
        let expect = std::f64::consts::PI * (0.6 * k).powi(2);
        let positive: f64 = d.mpolys.iter().map(signed_area).filter(|a| *a > 0.0).sum();
        let negative: f64 = -d.mpolys.iter().map(signed_area).filter(|a| *a < 0.0).sum::<f64>();
        for (name, area) in [("front", positive), ("back", negative)] {
            let err = (area - expect).abs() / expect;
            eprintln!("depth {z} {name}: {area:.1} px^2 vs {expect:.1}");
            // The outline is the equator, a patch boundary, so under crack-free dicing it is
            // its shared polyline: chords inscribed in the circle, each straying at most the
            // flatness bound `tol` pixels at its middle (split/edge.rs). A circular segment
            // of chord `c` and sagitta `h` has area at most 2/3 c h, so the polygon misses
            // at most 2/3 tol (2 pi k r) of pi (k r)^2: a fraction 4/3 tol / (k r), 0.19%
            // at tol = 0.05 and k r = 36 pixels. (Before crack-free dicing the outline had a
            // vertex every pixel, and missed about pi/6 px^2.)
            let tol = f64::from(s.hider.flatness);
            let bound = 4.0 / 3.0 * tol / (0.6 * k);
            assert!(err < bound, "depth {z} {name}: {area} vs {expect} ({:.3}%)", 100.0 * err);
        }
    }
}
