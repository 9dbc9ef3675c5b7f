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
//! Each bucket first polls [`cancel::requested`]; a cancelled frame ends with
//! [`RenderError::Cancelled`].
//!
//! Invariant (determinism): a sample's result depends only on the scene, the seed, its pixel
//! and its index: the pixel's `NS` samples form one stratified set of secondary-ray choices
//! ([`Strata::new`]`(seed, hash(pixel), s, NS)`), so the image is bit-identical for any
//! thread count.

use std::time::{Duration, Instant};

use glam::Vec2;
use rayon::prelude::*;
use reyes_film::{Film, Window};
use reyes_sampling::{Strata, hash};
use reyes_scene::Scene;
use reyes_shade::{RayCounts, Shading, Traced};
use reyes_trace::{Ray, Tracer};

use crate::buckets::{self, BucketResult};
use crate::cancel;
use crate::pool::{self, Pool};
use crate::settings::Stages;
use crate::stats::{RaySummary, RenderStats};
use crate::{RenderError, RenderOptions, Rendered};

/// Key of the per-pixel stratified sets ("pixel").
const PIXEL_SET: u64 = 0x0070_6978_656c;

/// Render `scene` with the ray-tracing hider: primary rays shaded by
/// [`Shading::trace`] with the distributed rays of the materials and lights.
pub fn render_raytraced(scene: &Scene, opts: &RenderOptions) -> Result<Rendered, RenderError> {
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
pub fn render_with<F>(
    scene: &Scene,
    opts: &RenderOptions,
    t_build: Duration,
    engine: (u64, u64),
    trace: F,
) -> Result<Rendered, RenderError>
where
    F: Fn(&Ray, f32, &mut Strata, &mut RayCounts) -> Traced + Sync,
{
    let Stages { frame, camera, hider, table } = Stages::new(scene, |hider| hider)?;
    let pool = Pool::new(opts.threads)?;
    let ns = hider.ns();
    let seed = scene.hider.seed;
    let moving = !scene.camera.motion.is_empty();
    let (hither, yon) = (camera.hither(), camera.yon());
    let t_max = yon - hither;

    let selected = match opts.buckets {
        Some(list) => list.to_vec(),
        None => buckets::scene_buckets(scene, &frame),
    };
    let t1 = Instant::now();
    let results = pool.install(|| {
        selected
            .par_iter()
            .map_init(Buffers::default, |buf, &b| {
                if cancel::requested() {
                    // Skipped: the frame is discarded below.
                    return (BucketResult::default(), Default::default());
                }
                if let Some(r) = opts.done.and_then(|d| d.get(&b)) {
                    return (r.clone(), Default::default());
                }
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
                        let k = pixel * ns + s;
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
                    pool::splat_bucket(&table, &frame, b, &buf.rgba, &buf.z, &mut buf.window);
                    Some(buf.window.clone())
                };
                let result = BucketResult { window: result, aov: None };
                if let Some(cb) = opts.on_result {
                    cb(b, &result);
                }
                if let Some(cb) = opts.on_bucket {
                    cb();
                }
                (result, (primary, hits, counts))
            })
            .collect::<Vec<_>>()
    });
    let t_hide = t1.elapsed();
    if cancel::requested() {
        return Err(RenderError::Cancelled);
    }

    // Fixed order: bucket raster order, whatever order the buckets finished in.
    let t2 = Instant::now();
    let mut film = Film::new(scene.image.width, scene.image.height);
    let mut rays =
        RaySummary { ray_hider: true, primitives: engine.0, nodes: engine.1, ..Default::default() };
    let mut buckets_rendered = 0;
    let mut kept = Vec::new();
    for (&b, (result, (primary, hits, counts))) in selected.iter().zip(results) {
        rays.primary += primary;
        rays.hits += hits;
        rays.secondary.add(&counts);
        buckets_rendered += usize::from(result.window.is_some());
        buckets::add(&mut film, None, &result);
        if opts.keep_buckets {
            kept.push((b, result));
        }
    }
    let t_film = t2.elapsed();
    let stats = RenderStats {
        buckets_rendered,
        hider: reyes_hider::Stats {
            hits: rays.hits,
            misses: rays.primary - rays.hits,
            ..Default::default()
        },
        t_dice: t_build,
        t_hide,
        t_film,
        rays: Some(rays),
        ..RenderStats::new(scene, hider.config(), frame)
    };
    Ok(Rendered { film, stats, aovs: None, buckets: kept, warnings: Vec::new() })
}
