//! Sampling, filtering and bucketing: the [`Hider`] settings, its patterns and filter, and
//! the [`Original`] switches that reproduce the 1985 behaviour.
//!
//! Invariant: `Default` of every type here is what an absent RON field gives.

use serde::{Deserialize, Serialize};

/// Sampling, filtering and bucketing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Hider {
    /// Which visibility algorithm renders the frame.
    pub method: HiderMethod,
    /// Samples per pixel as (nx, ny): NS = nx * ny strata per pixel.
    pub pixel_samples: (u32, u32),
    /// Appendix A's `jitter on/off`. `false` is the regular grid of FIG. 3 and overrides `pattern`.
    pub jitter: bool,
    /// Which jittered spatial pattern (FIGS. 5-7) to use when `jitter` is on.
    pub pattern: SpatialPattern,
    /// How each sample's time is chosen within its time stratum (FIGS. 13-15).
    pub time_pattern: TimePattern,
    /// Reconstruction filter.
    pub filter: Filter,
    /// Bucket size in pixels (x, y).
    pub bucket_size: (u32, u32),
    /// Target micropolygon area in pixels (> 0).
    pub shading_rate: f32,
    /// Seed of every pseudo-random choice.
    pub seed: u64,
    /// Largest number of micropolygons in one diced grid; bigger primitives are split.
    pub max_grid_size: u32,
    /// Geometric accuracy in raster pixels (>= 0; 0 turns the bound off): grids are diced
    /// finely enough that the flat micropolygons lie within this distance of the true
    /// surface, silhouettes included, whatever the shading rate (RenderMan's
    /// `GeometricApproximation "flatness"`).
    pub flatness: f32,
    /// The same bound as a fraction of each patch's raster extent (>= 0; 0 is off); the
    /// smaller of the two holds. What keeps small objects their true size: at 1/512 a disk's
    /// polygon loses at most about 0.5% of its area, however small the disk.
    pub relative_flatness: f32,
    /// Motion-aware dicing, RenderMan's `GeometricApproximation "motionfactor"` (>= 0; 0, the
    /// default, is off): a patch that moves `B` pixels over the shutter is diced at the
    /// shading rate times `1 + motion_factor * B / 16` (docs/geometry.md). The scene's value;
    /// an object may give its own.
    pub motion_factor: f32,
    /// Focus-aware dicing, RenderMan's `GeometricApproximation "focusfactor"` (>= 0; 0 is
    /// off): a patch whose circle of confusion is `C` pixels across is diced at the shading
    /// rate times `1 + focus_factor * C / 16`. The scene's value; an object may give its own.
    pub focus_factor: f32,
    /// Drop back-facing micropolygons of closed, opaque objects (pinhole cameras only; not
    /// matte, glass, CSG operands or displaced objects; only objects wholly beyond hither):
    /// they can never be seen, and they are about half the micropolygons and sample tests
    /// of a scene of balls. On by default, which crack-free dicing makes safe (the back
    /// faces used to fill the cracks between grids diced at different rates). An object's
    /// own `sides: 1` culls its back faces whether closed or not (RenderMan's `Sides 1`).
    pub cull_back_faces: bool,
    /// Crack-free dicing: neighbouring grids diced at different rates share their boundary
    /// points (docs/geometry.md, "Crack-free dicing"), so no sample falls between them. On
    /// by default; off reproduces the dicer before it (each grid's boundary on the surface).
    pub crack_free: bool,
    /// Occlusion culling in the stochastic hider: each bucket's micropolygons are sampled
    /// front to back, and one that lies behind opaque surfaces at every sample it could
    /// touch (over the shutter and the lens) is skipped, as is each sample where it does.
    /// The image is the same bit for bit either way (docs/architecture.md, "Occlusion
    /// culling"); `false` is for comparison.
    pub occlusion_cull: bool,
    /// How a depth output (`Display "zfile"`, `"shadow"`) makes a pixel's depth from its
    /// samples: RenderMan's `Hider "hidden" "depthfilter"` (docs/textures.md).
    pub depth_filter: DepthFilter,
    /// Adaptive sampling (the patent's reduced-scale repetition of the pattern): off unless
    /// `max_level` > 0.
    pub adaptive: Adaptive,
    /// Switches that reproduce the original 1985 behaviour where it differs from ours.
    pub original: Original,
}

/// RenderMan's depth filters: how a depth map's pixel is made from its samples' depths.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum DepthFilter {
    /// The least depth of the pixel's samples (RenderMan's default).
    #[default]
    Min,
    /// The greatest.
    Max,
    /// Their mean.
    Average,
    /// At each sample, halfway between the nearest surface and the next one behind it
    /// (infinite where there is none), then the least over the pixel: a surface's own
    /// points then lie well in front of its stored depth, so a shadow map needs no bias
    /// against self-shadowing.
    Midpoint,
}

/// Adaptive sampling: after a pixel's samples, a pixel whose samples disagree (some channel
/// of colour or alpha spreads by more than `threshold`) gets the same pattern again at half
/// scale in each quadrant, and so on for quadrants that still disagree, down to `max_level`
/// (docs/sampling.md). Stochastic hider only.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Adaptive {
    /// Deepest refinement: 0 (the default) is off; a leaf of level L is 2^-L pixels across.
    pub max_level: u32,
    /// Largest spread (max - min) of any channel among a region's samples that does not
    /// refine it.
    pub threshold: f32,
}

impl Default for Adaptive {
    fn default() -> Self {
        Adaptive { max_level: 0, threshold: 0.1 }
    }
}

impl Default for Hider {
    fn default() -> Self {
        Hider {
            method: HiderMethod::default(),
            pixel_samples: (4, 4),
            jitter: true,
            pattern: SpatialPattern::default(),
            time_pattern: TimePattern::default(),
            filter: Filter::default(),
            bucket_size: (16, 16),
            shading_rate: 1.0,
            seed: 0,
            max_grid_size: 256,
            flatness: 0.05,
            relative_flatness: 1.0 / 512.0,
            motion_factor: 0.0,
            focus_factor: 0.0,
            cull_back_faces: true,
            crack_free: true,
            occlusion_cull: true,
            depth_filter: DepthFilter::default(),
            adaptive: Adaptive::default(),
            original: Original::default(),
        }
    }
}

/// The visibility algorithm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum HiderMethod {
    /// Appendix A: dice into micropolygons, shade the vertices, point-sample the micropolygons.
    #[default]
    Stochastic,
    /// Appendix B: trace a primary ray per sample (same positions, times, lens positions and
    /// filter) and shade where it hits, with the distributed rays of the materials and lights.
    RayTrace,
}

/// Jittered spatial sampling patterns of the patent (FIG. 3 is `jitter: false`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum SpatialPattern {
    /// FIG. 5: one jittered pattern (one point anywhere in each cell), repeated in every pixel.
    Fig5,
    /// FIG. 6: each cell's point anywhere in the cell, new in every pixel (Appendix A's jitter).
    #[default]
    Fig6,
    /// FIG. 7: a FIG. 5 reference pattern plus a bounded random offset in every pixel.
    Fig7,
    /// Pure random: every sample uniform anywhere in its pixel, no stratification.
    Random,
    /// Owen-scrambled Sobol (0,2) per pixel; needs power-of-two `pixel_samples`, else `Fig6`.
    Sobol,
    /// One Owen-scrambled Sobol sequence over position, time and lens jointly per pixel, with
    /// correlated multi-jittered offsets within each stratum (docs/sampling.md); needs
    /// power-of-two `pixel_samples`, else `Fig6` (with a warning).
    SobolJoint,
}

/// Temporal patterns of the patent (FIGS. 13-15), the counterparts in time of FIGS. 5-7.
/// With `jitter: false` every sample takes its time stratum's centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum TimePattern {
    /// FIG. 13: one pseudo-random time per stratum, the same in every pixel.
    Fig13,
    /// FIG. 14: a new pseudo-random time anywhere in the stratum for every pixel (Appendix A).
    #[default]
    Fig14,
    /// FIG. 15: a FIG. 13 reference time plus a pseudo-random shift of at most a quarter stratum.
    Fig15,
}

/// Reconstruction filter (`VisFilter`; RenderMan's `PixelFilter "name" xwidth ywidth`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Filter {
    /// Kernel.
    pub kind: FilterKind,
    /// Full width in x, in pixels (> 0): RenderMan's `xwidth`.
    pub width: f32,
    /// Full width in y, in pixels (> 0): RenderMan's `ywidth`. `None` (the default, and what
    /// every scene written before it existed means) is `width`: a filter as wide as it is
    /// tall, computed exactly as the width-only filter always was.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f32>,
}

impl Filter {
    /// A filter as wide as it is tall (`height: None`).
    pub const fn new(kind: FilterKind, width: f32) -> Filter {
        Filter { kind, width, height: None }
    }

    /// The full width in y: `height`, or `width` when it is absent.
    pub fn y_width(&self) -> f32 {
        self.height.unwrap_or(self.width)
    }

    /// The larger of the two full widths: what the bucket border and the filter table's
    /// footprint must reach.
    pub fn max_width(&self) -> f32 {
        self.width.max(self.y_width())
    }
}

impl Default for Filter {
    fn default() -> Self {
        Filter::new(FilterKind::Gaussian, 2.0)
    }
}

/// The filter kernels: the five of Appendix A, unchanged, and the RenderMan pixel filters
/// (the `Ri` kinds, each with its own x and y width), as the RenderMan Interface
/// Specification 3.2 (section 4.1.2 `RiPixelFilter`, Appendix E) and the peer renderers
/// Aqsis 1.8 and Pixie 2.2 define them. The formulas, and where the peers depart from the
/// spec, are documented in `reyes_film::kernel` and `docs/scene-format.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FilterKind {
    /// Appendix A's box.
    Box,
    /// Appendix A's truncated Gaussian `exp(-r^2) - exp(-(w/2)^2)` (not RenderMan's: see
    /// [`FilterKind::RiGaussian`]).
    Gaussian,
    /// Appendix A's separable sinc `sin(2x)/x`, truncated to the footprint.
    Sinc,
    /// Appendix A's separable tent.
    Bartlett,
    /// Appendix A's jinc `J1(2r)/r`, truncated to the footprint.
    Bessel,
    /// RenderMan `"box"` (`RiBoxFilter`, RI Spec 3.2 E.1): 1 inside the x/y widths.
    RiBox,
    /// RenderMan `"triangle"` (`RiTriangleFilter`, E.2), as Aqsis and Pixie draw it: a
    /// pyramid, the smaller of the two tents.
    RiTriangle,
    /// RenderMan `"catmull-rom"` (`RiCatmullRomFilter`, E.3): the radial Catmull-Rom cubic of
    /// support radius 2, cut to the x/y widths.
    RiCatmullRom,
    /// RenderMan `"gaussian"` (`RiGaussianFilter`, E.4):
    /// `exp(-2 ((2x/xw)^2 + (2y/yw)^2))` inside the x/y widths.
    RiGaussian,
    /// RenderMan `"sinc"` (`RiSincFilter`, E.5), windowed as Aqsis and Pixie do:
    /// `cos(pi x / (2 xw)) sin(pi x) / (pi x)` times the same in y.
    RiSinc,
    /// `"disk"` (`RiDiskFilter` of Aqsis and Pixie, PRMan's ri.h): 1 inside the ellipse of the
    /// widths.
    RiDisk,
    /// `"bessel"` (`RiBesselFilter` as Aqsis draws it): the jinc `2 J1(pi r) / r` under a
    /// half-cosine window, inside the ellipse of the widths.
    RiBessel,
    /// `"mitchell"` (`RiMitchellFilter` of Aqsis and Pixie): the separable Mitchell-Netravali
    /// cubic with B = C = 1/3, its argument `2|x|/xw`.
    RiMitchell,
    /// `"blackman-harris"` (`RiBlackmanHarrisFilter` of Pixie): the radial four-term
    /// Blackman-Harris window in `sqrt((x/xw)^2 + (y/yw)^2)`.
    RiBlackmanHarris,
}

impl FilterKind {
    /// Every kind, the five of Appendix A first.
    pub const ALL: [FilterKind; 14] = [
        FilterKind::Box,
        FilterKind::Gaussian,
        FilterKind::Sinc,
        FilterKind::Bartlett,
        FilterKind::Bessel,
        FilterKind::RiBox,
        FilterKind::RiTriangle,
        FilterKind::RiCatmullRom,
        FilterKind::RiGaussian,
        FilterKind::RiSinc,
        FilterKind::RiDisk,
        FilterKind::RiBessel,
        FilterKind::RiMitchell,
        FilterKind::RiBlackmanHarris,
    ];

    /// The RenderMan kinds (the `Ri` kinds), in the order of [`FilterKind::ALL`].
    pub const RENDERMAN: &'static [FilterKind] = FilterKind::ALL.split_at(5).1;

    /// The RenderMan filter name of an `Ri` kind, as RIB's `PixelFilter` spells it
    /// (`"catmull-rom"`); `None` for the Appendix A kernels.
    pub const fn renderman_name(self) -> Option<&'static str> {
        match self {
            FilterKind::Box
            | FilterKind::Gaussian
            | FilterKind::Sinc
            | FilterKind::Bartlett
            | FilterKind::Bessel => None,
            FilterKind::RiBox => Some("box"),
            FilterKind::RiTriangle => Some("triangle"),
            FilterKind::RiCatmullRom => Some("catmull-rom"),
            FilterKind::RiGaussian => Some("gaussian"),
            FilterKind::RiSinc => Some("sinc"),
            FilterKind::RiDisk => Some("disk"),
            FilterKind::RiBessel => Some("bessel"),
            FilterKind::RiMitchell => Some("mitchell"),
            FilterKind::RiBlackmanHarris => Some("blackman-harris"),
        }
    }

    /// The `Ri` kind of a RenderMan filter name (RIB's `PixelFilter "name"`), compared
    /// without regard to ASCII case (Pixie lower-cases the name first); `None` for a name we do
    /// not know.
    pub fn from_renderman_name(name: &str) -> Option<FilterKind> {
        FilterKind::ALL
            .into_iter()
            .find(|k| k.renderman_name().is_some_and(|n| n.eq_ignore_ascii_case(name)))
    }

    /// Is this one of the RenderMan kernels (the `Ri` kinds)?
    pub const fn is_renderman(self) -> bool {
        self.renderman_name().is_some()
    }
}

/// Reproduce the original Appendix A behaviour where we deliberately differ
/// (see docs/appendix-a.md). All `false` by default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Original {
    /// Use the original `permute`, which is not a permutation for some NS (3.4).
    pub permute: bool,
    /// Five 512-entry jitter tables laid out back to back, read past their ends as the C did (3.2).
    pub jitter_tables: bool,
    /// Box kernel cut on signed offsets at the full width (3.16).
    pub box_filter: bool,
    /// Bartlett kernel with the full width as half-width (3.16).
    pub bartlett_filter: bool,
    /// Sinc kernel centre value 1 instead of its limit 2 (2.3).
    pub sinc_filter: bool,
    /// CSG operands compared by depth-range minima, as Appendix A's `csg_resolve_surface`
    /// did, instead of exact depths (3.15).
    pub csg_order: bool,
    /// Matte and opacity of a sample taken from the deepest composited surface, so a matte
    /// behind a transparent surface drops the whole sample (3.14).
    pub matte: bool,
    /// Sample s has time stratum s in every pixel, tying time to sub-pixel position (3.3).
    pub time_pairing: bool,
    /// The square, uncentred lens of the original (the "kludge", 3.8), with lens position
    /// tied to screen position.
    pub lens: bool,
    /// Moving micropolygons that straddle hither or yon at a sample's time are rejected for
    /// that sample instead of clipped (3.6).
    pub moving_clip: bool,
    /// Vertices move linearly in raster space over a motion segment (Appendix A), instead of
    /// along the perspective-correct path of a vertex moving linearly in eye space (the
    /// `ALPHABETA` time warp Appendix A declares but never uses).
    pub linear_motion: bool,
}
