//! RenderMan's camera, light and material features through the whole pipeline: a screen
//! window is an exact crop of a magnified view, an orthographic sphere is a disk of its own
//! radius at any distance, both hiders agree under orthographic cameras and screen windows,
//! an object's light set acts in both hiders and its shading rate sets its micropolygons.

use reyes_film::Film;
use reyes_render::{RenderOptions, render};
use reyes_scene::Scene;
use reyes_testkit::fixtures::parse;
use reyes_testkit::image::psnr;

use crate::raytrace::opaque_scene;

fn film(scene: &Scene) -> Film {
    render(scene, &RenderOptions::default()).unwrap().film
}

/// A floor patch, a Plastic ball, a moving Metal ball and a torus under ambient, distant and
/// spot lights, seen by a perspective camera on a `width x 32` image with screen window
/// `window`, in buckets one row tall, rendered by `method`.
fn window_scene(width: u32, window: &str, method: &str) -> Scene {
    parse(&format!(
        "Scene(image: (width: {width}, height: 32),
           camera: (eye: (0.0, 0.5, -6.0), look_at: (0.0, 0.2, 0.0), fov: 40.0,
                    screen_window: Some({window})),
           hider: (method: {method}, pixel_samples: (3, 3), bucket_size: (16, 64), seed: 11),
           lights: [Ambient(intensity: 0.2), Distant(from: (-1.0, 2.0, -2.0), intensity: 0.9),
                    Spot(from: (2.0, 4.0, -3.0), to: (0.0, 0.0, 0.0), intensity: 20.0, cone_angle: 25.0)],
           objects: [
             (shape: BilinearPatch(points: ((-6.0, -0.8, -2.0), (6.0, -0.8, -2.0), (-6.0, -0.8, 9.0), (6.0, -0.8, 9.0))),
              material: Matte(color: (0.5, 0.55, 0.6))),
             (shape: Sphere(radius: 0.8), transform: [Translate((-1.6, 0.0, 0.0))], interpolation: Gouraud,
              material: Plastic(color: (0.9, 0.2, 0.1))),
             (shape: Sphere(radius: 0.6), interpolation: Gouraud, material: Metal(color: (0.9, 0.7, 0.3)),
              motion: [(time: 0.0, transform: [Translate((0.1, 0.3, 0.5))]),
                       (time: 1.0, transform: [Translate((0.3, 0.4, 0.5))])]),
             (shape: Torus(major_radius: 0.6, minor_radius: 0.2),
              transform: [Rotate(angle: 60.0, axis: (1.0, 0.0, 0.0)), Translate((1.7, 0.1, 0.5))],
              material: Matte(color: (0.2, 0.4, 0.95))),
           ])"
    ))
}

// A 64 x 32 image (aspect a = 2) with the left half (-2, 0, -1, 1) of its default window is
// the default view (-2, 2, -1, 1) magnified twice across. Rendered at 128 x 32 with that
// default window written out, the magnified view's left 64 columns are the same picture, and
// exactly (bit for bit) the same numbers, because everything a pixel depends on is the same:
// the raster mapping (64/2 = 128/4 = 32 pixels per screen unit across, the same centre
// 2 * 32 = 64, all exact in floating point), so every micropolygon touching those columns is diced and
// projected alike; the samples, which hash the global pixel and the bucket index (one bucket
// row, so the first buckets have the same indices in both frames); and the film, whose
// border columns past the narrow image's edge belong to buckets both frames have. Nothing
// else (the filter's reach across the edge included) can differ.
#[test]
fn a_screen_window_is_an_exact_crop_of_the_magnified_view() {
    for method in ["Stochastic", "RayTrace"] {
        let half = film(&window_scene(64, "(-2.0, 0.0, -1.0, 1.0)", method));
        let wide = film(&window_scene(128, "(-2.0, 2.0, -1.0, 1.0)", method));
        let mut seen = 0;
        for y in 0..32 {
            for x in 0..64 {
                let (a, b) = (half.pixel(x, y).unwrap(), wide.pixel(x, y).unwrap());
                assert_eq!(a.map(f32::to_bits), b.map(f32::to_bits), "{method}: pixel ({x}, {y})");
                assert_eq!(half.depth(x, y).map(f32::to_bits), wide.depth(x, y).map(f32::to_bits));
                seen += usize::from(a[3] > 0.0);
            }
        }
        assert!(seen > 500, "{method}: the crop shows the scene ({seen} pixels)");
    }
}

/// A white unlit sphere of radius 0.6 at depth `z`, centred 0.25 right and 0.1 up of the view
/// axis, seen by an orthographic camera with the default window on a 64 x 64 image (32
/// pixels per unit), `n x n` samples, box filter: alpha is each pixel's sample coverage.
///
/// The ball's axis is tilted off the view direction. Along it, an orthographic projection
/// would put each latitude circle of the front half exactly onto one of the back half, and
/// the T-junction cracks the dicer allows between grids diced at different rates (see
/// reyes-dice) on a split latitude of the front would meet those of the back, leaving a
/// sample uncovered now and then; tilted, the back half fills the front's cracks.
fn ortho_ball(z: f32, n: u32, seed: u64) -> Scene {
    parse(&format!(
        "Scene(image: (width: 64, height: 64),
           camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                    hither: 0.1, yon: 2000.0),
           hider: (pixel_samples: ({n}, {n}), filter: (kind: Box, width: 1.0), seed: {seed}),
           objects: [(shape: Sphere(radius: 0.6),
                      transform: [Rotate(angle: 37.0, axis: (1.0, 0.3, 0.0)), Translate((0.25, 0.1, {z:?}))],
                      material: Constant(color: (1.0, 1.0, 1.0)))])"
    ))
}

// The disk has radius R = 0.6 * 32 = 19.2 pixels and centre (32 + 8, 32 - 3.2) whatever the
// depth. Pixels wholly inside it must be exactly covered and pixels wholly outside exactly
// empty. The total coverage estimates the disk's area pi R^2 = 1158.1 px^2: each pixel the
// edge cuts, sampled with one jittered point in each cell of an n x n grid, has coverage
// variance at most (2n - 1) / (4 n^4) (at most 2n - 1 cells cut, each a Bernoulli of
// variance <= 1/4 weighted 1/n^2, as the triangle test derives it), and pixels are
// independent, so the sum's standard deviation is at most sigma = sqrt(N (2n-1) / (4 n^4))
// over the N cut pixels (counted generously: every pixel whose centre is within 0.75 of the
// circle). The diced outline, a polygon inscribed in the circle with sides of a pixel or
// so, loses about pi/6 px^2 (the dicer's test measures 1.1 at R = 36); allow 2. A correct
// renderer is within 2 + 4.5 sigma (about 7 px^2, 0.6%) with overwhelming probability,
// while a perspective camera's disk would shrink in inverse proportion to the depth.
#[test]
fn an_orthographic_sphere_is_a_disk_of_its_radius_at_any_distance() {
    let (radius, cx, cy) = (19.2f64, 40.0f64, 28.8f64);
    let n = 4u32;
    let expect = std::f64::consts::PI * radius * radius;
    for (z, seed) in [(3.0f32, 1u64), (30.0, 2), (300.0, 3), (1500.0, 4)] {
        let film = film(&ortho_ball(z, n, seed));
        let (mut total, mut cut) = (0.0f64, 0usize);
        for py in 0..64u32 {
            for px in 0..64u32 {
                let a = f64::from(film.pixel(px, py).unwrap()[3]);
                total += a;
                let d = (f64::from(px) + 0.5 - cx).hypot(f64::from(py) + 0.5 - cy);
                if d + 0.75 < radius - 0.05 {
                    assert_eq!(a, 1.0, "depth {z}: pixel ({px}, {py}) inside the disk");
                } else if d - 0.75 > radius + 0.05 {
                    assert_eq!(a, 0.0, "depth {z}: pixel ({px}, {py}) outside the disk");
                } else {
                    cut += 1;
                }
            }
        }
        let nf = f64::from(n);
        let sigma = (cut as f64 * (2.0 * nf - 1.0) / (4.0 * nf.powi(4))).sqrt();
        let tol = 2.0 + 4.5 * sigma;
        eprintln!(
            "orthographic ball at depth {z}: coverage {total:.2} px^2, disk {expect:.2}, tolerance {tol:.2}"
        );
        assert!((total - expect).abs() <= tol, "depth {z}: {total} vs {expect} (tolerance {tol})");
    }
}

/// The cameras both hiders are compared under, as extra camera fields of `opaque_scene`.
const CAMERAS: [(&str, &str, bool); 4] = [
    (
        "orthographic",
        ", projection: Orthographic, screen_window: Some((-3.2, 3.2, -2.0, 2.8))",
        false,
    ),
    (
        "orthographic, moving objects",
        ", projection: Orthographic, screen_window: Some((-3.2, 3.2, -2.0, 2.8))",
        true,
    ),
    (
        "orthographic camera motion",
        ", projection: Orthographic, screen_window: Some((-3.2, 3.2, -2.0, 2.8)),
           motion: [(time: 0.0, eye: (0.0, 0.5, -1.0), look_at: (0.0, 0.3, 8.0)),
                    (time: 1.0, eye: (0.4, 0.7, -1.0), look_at: (0.2, 0.3, 8.0))]",
        true,
    ),
    (
        "off-centre, stretched screen window with a lens",
        ", screen_window: Some((-0.9, 0.5, -0.55, 0.6)),
           lens: Some((focal_length: 0.4, f_stop: 2.0, focal_distance: 6.0))",
        false,
    ),
];

// As the ray-tracing tests argue for the perspective cameras: both hiders read the same
// samples and filter them alike, so they differ only near silhouettes and by Gouraud against
// exact shading, about 40 dB; a wrong orthographic ray or window mapping moves whole edges by
// pixels and falls below 30 dB.
#[test]
fn both_hiders_agree_under_orthographic_cameras_and_screen_windows() {
    let mut report = Vec::new();
    for (what, camera, moving) in CAMERAS {
        let reyes = film(&opaque_scene(camera, moving, "Stochastic"));
        let rays = film(&opaque_scene(camera, moving, "RayTrace"));
        let p = psnr(&reyes, &rays);
        report.push(format!("{what}: {p:.1} dB"));
        assert!(p > 35.0, "{what}: PSNR {p:.1} dB");
        let covered = reyes.rgba().iter().filter(|p| p[3] > 0.5).count();
        assert!(covered > reyes.rgba().len() / 4, "{what}: the scene is in view ({covered})");
    }
    eprintln!("PSNR, stochastic vs ray-tracing hider: {}", report.join(", "));
}

/// Two matte balls under a shadowing spot light and an ambient light; the right one has the
/// light set `set`.
fn lit_balls(set: &str, method: &str) -> Scene {
    parse(&format!(
        "Scene(image: (width: 96, height: 48),
           camera: (eye: (0.0, 0.0, -8.0), look_at: (0.0, 0.0, 0.0), fov: 30.0),
           hider: (method: {method}, pixel_samples: (2, 2), seed: 3),
           lights: [Ambient(intensity: 0.1),
                    Spot(from: (0.0, 6.0, -6.0), to: (0.0, 0.0, 0.0), intensity: 60.0,
                         cone_angle: 40.0, shadows: true)],
           objects: [
             (shape: Sphere(radius: 1.0), transform: [Translate((-1.5, 0.0, 0.0))],
              material: Matte(color: (1.0, 1.0, 1.0))),
             (shape: Sphere(radius: 1.0), transform: [Translate((1.5, 0.0, 0.0))],
              material: Matte(color: (1.0, 1.0, 1.0)), lights: {set}),
           ])"
    ))
}

/// The largest red value over the pixels left or right of the image's middle.
fn brightest(film: &Film, right: bool) -> f32 {
    let (w, h) = (film.width(), film.height());
    let xs = if right { w / 2..w } else { 0..w / 2 };
    xs.flat_map(|x| (0..h).map(move |y| (x, y)))
        .map(|(x, y)| film.pixel(x, y).unwrap()[0])
        .fold(0.0, f32::max)
}

#[test]
fn light_sets_act_in_both_hiders() {
    for method in ["Stochastic", "RayTrace"] {
        let all = film(&lit_balls("None", method));
        let spot_only = film(&lit_balls("Some([1])", method));
        let ambient_only = film(&lit_balls("Some([0])", method));
        let none = film(&lit_balls("Some([])", method));
        // The left ball, lit by everything, is the same in every scene.
        for f in [&spot_only, &ambient_only, &none] {
            assert_eq!(brightest(f, false), brightest(&all, false), "{method}");
        }
        // The right ball: the ambient light alone gives it exactly 0.1 (a matte white ball
        // without the spot light); nothing at all leaves it black but covered.
        let lit = brightest(&all, true);
        assert!(lit > 0.5, "{method}: the spot light lights the right ball ({lit})");
        assert!((brightest(&ambient_only, true) - 0.1).abs() < 1e-4, "{method}");
        assert_eq!(brightest(&none, true), 0.0, "{method}");
        let alpha: f32 = none.rgba().iter().map(|p| p[3]).sum();
        assert!(alpha > 300.0, "{method}: the unlit ball still covers its pixels ({alpha})");
        assert!((brightest(&spot_only, true) - (lit - 0.1)).abs() < 0.02, "{method}");
    }
}

/// One ball filling much of a 160 x 120 image, diced at its own shading rate `rate`.
fn ball_at_rate(rate: &str) -> Scene {
    parse(&format!(
        "Scene(image: (width: 160, height: 120),
           camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), fov: 40.0),
           hider: (pixel_samples: (2, 2), shading_rate: 1.0),
           lights: [Ambient(intensity: 0.1), Distant(from: (1.0, 1.0, -1.0))],
           objects: [(shape: Sphere(radius: 1.0), material: Matte(color: (1.0, 1.0, 1.0)),
                      shading_rate: {rate})])"
    ))
}

// The micropolygon count `--stats` reports follows the object's own rate: each grid side
// has ceil(length / sqrt(rate)) micropolygons and ceil(2x) <= 2 ceil(x), so a quarter of the
// rate gives at most four times as many, a little fewer where a side rounds up at the coarse
// rate; and the scene's own rate written on the object changes nothing. The rate's own rule:
// crack-free dicing rounds a count to a multiple of its sides' polyline floors
// (split/edge.rs), which raises coarse rates' counts most, so it is off here.
#[test]
fn an_objects_shading_rate_sets_its_micropolygon_count() {
    let count = |rate: &str| {
        let mut scene = ball_at_rate(rate);
        scene.hider.crack_free = false;
        render(&scene, &RenderOptions::default()).unwrap().stats.micropolygons as f64
    };
    let (base, same, fine) = (count("None"), count("Some(1.0)"), count("Some(0.25)"));
    eprintln!("micropolygons at rates 1 and 0.25: {base}, {fine}");
    assert_eq!(base, same);
    let ratio = fine / base;
    assert!((3.2..=4.0).contains(&ratio), "a quarter of the rate: {ratio:.2}x micropolygons");
}

/// Under an orthographic camera a point moving linearly in camera space moves linearly in
/// raster (the projection is affine), so a ball moving across and away from the camera
/// must render exactly as with the hider's straight-line motion
/// (`hider.original.linear_motion`), bit for bit: the perspective-correct warp, which
/// weights a vertex's raster displacement by its depth ratio, is for perspective cameras.
#[test]
fn orthographic_motion_is_straight_in_raster() {
    let scene = |linear: bool| {
        parse(&format!(
            "Scene(image: (width: 64, height: 64),
               camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                        hither: 0.1, yon: 100.0, shutter: (open: 0.0, close: 1.0)),
               hider: (pixel_samples: (4, 4), seed: 7, original: (linear_motion: {linear})),
               objects: [(shape: Sphere(radius: 0.4),
                          motion: [(time: 0.0, transform: [Translate((-0.5, 0.0, 2.0))]),
                                   (time: 1.0, transform: [Translate((0.5, 0.2, 9.0))])],
                          material: Constant(color: (1.0, 1.0, 1.0)))])"
        ))
    };
    let (warped, straight) = (film(&scene(false)), film(&scene(true)));
    assert_eq!(
        warped.rgba(),
        straight.rgba(),
        "the default path bends under an orthographic camera"
    );
}
