//! The ray-tracing hider (Appendix B, `pray.c`): one primary ray per sample instead of
//! dicing and point-sampling micropolygons.
//!
//! Everything but visibility is shared with the stochastic hider, so the two images agree
//! where the scene allows: the samples (positions, times, lens positions) come from the same
//! [`Hider`] tables and per-bucket generation, the per-sample composites are laid out as the
//! hider's `BucketOutput` (`pixel * NS + s`) and go through the same filter table, `splat`,
//! bucket windows and film, added in bucket raster order.
//!
//! The primary ray of a sample is [`CameraSetup::primary_ray`] of the camera at the sample's
//! time ([`CameraSetup::at_time`]): from the lens point `-R (lx, ly)` on the lens plane
//! through the pinhole point of the sample's raster position on the plane of focus (eye depth
//! `focal_distance`), so that every point the stochastic hider draws at that raster position
//! for that lens position lies on the ray. Appendix B aimed at the point at Euclidean
//! distance `focaldistance` along the pinhole ray (a spherical surface of focus, its 3.4); we
//! keep Appendix A's plane so that both hiders focus alike. The ray starts at the hither
//! plane and ends at the yon plane: its direction has unit eye-depth component, so the ray
//! parameter plus `hither` is the eye depth written to the film's z.
//!
//! Invariant (determinism): a sample's result depends only on the scene, the seed, its pixel
//! and its index: the pixel's `NS` samples form one stratified set of secondary-ray choices
//! ([`Strata::new`]`(seed, hash(pixel), s, NS)`), so the image is bit-identical for any
//! thread count.

use std::time::{Duration, Instant};

use glam::Vec2;
use rayon::prelude::*;
use reyes_dice::CameraSetup;
use reyes_film::{Film, Window, splat};
use reyes_hider::Hider;
use reyes_sampling::Strata;
use reyes_sampling::hash;
use reyes_scene::Scene;
use reyes_shade::{RayCounts, Shading, Traced};
use reyes_trace::{Ray, Tracer};

use crate::{
    RaySummary, RenderError, RenderOptions, RenderStats, Rendered, filter_table, frame_for,
    hider_config,
};

/// Key of the per-pixel stratified sets ("pixel").
const PIXEL_SET: u64 = 0x0070_6978_656c;

/// Render `scene` with the ray-tracing hider: primary rays shaded by
/// [`Shading::trace`] with the distributed rays of the materials and lights.
pub(crate) fn render_raytraced(
    scene: &Scene,
    opts: &RenderOptions,
) -> Result<Rendered, RenderError> {
    let t0 = Instant::now();
    let tracer = Tracer::new(scene);
    let shading = Shading::new(scene, &tracer);
    let engine = (tracer.primitive_count() as u64, tracer.node_count() as u64);
    let t_build = t0.elapsed();
    render_with(scene, opts, t_build, engine, |ray, t_max, strata, counts| {
        shading.trace_counted(ray, t_max, strata, counts)
    })
}

/// Per-thread buffers, reused from bucket to bucket.
#[derive(Default)]
struct Buffers {
    window: Window,
    rgba: Vec<[f32; 4]>,
    z: Vec<f32>,
}

/// The ray-tracing hider over any `trace` (the real shading, or a stand-in in tests):
/// `trace(ray, t_max, strata, counts)` is what a primary ray sees up to parameter `t_max`,
/// adding the secondary rays it traces to `counts`.
/// `t_build` is the time spent building the ray engine and `engine` its (primitive, node)
/// counts, for the statistics.
pub(crate) fn render_with<F>(
    scene: &Scene,
    opts: &RenderOptions,
    t_build: Duration,
    engine: (u64, u64),
    trace: F,
) -> Result<Rendered, RenderError>
where
    F: Fn(&Ray, f32, &mut Strata, &mut RayCounts) -> Traced + Sync,
{
    let frame = frame_for(scene);
    let camera = CameraSetup::new(scene);
    let config = hider_config(scene, &camera);
    let hider = Hider::new(config, frame);
    let table = filter_table(scene, &hider).map_err(RenderError::Film)?;
    let ns = hider.ns();
    let seed = scene.hider.seed;
    let moving = !scene.camera.motion.is_empty();
    let (hither, yon) = (camera.hither(), camera.yon());
    let t_max = yon - hither;

    let t1 = Instant::now();
    let run = || {
        (0..frame.bucket_count())
            .into_par_iter()
            .map_init(Buffers::default, |buf, b| {
                let (left, top) = frame.bucket_origin(b);
                let (bw, bh) = (frame.bucket_w as usize, frame.bucket_h as usize);
                let p_count = bw * bh;
                let smp = hider.bucket_samples(b);
                buf.rgba.clear();
                buf.rgba.resize(p_count * ns, [0.0; 4]);
                buf.z.clear();
                buf.z.resize(p_count * ns, f32::INFINITY);
                let mut hits = 0;
                let mut counts = RayCounts::default();
                for pixel in 0..p_count {
                    let gx = left as i64 + (pixel % bw) as i64;
                    let gy = top as i64 + (pixel / bw) as i64;
                    let set = hash(seed, &[PIXEL_SET, gx as u64, gy as u64]);
                    for s in 0..ns {
                        let k = s * p_count + pixel;
                        let time = smp.t[k];
                        let raster = Vec2::new(left as f32 + smp.x[k], top as f32 + smp.y[k]);
                        let lens = (smp.lx[k], smp.ly[k]);
                        let (origin, dir) = if moving {
                            camera.at_time(scene, time).primary_ray(raster, lens)
                        } else {
                            camera.primary_ray(raster, lens)
                        };
                        let ray = Ray::new(origin + dir * hither, dir, time);
                        let mut strata = Strata::new(seed, set, s as u32, ns as u32);
                        let seen = trace(&ray, t_max, &mut strata, &mut counts);
                        let out = pixel * ns + s;
                        buf.rgba[out] = seen.rgba;
                        if seen.t.is_finite() {
                            buf.z[out] = hither + seen.t;
                        }
                        if seen.t.is_finite() || seen.rgba != [0.0; 4] {
                            hits += 1;
                        }
                    }
                }
                let primary = (p_count * ns) as u64;
                let result = if hits == 0 {
                    // Nothing seen: the window would add nothing to the film.
                    None
                } else {
                    splat(
                        &table,
                        left,
                        top,
                        frame.bucket_w,
                        frame.bucket_h,
                        &buf.rgba,
                        &buf.z,
                        &mut buf.window,
                    );
                    Some(buf.window.clone())
                };
                if let Some(cb) = opts.on_bucket {
                    cb();
                }
                (result, primary, hits, counts)
            })
            .collect::<Vec<_>>()
    };
    let results = match opts.threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| RenderError::Threads(e.to_string()))?
            .install(run),
        None => run(),
    };
    let t_hide = t1.elapsed();

    // Fixed order: bucket raster order, whatever order the buckets finished in.
    let t2 = Instant::now();
    let mut film = Film::new(scene.image.width, scene.image.height);
    let mut rays =
        RaySummary { ray_hider: true, primitives: engine.0, nodes: engine.1, ..Default::default() };
    let mut buckets_rendered = 0;
    for (window, primary, hits, counts) in &results {
        rays.primary += primary;
        rays.hits += hits;
        rays.secondary.add(counts);
        if let Some(w) = window {
            film.add(w);
            buckets_rendered += 1;
        }
    }
    let t_film = t2.elapsed();
    let stats = RenderStats {
        width: scene.image.width,
        height: scene.image.height,
        samples: (config.nx, config.ny),
        filter: scene.hider.filter,
        frame,
        buckets_rendered,
        dice: Default::default(),
        micropolygons: 0,
        hider: reyes_hider::Stats {
            hits: rays.hits,
            misses: rays.primary - rays.hits,
            ..Default::default()
        },
        t_dice: t_build,
        t_hide,
        t_film,
        t_write: Default::default(),
        peak_memory: None,
        rays: Some(rays),
    };
    Ok(Rendered { film, stats })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render;
    use reyes_scene::Material;

    /// An opaque scene of constant colours: spheres, a bilinear patch, a mesh and a torus,
    /// with `camera` (extra camera fields) and, when `moving`, moving objects.
    fn scene(camera: &str, moving: bool, method: &str) -> Scene {
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
        let text = format!(
            "Scene(image: (width: 96, height: 72),
               camera: (eye: (0.0, 0.5, -1.0), look_at: (0.0, 0.3, 8.0), fov: 40.0, hither: 0.5, yon: 40.0 {camera}),
               hider: (method: {method}, pixel_samples: (4, 4), filter: (kind: Gaussian, width: 2.0), seed: 11),
               objects: [
                 (shape: BilinearPatch(points: ((-6.0, -0.8, 1.0), (6.0, -0.8, 1.0), (-6.0, -0.8, 30.0), (6.0, -0.8, 30.0))),
                  material: Constant(color: (0.3, 0.35, 0.4))),
                 (shape: Sphere(radius: 0.8), transform: [Translate((-1.3, 0.2, 6.0))], {sphere_motion}
                  material: Constant(color: (0.9, 0.2, 0.1))),
                 (shape: Sphere(radius: 0.5, zmin: Some(-0.3), thetamax: 300.0),
                  transform: [Rotate(angle: -90.0, axis: (1.0, 0.0, 0.0)), Translate((1.6, 0.6, 5.0))],
                  material: Constant(color: (0.2, 0.8, 0.3))),
                 (shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.3), (0.0, 1.0, 0.0), (0.5, 1.8, 0.2)],
                              faces: [[0, 1, 2, 3], [3, 2, 4]]),
                  transform: [Translate((1.0, -0.6, 9.0))],
                  material: Constant(color: (0.9, 0.9, 0.2))),
                 (shape: Torus(major_radius: 0.7, minor_radius: 0.25),
                  transform: [Rotate(angle: 60.0, axis: (1.0, 0.0, 0.0)), Translate((0.3, 1.1, 8.0))], {torus_motion}
                  material: Constant(color: (0.2, 0.4, 0.95))),
               ])"
        );
        reyes_scene::parse(&text, std::path::Path::new("test.ron")).unwrap()
    }

    /// The ray hider with a stand-in for the shading: the constant colour of the object hit.
    fn ray_hider(scene: &Scene, threads: Option<usize>) -> Film {
        let tracer = Tracer::new(scene);
        let opts = RenderOptions { threads, ..Default::default() };
        let standin = |ray: &Ray, t_max: f32, _: &mut Strata, _: &mut RayCounts| match tracer
            .intersect(ray, t_max)
        {
            Some(hit) => {
                let c = match &scene.objects[hit.object as usize].material {
                    Material::Constant { color, .. } => *color,
                    _ => [1.0; 3],
                };
                Traced { rgba: [c[0], c[1], c[2], 1.0], t: hit.t }
            }
            None => Traced { rgba: [0.0; 4], t: f32::INFINITY },
        };
        render_with(scene, &opts, Duration::ZERO, (0, 0), standin).unwrap().film
    }

    /// Peak signal-to-noise ratio of `b` against `a` over every channel of RGBA (peak 1).
    fn psnr(a: &Film, b: &Film) -> f64 {
        let (mut se, mut n) = (0.0f64, 0usize);
        for y in 0..a.height() {
            for x in 0..a.width() {
                let (p, q) = (a.pixel(x, y).unwrap(), b.pixel(x, y).unwrap());
                for c in 0..4 {
                    se += f64::from(p[c] - q[c]).powi(2);
                    n += 1;
                }
            }
        }
        10.0 * (n as f64 / se.max(1e-30)).log10()
    }

    fn compare(camera: &str, moving: bool) -> f64 {
        let reyes = render(&scene(camera, moving, "Stochastic"), &Default::default()).unwrap();
        let rays = ray_hider(&scene(camera, moving, "RayTrace"), None);
        psnr(&reyes.film, &rays)
    }

    // Both hiders read the same samples, so they differ only where a sample's visibility
    // differs: near silhouettes, where the micropolygons' flat facets (about a pixel across)
    // and the hider's screen-space motion interpolation stand off the true surface by a
    // small fraction of a pixel. A sample flipping there costs at most the colour contrast
    // (< 1) times its filter weight; a few per cent of edge samples flipping gives an MSE of
    // order 1e-4 over the image, 40 dB. A wrong lens or time mapping moves whole edges by
    // pixels and falls below 30 dB.
    #[test]
    fn the_ray_hider_draws_what_the_stochastic_hider_draws() {
        let pinhole = compare("", false);
        let lens =
            compare(", lens: Some((focal_length: 0.4, f_stop: 2.0, focal_distance: 6.0))", false);
        let blur = compare("", true);
        let camera_motion = compare(
            ", motion: [(time: 0.0, eye: (0.0, 0.5, -1.0), look_at: (0.0, 0.3, 8.0)),
                        (time: 1.0, eye: (0.4, 0.7, -1.0), look_at: (0.2, 0.3, 8.0))]",
            true,
        );
        eprintln!(
            "PSNR pinhole {pinhole:.1} dB, lens {lens:.1}, motion {blur:.1}, camera motion {camera_motion:.1}"
        );
        for (what, p) in
            [("pinhole", pinhole), ("lens", lens), ("motion", blur), ("camera", camera_motion)]
        {
            assert!(p > 35.0, "{what}: PSNR {p:.1} dB");
        }
    }

    #[test]
    fn the_ray_hider_is_deterministic_across_threads() {
        let s = scene(
            ", lens: Some((focal_length: 0.4, f_stop: 2.0, focal_distance: 6.0))",
            true,
            "RayTrace",
        );
        let a = ray_hider(&s, Some(1));
        let b = ray_hider(&s, Some(3));
        assert!(a == b, "thread count changed the image");
    }
}
