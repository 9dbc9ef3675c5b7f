//! The RenderMan geometry through the whole pipeline: hyperboloids that are cylinders and
//! cones draw as those shapes; a wrapped B-spline tube covers its silhouette without a seam;
//! both hiders draw a scene of every new shape alike (still, moving and deforming); and
//! the images do not depend on the thread count.

use reyes_film::Film;
use reyes_render::{RenderOptions, render};
use reyes_scene::Scene;
use reyes_testkit::fixtures::{NURBS_CIRCLE_KNOTS, nurbs_circle_points, parse};
use reyes_testkit::image::psnr;

fn render_film(scene: &Scene, threads: Option<usize>) -> Film {
    render(scene, &RenderOptions { threads, ..Default::default() }).unwrap().film
}

/// One object of `shape` (tipped so its axis is up the screen) under the given hider.
fn one_shape(shape: &str, method: &str) -> Scene {
    parse(&format!(
        "Scene(image: (width: 96, height: 72),
           camera: (eye: (0.0, 1.0, -6.0), look_at: (0.0, 0.0, 0.0), fov: 40.0, hither: 0.5, yon: 40.0),
           hider: (method: {method}, pixel_samples: (4, 4), seed: 3),
           lights: [Ambient(intensity: 0.2), Distant(from: (-1.0, 2.0, -2.0), intensity: 0.9)],
           objects: [(shape: {shape}, transform: [Rotate(angle: -90.0, axis: (1.0, 0.0, 0.0))],
                      material: Plastic(color: (0.8, 0.4, 0.2)))])"
    ))
}

/// Alpha (coverage) of every pixel.
fn alpha(film: &Film) -> Vec<f32> {
    film.rgba().iter().map(|p| p[3]).collect()
}

// The dicer evaluates a hyperboloid from (1, 0, -1) to (1, 0, 1) with exactly the
// cylinder's positions (cos, sin, -1 + 2 v), and one from (r, 0, 0) to (0, 0, h) with the
// cone's, so the stochastic hider's coverage is bit for bit the same; the normals differ by
// the rounding of a normalisation, so colours agree to float precision. The ray engine
// solves a different (but equivalent) quadratic: its silhouettes agree up to rounding.
#[test]
fn hyperboloids_draw_as_the_cylinder_and_the_cone() {
    for (hyperboloid, quadric) in [
        (
            "Hyperboloid(point1: (1.0, 0.0, -1.0), point2: (1.0, 0.0, 1.0), thetamax: 300.0)",
            "Cylinder(radius: 1.0, zmin: -1.0, zmax: 1.0, thetamax: 300.0)",
        ),
        (
            "Hyperboloid(point1: (1.2, 0.0, -1.0), point2: (1.2, 0.0, 0.8))",
            "Cylinder(radius: 1.2, zmin: -1.0, zmax: 0.8)",
        ),
        (
            "Hyperboloid(point1: (1.0, 0.0, 0.0), point2: (0.0, 0.0, 1.5))",
            "Cone(height: 1.5, radius: 1.0)",
        ),
    ] {
        let (h, q) = (
            render_film(&one_shape(hyperboloid, "Stochastic"), None),
            render_film(&one_shape(quadric, "Stochastic"), None),
        );
        assert_eq!(alpha(&h), alpha(&q), "{hyperboloid}: the same silhouette");
        let p = psnr(&h, &q);
        assert!(p > 80.0, "{hyperboloid}: PSNR {p:.1} dB against {quadric}");
        let (h, q) = (
            render_film(&one_shape(hyperboloid, "RayTrace"), None),
            render_film(&one_shape(quadric, "RayTrace"), None),
        );
        let p = psnr(&h, &q);
        assert!(p > 60.0, "{hyperboloid}: ray-traced PSNR {p:.1} dB against {quadric}");
    }
}

/// A uniform B-spline tube of radius 0.9 around z, 12 points around (wrapped), 5 along.
fn tube() -> String {
    let mut points = Vec::new();
    for j in 0..5 {
        for i in 0..12 {
            let a = i as f32 * std::f32::consts::TAU / 12.0;
            points.push(format!("({}, {}, {})", a.cos(), a.sin(), j as f32 * 0.6 - 1.2));
        }
    }
    format!(
        "PatchMesh(kind: Bicubic, nu: 12, nv: 5, uwrap: Periodic, ubasis: BSpline, vbasis: BSpline, \
         points: [{}])",
        points.join(", ")
    )
}

// A wrapped tube seen side-on covers a band of the image completely: a seam (a crack
// between the last sub-patch and the first) would let the black background through. The
// tube is turned so that its seam (u = 0) faces the camera (one of the two turns), then away.
#[test]
fn a_wrapped_b_spline_tube_has_no_seam() {
    for (method, turn) in
        [("Stochastic", 90.0), ("Stochastic", -90.0), ("RayTrace", 90.0), ("RayTrace", -90.0)]
    {
        let scene = parse(&format!(
            "Scene(image: (width: 64, height: 64),
               camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), fov: 40.0),
               hider: (method: {method}, pixel_samples: (4, 4)),
               lights: [Ambient(intensity: 1.0)],
               objects: [(shape: {}, transform: [Rotate(angle: {turn:?}, axis: (0.0, 0.0, 1.0)),
                                                 Rotate(angle: -90.0, axis: (1.0, 0.0, 0.0))],
                          material: Constant(color: (1.0, 1.0, 1.0)))])",
            tube()
        ));
        let film = render_film(&scene, None);
        // The tube spans |x| < 0.9 and |y| < 0.6 in world units: the pixels well inside.
        let px = |w: f32| 32.0 + w * 32.0 / (5.0 * (20.0_f32).to_radians().tan());
        let (x0, x1) = (px(-0.7) as u32, px(0.7) as u32);
        let (y0, y1) = (px(-0.45) as u32, px(0.45) as u32);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let p = film.pixel(x, y).unwrap();
                assert!(p[3] > 0.999 && p[0] > 0.999, "{method}: pixel ({x}, {y}) = {p:?}");
            }
        }
    }
}

/// Every new shape: a hyperboloid, the tube, a NURBS cylinder, a Catmull-Rom sheet and a
/// bilinear mesh floor, with a moving hyperboloid and a deforming Catmull-Rom sheet when
/// `moving` (the sheet's keys shift it, keeping its shape).
fn new_shapes(method: &str, moving: bool) -> Scene {
    let pw: Vec<String> = nurbs_circle_points([-0.8, 0.8])
        .iter()
        .map(|p| format!("({}, {}, {}, {})", p[0], p[1], p[2], p[3]))
        .collect();
    // The sheet's control points, raised by `dy`, at heights `0.15 ((k * zstep) % 7)`.
    let net = |dy: f32, zstep: usize| -> Vec<String> {
        (0..16)
            .map(|k| {
                format!(
                    "({}, {}, {})",
                    (k % 4) as f32 * 0.6 - 0.9,
                    (k / 4) as f32 * 0.5 + dy,
                    ((k * zstep) % 7) as f32 * 0.15
                )
            })
            .collect()
    };
    let (sheet, lifted) = (net(0.0, 5), net(0.3, 3));
    let (hyp_motion, deform) = if moving {
        (
            "motion: [(time: 0.0, transform: [Rotate(angle: -90.0, axis: (1.0, 0.0, 0.0)), Translate((-2.2, 0.4, 1.0))]),
                      (time: 1.0, transform: [Rotate(angle: -80.0, axis: (1.0, 0.0, 0.0)), Translate((-1.9, 0.6, 1.0))])],"
                .to_string(),
            format!(
                "deform: [(time: 0.0, points: [{}]), (time: 1.0, points: [{}])],",
                sheet.join(", "),
                lifted.join(", ")
            ),
        )
    } else {
        (String::new(), String::new())
    };
    parse(&format!(
        "Scene(image: (width: 128, height: 96),
           camera: (eye: (0.0, 1.5, -7.0), look_at: (0.0, 0.3, 0.0), fov: 40.0, hither: 0.5, yon: 40.0),
           hider: (method: {method}, pixel_samples: (4, 4), filter: (kind: Gaussian, width: 2.0), seed: 5),
           lights: [Ambient(intensity: 0.2), Distant(from: (-1.0, 2.0, -2.0), to: (0.0, 0.0, 0.0), intensity: 0.9)],
           objects: [
             (shape: PatchMesh(kind: Bilinear, nu: 3, nv: 2,
                points: [(-6.0, -1.0, -2.0), (0.0, -1.2, -2.0), (6.0, -1.0, -2.0), (-6.0, -1.0, 12.0), (0.0, -1.2, 12.0), (6.0, -1.0, 12.0)]),
              material: Matte(color: (0.5, 0.55, 0.6))),
             (shape: Hyperboloid(point1: (0.8, -0.5, -0.8), point2: (0.8, 0.5, 0.8), thetamax: 320.0),
              transform: [Rotate(angle: -90.0, axis: (1.0, 0.0, 0.0)), Translate((-2.2, 0.4, 1.0))], {hyp_motion}
              interpolation: Gouraud, material: Matte(color: (0.9, 0.3, 0.1))),
             (shape: {tube}, transform: [Rotate(angle: -90.0, axis: (1.0, 0.0, 0.0)), Scale((0.7, 0.7, 0.7)), Translate((0.0, 0.3, 1.5))],
              interpolation: Gouraud, material: Matte(color: (0.2, 0.8, 0.3))),
             (shape: NuPatch(nu: 9, uorder: 3, uknot: {knots:?}, umin: 0.0, umax: 1.0,
                             nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [{pw}]),
              transform: [Rotate(angle: -90.0, axis: (1.0, 0.0, 0.0)), Scale((0.7, 0.7, 0.7)), Translate((2.2, 0.2, 1.0))],
              interpolation: Gouraud, material: Matte(color: (0.2, 0.3, 0.9))),
             (shape: PatchMesh(kind: Bicubic, nu: 4, nv: 4, ubasis: CatmullRom, vbasis: Bezier,
                               points: [{sheet}]),
              transform: [Translate((0.0, -0.9, -1.5))], {deform}
              interpolation: Gouraud, material: Matte(color: (0.9, 0.9, 0.3))),
           ])",
        tube = tube(),
        knots = NURBS_CIRCLE_KNOTS,
        pw = pw.join(", "),
        sheet = sheet.join(", "),
    ))
}

// As `both_hiders_draw_the_same_opaque_scenes` (raytrace.rs): the hiders differ where a
// sample's visibility differs near silhouettes and by Gouraud against per-hit shading, 40 dB
// or so. The ray engine's tessellation adds at most 1/1000 of a patch's size (here under
// 0.005 world units, a tenth of a pixel), and its interpolated normals differ from the exact
// ones by the same order, so the threshold stays 35 dB. Measured: 57 dB still. Moving, the
// stochastic hider shades once at shutter open while the ray hider shades at each ray's
// time and place, so the turning hyperboloid and the deforming sheet differ in shading as
// well: 38.5 dB (the same scene with the sheet replaced by a deforming `BilinearPatch`,
// which existed before these shapes, gives 36 dB), still above 35 dB, while a wrong time,
// key or tessellation moves whole edges by pixels and falls below 30 dB.
#[test]
fn both_hiders_draw_the_new_shapes_alike() {
    let mut report = Vec::new();
    for moving in [false, true] {
        let reyes = render_film(&new_shapes("Stochastic", moving), None);
        let rays = render_film(&new_shapes("RayTrace", moving), None);
        let p = psnr(&reyes, &rays);
        report.push(format!("moving {moving}: {p:.1} dB"));
        assert!(p > 35.0, "moving {moving}: PSNR {p:.1} dB");
    }
    eprintln!("PSNR, stochastic vs ray-tracing hider, new shapes: {}", report.join(", "));
}

#[test]
fn the_new_shapes_render_the_same_for_any_thread_count() {
    for method in ["Stochastic", "RayTrace"] {
        let scene = new_shapes(method, true);
        let one = render_film(&scene, Some(1));
        for threads in [2, 8] {
            assert!(render_film(&scene, Some(threads)) == one, "{method}: {threads} threads");
        }
    }
}
