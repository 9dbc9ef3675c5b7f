//! Lazy dicing: micropolygons made row of buckets by row of buckets and released as soon as
//! the last bucket that needs them is rendered, so memory follows the buckets in flight, not
//! the size of the scene.
//!
//! Every surface starts as a root patch that is bounded (the split stage's test grid and
//! margin-grown raster bound, see [`Splitter::decide_bound`]) when the [`Dicer`] is made: a
//! culled root is dropped, any other waits in the queue of its *first row*, the bucket row
//! of the top of its bound (row 0 when it has no raster bound, e.g. it reaches behind the
//! eye). [`Dicer::dice_row`]`(r)` takes the patches queued for row `r` and runs bound/split/
//! dice on them (in parallel over patches): a split child whose first row is still `r` (or
//! earlier, which a child's bound lying in its parent's makes impossible up to the margin
//! heuristic) is processed at once, any other child waits in its own row's queue. A diced
//! grid's micropolygons are listed in every bucket they touch and kept until the last row
//! they touch has been rendered ([`Dicer::release_row`]).
//!
//! Invariants:
//! * Order. A grid's key is (object, surface, split path), the path's bits left-aligned
//!   (bit `63 - d` set when the grid lies in the upper half of split `d + 1`). Keys are
//!   unique and their order is the eager dicer's depth-first, lower-half-first emission
//!   order. A bucket's list is sorted by (key, index within the grid) before it is read, so
//!   it holds exactly the eager dicer's list, in the same order, whatever the thread count,
//!   scheduling or the row a grid was diced in.
//! * Counts. Every patch is decided once and counted once (as in the eager dicer), so
//!   [`DiceStats`] over a whole frame are the eager dicer's.
//! * Overlap. [`Dicer::dice_row`] is [`Dicer::take_row`] (`&mut`), [`Dicer::process_row`]
//!   (`&self`, the expensive part) and [`Dicer::finish_row`] (`&mut`), so a renderer may
//!   process row `r + 1` while it still reads row `r`'s buckets; what a row holds is the
//!   same either way (the grids, lists and counts do not depend on when a row is processed).
//! * Bounds. No micropolygon may touch a bucket row already handed out: the bounds are
//!   conservative only up to the split stage's safety margin (25% of the extent plus 2
//!   pixels), so this is checked for every micropolygon, and a violation is an error
//!   ([`DiceError::BoundMissed`]) after which the caller starts again with
//!   [`Dicer::new_eager`], which dices everything in row 0 (the whole scene in memory, as
//!   before lazy dicing) and so cannot miss.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use rayon::prelude::*;
use reyes_hider::{CsgTree, Frame, Micropolygon};
use reyes_scene::Scene;

use crate::aov::VertexAovs;
use crate::bucket::{BucketRange, Bucketer};
use crate::camera::{self, CameraSetup};
use crate::csg::{CsgSetup, OperandBounds};
use crate::dice::{self, Emitter, Grid, ObjectContext};
use crate::hook::DiceOptions;
use crate::motion::{CameraMotion, ObjectMotion, Pose, ShutterTime};
use crate::split::{Decision, MAX_SPLIT_DEPTH, Patch, Splitter};
use crate::{DiceError, DiceStats, check_frame};

mod access;

/// What one held micropolygon takes, for the budget's messages: the micropolygon itself,
/// its grid's shading and bucket ranges, and a few bucket-list entries.
pub const MICROPOLYGON_BYTES: u64 = 2 * std::mem::size_of::<Micropolygon>() as u64;

// Split paths must fit a `u64`, one bit per split.
const _: () = assert!(MAX_SPLIT_DEPTH < 64);

/// Where a grid comes in the eager dicer's emission order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct GridKey {
    /// Index of the object in the scene.
    object: u32,
    /// Index of the surface within the object.
    surface: u32,
    /// Split path, left-aligned: bit `63 - d` is set when the patch is the upper half of
    /// its split at depth `d` (0-based). Grids are leaves of the split tree, so no grid's
    /// path is a prefix of another's, and depth-first pre-order is the order of the paths.
    path: u64,
}

impl GridKey {
    /// The key of the lower (`upper == false`) or upper half of a patch at `depth`.
    fn child(self, depth: u32, upper: bool) -> GridKey {
        GridKey { path: self.path | (u64::from(upper) << (63 - depth)), ..self }
    }
}

/// A patch waiting to be processed, with its decision (made when it was bounded).
#[derive(Debug, Clone)]
struct Task {
    key: GridKey,
    patch: Patch,
    decision: Decision,
}

/// A freshly diced grid.
pub(crate) struct NewGrid {
    pub key: GridKey,
    pub grid: Grid,
    /// The buckets each of its micropolygons touches.
    pub ranges: Vec<BucketRange>,
}

/// What processing some patches made.
#[derive(Default)]
pub(crate) struct Wave {
    /// Diced grids with at least one micropolygon, in key order when the tasks were.
    pub grids: Vec<NewGrid>,
    /// Patches for later rows: `(row, task)`.
    deferred: Vec<(u32, Task)>,
    /// Patches to dice in this row, with their grid size, in key order when the tasks were:
    /// the split walk only plans them (charging their micropolygons to the budget), and
    /// they are diced once the whole row is known to fit.
    leaves: Vec<Leaf>,
    /// Counts.
    pub stats: DiceStats,
    /// The first shading-language failure (which ends the render).
    pub shader_error: Option<String>,
}

impl Wave {
    fn append(&mut self, mut other: Wave) {
        if self.shader_error.is_none() {
            self.shader_error = other.shader_error.take();
        }
        self.grids.append(&mut other.grids);
        self.deferred.append(&mut other.deferred);
        self.leaves.append(&mut other.leaves);
        self.stats.add(&other.stats);
    }
}

/// A patch the split walk decided to dice, and its grid size.
struct Leaf {
    task: Task,
    nu: u32,
    nv: u32,
}

/// One object's motion, shading and split decisions.
struct ObjectSetup<'a> {
    motion: ObjectMotion,
    ctx: ObjectContext<'a>,
    /// The decisions at the object's own shading rate; `None`: the dicer's (the scene's rate).
    splitter: Option<Splitter>,
}

impl ObjectSetup<'_> {
    /// The split and dice decisions for this object, `scene` being the dicer's.
    fn splitter<'s>(&'s self, scene: &'s Splitter) -> &'s Splitter {
        self.splitter.as_ref().unwrap_or(scene)
    }
}

/// The patches of one bucket row, taken from its queue ([`Dicer::take_row`]).
#[derive(Debug)]
pub struct RowWork {
    row: u32,
    tasks: Vec<Task>,
}

/// What processing one bucket row's patches made ([`Dicer::process_row`]), to be listed in
/// its buckets ([`Dicer::finish_row`]).
pub struct RowWave {
    row: u32,
    wave: Wave,
}

/// A grid kept for the buckets that still need it.
struct Slot {
    key: GridKey,
    /// `None` once released.
    grid: Option<Grid>,
}

/// Dices a scene row of buckets by row of buckets (see the module documentation).
///
/// Use: for `r` in `0..rows()` in order, [`Dicer::dice_row`]`(r)`, then read the buckets of
/// row `r` ([`Dicer::copy_bucket`], from any number of threads), then
/// [`Dicer::release_row`]`(r)`. [`Dicer::stats`] are complete after the last row.
pub struct Dicer<'a> {
    frame: Frame,
    camera: CameraSetup,
    splitter: Splitter,
    bucketer: Bucketer,
    /// Per object of the scene (`None`: nothing to dice).
    objects: Vec<Option<ObjectSetup<'a>>>,
    csg_trees: Vec<CsgTree>,
    /// Everything goes in row 0.
    eager: bool,
    /// The hider moves micropolygons under the perspective warp ([`Emitter::warp`]).
    warp: bool,
    /// Shade every grid vertex ([`DiceOptions::shade_every_vertex`]).
    shade_all: bool,
    /// Patches waiting for each bucket row.
    pending: Vec<Vec<Task>>,
    /// Grids alive (or released, with no micropolygons), and the free slots.
    slots: Vec<Slot>,
    free: Vec<u32>,
    /// Per bucket row, the slots whose last row it is.
    release: Vec<Vec<u32>>,
    /// Per bucket: (slot, index in the grid) of every micropolygon touching it.
    lists: Vec<Vec<(u32, u32)>>,
    /// The next row `dice_row` accepts.
    next_row: u32,
    /// Micropolygons held now, and at most.
    alive: u64,
    peak_alive: u64,
    /// The most micropolygons that may be held at once ([`DiceOptions::max_micropolygons`]).
    max_alive: u64,
    /// Micropolygons diced in the current wave so far (all threads), and whether the wave
    /// went over `max_alive` (its remaining patches are then dropped: the row fails).
    charged: AtomicU64,
    over_budget: AtomicBool,
    /// A shading-language shader failed: the remaining grids are not diced.
    shader_failed: AtomicBool,
    stats: DiceStats,
    /// The trim regions of the scene's trimmed NURBS patches, in object order.
    trims: Vec<std::sync::Arc<reyes_scene::patches::trim::TrimRegion>>,
}

impl<'a> Dicer<'a> {
    /// A lazy dicer for `scene` in the buckets of `frame` (which must be the layout of the
    /// scene's image): bounds every surface and queues it in its first row.
    pub fn new(scene: &Scene, frame: &Frame, options: &DiceOptions<'a>) -> Result<Self, DiceError> {
        Dicer::setup(scene, frame, options, false)
    }

    /// A dicer that dices the whole scene in row 0 (and so never misses a bound).
    pub fn new_eager(
        scene: &Scene,
        frame: &Frame,
        options: &DiceOptions<'a>,
    ) -> Result<Self, DiceError> {
        Dicer::setup(scene, frame, options, true)
    }

    fn setup(
        scene: &Scene,
        frame: &Frame,
        options: &DiceOptions<'a>,
        eager: bool,
    ) -> Result<Self, DiceError> {
        check_frame(scene, frame)?;
        camera::check_camera(&scene.camera)?;
        let camera_motion = CameraMotion::new(scene);
        let camera = camera_motion.setup().clone();
        let shutter = ShutterTime::new(&scene.camera.shutter);
        let hider = &scene.hider;
        let splitter = Splitter::new(&camera, frame, hider.shading_rate, hider.max_grid_size)
            .with_flatness(hider.flatness, hider.relative_flatness)
            .with_blur_factors(hider.motion_factor, hider.focus_factor);
        let bucketer = Bucketer::new(frame, camera.lens(), camera.hither(), camera.yon());
        let csg = CsgSetup::new(scene);
        let bounds = OperandBounds::new(scene, &csg, (&camera_motion, &shutter), &splitter);
        let rows = frame.buckets_y as usize;
        let aovs = VertexAovs::for_scene(scene).map(std::sync::Arc::new);
        let ids = if aovs.is_some() { crate::aov::object_ids(scene) } else { Vec::new() };
        // Look development: the render's textures, or the dicer's own.
        let own_lookdev = match options.lookdev {
            None if scene.has_lookdev() => Some(crate::Lookdev::load(scene)?),
            _ => None,
        };
        let lookdev = options.lookdev.or(own_lookdev.as_ref());
        let mut dicer = Dicer {
            frame: *frame,
            camera,
            splitter,
            bucketer,
            objects: Vec::with_capacity(scene.objects.len()),
            csg_trees: Vec::new(),
            eager,
            warp: !scene.hider.original.linear_motion
                && scene.camera.projection == reyes_scene::Projection::Perspective,
            shade_all: options.shade_every_vertex,
            pending: vec![Vec::new(); rows],
            slots: Vec::new(),
            free: Vec::new(),
            release: vec![Vec::new(); rows],
            lists: vec![Vec::new(); frame.bucket_count()],
            next_row: 0,
            alive: 0,
            peak_alive: 0,
            max_alive: options.max_micropolygons.unwrap_or(u64::MAX),
            charged: AtomicU64::new(0),
            over_budget: AtomicBool::new(false),
            shader_failed: AtomicBool::new(false),
            stats: DiceStats::default(),
            trims: Vec::new(),
        };
        for (i, object) in scene.objects.iter().enumerate() {
            let leaf = csg.leaf.get(i).copied().flatten();
            // A CSG operand must be a closed solid: it gets its end caps.
            let motion = ObjectMotion::new(object, &camera_motion, &shutter, leaf.is_some());
            let Some(open) = motion.moments().first() else {
                dicer.objects.push(None);
                continue;
            };
            let (place, looks) =
                ((&open.place, leaf, &dicer.camera), (aovs.as_ref(), &ids[..], lookdev));
            let (mut ctx, reach) =
                dice::setup_object(scene, i, place, options, looks, &mut dicer.trims);
            // RenderMan's ShadingRate and flatness are attributes: an object may dice at its
            // own rate and accuracy.
            let rate = object.shading_rate.filter(|&rate| rate != hider.shading_rate);
            let flatness = object.flatness.filter(|&f| f != hider.flatness);
            // So are GeometricApproximation's motionfactor and focusfactor.
            let motion_factor = object.motion_factor.filter(|&f| f != hider.motion_factor);
            let focus_factor = object.focus_factor.filter(|&f| f != hider.focus_factor);
            let blur = motion_factor.is_some() || focus_factor.is_some();
            // Displacement: bounds grow by the most a point can move, in camera space.
            let displace = reach * motion.largest_scale();
            let own =
                rate.is_some() || flatness.is_some() || blur || displace > 0.0 || leaf.is_some();
            let splitter = own.then(|| {
                dicer
                    .splitter
                    .with_shading_rate(rate.unwrap_or(hider.shading_rate))
                    .with_flatness(flatness.unwrap_or(hider.flatness), hider.relative_flatness)
                    .with_blur_factors(
                        motion_factor.unwrap_or(hider.motion_factor),
                        focus_factor.unwrap_or(hider.focus_factor),
                    )
                    .with_displacement(displace)
                    .with_csg_depth(leaf.map(|(tree, _)| (bounds.clone(), tree, i as u32)))
            });
            let decide = splitter.as_ref().unwrap_or(&dicer.splitter);
            // Crack-free dicing needs boundary points the displacement would move apart.
            let crack_free = scene.hider.crack_free && reach == 0.0;
            // The back of a closed object shows through where hither cuts it open.
            let mut beyond_hither = true;
            // Neighbouring surfaces of one object share their common sides (roots.rs).
            // A blobby's faces are pieces of one surface: its extent scales their flatness.
            let whole = crate::roots::blobby_extent(&motion, decide);
            let mut roots = crate::roots::Roots::new(object, crack_free, motion.surface_count())
                .with_extent(whole.clone());
            for surface in 0..motion.surface_count() {
                dicer.stats.primitives += 1;
                let poses = motion.poses(surface);
                beyond_hither &= decide.beyond_hither(&poses);
                let root = roots.root(decide, surface, &poses);
                let extent = whole.clone().unwrap_or_else(|| decide.extent(&poses, &root));
                let patch = root.with_extent(extent);
                let (decision, top) = decide.decide_bound(&poses, &patch);
                if decision == Decision::Cull {
                    dicer.stats.patches_culled += 1;
                    continue;
                }
                let key = GridKey { object: i as u32, surface: surface as u32, path: 0 };
                let row = dicer.row_of(top, 0);
                dicer.pending[row as usize].push(Task { key, patch, decision });
            }
            ctx.cull_back &= beyond_hither || object.one_sided;
            dicer.objects.push(Some(ObjectSetup { motion, ctx, splitter }));
        }
        dicer.csg_trees = csg.trees;
        Ok(dicer)
    }

    /// The bucket row the top `top` of a patch's raster bound lies in (row 0 without a
    /// bound), but not before `current`; always `current` for an eager dicer.
    fn row_of(&self, top: Option<f32>, current: u32) -> u32 {
        if self.eager {
            return current;
        }
        let f = &self.frame;
        let Some(y) = top else { return current };
        // As `Frame::buckets_touched` rounds: extended-screen pixels start at -border.
        let y = (y + f.border as f32).floor();
        let last_px = (f.buckets_y * f.bucket_h) as f32 - 1.0;
        let row = if y > 0.0 { y.min(last_px) as u32 / f.bucket_h } else { 0 };
        row.max(current)
    }

    /// Process the patches queued for row `row` (see the module documentation) and prepare
    /// the lists of its buckets. Rows must be diced in order, each once.
    ///
    /// The same as [`Dicer::take_row`], [`Dicer::process_row`] and [`Dicer::finish_row`] in
    /// turn.
    ///
    /// Errors with [`DiceError::BoundMissed`] if a micropolygon touches an earlier row (the
    /// dicer is then unusable: start again with [`Dicer::new_eager`]).
    pub fn dice_row(&mut self, row: u32) -> Result<(), DiceError> {
        let work = self.take_row(row);
        let wave = self.process_row(work);
        self.finish_row(wave)
    }

    /// Take the patches queued for row `row`, to be processed by [`Dicer::process_row`].
    /// Rows must be taken in order, each once, and each finished ([`Dicer::finish_row`])
    /// before the next is taken: row `row`'s queue is complete once row `row - 1` is
    /// finished (a row's children for later rows are queued when it is finished).
    pub fn take_row(&mut self, row: u32) -> RowWork {
        assert_eq!(row, self.next_row, "rows are diced in order");
        self.next_row += 1;
        let mut tasks = std::mem::take(&mut self.pending[row as usize]);
        tasks.sort_by_key(|t| t.key);
        self.charged.store(0, Ordering::Relaxed);
        RowWork { row, tasks }
    }

    /// Bound, split, dice and shade the patches of a taken row (in parallel over patches).
    /// This only reads the dicer, so it may run while the buckets of rows finished before
    /// are read ([`Dicer::copy_bucket`]) and before they are released: the renderer dices
    /// row `r + 1` while it renders row `r`. The micropolygons still held for those rows
    /// count toward [`DiceOptions::max_micropolygons`] meanwhile, as they are in memory.
    pub fn process_row(&self, work: RowWork) -> RowWave {
        RowWave { row: work.row, wave: self.wave(work.row, work.tasks) }
    }

    /// List a processed row's grids in the buckets they touch, queue its patches for later
    /// rows, and put its buckets' lists in emission order: its buckets can then be read.
    ///
    /// Errors as [`Dicer::dice_row`].
    pub fn finish_row(&mut self, wave: RowWave) -> Result<(), DiceError> {
        let RowWave { row, mut wave } = wave;
        if let Some(message) = wave.shader_error.take() {
            return Err(DiceError::Shader { message });
        }
        if self.over_budget.load(Ordering::Relaxed) {
            let limit = self.max_alive;
            let mb = limit.saturating_mul(MICROPOLYGON_BYTES) >> 20;
            return Err(DiceError::MicropolygonBudget { limit, mb });
        }
        self.stats.add(&wave.stats);
        for (r, task) in wave.deferred {
            self.pending[r as usize].push(task);
        }
        for grid in wave.grids {
            self.keep(grid, row)?;
        }
        self.peak_alive = self.peak_alive.max(self.alive);
        // Lists gather grids of several rows: put each in emission order.
        let (slots, buckets) = (&self.slots, self.row_buckets(row));
        self.lists[buckets].par_iter_mut().for_each(|list| {
            list.sort_by_key(|&(s, i)| (slots[s as usize].key, i));
        });
        Ok(())
    }

    /// Bucket indices of row `row`.
    fn row_buckets(&self, row: u32) -> std::ops::Range<usize> {
        let across = self.frame.buckets_x as usize;
        row as usize * across..(row as usize + 1) * across
    }

    /// List a grid diced in row `row` in the buckets it touches, and keep it until its
    /// last row.
    fn keep(&mut self, grid: NewGrid, row: u32) -> Result<(), DiceError> {
        let slot = match self.free.pop() {
            Some(s) => s,
            None => {
                self.slots.push(Slot { key: grid.key, grid: None });
                (self.slots.len() - 1) as u32
            }
        };
        let mut last = row;
        for (i, range) in grid.ranges.iter().enumerate() {
            let [_, (y0, y1)] = *range;
            if y0 < row {
                return Err(DiceError::BoundMissed { row, bucket_row: y0 });
            }
            last = last.max(y1);
            for b in self.bucketer.buckets(*range) {
                self.lists[b].push((slot, i as u32));
                self.stats.bucket_entries += 1;
            }
        }
        let n = grid.grid.len() as u64;
        self.stats.micropolygons += n;
        self.alive += n;
        self.release[last as usize].push(slot);
        self.slots[slot as usize] = Slot { key: grid.key, grid: Some(grid.grid) };
        Ok(())
    }

    /// Micropolygons touching bucket `b`.
    pub fn bucket_len(&self, b: usize) -> usize {
        self.lists.get(b).map_or(0, Vec::len)
    }

    /// Copy the micropolygons touching bucket `b` (of a row diced and not yet released) into
    /// `out`, in the eager dicer's order.
    pub fn copy_bucket(&self, b: usize, out: &mut Vec<Micropolygon>) {
        out.clear();
        if let Some(list) = self.lists.get(b) {
            out.reserve(list.len());
            out.extend(list.iter().map(|&(s, i)| {
                let grid = self.slots[s as usize].grid.as_ref();
                grid.expect("a listed grid is kept until its last row").micropolygon(i as usize)
            }));
        }
    }

    /// Copy the AOV values of the micropolygons touching bucket `b` into `out`, in
    /// [`Dicer::copy_bucket`]'s order, `4 * stride` floats each ([`VertexAovs`]); nothing
    /// when the scene writes no AOVs.
    pub fn copy_bucket_aovs(&self, b: usize, out: &mut Vec<f32>) {
        out.clear();
        if let Some(list) = self.lists.get(b) {
            for &(s, i) in list {
                let grid = self.slots[s as usize].grid.as_ref();
                let grid = grid.expect("a listed grid is kept until its last row");
                grid.micropolygon_aovs(i as usize, out);
            }
        }
    }

    /// Copy the trim data of the micropolygons touching bucket `b` into `out`, in
    /// [`Dicer::copy_bucket`]'s order (zeros for a micropolygon that is not trimmed).
    pub fn copy_bucket_trims(&self, b: usize, out: &mut Vec<reyes_hider::TrimRef>) {
        out.clear();
        for &(s, i) in self.lists.get(b).map_or(&[][..], Vec::as_slice) {
            let grid = self.slots[s as usize].grid.as_ref();
            out.push(grid.expect("a listed grid is kept until its last row").trim_ref(i as usize));
        }
    }

    /// Drop the lists of row `row`'s buckets and every grid whose last row it is.
    pub fn release_row(&mut self, row: u32) {
        for b in self.row_buckets(row) {
            self.lists[b] = Vec::new();
        }
        for slot in std::mem::take(&mut self.release[row as usize]) {
            if let Some(grid) = self.slots[slot as usize].grid.take() {
                self.alive -= grid.len() as u64;
            }
            self.free.push(slot);
        }
    }

    /// Process `tasks` for row `row`, in parallel; the result is in task order.
    ///
    /// Each task in two passes: its split walk decides every grid and charges its
    /// micropolygons to the row's budget, then the grids are diced and shaded, only if the
    /// row still fits. A patch that would overrun the budget is thus refused after its
    /// splits alone, before the far costlier dicing and shading of micropolygons that could
    /// not be held anyway.
    fn wave(&self, row: u32, tasks: Vec<Task>) -> Wave {
        let parts: Vec<Wave> = tasks
            .into_par_iter()
            .map(|task| {
                let mut wave = Wave::default();
                if let Some(object) = &self.objects[task.key.object as usize] {
                    let poses = object.motion.poses(task.key.surface as usize);
                    self.run(object, &poses, task, row, &mut wave);
                    let leaves = std::mem::take(&mut wave.leaves);
                    if !self.over_budget.load(Ordering::Relaxed) {
                        let diced: Vec<Wave> = leaves
                            .into_par_iter()
                            .map(|leaf| {
                                let mut w = Wave::default();
                                self.dice_leaf(object, &poses, leaf, &mut w);
                                w
                            })
                            .collect();
                        for part in diced {
                            wave.append(part);
                        }
                    }
                }
                wave
            })
            .collect();
        let mut all = Wave::default();
        for part in parts {
            all.append(part);
        }
        all
    }

    /// Dice and shade a planned grid.
    fn dice_leaf(&self, object: &ObjectSetup<'_>, poses: &[Pose<'_>], leaf: Leaf, out: &mut Wave) {
        let Leaf { task, nu, nv } = leaf;
        let (hither, yon) = (self.camera.hither(), self.camera.yon());
        let mut em = Emitter::new(&self.bucketer, hither, yon, self.splitter.near());
        em.warp = self.warp;
        em.shade_all = self.shade_all;
        if self.shader_failed.load(Ordering::Relaxed) {
            return;
        }
        em.dice(&self.camera, &object.ctx, task.key.surface as usize, poses, &task.patch, (nu, nv));
        out.stats.shader_nonfinite += em.sl_counts.nonfinite;
        out.stats.shader_instructions += em.sl_counts.instructions;
        if let Some(e) = em.sl_error.take() {
            self.shader_failed.store(true, Ordering::Relaxed);
            out.shader_error.get_or_insert(e);
            return;
        }
        out.stats.culled += em.culled;
        out.stats.backfacing += em.backfacing;
        out.stats.crossing += em.crossing;
        out.stats.moving += em.moving;
        out.stats.displacement_escapes += em.escaped;
        out.stats.shaded += em.shaded;
        out.stats.trimmed += em.trimmed;
        out.stats.trim_boundary += em.trim_boundary;
        if em.grid.len() > 0 {
            em.grid.shrink_to_fit();
            out.grids.push(NewGrid { key: task.key, grid: em.grid, ranges: em.ranges });
        }
    }

    /// Process one patch: split it (children for this row processed now, depth first,
    /// lower half first; the others queued) or dice it.
    fn run(
        &self,
        object: &ObjectSetup<'_>,
        poses: &[Pose<'_>],
        task: Task,
        row: u32,
        out: &mut Wave,
    ) {
        if self.over_budget.load(Ordering::Relaxed) {
            return;
        }
        match task.decision {
            Decision::Cull => out.stats.patches_culled += 1,
            Decision::Split { along_u, hither, count } => {
                out.stats.splits += 1;
                out.stats.hither_splits += u64::from(hither);
                let mut now = Vec::with_capacity(2);
                let splitter = object.splitter(&self.splitter);
                let halves = splitter.split(poses, &task.patch, (along_u, hither, count));
                for (k, patch) in halves.into_iter().enumerate() {
                    let key = task.key.child(task.patch.depth, k == 1);
                    let (decision, top) = splitter.decide_bound(poses, &patch);
                    if decision == Decision::Cull {
                        out.stats.patches_culled += 1;
                        continue;
                    }
                    let child = Task { key, patch, decision };
                    match self.row_of(top, row) {
                        r if r == row => now.push(child),
                        r => out.deferred.push((r, child)),
                    }
                }
                let mut now = now.into_iter();
                match (now.next(), now.next()) {
                    (Some(a), Some(b)) => {
                        let (wa, wb) = rayon::join(
                            || {
                                let mut w = Wave::default();
                                self.run(object, poses, a, row, &mut w);
                                w
                            },
                            || {
                                let mut w = Wave::default();
                                self.run(object, poses, b, row, &mut w);
                                w
                            },
                        );
                        out.append(wa);
                        out.append(wb);
                    }
                    (Some(a), None) => self.run(object, poses, a, row, out),
                    _ => {}
                }
            }
            Decision::Dice { nu, nv, limited, extra } => {
                // Charge the grid when it is planned: a walk stops as soon as it is over.
                let n = u64::from(nu) * u64::from(nv);
                let before = self.charged.fetch_add(n, Ordering::Relaxed);
                if self.alive.saturating_add(before).saturating_add(n) > self.max_alive {
                    self.over_budget.store(true, Ordering::Relaxed);
                    return;
                }
                out.stats.grids += 1;
                out.stats.vertices += u64::from(nu + 1) * u64::from(nv + 1);
                out.stats.depth_limited += u64::from(limited);
                out.stats.flatness += u64::from(extra);
                out.leaves.push(Leaf { task, nu, nv });
            }
        }
    }

    /// Dice the whole scene at once (an eager dicer's row 0), grids in emission order.
    pub(crate) fn dice_all(mut self) -> (Wave, Bucketer, Vec<CsgTree>) {
        debug_assert!(self.eager);
        let mut tasks = std::mem::take(&mut self.pending[0]);
        tasks.sort_by_key(|t| t.key);
        let mut wave = self.wave(0, tasks);
        wave.grids.sort_by_key(|g| g.key);
        wave.stats.add(&self.stats);
        (wave, self.bucketer, self.csg_trees)
    }
}
