//! reyes-render library: wires the stages together (scene → dicer → hider → film) and owns
//! the one parallel loop of the renderer, over buckets.
//!
//! Invariant (determinism): every bucket's result depends only on the scene, the seed and the
//! bucket index, and bucket windows are added to the image in bucket raster order, so the
//! output is bit-identical for any thread count and scheduling.
#![deny(missing_docs)]

pub mod golden;
pub mod measure;
mod stats;
pub mod study;

use std::time::Instant;

use rayon::prelude::*;
use reyes_dice::{CameraSetup, DiceStats, dice_scene};
use reyes_film::{Film, FilterTable, Window, splat};
use reyes_hider::{
    Frame, Hider, HiderConfig, LensShape, MatteRule, Pairing, Pattern, Scratch, ShutterShape,
    border_for_filter_width,
};
use reyes_scene::{Scene, SpatialPattern};

pub use stats::{RenderStats, peak_memory};

/// Errors while rendering a valid scene.
#[derive(Debug)]
pub enum RenderError {
    /// The dicer failed.
    Dice(reyes_dice::DiceError),
    /// The film stage failed (e.g. a degenerate filter).
    Film(reyes_film::FilmError),
    /// The thread pool could not be built.
    Threads(String),
}

impl std::fmt::Display for RenderError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RenderError::Dice(e) => write!(f, "dicing failed: {e}"),
            RenderError::Film(e) => write!(f, "{e}"),
            RenderError::Threads(e) => write!(f, "cannot start render threads: {e}"),
        }
    }
}

impl std::error::Error for RenderError {}

/// Options that are not part of the scene.
#[derive(Default)]
pub struct RenderOptions<'a> {
    /// Worker threads (None: rayon's default, one per core).
    pub threads: Option<usize>,
    /// Called once per finished bucket (from worker threads), e.g. to advance a progress bar.
    pub on_bucket: Option<&'a (dyn Fn() + Sync)>,
}

/// A rendered frame.
pub struct Rendered {
    /// The image.
    pub film: Film,
    /// What it took.
    pub stats: RenderStats,
}

/// The hider configuration a scene asks for.
pub fn hider_config(scene: &Scene, camera: &CameraSetup) -> HiderConfig {
    let h = &scene.hider;
    let pattern = if !h.jitter {
        Pattern::Regular
    } else {
        match h.pattern {
            SpatialPattern::Fig5 => Pattern::Fig5,
            SpatialPattern::Fig6 => Pattern::Fig6,
            SpatialPattern::Fig7 => Pattern::Fig7,
            SpatialPattern::Random => Pattern::Random,
            SpatialPattern::Sobol => Pattern::Sobol,
        }
    };
    HiderConfig {
        nx: h.pixel_samples.0,
        ny: h.pixel_samples.1,
        pattern,
        time_pairing: if h.original.time_pairing {
            Pairing::Original
        } else {
            Pairing::Decorrelated
        },
        time_pattern: match h.time_pattern {
            reyes_scene::TimePattern::Fig13 => reyes_hider::TimePattern::Fig13,
            reyes_scene::TimePattern::Fig14 => reyes_hider::TimePattern::Fig14,
            reyes_scene::TimePattern::Fig15 => reyes_hider::TimePattern::Fig15,
        },
        shutter: match scene.camera.shutter.shape {
            reyes_scene::ShutterShape::Uniform => ShutterShape::Uniform,
            reyes_scene::ShutterShape::Gradual { ramp } => ShutterShape::Gradual { ramp },
        },
        lens_shape: if h.original.lens { LensShape::OriginalSquare } else { LensShape::Disk },
        lens: camera.lens(),
        hither: scene.camera.hither,
        yon: scene.camera.yon,
        seed: h.seed,
        original_permute: h.original.permute,
        original_jitter_tables: h.original.jitter_tables,
        original_moving_clip: h.original.moving_clip,
        matte: if h.original.matte { MatteRule::Original } else { MatteRule::Holdout },
        csg_order: if h.original.csg_order {
            reyes_hider::CsgOrder::Original
        } else {
            reyes_hider::CsgOrder::Exact
        },
        scan_all: false,
    }
}

/// The bucket layout a scene asks for.
pub fn frame_for(scene: &Scene) -> Frame {
    Frame::new(
        scene.image.width,
        scene.image.height,
        border_for_filter_width(scene.hider.filter.width),
        scene.hider.bucket_size.0,
        scene.hider.bucket_size.1,
    )
}

/// Render a validated scene.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Result<Rendered, RenderError> {
    let t0 = Instant::now();
    let frame = frame_for(scene);
    let camera = CameraSetup::new(scene);
    let config = hider_config(scene, &camera);
    let diced = dice_scene(scene, &frame).map_err(RenderError::Dice)?;
    let t_dice = t0.elapsed();

    let hider = Hider::new(config, frame).with_csg(diced.csg_trees.clone());
    let f = &scene.hider.filter;
    let table = FilterTable::new(
        f.kind,
        f.width,
        config.nx,
        config.ny,
        &hider.tables().location,
        &scene.hider.original,
    )
    .map_err(RenderError::Film)?;

    let t1 = Instant::now();
    let run = || {
        (0..frame.bucket_count())
            .into_par_iter()
            .map_init(
                || (Scratch::new(), Window::default()),
                |(scratch, window), b| {
                    let list = &diced.buckets[b];
                    let result = if list.is_empty() {
                        // Appendix A's `emptybucket`: nothing to display.
                        None
                    } else {
                        scratch.stats = Default::default();
                        let out = hider.render_bucket(b, &diced.mpolys, list, scratch);
                        let (left, top) = frame.bucket_origin(b);
                        splat(
                            &table,
                            left,
                            top,
                            frame.bucket_w,
                            frame.bucket_h,
                            out.rgba,
                            out.z,
                            window,
                        );
                        Some((window.clone(), scratch.stats))
                    };
                    if let Some(cb) = opts.on_bucket {
                        cb();
                    }
                    result
                },
            )
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
    let mut hider_stats = reyes_hider::Stats::default();
    let mut buckets_rendered = 0;
    for (window, s) in results.iter().flatten() {
        film.add(window);
        hider_stats.merge(s);
        buckets_rendered += 1;
    }
    let t_film = t2.elapsed();

    let stats = RenderStats {
        width: scene.image.width,
        height: scene.image.height,
        samples: (config.nx, config.ny),
        filter: *f,
        frame,
        buckets_rendered,
        dice: dice_summary(&diced.stats),
        micropolygons: diced.mpolys.len() as u64,
        hider: hider_stats,
        t_dice,
        t_hide,
        t_film,
        t_write: Default::default(),
        peak_memory: None,
    };
    Ok(Rendered { film, stats })
}

fn dice_summary(d: &DiceStats) -> stats::DiceSummary {
    stats::DiceSummary {
        primitives: d.primitives,
        splits: d.splits,
        grids: d.grids,
        culled: d.culled,
    }
}
