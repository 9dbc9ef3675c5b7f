//! reyes-render library: wires the stages together (scene → dicer → hider → film) and owns
//! the one parallel loop of the renderer, over buckets.
//!
//! Invariant (determinism): every bucket's result depends only on the scene, the seed and the
//! bucket index, and bucket windows are added to the image in bucket raster order, so the
//! output is bit-identical for any thread count and scheduling.
#![deny(missing_docs)]

pub mod golden;
pub mod measure;
mod rayhide;
mod stats;
pub mod study;
mod vertex;

use std::time::{Duration, Instant};

use rayon::prelude::*;
use reyes_dice::{CameraSetup, DiceError, DiceOptions, DiceStats, Dicer};
use reyes_film::{Film, FilterTable, Window, splat};
use reyes_hider::{
    Frame, Hider, HiderConfig, LensShape, MatteRule, Pairing, Pattern, Scratch, ShutterShape,
    border_for_filter_width,
};
use reyes_scene::{Scene, SpatialPattern};

pub use stats::{RaySummary, RenderStats, peak_memory};

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
        shutter: shutter_shape(scene.camera.shutter.shape),
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

/// The filter table of a scene's `hider.filter` over `hider`'s sample locations (shared by
/// both hiders and the golden tolerance).
pub fn filter_table(scene: &Scene, hider: &Hider) -> Result<FilterTable, reyes_film::FilmError> {
    let f = &scene.hider.filter;
    let config = hider.config();
    FilterTable::new(
        f.kind,
        f.width,
        config.nx,
        config.ny,
        &hider.tables().location,
        &scene.hider.original,
    )
}

/// The hider's time density for a scene's shutter shape.
pub(crate) fn shutter_shape(shape: reyes_scene::ShutterShape) -> ShutterShape {
    match shape {
        reyes_scene::ShutterShape::Uniform => ShutterShape::Uniform,
        reyes_scene::ShutterShape::Gradual { ramp } => ShutterShape::Gradual { ramp },
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
    if scene.hider.method == reyes_scene::HiderMethod::RayTrace {
        return rayhide::render_raytraced(scene, opts);
    }
    if reyes_shade::Shading::needed(scene) {
        // Shadows, area lights, reflection, refraction or patterns: ray-traced vertex shading.
        return vertex::render_shaded(scene, opts);
    }
    // The dicer shades vertices with its own local illumination.
    let dice_options = DiceOptions::default();
    render_diced(scene, opts, &dice_options)
}

/// Render a validated scene with the stochastic hider, dicing it lazily row of buckets by row
/// of buckets ([`Dicer`]) with `dice_options`. Should a patch bound miss (a micropolygon
/// touching a row already rendered), the frame is rendered again with the whole scene
/// diced up front, which gives the same image.
pub fn render_diced(
    scene: &Scene,
    opts: &RenderOptions,
    dice_options: &DiceOptions<'_>,
) -> Result<Rendered, RenderError> {
    let pool = match opts.threads {
        Some(n) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| RenderError::Threads(e.to_string()))?,
        ),
        None => None,
    };
    let run = |eager: bool| match &pool {
        Some(pool) => pool.install(|| render_rows(scene, opts, dice_options, eager)),
        None => render_rows(scene, opts, dice_options, eager),
    };
    match run(false) {
        Err(RenderError::Dice(DiceError::BoundMissed { .. })) => run(true),
        result => result,
    }
}

/// The bucket loop: per row of buckets, dice what it needs, render its buckets in parallel,
/// add their windows to the film in raster order, release what no later row needs.
fn render_rows(
    scene: &Scene,
    opts: &RenderOptions,
    dice_options: &DiceOptions<'_>,
    eager: bool,
) -> Result<Rendered, RenderError> {
    let t0 = Instant::now();
    let frame = frame_for(scene);
    let camera = CameraSetup::new(scene);
    let config = hider_config(scene, &camera);
    let mut dicer = if eager {
        Dicer::new_eager(scene, &frame, dice_options)
    } else {
        Dicer::new(scene, &frame, dice_options)
    }
    .map_err(RenderError::Dice)?;
    let mut t_dice = t0.elapsed();

    let hider = Hider::new(config, frame).with_csg(dicer.csg_trees().to_vec());
    let table = filter_table(scene, &hider).map_err(RenderError::Film)?;

    let (mut t_hide, mut t_film) = (Duration::ZERO, Duration::ZERO);
    let mut film = Film::new(scene.image.width, scene.image.height);
    let mut hider_stats = reyes_hider::Stats::default();
    let mut buckets_rendered = 0;
    let across = frame.buckets_x as usize;
    for row in 0..dicer.rows() {
        let t = Instant::now();
        dicer.dice_row(row).map_err(RenderError::Dice)?;
        t_dice += t.elapsed();

        let t = Instant::now();
        let first = row as usize * across;
        let diced = &dicer;
        let results = (first..first + across)
            .into_par_iter()
            .map_init(
                || (Scratch::new(), Window::default(), Vec::new(), Vec::new()),
                |(scratch, window, mpolys, list), b| {
                    let result = if diced.bucket_len(b) == 0 {
                        // Appendix A's `emptybucket`: nothing to display.
                        None
                    } else {
                        // The bucket's own contiguous copy, indexed 0..n.
                        diced.copy_bucket(b, mpolys);
                        let n = mpolys.len() as u32;
                        if (list.len() as u32) < n {
                            list.extend(list.len() as u32..n);
                        }
                        scratch.stats = Default::default();
                        let out = hider.render_bucket(b, mpolys, &list[..n as usize], scratch);
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
            .collect::<Vec<_>>();
        t_hide += t.elapsed();

        // Fixed order: bucket raster order, whatever order the buckets finished in.
        let t = Instant::now();
        for (window, s) in results.iter().flatten() {
            film.add(window);
            hider_stats.merge(s);
            buckets_rendered += 1;
        }
        t_film += t.elapsed();
        dicer.release_row(row);
    }
    let dice_stats = dicer.stats();

    let stats = RenderStats {
        width: scene.image.width,
        height: scene.image.height,
        samples: (config.nx, config.ny),
        filter: scene.hider.filter,
        frame,
        buckets_rendered,
        dice: stats::DiceSummary {
            peak_micropolygons: dicer.peak_micropolygons(),
            eager,
            ..dice_summary(&dice_stats)
        },
        micropolygons: dice_stats.micropolygons,
        hider: hider_stats,
        t_dice,
        t_hide,
        t_film,
        t_write: Default::default(),
        peak_memory: None,
        rays: None,
    };
    Ok(Rendered { film, stats })
}

fn dice_summary(d: &DiceStats) -> stats::DiceSummary {
    stats::DiceSummary {
        primitives: d.primitives,
        splits: d.splits,
        grids: d.grids,
        culled: d.culled,
        peak_micropolygons: 0,
        eager: false,
    }
}
