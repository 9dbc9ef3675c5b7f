//! reyes-dice: bound, split, dice, shade and bucket a scene's primitives into micropolygons.
//!
//! Stage: second in the pipeline, between the scene model and the hider. Deterministic:
//! the same scene and frame give bit-identical output whatever the thread count (no
//! hash-map iteration; patches are diced in parallel, but every grid has a key giving its
//! place in the order objects, surfaces, patches (depth first) and grid cells are visited,
//! and results are put in that order).
//!
//! Two drivers share the stages: [`dice_scene`] dices the whole scene up front (every
//! micropolygon in memory at once), [`Dicer`] (`lazy.rs`) dices a row of buckets at a time,
//! each patch when the first row its bound touches comes up, and releases micropolygons
//! after the last row they touch, so memory follows the buckets in flight. Both give the
//! same bucket lists (the same micropolygons in the same order) and the same counts.
//!
//! Pipeline per object (in scene order): work out the object's motion over the shutter
//! (`motion.rs`: its breakpoints, and at each the object-to-world placement and the camera),
//! turn the shape into parametric surfaces (quadrics and the hyperboloid, bilinear patches,
//! one patch per mesh face, one per patch-mesh sub-patch and per NURBS knot span), then REYES
//! bound/split/dice per surface:
//!
//! * **Motion.** Time is normalised over the shutter, `t = (time - open) / (close - open)`.
//!   The breakpoints are {0, 1} and the normalised times of the object's transform and
//!   deformation keys and of the camera's keys, sorted and distinct; with no keys at all, or
//!   a closed shutter (`close == open`: everything at `open`), the only breakpoint is 0. Keys
//!   are held before the first and after the last and linear in between: transform keys
//!   lerp the world-space points of the two keys' matrices, camera keys lerp eye, look-at
//!   point and up before building the basis, deformation keys lerp control points.
//! * **Bound.** A patch is judged on an 8x8 test grid of camera-space points per breakpoint.
//!   It is culled if at every breakpoint all test points are in front of hither, or at every
//!   one all are beyond yon, or (when all are in
//!   front of the eye) the union over the breakpoints of its projected bounds misses the
//!   bucket grid, or (pinhole camera, some points at or behind the eye) at every breakpoint
//!   all points lie outside the same side plane of the view frustum (through the eye for a
//!   perspective camera, parallel to the view for an orthographic one). Micropolygons move
//!   linearly in raster space between breakpoints, so these unions hold them at every time.
//!   Every bound is grown by a safety margin, 25% of its extent plus 2 pixels, because test
//!   points do not bound a curved surface: between samples it bulges outward by up to its
//!   sagitta. With a lens the projected bound also grows by the blur (`LensSetup::grow`).
//!   A bicubic patch-mesh sub-patch or NURBS span (a rational Bezier patch) also bounds each
//!   piece by its control hull, which encloses it whatever its curvature.
//! * **Split.** A patch straddling hither at any breakpoint (some test z below it, not all)
//!   is halved along its longer camera-space direction, at most 12 times; then it is diced
//!   anyway. Otherwise the grid aims at micropolygons of the shading rate's area (RenderMan's
//!   definition): the mean projected row and column lengths, scaled by the square root of
//!   the patch's area over their product (shear), the largest over all breakpoints, over
//!   `sqrt(rate)` give the unrounded counts, and the grid nearest them in area is taken
//!   (docs/geometry.md, "Dicing to the shading rate"), `rate` the object's own
//!   `shading_rate` or else `hider.shading_rate`, or
//!   more where the flatness rule asks for more (`Splitter::with_flatness`: the grid within
//!   `min(flatness, relative_flatness * extent)` pixels of the true surface);
//!   above `max_grid_size` micropolygons the patch is halved along the longer projected
//!   direction (at most 40 splits deep, beyond which the grid is shrunk). One decision holds
//!   for every breakpoint, so all times share one grid topology.
//! * **Dice.** The `(nu+1) x (nv+1)` vertex grid is evaluated and projected at every
//!   breakpoint (perspective or orthographic, through the screen window: see `camera.rs`)
//!   and emitted as `nu x nv` micropolygons per segment
//!   `[t_a, t_b]`: `v` the positions at `t_a`, `speed` the displacement to `t_b`,
//!   `time = [t_a, t_b]`, `MOVING` if any speed is non-zero or the segment is not the whole
//!   shutter. Consecutive segments over which a micropolygon does not move are merged; a
//!   micropolygon still over the whole shutter is one record with time `[0, 1]` and zero
//!   speed, so a still scene diced exactly as before motion existed.
//! * **Shade.** Once every cell of a grid is decided (kept, or culled below), the vertices
//!   the kept micropolygons use are shaded once in world space at shutter open (t = 0) under
//!   the object's light set; the others are not shaded at all (cull before shading, as PRMan
//!   and Pixie do). [`DiceStats::shaded`] counts the vertices shaded.
//!
//! Eye plane: no vertex with `z <= 0` is projected. A still micropolygon with a vertex nearer
//! than `hither / 2` is dropped; a moving one keeps the part of its segment during which
//! every vertex is at least `hither / 2` deep (camera-space positions move linearly, so that
//! is one interval, computed exactly from the camera-space positions the grid keeps for
//! grids that come near the eye), as a micropolygon over that part of the shutter whose
//! ends are the projections of the moving points: an object passing the eye keeps what is
//! seen of it in front of hither. Below `hither / 2` the hider's `bounddof` assumes nothing nearer, splitting
//! has made such quads tiny in parameter space, and at `z < hither/2` a micropolygon that
//! also reaches past hither would span a depth range huge compared to its size, i.e. it is
//! seen nearly edge-on and covers almost nothing. One with some vertex outside
//! `[hither, yon]` at either end of its segment (but not all in front of hither at both
//! ends, nor all beyond yon at both ends, which are dropped) is flagged
//! `HITHER_YON_CROSSING` for per-sample clipping in the hider.
//!
//! Labels: every micropolygon carries its object's flags (`OPAQUE`, `MATTE`, `GOURAUD` for
//! `interpolation: Gouraud`, `GLASS` with `glass_opacity = a` for `glass: Some(a)`) and CSG
//! label: an object that is an operand of a solid has `(csg_tree, csg_node)` = its
//! `(tree index, slot id)` in [`CsgSetup`] (whose trees are [`Diced::csg_trees`]), every
//! other object `(0, 0)`. A CSG operand must be a closed solid, so cylinders, cones and
//! paraboloids used as operands are diced with their end caps as extra surfaces of the same
//! object (same placement, motion, material and labels), each facing out of the solid; an
//! object in no solid is diced exactly as without CSG.
//!
//! Grids are stored compactly (`dice::Grid`: each vertex once, a short record per kept
//! micropolygon) and a micropolygon's full record is built when a bucket's list is read.
//!
//! Bucketing: `buckets[b]` lists, in increasing order, every micropolygon whose screen bound
//! over its segment ([`screen_bound`]: the vertices at both ends, grown by the lens) touches
//! bucket `b` ([`reyes_hider::Frame::buckets_touched`]).
//! Neighbouring grids may be diced at different rates, so T-junction cracks are possible.
//!
//! Back faces (`hider.cull_back_faces`, off by default): for a closed, opaque object drawn
//! on its own under a pinhole camera, a micropolygon whose raster winding shows its back
//! over its whole segment (every corner's signed area, a quadratic in time, below a margin)
//! is dropped and counted in `culled` and `backfacing`. Which winding is the back is
//! calibrated per grid against the outward normal at a clearly facing vertex. Off by
//! default because back faces also fill the cracks above.
#![deny(missing_docs)]

mod aov;
mod bucket;
mod camera;
mod csg;
mod dice;
mod displace;
mod hook;
mod lazy;
mod lookdev;
mod motion;
mod roots;
mod shade;
mod shapes;
mod sl;
pub mod slinfo;
mod sltex;
mod split;
mod spot;
mod trim;

pub use aov::{VertexAovs, object_ids};
pub use bucket::screen_bound;
pub use camera::{CameraSetup, Viewer};
pub use csg::CsgSetup;
pub use hook::{DiceOptions, VertexContext, VertexShader};
pub use lazy::{Dicer, MICROPOLYGON_BYTES, RowWave, RowWork};
pub use lookdev::{Lookdev, Looked};

impl From<TextureError> for DiceError {
    fn from(e: TextureError) -> DiceError {
        DiceError::Texture { message: e.to_string(), code: e.exit_code() }
    }
}
pub use reyes_texture::{TextureError, TextureStats};
pub use shade::{Shader, facing};
pub use sl::depth_map_matrices;
pub use spot::{SpotLight, smoothstep};

use reyes_hider::{CsgTree, Frame, Micropolygon};
use reyes_scene::Scene;

/// The diced scene: micropolygons and, per bucket, the indices of those that touch it.
#[derive(Debug, Clone, PartialEq)]
pub struct Diced {
    /// Every emitted micropolygon, in emission order.
    pub mpolys: Vec<Micropolygon>,
    /// One list per bucket (raster order of buckets): increasing indices into `mpolys`.
    pub buckets: Vec<Vec<u32>>,
    /// The CSG tree of every solid ([`CsgSetup::trees`]); a micropolygon with
    /// `csg_node != 0` belongs to `csg_trees[csg_tree]`.
    pub csg_trees: Vec<CsgTree>,
    /// Counts.
    pub stats: DiceStats,
}

/// Counts from dicing a scene.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DiceStats {
    /// Surfaces entering bound/split/dice: one per quadric or patch, one per mesh face
    /// (one per fan triangle for faces of more than four vertices), one per patch-mesh
    /// sub-patch or NURBS knot span, one per end cap of a CSG operand.
    pub primitives: u64,
    /// Patches split in two (for any reason).
    pub splits: u64,
    /// Of `splits`, those made because the patch straddled the hither plane.
    pub hither_splits: u64,
    /// Patches culled before dicing (behind hither, beyond yon, off the bucket grid).
    pub patches_culled: u64,
    /// Grids diced at a split limit (straddling hither, or too deep), possibly shrunk.
    pub depth_limited: u64,
    /// Grids diced.
    pub grids: u64,
    /// Of the micropolygons diced, those the flatness rule (`hider.flatness`) added to what
    /// the shading rate asked for: `nu * nv` minus the shading rate's grid, summed over grids.
    pub flatness: u64,
    /// Micropolygons emitted (`mpolys.len()`).
    pub micropolygons: u64,
    /// Diced micropolygons dropped: a vertex nearer than hither/2 or not finite, entirely
    /// in front of hither or beyond yon, or touching no bucket.
    pub culled: u64,
    /// Of `culled`, back faces of closed opaque objects (see the module doc).
    pub backfacing: u64,
    /// Emitted micropolygons flagged `HITHER_YON_CROSSING`.
    pub crossing: u64,
    /// Emitted micropolygons flagged `MOVING` (moving, or existing for part of the shutter).
    pub moving: u64,
    /// Total entries over all bucket lists.
    pub bucket_entries: u64,
    /// Diced cells with a corner displaced further than its object's declared displacement
    /// bound (counted, and still rendered: bounds use the displacement's own bound too).
    pub displacement_escapes: u64,
    /// Grid vertices diced (`(nu + 1) (nv + 1)` per grid).
    pub vertices: u64,
    /// Of `vertices`, those shaded: the corners of kept micropolygons (a grid is shaded
    /// after its cells are decided, so vertices only culled micropolygons use are not;
    /// a grid shaded by a shading-language shader is shaded whole).
    pub shaded: u64,
    /// Diced cells of trimmed NURBS patches dropped whole: their parameter rectangle lies
    /// in the trimmed region (not counted in `culled`).
    pub trimmed: u64,
    /// Emitted micropolygons flagged `TRIMMED` (a trim curve crosses them: the hider tests
    /// each sample inside them).
    pub trim_boundary: u64,
    /// Floats a shading-language shader left non-finite (replaced by 0 before the hider) or
    /// stored so while it ran.
    pub shader_nonfinite: u64,
    /// Instructions the shading-language machine ran.
    pub shader_instructions: u64,
}

impl DiceStats {
    /// Add `other`'s counts to these.
    pub fn add(&mut self, other: &DiceStats) {
        let DiceStats {
            primitives,
            splits,
            hither_splits,
            patches_culled,
            depth_limited,
            grids,
            flatness,
            micropolygons,
            culled,
            backfacing,
            crossing,
            moving,
            bucket_entries,
            displacement_escapes,
            vertices,
            shaded,
            trimmed,
            trim_boundary,
            shader_nonfinite,
            shader_instructions,
        } = *other;
        self.primitives += primitives;
        self.splits += splits;
        self.hither_splits += hither_splits;
        self.patches_culled += patches_culled;
        self.depth_limited += depth_limited;
        self.grids += grids;
        self.flatness += flatness;
        self.micropolygons += micropolygons;
        self.backfacing += backfacing;
        self.culled += culled;
        self.crossing += crossing;
        self.moving += moving;
        self.bucket_entries += bucket_entries;
        self.displacement_escapes += displacement_escapes;
        self.vertices += vertices;
        self.shaded += shaded;
        self.trimmed += trimmed;
        self.trim_boundary += trim_boundary;
        self.shader_nonfinite += shader_nonfinite;
        self.shader_instructions += shader_instructions;
    }
}

/// Why a scene could not be diced.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DiceError {
    /// A texture map could not be loaded (the message names the file).
    #[error("{message}")]
    Texture {
        /// The loader's message.
        message: String,
        /// Its exit code: 1 for I/O, 2 for a file that is not a usable image.
        code: u8,
    },
    /// The camera's eye and look-at points coincide.
    #[error("camera eye and look_at coincide, so there is no view direction")]
    EyeAtLookAt,
    /// The camera's up vector is parallel to the view direction.
    #[error("camera up vector is parallel to the view direction")]
    UpParallelToView,
    /// The frame is not the bucket layout of the scene's image.
    #[error(
        "frame {frame_width}x{frame_height} (buckets {bucket_w}x{bucket_h}) is not a valid bucket layout of the {width}x{height} image"
    )]
    FrameMismatch {
        /// Frame width.
        frame_width: u32,
        /// Frame height.
        frame_height: u32,
        /// Frame bucket width.
        bucket_w: u32,
        /// Frame bucket height.
        bucket_h: u32,
        /// Scene image width.
        width: u32,
        /// Scene image height.
        height: u32,
    },
    /// The memory budget's share for micropolygons is used up.
    #[error(
        "memory limit reached: dicing a row of buckets needs more than {limit} micropolygons held at once (about {mb} MB); raise --memory-limit or the shading rate"
    )]
    MicropolygonBudget {
        /// The most micropolygons the budget allows.
        limit: u64,
        /// What they take, in MB (at the budget's bytes per micropolygon).
        mb: u64,
    },
    /// A shading-language shader failed on a grid (its instruction budget spent, most
    /// likely): the message names the object and the shader.
    #[error("{message}")]
    Shader {
        /// The one-line message.
        message: String,
    },
    /// More micropolygons than bucket lists can index.
    #[error("more than {limit} micropolygons; raise the shading rate or simplify the scene")]
    TooManyMicropolygons {
        /// The limit.
        limit: u64,
    },
    /// Lazy dicing ([`Dicer`]): a micropolygon diced for row `row` touches the earlier
    /// bucket row `bucket_row`, already rendered (a patch bound was not conservative).
    #[error(
        "a micropolygon diced for bucket row {row} touches row {bucket_row}, already rendered (a patch bound was not conservative)"
    )]
    BoundMissed {
        /// The row being diced.
        row: u32,
        /// The earlier row the micropolygon touches.
        bucket_row: u32,
    },
}

/// Check that `frame` is what `Frame::new` lays out for the scene's image.
fn check_frame(scene: &Scene, frame: &Frame) -> Result<(), DiceError> {
    let ok = frame.bucket_w > 0
        && frame.bucket_h > 0
        && *frame
            == Frame::new(
                scene.image.width,
                scene.image.height,
                frame.border,
                frame.bucket_w,
                frame.bucket_h,
            );
    if ok {
        Ok(())
    } else {
        Err(DiceError::FrameMismatch {
            frame_width: frame.width,
            frame_height: frame.height,
            bucket_w: frame.bucket_w,
            bucket_h: frame.bucket_h,
            width: scene.image.width,
            height: scene.image.height,
        })
    }
}

/// Dice every object of `scene` into shaded micropolygons and sort them into the buckets
/// of `frame` (which must be the layout of the scene's image).
pub fn dice_scene(scene: &Scene, frame: &Frame) -> Result<Diced, DiceError> {
    dice_scene_with(scene, frame, &DiceOptions::default())
}

/// [`dice_scene`] with options (a vertex shader replacing the local illumination).
pub fn dice_scene_with(
    scene: &Scene,
    frame: &Frame,
    options: &DiceOptions,
) -> Result<Diced, DiceError> {
    let (mut wave, bucketer, csg_trees) = Dicer::new_eager(scene, frame, options)?.dice_all();
    if let Some(message) = wave.shader_error.take() {
        return Err(DiceError::Shader { message });
    }
    let mut stats = wave.stats;
    let total: usize = wave.grids.iter().map(|g| g.grid.len()).sum();
    if total > MAX_MICROPOLYGONS {
        return Err(DiceError::TooManyMicropolygons { limit: MAX_MICROPOLYGONS as u64 });
    }
    let mut mpolys = Vec::with_capacity(total);
    let mut buckets = vec![Vec::new(); frame.bucket_count()];
    for grid in wave.grids {
        for (k, range) in grid.ranges.into_iter().enumerate() {
            let index = mpolys.len() as u32;
            for b in bucketer.buckets(range) {
                buckets[b].push(index);
                stats.bucket_entries += 1;
            }
            mpolys.push(grid.grid.micropolygon(k));
        }
    }
    stats.micropolygons = mpolys.len() as u64;
    Ok(Diced { mpolys, buckets, csg_trees, stats })
}

/// Largest number of micropolygons [`dice_scene`] gives: bucket lists index them with `u32`.
const MAX_MICROPOLYGONS: usize = u32::MAX as usize;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_display_on_one_line() {
        let errors = [
            DiceError::EyeAtLookAt,
            DiceError::UpParallelToView,
            DiceError::FrameMismatch {
                frame_width: 1,
                frame_height: 2,
                bucket_w: 3,
                bucket_h: 4,
                width: 5,
                height: 6,
            },
            DiceError::TooManyMicropolygons { limit: 7 },
            DiceError::BoundMissed { row: 8, bucket_row: 9 },
        ];
        for e in errors {
            let s = e.to_string();
            assert!(!s.is_empty() && !s.contains('\n'), "{s:?}");
        }
    }
}
