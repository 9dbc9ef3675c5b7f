//! The one place where scene settings become stage settings: the hider's configuration, the
//! bucket frame, the filter table and the shutter's time density. Both hiders, the golden
//! harness and the tests read them from here, so they cannot drift apart.
//!
//! Invariant: every function here is a pure function of the (validated) scene.

use reyes_dice::CameraSetup;
use reyes_film::{FilmError, FilterTable};
use reyes_hider::{
    CsgOrder, Frame, Hider, HiderConfig, LensShape, MatteRule, Pairing, Pattern, ShutterShape,
    TimePattern, border_for_filter_width,
};
use reyes_scene::{Scene, SpatialPattern};

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
            SpatialPattern::SobolJoint => Pattern::SobolJoint,
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
            reyes_scene::TimePattern::Fig13 => TimePattern::Fig13,
            reyes_scene::TimePattern::Fig14 => TimePattern::Fig14,
            reyes_scene::TimePattern::Fig15 => TimePattern::Fig15,
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
        csg_order: if h.original.csg_order { CsgOrder::Original } else { CsgOrder::Exact },
        // An orthographic projection is affine: a path linear in camera space is linear in
        // raster, so the perspective warp (`ALPHABETA`) would bend a straight path.
        original_linear_motion: h.original.linear_motion
            || scene.camera.projection == reyes_scene::Projection::Orthographic,
        adaptive: (h.adaptive.max_level > 0).then_some(reyes_hider::Adaptive {
            max_level: h.adaptive.max_level,
            threshold: h.adaptive.threshold,
        }),
        scan_all: false,
        // The midpoint depth reads the surfaces behind the front one, which culling skips.
        occlusion_cull: h.occlusion_cull
            && !scene.outputs.aovs.iter().any(|a| a.source == reyes_scene::AovSource::ZMidpoint),
    }
}

/// Why a scene's `hider.pattern` is not used, when it is not: `Sobol` and `SobolJoint` need
/// power-of-two `pixel_samples` (and a one-to-one `Location`, which the original `permute`
/// gives for powers of two) and use FIG. 6 otherwise. `None` when the pattern applies.
pub fn pattern_fallback(scene: &Scene) -> Option<String> {
    let h = &scene.hider;
    let name = match h.pattern {
        SpatialPattern::Sobol => "Sobol",
        SpatialPattern::SobolJoint => "SobolJoint",
        _ => return None,
    };
    let (nx, ny) = h.pixel_samples;
    (h.jitter && !(nx.is_power_of_two() && ny.is_power_of_two())).then(|| {
        format!(
            "hider.pattern: {name} needs power-of-two pixel_samples; {nx} x {ny} renders with Fig6"
        )
    })
}

/// The filter table of a scene's `hider.filter` over `hider`'s sample locations (shared by
/// both hiders and the golden tolerance).
pub fn filter_table(scene: &Scene, hider: &Hider) -> Result<FilterTable, FilmError> {
    let config = hider.config();
    FilterTable::for_filter(
        &scene.hider.filter,
        config.nx,
        config.ny,
        &hider.tables().location,
        &scene.hider.original,
    )
}

/// The time density of a scene's shutter shape.
pub fn shutter_shape(shape: reyes_scene::ShutterShape) -> ShutterShape {
    match shape {
        reyes_scene::ShutterShape::Uniform => ShutterShape::Uniform,
        reyes_scene::ShutterShape::Gradual { ramp } => ShutterShape::Gradual { ramp },
    }
}

/// The bucket layout a scene asks for: its border reaches the larger of the filter's x and y
/// widths, as the filter table's footprint does.
pub fn frame_for(scene: &Scene) -> Frame {
    Frame::new(
        scene.image.width,
        scene.image.height,
        border_for_filter_width(scene.hider.filter.max_width()),
        scene.hider.bucket_size.0,
        scene.hider.bucket_size.1,
    )
}

/// Everything a hider needs of a scene, set up once: the frame, the camera, the hider with
/// its sample tables, and the filter table over its sample locations.
pub struct Stages {
    /// The bucket layout.
    pub frame: Frame,
    /// The camera.
    pub camera: CameraSetup,
    /// The stochastic hider (both hiders take their samples from it).
    pub hider: Hider,
    /// The reconstruction filter's table.
    pub table: FilterTable,
}

impl Stages {
    /// Set up the stages of `scene`; `hider` may add to the hider (CSG trees) before the
    /// filter table is built over its sample locations.
    pub fn new(scene: &Scene, hider: impl FnOnce(Hider) -> Hider) -> Result<Stages, FilmError> {
        Stages::with_frame(scene, frame_for(scene), hider)
    }

    /// [`Stages::new`] with the frame already laid out ([`frame_for`] of the scene).
    pub fn with_frame(
        scene: &Scene,
        frame: Frame,
        hider: impl FnOnce(Hider) -> Hider,
    ) -> Result<Stages, FilmError> {
        let camera = CameraSetup::new(scene);
        let hider = hider(Hider::new(hider_config(scene, &camera), frame));
        let table = filter_table(scene, &hider)?;
        Ok(Stages { frame, camera, hider, table })
    }
}
