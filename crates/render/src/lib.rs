//! reyes-render: renders a validated [`Scene`] into a [`Film`]. It wires the stages together
//! (scene → dicer → hider → film) and owns what is shared by both hiders:
//!
//! - [`settings`]: the one place where scene settings become stage settings (the hider's
//!   configuration, the bucket frame, the filter table, the shutter's shape);
//! - [`pool`]: the one thread pool and the splat of a bucket's samples into its window;
//! - [`stochastic`]: Appendix A's bucket loop, with lazy dicing row by row of buckets and,
//!   where the scene needs it, ray-traced vertex shading;
//! - [`rayhide`]: Appendix B's ray-tracing hider over the same samples and filter;
//! - [`stats`]: what `--stats` prints;
//! - [`cancel`]: the process-wide request to stop, polled before each bucket;
//! - [`buckets`]: which buckets a render draws (crop windows, tiles), what each hands the
//!   film, and their assembly into the frame (tile merges, checkpoints).
//!
//! Invariant (determinism): every bucket's result depends only on the scene, the seed and the
//! bucket index, and bucket windows are added to the image in bucket raster order, so the
//! output is bit-identical for any thread count and scheduling.
#![deny(missing_docs)]

pub mod aovs;
pub mod buckets;
pub mod budget;
pub mod cancel;
mod error;
mod imager;
pub mod pool;
pub mod rayhide;
pub mod settings;
pub mod stats;
pub mod stochastic;

pub use buckets::BucketResult;
pub use error::RenderError;
pub use reyes_film::Film;
pub use settings::{filter_table, frame_for, hider_config, shutter_shape};
pub use stats::{DiceSummary, LookdevSummary, RaySummary, RenderStats, ShaderSummary, peak_memory};
pub use stochastic::render_diced;

use reyes_scene::{HiderMethod, Scene};

/// What [`RenderOptions::on_result`] calls: with a bucket's index and its result.
pub type OnResult<'a> = dyn Fn(usize, &BucketResult) + Sync + 'a;

/// What [`RenderOptions::on_film_lines`] calls: with the film and the lines of it that have
/// just become final.
pub type OnFilmLines<'a> = dyn Fn(&Film, std::ops::Range<u32>) + Sync + 'a;

/// Options that are not part of the scene.
#[derive(Default)]
pub struct RenderOptions<'a> {
    /// Worker threads (None: rayon's default, one per core).
    pub threads: Option<usize>,
    /// Called once per finished bucket (from worker threads), e.g. to advance a progress bar.
    pub on_bucket: Option<&'a (dyn Fn() + Sync)>,
    /// The memory budget in bytes (None: no limit). A frame whose up-front estimate
    /// ([`budget::Estimate`]) exceeds it is refused with [`RenderError::WontFit`]; what is
    /// left bounds the micropolygons held at once.
    pub memory_limit: Option<u64>,
    /// The buckets to render, in raster order (None: those of the scene's crop window,
    /// [`buckets::scene_buckets`]). The film holds only what these add.
    pub buckets: Option<&'a [usize]>,
    /// Buckets already rendered (read back from a checkpoint): their results are used as
    /// they are, in their place in the raster order, and they are not rendered again.
    pub done: Option<&'a std::collections::BTreeMap<usize, BucketResult>>,
    /// Called with every bucket rendered (not those of `done`) as it finishes, from worker
    /// threads, e.g. to write it to a checkpoint.
    pub on_result: Option<&'a OnResult<'a>>,
    /// Keep every bucket's result in [`Rendered::buckets`] (for a tile file).
    pub keep_buckets: bool,
    /// Called, by the stochastic hider, with the film and a range of its lines that no bucket
    /// still to come adds to, in order down the frame and each line once, from a worker
    /// while the next rows' buckets render (e.g. to compress them,
    /// [`reyes_film::EarlyBlocks`]); the last range ends at the film's last line. A range
    /// starting at line 0 after others means the frame started again (the lines before are
    /// to be forgotten).
    pub on_film_lines: Option<&'a OnFilmLines<'a>>,
    /// Shade every grid vertex, also those that only culled micropolygons use
    /// ([`reyes_dice::DiceOptions::shade_every_vertex`]): the image is the same, for tests
    /// and measurements of culling before shading.
    pub shade_every_vertex: bool,
    /// The instruction budget of a shading-language shader on one grid (None:
    /// `reyes_scene::sl::exec::DEFAULT_BUDGET`); running out ends the render with
    /// [`RenderError::Shader`].
    pub shader_budget: Option<u64>,
}

/// A rendered frame.
pub struct Rendered {
    /// The image.
    pub film: Film,
    /// What it took.
    pub stats: RenderStats,
    /// The AOVs, when the scene writes any.
    pub aovs: Option<aovs::RenderedAovs>,
    /// With [`RenderOptions::keep_buckets`]: each bucket's result, in raster order.
    pub buckets: Vec<(usize, BucketResult)>,
    /// What the user should hear about (a displacement without or beyond its declared
    /// bound), one line each.
    pub warnings: Vec<String>,
}

/// Render a validated scene: with the ray-tracing hider when the scene asks for it, else
/// with the stochastic hider, shading vertices with distributed rays where the scene needs
/// them (shadows, area lights, reflection, refraction, patterns) and with the dicer's local
/// illumination otherwise.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Result<Rendered, RenderError> {
    if let Some(limit) = opts.memory_limit {
        let threads = opts.threads.unwrap_or_else(rayon::current_num_threads);
        let estimate = budget::Estimate::new(scene, threads);
        if estimate.total() > limit {
            // Each part rounded up to whole MB, and the total their sum, so that the message
            // adds up (the rounded total of the bytes could be 1 or 2 MB less).
            let (film, buckets, base) = (
                budget::mb(estimate.film),
                budget::mb(estimate.buckets),
                budget::mb(estimate.base),
            );
            return Err(RenderError::WontFit {
                need: film + buckets + base,
                film,
                buckets,
                base,
                limit: limit >> 20,
            });
        }
    }
    let mut rendered = match scene.hider.method {
        HiderMethod::RayTrace if scene.has_shaders() => Err(RenderError::Shader {
            message: "the ray-tracing hider shades with the native materials only: a scene with shading-language shaders renders with the stochastic hider (Hider \"hidden\")".into(),
        }),
        HiderMethod::RayTrace => rayhide::render_raytraced(scene, opts),
        HiderMethod::Stochastic => stochastic::render_stochastic(scene, opts),
    }?;
    if scene.shaders.imager.is_some() {
        let budget = opts.shader_budget.unwrap_or(reyes_scene::sl::exec::DEFAULT_BUDGET);
        let film = std::mem::replace(&mut rendered.film, Film::new(0, 0));
        let (film, nonfinite) = imager::apply(scene, film, budget)?;
        rendered.film = film;
        if nonfinite > 0 {
            rendered.warnings.push(format!(
                "the imager produced {nonfinite} non-finite values (NaN or infinite), written as 0"
            ));
        }
    }
    Ok(rendered)
}
