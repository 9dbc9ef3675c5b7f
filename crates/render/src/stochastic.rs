//! The stochastic hider's frame (Appendix A): dice, shade and bucket the scene row of
//! buckets by row of buckets ([`Dicer`]), render each row's buckets in parallel with the
//! [`Hider`], splat their samples through the filter table, and add their windows to the
//! film in bucket raster order.
//!
//! Vertices are shaded by the dicer's local illumination, or, when the scene needs shadows,
//! area lights, reflection, refraction or patterns ([`Shading::needed`]), by the distributed
//! rays of [`RayVertexShader`].
//!
//! Each bucket first polls [`cancel::requested`]; a cancelled row is discarded and the frame
//! ends with [`RenderError::Cancelled`].
//!
//! Invariant (determinism): a bucket's window depends only on the scene, the seed and the
//! bucket; windows are added in raster order ([`buckets::assemble`]'s order), whichever
//! buckets this render draws and whichever it was handed already done.

use std::sync::Mutex;
use std::time::{Duration, Instant};

use rayon::prelude::*;
use reyes_dice::{DiceError, DiceOptions, DiceStats, Dicer, Lookdev};
use reyes_film::{AovFilm, AovSamples, AovWindow, Film, Window};
use reyes_hider::Scratch;
use reyes_scene::Scene;
use reyes_shade::{RayVertexShader, Shading};
use reyes_trace::Tracer;

use crate::aovs::{AovSetup, RenderedAovs};
use crate::buckets::{self, BucketResult};
use crate::cancel;
use crate::pool::{self, Pool};
use crate::settings::{Stages, frame_for, shutter_shape};
use crate::stats::{DiceSummary, LookdevSummary, RaySummary, RenderStats, ShaderSummary};
use crate::{RenderError, RenderOptions, Rendered};

/// Render `scene` with the stochastic hider, shading vertices with distributed rays where
/// the scene needs them and with the dicer's local illumination otherwise.
pub(crate) fn render_stochastic(
    scene: &Scene,
    opts: &RenderOptions,
) -> Result<Rendered, RenderError> {
    let lookdev = match scene.has_lookdev() {
        true => Some(Lookdev::load(scene).map_err(reyes_dice::DiceError::from)?),
        false => None,
    };
    let mut rendered = if Shading::needed(scene) {
        render_shaded(scene, opts, lookdev.as_ref())
    } else {
        render_diced(scene, opts, &DiceOptions { lookdev: lookdev.as_ref(), ..Default::default() })
    }?;
    if let Some(s) = rendered.stats.shaders.filter(|s| s.escapes > 0 && lookdev.is_none()) {
        rendered.warnings.push(format!(
            "{} micropolygons were displaced beyond their object's declared displacement bound (Attribute \"displacementbound\"); parts of them may be missing",
            s.escapes
        ));
    }
    if let Some(s) = rendered.stats.shaders.filter(|s| s.nonfinite > 0) {
        rendered.warnings.push(format!(
            "shaders produced {} non-finite values (NaN or infinite), rendered as 0",
            s.nonfinite
        ));
    }
    if let Some(l) = &lookdev {
        if l.read_failed() {
            return Err(RenderError::TextureRead);
        }
        rendered.warnings.extend(l.warnings().iter().cloned());
        rendered.warnings.extend(l.lookup_warnings());
        if let Some(s) = rendered.stats.lookdev.as_mut() {
            s.textures = l.texture_stats();
            if s.escapes > 0 {
                rendered.warnings.push(format!(
                    "{} micropolygons were displaced beyond their object's declared displacement bound (rendered whole: bounds use the displacement's own)",
                    s.escapes
                ));
            }
        }
    }
    Ok(rendered)
}

/// Render `scene` with the stochastic hider and ray-traced vertex shading. The statistics
/// gain the vertex and secondary-ray counts.
fn render_shaded(
    scene: &Scene,
    opts: &RenderOptions,
    lookdev: Option<&Lookdev>,
) -> Result<Rendered, RenderError> {
    // Validation refuses shading-component AOVs with ray-traced shading (outputs.rs).
    debug_assert!(!AovSetup::has_components(scene));
    let t0 = Instant::now();
    let tracer = Tracer::new(scene);
    let shading = Shading::new(scene, &tracer);
    let shader = RayVertexShader::new(scene, &shading, shutter_shape(scene.camera.shutter.shape));
    let t_build = t0.elapsed();
    let mut rendered = render_diced(
        scene,
        opts,
        &DiceOptions { vertex_shader: Some(&shader), lookdev, ..Default::default() },
    )?;
    rendered.stats.t_dice += t_build;
    let (vertices, secondary) = shader.counts();
    rendered.stats.rays = Some(RaySummary {
        ray_hider: false,
        primitives: tracer.primitive_count() as u64,
        nodes: tracer.node_count() as u64,
        vertices,
        vertex_rays: shader.rays(),
        secondary,
        ..Default::default()
    });
    Ok(rendered)
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
    let pool = Pool::new(opts.threads)?;
    let mut dice_options = *dice_options;
    dice_options.shade_every_vertex |= opts.shade_every_vertex;
    dice_options.shader_budget = dice_options.shader_budget.or(opts.shader_budget);
    if let Some(limit) = opts.memory_limit {
        let threads = opts.threads.unwrap_or_else(|| pool.install(rayon::current_num_threads));
        let left = crate::budget::Estimate::new(scene, threads).micropolygons_left(limit);
        dice_options.max_micropolygons =
            Some(dice_options.max_micropolygons.map_or(left, |m| m.min(left)));
    }
    let dice_options = &dice_options;
    let run = |eager: bool| pool.install(|| render_rows(scene, opts, dice_options, eager));
    match run(false) {
        Err(RenderError::Dice(DiceError::BoundMissed { .. })) => run(true),
        result => result,
    }
}

/// One [`Buffers`] per worker thread, kept for the whole frame: the bucket arrays (samples,
/// visible points, windows) grow to their largest bucket once per thread, instead of being
/// made again for every piece rayon splits a row into. Allocating them anew each time churned
/// megabytes per row through the allocator, which then held on to the freed memory: the
/// peak resident size of `heavy-motion` was half again its live heap.
struct ThreadBuffers(Vec<Mutex<Buffers>>);

impl ThreadBuffers {
    fn new() -> ThreadBuffers {
        ThreadBuffers((0..rayon::current_num_threads()).map(|_| Mutex::default()).collect())
    }

    /// `f` with the current worker's buffers; or, should they be in use (a worker that took
    /// another bucket while inside one) or out of reach, with fresh ones.
    fn with<R>(&self, f: impl FnOnce(&mut Buffers) -> R) -> R {
        let slot = rayon::current_thread_index().and_then(|i| self.0.get(i));
        match slot.and_then(|m| m.try_lock().ok()) {
            Some(mut held) => f(&mut held),
            None => f(&mut Buffers::default()),
        }
    }
}

/// Per-thread buffers, reused from bucket to bucket.
#[derive(Default)]
struct Buffers {
    scratch: Scratch,
    window: Window,
    /// The bucket's own contiguous copy of its micropolygons.
    mpolys: Vec<reyes_hider::Micropolygon>,
    /// `0..n`: the indices of `mpolys`.
    list: Vec<u32>,
    /// With AOVs: the per-vertex AOV values of `mpolys`, and the bucket's AOV window.
    aov_data: Vec<f32>,
    aov_window: AovWindow,
}

/// The bucket loop: per row of buckets, render its buckets in parallel while the next row is
/// diced, add their windows to the film in raster order, release what no later row needs.
///
/// Time: `t_hide` is the wall time of the rows' bucket loops with the next rows' dicing
/// overlapped; `t_dice` the dicing outside them (the first row, listing each row's grids).
fn render_rows(
    scene: &Scene,
    opts: &RenderOptions,
    dice_options: &DiceOptions<'_>,
    eager: bool,
) -> Result<Rendered, RenderError> {
    let t0 = Instant::now();
    let frame = frame_for(scene);
    let mut dicer = if eager {
        Dicer::new_eager(scene, &frame, dice_options)
    } else {
        Dicer::new(scene, &frame, dice_options)
    }?;
    let mut t_dice = t0.elapsed();
    let Stages { hider, table, .. } = Stages::with_frame(scene, frame, |hider| {
        hider.with_csg(dicer.csg_trees().to_vec()).with_trims(dicer.trim_regions())
    })?;
    let max_points = opts.memory_limit.map(|limit| {
        let threads = rayon::current_num_threads();
        crate::budget::Estimate::new(scene, threads).points_left(limit, threads)
    });
    let hider = match max_points {
        Some(max) => hider.with_max_points(max),
        None => hider,
    };

    let (mut t_hide, mut t_film) = (Duration::ZERO, Duration::ZERO);
    let mut film = Film::new(scene.image.width, scene.image.height);
    let aov = AovSetup::for_scene(scene);
    let mut aov_film = aov
        .as_ref()
        .map(|a| AovFilm::new(scene.image.width, scene.image.height, a.plan.channels()));
    let mut hider_stats = reyes_hider::Stats::default();
    let mut buckets_rendered = 0;
    let mut kept = Vec::new();
    let across = frame.buckets_x as usize;
    let selected = match opts.buckets {
        Some(list) => list.to_vec(),
        None => buckets::scene_buckets(scene, &frame),
    };
    // Rows after the last selected bucket's are neither diced nor rendered.
    let rows = selected.last().map_or(0, |&b| (b / across + 1) as u32).min(dicer.rows());
    let mut next = 0;
    let buffers = ThreadBuffers::new();
    // Row 0 is diced alone; from then on row `row + 1` is diced while row `row` renders
    // (rayon::join: a worker with no bucket left takes dicing work and the other way round),
    // so a row's slowest bucket no longer leaves the other workers idle.
    if rows > 0 {
        let t = Instant::now();
        dicer.dice_row(0)?;
        t_dice += t.elapsed();
    }
    // The film's lines that no later row adds to: those above the next row's windows.
    // Buckets tile the extended screen (raster -border on), and a window reaches a border
    // further: row r + 1's windows start at raster (r + 1) bh - 2 border.
    let height = scene.image.height;
    let final_after = |row: u32| match row + 1 < frame.buckets_y {
        true => ((row + 1) * frame.bucket_h).saturating_sub(2 * frame.border).min(height),
        false => height,
    };
    // Lines handed to `on_film_lines` so far.
    let mut lines_done = 0;
    for row in 0..rows {
        if cancel::requested() {
            return Err(RenderError::Cancelled);
        }
        let ahead = (row + 1 < rows).then(|| dicer.take_row(row + 1));

        let t = Instant::now();
        let end = (row as usize + 1) * across;
        let count = selected[next..].partition_point(|&b| b < end);
        let row_buckets = &selected[next..next + count];
        next += count;
        let diced = &dicer;
        // The lines the rows added so far made final, handed on beside this row's buckets.
        let lines = lines_done..row.checked_sub(1).map_or(0, final_after);
        let film_now = &film;
        let (results, wave) = rayon::join(
            || {
                row_buckets
                    .par_iter()
                    .map(|&b| {
                        if cancel::requested() {
                            // Skipped: the row is discarded below.
                            return Default::default();
                        }
                        if let Some(r) = opts.done.and_then(|d| d.get(&b)) {
                            return (r.clone(), Default::default());
                        }
                        let result = buffers.with(|buf| {
                            render_bucket(diced, &hider, &table, &frame, aov.as_ref(), b, buf)
                        });
                        if let Some(cb) = opts.on_result {
                            cb(b, &result.0);
                        }
                        if let Some(cb) = opts.on_bucket {
                            cb();
                        }
                        result
                    })
                    .collect::<Vec<_>>()
            },
            || {
                rayon::join(
                    || ahead.map(|work| diced.process_row(work)),
                    || match opts.on_film_lines {
                        Some(cb) if !lines.is_empty() => cb(film_now, lines.clone()),
                        _ => {}
                    },
                )
                .0
            },
        );
        lines_done = lines_done.max(lines.end);
        t_hide += t.elapsed();
        if cancel::requested() {
            return Err(RenderError::Cancelled);
        }

        // Fixed order: bucket raster order, whatever order the buckets finished in.
        let t = Instant::now();
        for (&b, (result, s)) in row_buckets.iter().zip(results) {
            hider_stats.merge(&s);
            buckets_rendered += usize::from(result.window.is_some());
            buckets::add(&mut film, aov_film.as_mut(), &result);
            if opts.keep_buckets {
                kept.push((b, result));
            }
        }
        t_film += t.elapsed();
        if let (Some(limit), true) = (max_points, hider_stats.dropped_points > 0) {
            return Err(RenderError::VisiblePointBudget { limit });
        }
        // The next row's grids are listed before this row's are dropped: both were in
        // memory while they overlapped, and the peak says so.
        if let Some(wave) = wave {
            let t = Instant::now();
            dicer.finish_row(wave)?;
            t_dice += t.elapsed();
        }
        dicer.release_row(row);
    }
    // The rest of the frame, once every row is in.
    if let Some(cb) = opts.on_film_lines.filter(|_| lines_done < height) {
        let t = Instant::now();
        cb(&film, lines_done..height);
        t_film += t.elapsed();
    }
    let dice_stats = dicer.stats();
    let stats = RenderStats {
        buckets_rendered,
        dice: DiceSummary {
            peak_micropolygons: dicer.peak_micropolygons(),
            eager,
            ..dice_summary(&dice_stats)
        },
        micropolygons: dice_stats.micropolygons,
        hider: hider_stats,
        t_dice,
        t_hide,
        t_film,
        shaders: scene.objects.iter().any(|o| o.shaders.is_some()).then_some(ShaderSummary {
            instructions: dice_stats.shader_instructions,
            nonfinite: dice_stats.shader_nonfinite,
            escapes: dice_stats.displacement_escapes,
        }),
        lookdev: scene.has_lookdev().then(|| LookdevSummary {
            vertices: dice_stats.shaded,
            escapes: dice_stats.displacement_escapes,
            ..Default::default()
        }),
        ..RenderStats::new(scene, hider.config(), frame)
    };
    let aovs = aov.zip(aov_film).map(|(a, film)| RenderedAovs { film, layers: a.layers });
    Ok(Rendered { film, stats, aovs, buckets: kept, warnings: Vec::new() })
}

/// Render bucket `b` of the diced scene: its beauty window (None if nothing is in it) and,
/// with AOVs, its AOV window; and the hider's statistics.
fn render_bucket(
    diced: &Dicer,
    hider: &reyes_hider::Hider,
    table: &reyes_film::FilterTable,
    frame: &reyes_hider::Frame,
    aov: Option<&AovSetup>,
    b: usize,
    buf: &mut Buffers,
) -> (BucketResult, reyes_hider::Stats) {
    // Appendix A's `emptybucket`: nothing to display (but its AOVs' background).
    let empty = diced.bucket_len(b) == 0;
    if empty && aov.is_none() {
        return Default::default();
    }
    diced.copy_bucket(b, &mut buf.mpolys);
    if hider.has_trims() {
        diced.copy_bucket_trims(b, buf.scratch.trims_mut());
    }
    let n = buf.mpolys.len() as u32;
    if (buf.list.len() as u32) < n {
        buf.list.extend(buf.list.len() as u32..n);
    }
    buf.scratch.stats = Default::default();
    let list = &buf.list[..n as usize];
    let aov_window = if let Some(a) = aov {
        diced.copy_bucket_aovs(b, &mut buf.aov_data);
        let out = hider.render_bucket_aovs(
            b,
            (&buf.mpolys, &buf.aov_data),
            list,
            &a.plan,
            &mut buf.scratch,
        );
        let beauty = out.beauty;
        pool::splat_bucket(table, frame, b, beauty.rgba, beauty.z, &mut buf.window);
        let samples = AovSamples {
            channels: a.plan.channels(),
            values: out.aov,
            front_z: out.front_z,
            x: &out.samples.x,
            y: &out.samples.y,
        };
        reyes_film::splat_aovs(
            table,
            frame.bucket_origin(b),
            (frame.bucket_w, frame.bucket_h),
            &a.channels,
            &samples,
            &mut buf.aov_window,
        );
        Some(buf.aov_window.clone())
    } else {
        let out = hider.render_bucket(b, &buf.mpolys, list, &mut buf.scratch);
        pool::splat_bucket(table, frame, b, out.rgba, out.z, &mut buf.window);
        // Adaptive sampling's samples, at their true positions and weights.
        let refined = out.refined.iter().map(|r| ([r.x, r.y], r.weight, r.rgba));
        reyes_film::splat_points(table, refined, &mut buf.window);
        None
    };
    let window = (!empty).then(|| buf.window.clone());
    (BucketResult { window, aov: aov_window }, buf.scratch.stats)
}

fn dice_summary(d: &DiceStats) -> DiceSummary {
    DiceSummary {
        primitives: d.primitives,
        splits: d.splits,
        grids: d.grids,
        flatness: d.flatness,
        vertices: d.vertices,
        shaded: d.shaded,
        culled: d.culled,
        peak_micropolygons: 0,
        eager: false,
        trimmed: d.trimmed,
        trim_boundary: d.trim_boundary,
    }
}
