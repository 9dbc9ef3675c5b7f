//! reyes-hider: a port of the stochastic hider of US 4,897,806, Appendix A (`ssvis.c`).
//!
//! Stage: takes one bucket's micropolygons, samples them at jittered positions, times and
//! lens positions, keeps per-sample visible-point lists, resolves them front to back, and
//! hands per-sample composites to the film stage. Single-threaded; the caller runs buckets
//! in parallel, each with its own [`Scratch`]. The hot loop is in `bucket.rs`.
//!
//! Map of Appendix A functions to this crate: see docs/appendix-a.md.
#![deny(missing_docs)]

pub mod aov;
mod bucket;
pub mod frame;
pub mod inside;
pub mod lens;
pub mod mpoly;
pub mod samples;
pub mod tables;
pub mod trim;

pub use aov::{AovPlan, AovValue, bilinear_weights};
pub use bucket::{Adaptive, RefinedSample, disagree, gouraud};
pub use frame::{Frame, border_for_filter_width};
pub use lens::LensSetup;
pub use mpoly::{Micropolygon, flags};
pub use reyes_csg::{CsgExpr, CsgOp, CsgOrder, CsgTree, MatteRule, VisPoint};
pub use samples::{
    BucketSamples, LensShape, Needs, Pairing, Pattern, SampleSpec, ShutterShape, TimePattern,
};
pub use tables::Tables;
pub use trim::TrimRef;

/// Everything the hider needs to know about a frame (the arguments of `VisParam`,
/// `VisCamera` and `VisNewFrame`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HiderConfig {
    /// Strata across a pixel (`NxGrid`).
    pub nx: u32,
    /// Strata down a pixel (`NyGrid`).
    pub ny: u32,
    /// Spatial pattern; [`Pattern::Regular`] is Appendix A's `jitter off`.
    pub pattern: Pattern,
    /// Time pairing.
    pub time_pairing: Pairing,
    /// Time pattern within each stratum (FIGS. 13-15).
    pub time_pattern: TimePattern,
    /// Shutter shape (time density).
    pub shutter: ShutterShape,
    /// Lens sample shape.
    pub lens_shape: LensShape,
    /// Thin lens, or `None` for a pinhole (`PinHoleCamera`).
    pub lens: Option<LensSetup>,
    /// Near clipping depth.
    pub hither: f32,
    /// Far clipping depth.
    pub yon: f32,
    /// Seed of the jitter tables and the per-bucket offsets.
    pub seed: u64,
    /// Use the original (non-bijective) `permute`.
    pub original_permute: bool,
    /// Use five 512-entry jitter tables read past their ends, as the C did.
    pub original_jitter_tables: bool,
    /// Reject moving hither/yon-crossing micropolygons per sample instead of clipping them.
    pub original_moving_clip: bool,
    /// Matte compositing rule.
    pub matte: MatteRule,
    /// Depth comparison across CSG operands.
    pub csg_order: CsgOrder,
    /// Move vertices linearly in raster space over a motion segment, as Appendix A did,
    /// instead of along the projective path of a vertex moving linearly in eye space
    /// (Appendix A's `ALPHABETA` hook, `beta = alpha / (alpha + (1 - alpha) z0/z1)`).
    pub original_linear_motion: bool,
    /// Adaptive sampling (the patent's reduced-scale repetition), or `None` (the default).
    pub adaptive: Option<Adaptive>,
    /// Test every sample of the bucket against every micropolygon, with no bound culling.
    /// For tests and study: the image must not change, only the sample-test count.
    pub scan_all: bool,
    /// Occlusion culling (`hider.occlusion_cull`): sample each bucket's micropolygons front
    /// to back and skip what lies behind opaque surfaces at every sample it could touch.
    /// The image does not change, bit for bit; only the work counts do.
    pub occlusion_cull: bool,
}

impl Default for HiderConfig {
    fn default() -> Self {
        HiderConfig {
            nx: 4,
            ny: 4,
            pattern: Pattern::Fig6,
            time_pairing: Pairing::Decorrelated,
            time_pattern: TimePattern::Fig14,
            shutter: ShutterShape::Uniform,
            lens_shape: LensShape::Disk,
            lens: None,
            hither: 0.1,
            yon: 1000.0,
            seed: 0,
            original_permute: false,
            original_jitter_tables: false,
            original_moving_clip: false,
            matte: MatteRule::Holdout,
            csg_order: CsgOrder::Exact,
            original_linear_motion: false,
            adaptive: None,
            scan_all: false,
            occlusion_cull: true,
        }
    }
}

/// The per-frame hider: tables built once (`VisNewFrame` / `tablesinit`), shared read-only by
/// every bucket.
#[derive(Debug, Clone)]
pub struct Hider {
    config: HiderConfig,
    frame: Frame,
    tables: Tables,
    spec: SampleSpec,
    /// Per time slice tau: the times `[warp(tau/NS), warp((tau+1)/NS)]` its samples lie in.
    slice_times: Vec<[f32; 2]>,
    /// CSG trees (`CSGNewTree`), indexed by the micropolygons' `csg_tree`.
    csg: Vec<CsgTree>,
    /// Most visible points one bucket keeps ([`Hider::with_max_points`]).
    max_points: u64,
    /// Trim regions of trimmed NURBS patches ([`Hider::with_trims`]).
    trims: Vec<std::sync::Arc<reyes_scene::patches::trim::TrimRegion>>,
}

/// Hider statistics (Appendix A `VisPrint("stat")`), summed over buckets.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Sample tests that created a visible point (`Hit`).
    pub hits: u64,
    /// Sample tests that did not (`Miss`).
    pub misses: u64,
    /// Exact-depth interpolations (`Lerp`).
    pub lerps: u64,
    /// Micropolygon-in-bucket visits.
    pub micropolygons: u64,
    /// Largest number of visible points alive in one bucket (`NVisMaxUsed`).
    pub peak_points: u64,
    /// Visible points not kept because a bucket reached [`Hider::with_max_points`].
    pub dropped_points: u64,
    /// Visible points created in all.
    pub points: u64,
    /// Time spent testing samples (`VisEndBucket`'s loops), summed over threads, in ns.
    pub sample_ns: u64,
    /// Time spent resolving visible-point lists (`CSGResolve`), summed over threads, in ns.
    pub resolve_ns: u64,
    /// Pixels refined by adaptive sampling.
    pub refined_pixels: u64,
    /// Samples added by adaptive sampling (beyond NS per pixel).
    pub extra_samples: u64,
    /// Micropolygon-in-bucket visits skipped whole by occlusion culling (behind opaque
    /// surfaces at every sample they could touch).
    pub occlusion_culled: u64,
    /// Candidate samples not tested because an opaque surface is nearer there.
    pub occluded_tests: u64,
    /// Samples inside a trimmed micropolygon tested against its trim curves.
    pub trim_tests: u64,
    /// Of `trim_tests`, the samples trimmed away (counted as misses).
    pub trimmed: u64,
}

impl Stats {
    /// Add another bucket's (or thread's) statistics; peaks take the maximum.
    pub fn merge(&mut self, o: &Stats) {
        self.hits += o.hits;
        self.misses += o.misses;
        self.lerps += o.lerps;
        self.micropolygons += o.micropolygons;
        self.peak_points = self.peak_points.max(o.peak_points);
        self.dropped_points += o.dropped_points;
        self.points += o.points;
        self.sample_ns += o.sample_ns;
        self.resolve_ns += o.resolve_ns;
        self.refined_pixels += o.refined_pixels;
        self.extra_samples += o.extra_samples;
        self.occlusion_culled += o.occlusion_culled;
        self.occluded_tests += o.occluded_tests;
        self.trim_tests += o.trim_tests;
        self.trimmed += o.trimmed;
    }
}

/// Per-thread working memory, reused from bucket to bucket so the sampling loop does not
/// allocate once warmed up.
#[derive(Debug, Default, Clone)]
pub struct Scratch {
    samples: BucketSamples,
    heads: Vec<u32>,
    points: Vec<reyes_csg::VisPoint>,
    rgba: Vec<[f32; 4]>,
    z: Vec<f32>,
    slices: bucket::SliceSamples,
    /// With AOVs: the micropolygon of each visible point, each sample's AOV values
    /// (`pixel*NS + s` times the plan's channels), its front depth, and one sample's steps.
    keep_mp: bool,
    point_mp: Vec<u32>,
    aov: Vec<f32>,
    front_z: Vec<f32>,
    steps: aov::Steps,
    refine: bucket::RefineScratch,
    occlusion: bucket::Occlusion,
    /// The trim data of the bucket's micropolygons, in their order ([`Scratch::trims_mut`]).
    trims: Vec<TrimRef>,
    /// Statistics accumulated by every bucket this scratch has rendered.
    pub stats: Stats,
}

impl Scratch {
    /// Empty scratch.
    pub fn new() -> Scratch {
        Scratch::default()
    }

    /// The trim data of the micropolygons the next bucket renders, one per micropolygon in
    /// their order, for a frame with trimmed patches (the renderer fills it before
    /// [`Hider::render_bucket`]; only micropolygons flagged `TRIMMED` read theirs).
    pub fn trims_mut(&mut self) -> &mut Vec<TrimRef> {
        &mut self.trims
    }
}

/// One bucket's per-sample result, indexed `pixel*NS + s` with `pixel = y*XPerBucket + x`.
#[derive(Debug, Clone, Copy)]
pub struct BucketOutput<'a> {
    /// Premultiplied colour and alpha per sample (zeros where nothing is visible).
    pub rgba: &'a [[f32; 4]],
    /// Depth of the opaque surface that ended each sample's composite, or +inf.
    pub z: &'a [f32],
    /// Adaptive sampling's samples, each with its true position and weight; the colours of
    /// the refined pixels' own samples in `rgba` are zero (they stand for nothing). Empty
    /// without [`HiderConfig::adaptive`].
    pub refined: &'a [RefinedSample],
}

/// One bucket's per-sample result with AOVs ([`Hider::render_bucket_aovs`]), indexed as
/// [`BucketOutput`].
#[derive(Debug, Clone, Copy)]
pub struct AovBucketOutput<'a> {
    /// The beauty, exactly as [`Hider::render_bucket`] gives it.
    pub beauty: BucketOutput<'a>,
    /// The plan's channels of every sample, `[(pixel*NS + s) * channels + c]`.
    pub aov: &'a [f32],
    /// Depth of each sample's front-most visible point, opaque or not, or +inf.
    pub front_z: &'a [f32],
    /// The bucket's samples (positions for the nearest-sample filter).
    pub samples: &'a BucketSamples,
}

impl Hider {
    /// Set up a frame: builds the tables (`tablesinit`).
    pub fn new(config: HiderConfig, frame: Frame) -> Hider {
        let tables = Tables::new(
            config.nx,
            config.ny,
            frame.pixels_per_bucket(),
            config.pattern != Pattern::Regular,
            config.seed,
            config.original_jitter_tables,
            config.original_permute,
        );
        let spec = SampleSpec {
            pattern: config.pattern,
            time_pairing: config.time_pairing,
            time_pattern: config.time_pattern,
            shutter: config.shutter,
            lens_shape: config.lens_shape,
            seed: config.seed,
        };
        let ns = tables.ns;
        let slice_times = (0..ns)
            .map(|tau| {
                let (a, b) = (tau as f32 / ns as f32, (tau + 1) as f32 / ns as f32);
                [config.shutter.warp(a), config.shutter.warp(b)]
            })
            .collect();
        Hider {
            config,
            frame,
            tables,
            spec,
            slice_times,
            csg: Vec::new(),
            max_points: u64::MAX,
            trims: Vec::new(),
        }
    }

    /// Register the scene's CSG trees (port of `CSGNewTree`); tree `n` resolves the
    /// micropolygons whose `csg_tree` is `n`. No limit but `u16` (the original had 64).
    pub fn with_csg(mut self, trees: Vec<CsgTree>) -> Hider {
        self.csg = trees;
        self
    }

    /// Register the trim regions of the scene's trimmed patches: a micropolygon flagged
    /// `TRIMMED` is trimmed by region `TrimRef::region` of its [`Scratch::trims_mut`] entry.
    pub fn with_trims(
        mut self,
        regions: Vec<std::sync::Arc<reyes_scene::patches::trim::TrimRegion>>,
    ) -> Hider {
        self.trims = regions;
        self
    }

    /// Whether the frame has trimmed patches (the renderer must then fill
    /// [`Scratch::trims_mut`]).
    pub fn has_trims(&self) -> bool {
        !self.trims.is_empty()
    }

    /// The same hider keeping at most `max` visible points in one bucket (the memory
    /// budget's share); a bucket that would keep more drops the rest and counts them in
    /// [`Stats::dropped_points`], which the caller treats as an exhausted budget.
    pub fn with_max_points(mut self, max: u64) -> Hider {
        self.max_points = max;
        self
    }

    /// The frame geometry.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// The configuration.
    pub fn config(&self) -> &HiderConfig {
        &self.config
    }

    /// The tables (`Location` feeds the filter table).
    pub fn tables(&self) -> &Tables {
        &self.tables
    }

    /// Samples per pixel.
    pub fn ns(&self) -> usize {
        self.tables.ns as usize
    }

    /// Port of `VisEndBucket` (sampling and `CSGResolve`; the film stage does `filter`).
    /// `list` indexes the micropolygons of `mpolys` that touch bucket `bucket`.
    pub fn render_bucket<'s>(
        &self,
        bucket: usize,
        mpolys: &[Micropolygon],
        list: &[u32],
        scratch: &'s mut Scratch,
    ) -> BucketOutput<'s> {
        self.sample_bucket(bucket, mpolys, list, scratch, None);
        self.refine_bucket(bucket, mpolys, list, scratch);
        BucketOutput { rgba: &scratch.rgba, z: &scratch.z, refined: &scratch.refine.out }
    }

    /// [`Hider::render_bucket`] with the AOVs of `plan`: `data` holds the per-vertex AOV
    /// values of `mpolys`, `4 * plan.stride` floats per micropolygon, in the same order.
    pub fn render_bucket_aovs<'s>(
        &self,
        bucket: usize,
        (mpolys, data): (&[Micropolygon], &[f32]),
        list: &[u32],
        plan: &AovPlan,
        scratch: &'s mut Scratch,
    ) -> AovBucketOutput<'s> {
        self.sample_bucket(bucket, mpolys, list, scratch, Some((plan, data)));
        AovBucketOutput {
            beauty: BucketOutput { rgba: &scratch.rgba, z: &scratch.z, refined: &[] },
            aov: &scratch.aov,
            front_z: &scratch.front_z,
            samples: &scratch.samples,
        }
    }

    /// The samples of bucket `bucket` (positions bucket-local), for study and tests.
    pub fn bucket_samples(&self, bucket: usize) -> BucketSamples {
        let (left, top) = self.frame.bucket_origin(bucket);
        let mut s = BucketSamples::default();
        s.generate(
            &self.tables,
            &self.spec,
            bucket,
            left,
            top,
            self.frame.bucket_w,
            self.frame.bucket_h,
            samples::Needs::ALL,
        );
        s
    }
}
