//! Distributed ray tracing through the whole pipeline: the ray-tracing hider (Appendix B)
//! against the stochastic hider (Appendix A), its determinism, the soft shadow of a disk
//! light measured on the image against similar triangles (both hiders), and the cost and
//! noise of ray-traced vertex shading as `raytrace.vertex_rays` grows.

use std::time::{Duration, Instant};

use reyes_film::Film;
use reyes_render::rayhide::render_with;
use reyes_render::{RenderOptions, render};
use reyes_sampling::Strata;
use reyes_scene::{Material, Scene};
use reyes_shade::{RayCounts, Traced};
use reyes_testkit::fixtures::parse;
use reyes_testkit::image::psnr;
use reyes_trace::{Ray, Tracer};

fn render_film(scene: &Scene, threads: Option<usize>) -> Film {
    render(scene, &RenderOptions { threads, ..Default::default() }).unwrap().film
}

/// An opaque scene lit without shadows (so nothing needs a secondary ray): spheres (one cut
/// and partly swept), a bilinear patch, a mesh and a torus, with extra camera fields, moving
/// objects when `moving`, and the hider `method`.
pub(crate) fn opaque_scene(camera: &str, moving: bool, method: &str) -> Scene {
    let (sphere_motion, torus_motion) = if moving {
        (
            "motion: [(time: 0.0, transform: [Translate((-1.3, 0.2, 6.0))]),
                      (time: 1.0, transform: [Translate((-0.7, 0.5, 6.0))])],",
            "motion: [(time: 0.0, transform: [Rotate(angle: 60.0, axis: (1.0, 0.0, 0.0)), Translate((0.3, 1.1, 8.0))]),
                      (time: 1.0, transform: [Rotate(angle: 80.0, axis: (1.0, 0.2, 0.0)), Translate((0.1, 1.3, 8.5))])],",
        )
    } else {
        ("", "")
    };
    parse(&format!(
        "Scene(image: (width: 128, height: 96),
           camera: (eye: (0.0, 0.5, -1.0), look_at: (0.0, 0.3, 8.0), fov: 40.0, hither: 0.5, yon: 40.0 {camera}),
           hider: (method: {method}, pixel_samples: (4, 4), filter: (kind: Gaussian, width: 2.0), seed: 5),
           lights: [Ambient(intensity: 0.2), Distant(from: (-1.0, 2.0, -2.0), to: (0.0, 0.0, 0.0), intensity: 0.9)],
           objects: [
             (shape: BilinearPatch(points: ((-6.0, -0.8, 1.0), (6.0, -0.8, 1.0), (-6.0, -0.8, 30.0), (6.0, -0.8, 30.0))),
              material: Matte(color: (0.5, 0.55, 0.6))),
             (shape: Sphere(radius: 0.8), transform: [Translate((-1.3, 0.2, 6.0))], {sphere_motion}
              interpolation: Gouraud, material: Matte(color: (0.9, 0.2, 0.1))),
             (shape: Sphere(radius: 0.5, zmin: Some(-0.3), thetamax: 300.0),
              transform: [Rotate(angle: -90.0, axis: (1.0, 0.0, 0.0)), Translate((1.6, 0.6, 5.0))],
              interpolation: Gouraud, material: Matte(color: (0.2, 0.8, 0.3))),
             (shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.3), (0.0, 1.0, 0.0), (0.5, 1.8, 0.2)],
                          faces: [[0, 1, 2, 3], [3, 2, 4]]),
              transform: [Translate((1.0, -0.6, 9.0))],
              interpolation: Gouraud, material: Matte(color: (0.9, 0.9, 0.2))),
             (shape: Torus(major_radius: 0.7, minor_radius: 0.25),
              transform: [Rotate(angle: 60.0, axis: (1.0, 0.0, 0.0)), Translate((0.3, 1.1, 8.0))], {torus_motion}
              interpolation: Gouraud, material: Constant(color: (0.2, 0.4, 0.95))),
           ])"
    ))
}

const LENS: &str = ", lens: Some((focal_length: 0.4, f_stop: 2.0, focal_distance: 6.0))";

/// The cameras and motions both hiders are compared under.
const CASES: [(&str, &str, bool); 5] = [
    ("pinhole", "", false),
    ("depth of field", LENS, false),
    ("motion blur", "", true),
    ("motion blur and depth of field", LENS, true),
    (
        "camera motion",
        ", motion: [(time: 0.0, eye: (0.0, 0.5, -1.0), look_at: (0.0, 0.3, 8.0)),
                    (time: 1.0, eye: (0.4, 0.7, -1.0), look_at: (0.2, 0.3, 8.0))]",
        true,
    ),
];

// Both hiders read the same sample positions, times and lens positions and filter them alike,
// so they differ only (a) where a sample's visibility differs: near silhouettes, where the
// flat micropolygons (about a pixel across at shading rate 1) and the hider's screen-space
// interpolation of motion stand off the true surface by a small fraction of a pixel, and
// (b) by shading: Gouraud-interpolated vertex colours against shading at the hit, which on
// these curved surfaces differ by the colour's second-order change across a micropolygon
// (1e-3 or so). With a few per cent of the samples near edges flipping at a contrast below
// 1 and filter weights of 1/16 or less, the mean squared error is of order 1e-4: 40 dB. A
// wrong lens, time or camera mapping moves whole edges by pixels and falls below 30 dB.
#[test]
fn both_hiders_draw_the_same_opaque_scenes() {
    let mut report = Vec::new();
    for (what, camera, moving) in CASES {
        let reyes = render_film(&opaque_scene(camera, moving, "Stochastic"), None);
        let rays = render_film(&opaque_scene(camera, moving, "RayTrace"), None);
        let p = psnr(&reyes, &rays);
        report.push(format!("{what}: {p:.1} dB"));
        assert!(p > 35.0, "{what}: PSNR {p:.1} dB");
    }
    eprintln!("PSNR, stochastic vs ray-tracing hider: {}", report.join(", "));
}

/// The ray hider over a stand-in for the shading: the unlit colour of the material hit.
fn standin_ray_hider(scene: &Scene, threads: Option<usize>) -> Film {
    let tracer = Tracer::new(scene);
    let opts = RenderOptions { threads, ..Default::default() };
    let standin = |ray: &Ray, t_max: f32, _: &mut Strata, _: &mut RayCounts| match tracer
        .intersect(ray, t_max)
    {
        Some(hit) => {
            let c = match &scene.objects[hit.object as usize].material {
                Material::Constant { color, .. } | Material::Matte { color, .. } => *color,
                _ => [1.0; 3],
            };
            Traced { rgba: [c[0], c[1], c[2], 1.0], t: hit.t }
        }
        None => Traced { rgba: [0.0; 4], t: f32::INFINITY },
    };
    render_with(scene, &opts, Duration::ZERO, (0, 0), standin).unwrap().film
}

// The ray hider's own visibility, with the shading taken out: every primary ray gets the
// unlit colour of what it hits, and the stochastic hider renders the same scene with
// Constant materials of those colours. They differ only where a sample's visibility
// differs, near silhouettes (see above): 40 dB or so, against below 30 dB for a wrong lens,
// time or camera mapping.
#[test]
fn the_ray_hiders_visibility_matches_the_stochastic_hiders() {
    for (what, camera, moving) in CASES {
        let mut reyes = opaque_scene(camera, moving, "Stochastic");
        reyes.lights.clear();
        for o in &mut reyes.objects {
            if let Material::Matte { color, opacity, .. } = o.material {
                o.material = Material::Constant { color, opacity };
            }
        }
        let reyes = render_film(&reyes, None);
        let rays = standin_ray_hider(&opaque_scene(camera, moving, "RayTrace"), None);
        let p = psnr(&reyes, &rays);
        assert!(p > 35.0, "{what}: PSNR {p:.1} dB");
    }
    // And its samples, like its shading, do not depend on the thread count.
    let s = opaque_scene(LENS, true, "RayTrace");
    assert!(standin_ray_hider(&s, Some(1)) == standin_ray_hider(&s, Some(3)));
}

/// A scene with every kind of secondary ray: an area light, glossy reflection, blurry
/// refraction, a lens and motion.
fn distributed_scene(method: &str) -> Scene {
    parse(&format!(
        "Scene(image: (width: 64, height: 48),
           camera: (eye: (0.0, 1.0, -4.0), look_at: (0.0, 0.5, 4.0), fov: 45.0 {LENS}),
           hider: (method: {method}, pixel_samples: (3, 3), seed: 9),
           raytrace: (vertex_rays: 2),
           lights: [Ambient(intensity: 0.1),
                    Area(shape: Disk(center: (1.0, 5.0, 2.0), normal: (0.0, -1.0, 0.0), radius: 1.0), intensity: 20.0)],
           objects: [
             (shape: BilinearPatch(points: ((-6.0, 0.0, -2.0), (6.0, 0.0, -2.0), (-6.0, 0.0, 12.0), (6.0, 0.0, 12.0))),
              material: Matte(color: (0.6, 0.6, 0.6)), reflect: Some((color: (0.3, 0.3, 0.3), gloss: 8.0))),
             (shape: Sphere(radius: 0.7),
              motion: [(time: 0.0, transform: [Translate((-0.8, 0.7, 3.0))]),
                       (time: 1.0, transform: [Translate((-0.3, 0.7, 3.0))])],
              material: Plastic(color: (0.9, 0.3, 0.2))),
             (shape: Sphere(radius: 0.6), transform: [Translate((0.9, 0.6, 2.0))],
              material: Plastic(color: (0.8, 0.9, 1.0), opacity: (0.3, 0.3, 0.3)),
              refract: Some((ior: 1.4, color: (0.8, 0.8, 0.8), blur: 5.0))),
           ])"
    ))
}

#[test]
fn the_ray_hider_is_deterministic_across_thread_counts() {
    let scene = distributed_scene("RayTrace");
    let one = render_film(&scene, Some(1));
    let two = render_film(&scene, Some(2));
    assert!(one.rgba().iter().any(|p| p[3] > 0.0));
    assert!(one == two, "the image depends on the thread count");
    // And so is the stochastic hider with ray-traced vertex shading.
    let scene = distributed_scene("Stochastic");
    assert!(render_film(&scene, Some(1)) == render_film(&scene, Some(2)));
}

// The penumbra set-up: a disk light of radius RL at height H above a ground plane, an opaque
// disk of radius RO at height HO between them, both centred on the vertical axis through the
// ground's origin. By similar triangles the umbra (no light point visible) on the ground has
// radius (RO H - RL HO)/(H - HO), and the penumbra ends at (RO H + RL HO)/(H - HO). The camera
// looks straight down from height E with PX pixels per ground unit at the image centre.
const H: f32 = 4.0;
const RL: f32 = 0.5;
const HO: f32 = 2.0;
const RO: f32 = 1.0;
const E: f32 = 20.0;
const SIZE: u32 = 80;
/// Pixels per unit at depth 1: (SIZE/2) / tan(fov/2) with tan(fov/2) = 0.2.
const K: f32 = 200.0;
const PX: f32 = K / E;

fn shadow_scene(method: &str, occluder: bool, vertex_rays: u32, seed: u64) -> Scene {
    let fov = 2.0 * 0.2f64.atan().to_degrees();
    let occluder = if occluder {
        format!(
            "(shape: Disk(radius: {RO}), transform: [Rotate(angle: 90.0, axis: (1.0, 0.0, 0.0)), Translate((0.0, {HO}, 0.0))],
              material: Constant(color: (0.0, 0.0, 0.0))),"
        )
    } else {
        String::new()
    };
    parse(&format!(
        "Scene(image: (width: {SIZE}, height: {SIZE}),
           camera: (eye: (0.0, {E}, 0.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 0.0, 1.0), fov: {fov}),
           hider: (method: {method}, pixel_samples: (4, 4), filter: (kind: Box, width: 1.0), seed: {seed}),
           raytrace: (vertex_rays: {vertex_rays}),
           lights: [Area(shape: Disk(center: (0.0, {H}, 0.0), normal: (0.0, -1.0, 0.0), radius: {RL}), intensity: 16.0)],
           objects: [
             (shape: BilinearPatch(points: ((-10.0, 0.0, -10.0), (10.0, 0.0, -10.0), (-10.0, 0.0, 10.0), (10.0, 0.0, 10.0))),
              material: Matte(color: (1.0, 1.0, 1.0), ka: 0.0, kd: 1.0)),
             {occluder}
           ])"
    ))
}

/// Distance of pixel (x, y)'s centre from the image centre, in pixels.
fn radius(x: u32, y: u32) -> f32 {
    let c = SIZE as f32 / 2.0;
    ((x as f32 + 0.5 - c).powi(2) + (y as f32 + 0.5 - c).powi(2)).sqrt()
}

/// Mean visible fraction of the light, shadowed over unshadowed ground (red channel), in
/// rings of half a pixel: `(ring centre radius, fraction)`.
fn visible_fraction(shadowed: &Film, open: &Film) -> Vec<(f32, f64)> {
    let bins = (SIZE as f32 / 2.0 * 2.0) as usize;
    let mut sum = vec![(0.0f64, 0usize); bins];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let b = (radius(x, y) * 2.0) as usize;
            if b < bins {
                let v = shadowed.pixel(x, y).unwrap()[0] / open.pixel(x, y).unwrap()[0];
                sum[b].0 += f64::from(v);
                sum[b].1 += 1;
            }
        }
    }
    sum.iter()
        .enumerate()
        .filter(|(_, (_, n))| *n > 0)
        .map(|(b, (s, n))| ((b as f32 + 0.5) / 2.0, s / *n as f64))
        .collect()
}

/// Where the visible fraction first rises above `eps` and first reaches `1 - eps`, outside
/// the occluder's own image (radius `RO K / (E - HO)` plus a pixel of filter and
/// rasterisation): the measured umbra and penumbra radii in pixels.
fn measured_radii(profile: &[(f32, f64)], eps: f64) -> (f32, f32) {
    let start = RO * K / (E - HO) + 1.0;
    let outside: Vec<_> = profile.iter().filter(|(r, _)| *r > start).collect();
    let umbra = outside.iter().find(|(_, v)| *v > eps).map_or(f32::NAN, |(r, _)| *r);
    let penumbra = outside.iter().find(|(_, v)| *v >= 1.0 - eps).map_or(f32::NAN, |(r, _)| *r);
    (umbra, penumbra)
}

// Predicted: umbra (1 * 4 - 0.5 * 2)/2 = 1.5 units = 15 px, penumbra (4 + 1)/2 = 2.5 units =
// 25 px. Tolerance 2 px, made of: (a) the threshold eps = 0.03: near either end the uncovered
// part of the light is a thin crescent whose area grows as d^1.5 with the distance d past
// the radius (here V ~ 2 d^1.5 near the umbra, 1 - V ~ 1.5 d^1.5 near the penumbra, d in
// ground units), so the fraction reaches eps about 0.06 units = 0.6 px past the radius;
// (b) the half-pixel rings and pixel footprint: 0.5 px; (c) noise: each ring averages 50 to
// 150 pixels of 16 stratified shadow rays each (the REYES path: micropolygons sharing
// vertices of 4 rays), a standard error below 0.01 in the fraction, which near the ends
// moves the crossing by well under a pixel. A mistake in the light or shadow geometry (a
// light twice the size, a point light, the occluder at the wrong height) moves an edge by
// 5 px or more.
#[test]
fn penumbra_radii_match_similar_triangles() {
    let predicted = ((RO * H - RL * HO) / (H - HO) * PX, (RO * H + RL * HO) / (H - HO) * PX);
    for (method, rays) in [("RayTrace", 1), ("Stochastic", 4)] {
        let shadowed = render_film(&shadow_scene(method, true, rays, 3), None);
        let open = render_film(&shadow_scene(method, false, rays, 3), None);
        let profile = visible_fraction(&shadowed, &open);
        let (umbra, penumbra) = measured_radii(&profile, 0.03);
        eprintln!(
            "{method}: umbra {umbra:.2} px (predicted {:.2}), penumbra {penumbra:.2} px (predicted {:.2})",
            predicted.0, predicted.1
        );
        assert!((umbra - predicted.0).abs() <= 2.0, "{method}: umbra {umbra} vs {}", predicted.0);
        assert!(
            (penumbra - predicted.1).abs() <= 2.0,
            "{method}: penumbra {penumbra} vs {}",
            predicted.1
        );
    }
}

// Noise of the REYES path's ray-traced vertex shading in the penumbra, measured seed against
// seed: two renders with different seeds differ only by their independent noise, so
// rms(a - b)/sqrt(2) is the noise of one (bias, such as the interpolation's blur, cancels).
// Each vertex averages R shadow rays drawn from a set of 16 R stratified over a 4 x 4 tile of
// vertices, so its variance falls at least as 1/R: noise 1 : 1/2 : 1/4 for R = 1, 4, 16. We
// ask for a fall by a quarter at each step (a vertex reusing one ray R times, or a set not
// spreading its members, does not fall at all).
#[test]
fn vertex_ray_noise_falls_as_vertex_rays_grow() {
    let ring = |x: u32, y: u32| {
        let r = radius(x, y);
        r > 17.0 && r < 23.0
    };
    let mut noise = Vec::new();
    let mut report = Vec::new();
    for rays in [1, 4, 16] {
        let t = Instant::now();
        let a = render_film(&shadow_scene("Stochastic", true, rays, 1), None);
        let secs = t.elapsed().as_secs_f64();
        let b = render_film(&shadow_scene("Stochastic", true, rays, 2), None);
        let (mut se, mut n) = (0.0f64, 0);
        for y in 0..SIZE {
            for x in 0..SIZE {
                if ring(x, y) {
                    let d = a.pixel(x, y).unwrap()[0] - b.pixel(x, y).unwrap()[0];
                    se += f64::from(d).powi(2);
                    n += 1;
                }
            }
        }
        let sd = (se / n as f64 / 2.0).sqrt();
        report.push(format!("vertex_rays {rays}: noise {sd:.4}, {secs:.3} s"));
        noise.push(sd);
    }
    eprintln!("penumbra noise (ring 17-23 px): {}", report.join("; "));
    assert!(noise[1] < 0.75 * noise[0], "{}", report.join("; "));
    assert!(noise[2] < 0.75 * noise[1], "{}", report.join("; "));
}
