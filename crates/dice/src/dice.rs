//! Dice stage: evaluate and project a patch's vertex grid at every breakpoint of its
//! motion, emit its micropolygons, one per segment between breakpoints, and then shade the
//! vertices the kept ones use.
//!
//! Invariants: vertex `k` of the micropolygon of grid cell `(i, j)` is grid vertex
//! `(i,j), (i+1,j), (i+1,j+1), (i,j+1)` for `k = 0..4`, stored as (raster x, raster y,
//! eye z); no vertex with `z <= 0` is ever projected; colours come from the geometry at
//! shutter open (time 0) and are the same in every segment; a vertex no kept micropolygon
//! uses is not shaded (its colour, transmittance and AOVs are zero, and never read). For a segment `[t_a, t_b]` an
//! emitted micropolygon has `v` = the positions at `t_a`, `speed` = positions at `t_b` minus
//! those at `t_a`, `time = [t_a, t_b]`, and `MOVING` iff some speed is non-zero or the segment
//! is not the whole shutter (a moving cell that comes nearer than `hither/2` during its
//! segment is emitted over the part of it in front of that, from positions between
//! breakpoints: see `Emitter::in_front`); every vertex is finite with `z >= hither/2` at both ends; it is
//! not entirely in front of hither at both ends nor entirely beyond yon at both ends; it
//! carries `HITHER_YON_CROSSING` iff some vertex is outside `[hither, yon]` at either end;
//! and it touches at least one bucket. Consecutive segments over which a micropolygon does
//! not move (bit for bit) are merged, so a still micropolygon is one record with time
//! `[0, 1]` and zero speed, exactly as without motion. Emission order is grid order, then
//! time order, so it is deterministic.
//!
//! A grid is diced in three passes, one module each: the positions (this file,
//! [`Emitter::dice`]: every vertex evaluated, displaced and projected at every breakpoint),
//! the cells (`emit.rs`: each cell's segments kept or dropped against the depth limits, back
//! faces (`facing.rs`) and buckets) and the shading of the vertices the kept cells use
//! (`shading.rs`). The grid store is `grid.rs`; what an object brings to all three (shader,
//! labels, hooks) is `object.rs`.

use glam::Vec3;
use reyes_hider::flags;
use reyes_scene::patches::trim::Coverage;

use crate::bucket::{BucketRange, Bucketer};
use crate::camera::CameraSetup;
use crate::displace;
use crate::motion::Pose;
use crate::split::Patch;

mod emit;
mod facing;
mod grid;
mod object;
mod shading;
mod slgrid;

pub(crate) use facing::cull_back_faces;
pub(crate) use grid::Grid;
use grid::overlap;
pub(crate) use object::{Hook, Labels, ObjectContext, setup_object};
use shading::Open;

/// A micropolygon's vertices at one time: raster x, raster y, eye z (x and y NaN where z is
/// not positive).
type Quad = [[f32; 3]; 4];

/// Dices grids, with the running counts.
#[derive(Debug, Clone)]
pub(crate) struct Emitter<'b> {
    /// The grid being emitted (take it after [`Emitter::dice`]).
    pub grid: Grid,
    /// The buckets each kept micropolygon touches (`ranges[k]` for kept micropolygon `k`).
    pub ranges: Vec<BucketRange>,
    /// Decides the buckets.
    bucketer: &'b Bucketer,
    /// Diced micropolygons dropped (near the eye, outside `[hither, yon]`, off every bucket).
    pub culled: u64,
    /// Emitted micropolygons flagged `HITHER_YON_CROSSING`.
    pub crossing: u64,
    /// Depths: vertices nearer than `near` are not kept.
    hither: f32,
    yon: f32,
    near: f32,
    /// One cell's positions at each breakpoint, with the breakpoint's time.
    quads: Vec<(f32, Quad)>,
    /// Scratch for the pieces of a segment ([`Emitter::in_front`]).
    parts: Vec<(Quad, Quad, [f32; 2])>,
    /// Emitted micropolygons flagged `MOVING`.
    pub moving: u64,
    /// Of `culled`, those dropped as back faces.
    pub backfacing: u64,
    /// Diced cells with a corner displaced beyond the object's declared bound.
    pub escaped: u64,
    /// The grid's winding sign when its back faces may be culled: a cell is front-facing
    /// where `sign * (raster signed area) > 0` ([`Emitter::calibrate`]).
    cull: Option<f32>,
    /// The camera, while emitting a grid that comes near the eye ([`Grid::cam`]).
    camera: Option<CameraSetup>,
    /// The hider moves a micropolygon whose depth changes perspective-correctly (Appendix
    /// A's `ALPHABETA`: straight in camera space), not linearly in raster: the back-face
    /// test follows ([`Emitter::backfacing`]).
    pub warp: bool,
    /// Grid vertices shaded (those the kept micropolygons use).
    pub shaded: u64,
    /// Shade every vertex of a grid, used or not ([`crate::DiceOptions::shade_every_vertex`]).
    pub shade_all: bool,
    /// Cells of trimmed patches dropped whole ([`crate::trim`]).
    pub trimmed: u64,
    /// Micropolygons flagged `TRIMMED`.
    pub trim_boundary: u64,
    /// Flag bits of the cell being emitted beyond the object's (`TRIMMED`).
    cell_flags: u32,
    /// What the shading-language machine counted, and its first error.
    pub sl_counts: crate::sl::SlCounts,
    /// The displacement shader's parameters after its run on the current grid, for the
    /// surface's `displacement()` calls.
    pub sl_displaced: Vec<(String, reyes_scene::sl::exec::Value)>,
    pub sl_error: Option<String>,
}

impl<'b> Emitter<'b> {
    /// An empty emitter dropping vertices nearer than `near` (`hither / 2`).
    pub fn new(bucketer: &'b Bucketer, hither: f32, yon: f32, near: f32) -> Emitter<'b> {
        Emitter {
            grid: Grid {
                nu: 1,
                count: 0,
                color: Vec::new(),
                trans: Vec::new(),
                pos: Vec::new(),
                labels: Labels {
                    flags: 0,
                    csg_tree: 0,
                    csg_node: 0,
                    glass_opacity: 0.0,
                    shaded_opacity: false,
                },
                kept: Vec::new(),
                cam: Vec::new(),
                extra: Vec::new(),
                aov: Vec::new(),
                aov_stride: 0,
                uv: Vec::new(),
                trim_region: 0,
            },
            ranges: Vec::new(),
            bucketer,
            culled: 0,
            crossing: 0,
            hither,
            yon,
            near,
            quads: Vec::new(),
            parts: Vec::new(),
            moving: 0,
            backfacing: 0,
            escaped: 0,
            cull: None,
            camera: None,
            warp: false,
            shaded: 0,
            shade_all: false,
            trimmed: 0,
            trim_boundary: 0,
            cell_flags: 0,
            sl_counts: Default::default(),
            sl_displaced: Vec::new(),
            sl_error: None,
        }
    }

    /// Dice `patch` of surface `surface` into `nu x nv` micropolygons at every breakpoint of
    /// its motion (`poses`, in time order, the first at time 0), emit into [`Emitter::grid`]
    /// (with their buckets in `ranges`) one micropolygon per cell and segment (merging still
    /// segments), in cell order, then time order, and shade at time 0 the vertices the kept
    /// micropolygons use.
    ///
    /// Order (PRMan's and Pixie's: cull before shading): first every vertex is evaluated,
    /// displaced and projected at every breakpoint, with its normal and direction to the eye
    /// at shutter open for the back-face calibration; then the winding is calibrated and
    /// every cell decided (depth limits, back faces, buckets); only then are the vertices
    /// that some kept micropolygon uses shaded ([`Emitter::shade`]). The others are left at
    /// zero colour, transmittance and AOVs, which nothing reads: [`Grid::micropolygon`] and
    /// [`Grid::micropolygon_aovs`] read only a kept cell's corners, and the bucketer only
    /// positions. Shading a vertex depends only on its own inputs (the
    /// [`crate::VertexShader`] seam's invariant: the surface point, its grid's rectangle and
    /// its `(i, j)`), so each shaded vertex gets the values it had when every vertex was
    /// shaded.
    pub fn dice(
        &mut self,
        camera: &CameraSetup,
        object: &ObjectContext<'_>,
        surface: usize,
        poses: &[Pose<'_>],
        patch: &Patch,
        (nu, nv): (u32, u32),
    ) {
        let hook = object.hook.map(|h| Hook { surface, ..h });
        let (nu, nv) = (nu as usize, nv as usize);
        let count = (nu + 1) * (nv + 1);
        // Look development hook (crate::displace), or the shading language's displacement
        // (`slgrid.rs`): the grid displaced along its normals at every breakpoint, and its
        // shading normals recomputed, before anything is shaded or projected; the lookups'
        // footprint is the grid's parameter spacing.
        let displaced = match &object.sl {
            Some(sl) if sl.shaders.displacement.is_some() => {
                self.sl_displace(sl, poses, patch, (nu, nv))
            }
            _ => object.look.as_ref().and_then(|l| displace::grid(l, poses, patch, (nu, nv))),
        };
        let g = &mut self.grid;
        g.nu = nu as u32;
        g.count = count as u32;
        g.labels = object.labels;
        g.color.clear();
        g.trans.clear();
        g.pos.clear();
        g.pos.reserve_exact(count * poses.len());
        g.kept.clear();
        g.kept.reserve_exact(nu * nv);
        g.cam.clear();
        g.extra.clear();
        let moving = poses.len() > 1;
        g.aov.clear();
        g.aov_stride = object.aov.as_ref().map_or(0, |(a, _)| a.stride());
        g.uv.clear();
        g.trim_region = object.trim.as_ref().map_or(0, |t| t.index);
        self.ranges.clear();
        self.ranges.reserve_exact(nu * nv);
        let project = |p_camera: Vec3| {
            if p_camera.is_finite() && p_camera.z > 0.0 {
                let r = camera.eye_to_raster(p_camera);
                [r.x, r.y, p_camera.z]
            } else {
                [f32::NAN, f32::NAN, p_camera.z]
            }
        };
        // Cosine between each vertex's normal and the direction to the eye at shutter open,
        // to calibrate the grid's winding (see `calibrate`); only when culling.
        let mut cosines = Vec::new();
        // What shading each vertex at shutter open will need, once the cells are decided.
        let mut opens = Vec::with_capacity(count);
        self.escaped += displaced.as_ref().map_or(0, |d| d.escaped);
        let boundary = |b: usize, u: f32, v: f32, i: usize, j: usize| {
            patch.sides.as_ref().and_then(|s| s.boundary(b, (u, v), (i, j), (nu, nv)))
        };
        // Crack-free grids of undisplaced surfaces put their inside vertices off the surface
        // by the facets' expected gap at an outline (`straddle`); their sides are the edges'
        // polylines, which straddle the curve on their own.
        let fold = patch.sides.is_some() && displaced.is_none() && nu >= 2 && nv >= 2;
        let perspective = camera.projection() == reyes_scene::Projection::Perspective;
        let mut opened = Vec::new();
        let (mut surf, mut moved, mut weights) = (Vec::new(), Vec::new(), Vec::new());
        for (b, pose) in poses.iter().enumerate() {
            if fold {
                surf.clear();
                for j in 0..=nv {
                    let v = Patch::at(patch.v, j, nv);
                    for i in 0..=nu {
                        let u = Patch::at(patch.u, i, nu);
                        if b == 0 {
                            opened.push(pose.surface.eval(u, v));
                        } else {
                            surf.push(pose.surface.position(u, v));
                        }
                    }
                }
                if b == 0 {
                    surf.extend(opened.iter().map(|sp| sp.p));
                }
                for p in surf.iter_mut() {
                    *p = pose.moment.world_and_camera(*p).1;
                }
                if b == 0 {
                    sight_weights(&surf, nu, nv, perspective, &mut weights);
                }
                straddle(&surf, nu, nv, &weights, &mut moved);
            }
            for j in 0..=nv {
                let v = Patch::at(patch.v, j, nv);
                for i in 0..=nu {
                    let u = Patch::at(patch.u, i, nu);
                    // A point batch's vertices are its disks', not a parametric grid's.
                    let batch = pose.surface.grid_vertex(patch.u, i, j, nu);
                    if b == 0 {
                        // Shutter open, where the vertex is shaded (REYES shades once, before
                        // motion): the surface point, displaced, and its normal.
                        let vertex = j * (nu + 1) + i;
                        let mut sp = match (batch, fold) {
                            (Some(sp), _) => sp,
                            (None, true) => opened[vertex],
                            (None, false) => pose.surface.eval(u, v),
                        };
                        // Crack-free dicing: a boundary vertex lies on its side's polyline,
                        // up to the edge tolerance off the surface; it is shaded (and its
                        // AOVs taken) at the surface point, so that rays it spawns leave from
                        // the surface, not from under it.
                        let on_polyline = boundary(0, u, v, i, j);
                        // Texture maps are looked up at the undisplaced point.
                        let p_lookup = sp.p;
                        // The facing of the grid is the surface's, not its bump's: culled
                        // objects are never displaced (their bound is 0), so this is the
                        // normal of the geometry drawn. A bumped normal tilts away from the
                        // eye near the silhouette and turned whole front-facing grids of
                        // lookdev.ron's checkered ball into back faces.
                        let n_facing = sp.n;
                        if let Some(d) = &displaced {
                            sp.p = d.position(0, vertex).unwrap_or(sp.p);
                            sp.n = d.normal(vertex);
                        }
                        let (p_world, p_shaded) = pose.moment.world_and_camera(sp.p);
                        let p_camera = match on_polyline {
                            Some(p) => pose.moment.world_and_camera(p).1,
                            None if fold => moved[vertex],
                            None => p_shaded,
                        };
                        let n_world = object.normal_to_world * sp.n;
                        if object.cull_back {
                            let to_eye = camera.viewer().seen_from(p_world) - p_world;
                            let n = object.normal_to_world * n_facing;
                            cosines.push(
                                n.dot(to_eye)
                                    / (n.length() * to_eye.length()).max(f32::MIN_POSITIVE),
                            );
                        }
                        g.pos.push(project(p_camera));
                        if moving {
                            g.cam.push(p_camera);
                        }
                        if let Some(t) = &object.trim {
                            g.uv.push(t.uv(surface, u, v));
                        }
                        opens.push(Open {
                            p_lookup,
                            p_object: sp.p,
                            tint: sp.tint,
                            opacity: sp.opacity,
                            p_world,
                            p_shaded,
                            n_world,
                        });
                    } else {
                        let p_object = match &displaced {
                            Some(d) => d.position(b, j * (nu + 1) + i),
                            None => None,
                        }
                        .or_else(|| boundary(b, u, v, i, j));
                        let p_camera = match (p_object, batch, fold) {
                            (Some(p), _, _) => pose.moment.world_and_camera(p).1,
                            (None, Some(sp), _) => pose.moment.world_and_camera(sp.p).1,
                            (None, None, true) => moved[j * (nu + 1) + i],
                            (None, None, false) => {
                                pose.moment.world_and_camera(pose.surface.position(u, v)).1
                            }
                        };
                        g.pos.push(project(p_camera));
                        g.cam.push(p_camera);
                    }
                }
            }
        }
        // Until shading, every vertex has zero colour and transmittance: the bucketer builds
        // each candidate micropolygon's record, colours included, to read its bound.
        g.color.resize(count, [0.0; 3]);
        g.trans.resize(count, [0.0; 3]);
        if object.overlap && patch.sides.is_some() {
            for b in 0..poses.len() {
                overlap(&mut self.grid.pos[b * count..(b + 1) * count], nu, nv);
            }
        }
        self.cull = if object.cull_back { self.calibrate(&cosines) } else { None };
        // Camera-space positions are needed only where some vertex comes near the eye,
        // goes beyond yon or changes depth by more than `DEPTH_RATIO` (`Emitter::in_front`).
        let (cam, n) = (&self.grid.cam, self.grid.count as usize);
        let deep = n > 0
            && cam.chunks(n).zip(cam.chunks(n).skip(1)).any(|(a, b)| {
                a.iter().zip(b).any(|(p, q)| p.z.max(q.z) > emit::DEPTH_RATIO * p.z.min(q.z))
            });
        if !deep && self.grid.cam.iter().all(|p| p.z >= self.near && p.z <= self.yon) {
            self.grid.cam = Vec::new();
        } else {
            self.camera = Some(camera.clone());
        }
        let mut quads = std::mem::take(&mut self.quads);
        let surface0 = poses.first().map(|p| p.surface);
        for cell in 0..(nu * nv) as u32 {
            if surface0.is_some_and(|s| s.skips(patch.u, cell as usize, nu)) {
                continue;
            }
            // A trimmed patch's cell: dropped whole in the trimmed region, flagged for the
            // hider's per-sample test where a trim curve crosses it.
            if let Some(t) = &object.trim {
                let uv = self.grid.corners(cell).map(|c| self.grid.uv[c]);
                self.cell_flags = match t.classify(uv) {
                    Coverage::Removed => {
                        self.trimmed += 1;
                        continue;
                    }
                    Coverage::Boundary => flags::TRIMMED,
                    Coverage::Kept => 0,
                };
            }
            let v = self.grid.quad(cell, 0);
            if poses.len() == 1 {
                // No motion: the whole shutter, still.
                self.emit(cell, (0, &v), None, [0.0, 1.0]);
            } else {
                quads.clear();
                quads.push((0.0, v));
                quads.extend(
                    poses
                        .iter()
                        .enumerate()
                        .skip(1)
                        .map(|(b, pose)| (pose.moment.t, self.grid.quad(cell, b as u32))),
                );
                self.emit_segments(cell, &quads);
            }
        }
        self.quads = quads;
        if let Some(open) = poses.first() {
            self.shade(camera, object, hook, open, patch, (nu, nv), &opens);
        }
    }
}

/// `moved`: the grid's camera-space surface points `surf` (`(nu + 1) x (nv + 1)`, row by
/// row), the inside ones moved along the surface's normal so that the flat micropolygons
/// straddle the true surface instead of cutting inside it (issue #36). The second
/// differences of the grid along u and v are `-k L^2` along the normal (`k` the normal
/// curvature in that direction, `L` the micropolygon side), and a bilinear facet whose
/// corners lie on the surface is on average `(k_u L_u^2 + k_v L_v^2) / 12` inside it: the
/// error in depth where a micropolygon faces the eye, which decides which surface is in
/// front where two cross (CSG). Where the surface folds away from the eye, the outline of
/// its facets is that of the vertices nearest the fold: a fold at a random place in a cell
/// has its nearest vertex at a mean squared distance `(L_u^2 + L_v^2) / 12` along the
/// surface, which the curvature puts `k (L_u^2 + L_v^2) / 24` inside the true outline on
/// average, half as much. So each inside vertex moves by `-n (n . (D_uu + D_vv)) w`, `n` the
/// grid's normal there, with `w = (1 + |cos|) / 24`, `cos` between the normal and the line
/// of sight: 1/12 facing the eye, 1/24 edge on. Outward on a convex surface, nothing on a
/// plane or along a ruled surface's straight lines (a bend within rounding moves nothing, so
/// flat grids are diced bit for bit as before). Boundary vertices stay (they are on the
/// edges' polylines, which straddle the curve on their own). `weights`: [`sight_weights`].
fn straddle(surf: &[Vec3], nu: usize, nv: usize, weights: &[f32], moved: &mut Vec<Vec3>) {
    moved.clear();
    moved.extend_from_slice(surf);
    for j in 1..nv {
        for i in 1..nu {
            let (p, n) = (surf[j * (nu + 1) + i], grid_normal(surf, nu, i, j));
            let bend = n.dot(laplacian(surf, nu, i, j));
            // A plane's bend is rounding: leave its vertices bit for bit where they were.
            let rounding = 32.0 * f32::EPSILON * p.abs().max_element();
            let shift = n * (bend * weights[j * (nu + 1) + i]);
            if bend.abs() > rounding && shift.is_finite() {
                moved[j * (nu + 1) + i] = p - shift;
            }
        }
    }
}

/// The weights `(1 + |cos|) / 24` of [`straddle`] for the inside vertices of `surf` (0 on the
/// boundary), taken once, at shutter open, so that a grid moved rigidly over the shutter
/// moves its vertices rigidly too.
fn sight_weights(surf: &[Vec3], nu: usize, nv: usize, perspective: bool, w: &mut Vec<f32>) {
    w.clear();
    w.resize(surf.len(), 0.0);
    for j in 1..nv {
        for i in 1..nu {
            let p = surf[j * (nu + 1) + i];
            let sight = if perspective { p.normalize_or_zero() } else { Vec3::Z };
            w[j * (nu + 1) + i] = (1.0 + grid_normal(surf, nu, i, j).dot(sight).abs()) / 24.0;
        }
    }
}

/// The unit normal of the grid `surf` at inside vertex `(i, j)`, from central differences.
fn grid_normal(surf: &[Vec3], nu: usize, i: usize, j: usize) -> Vec3 {
    let at = |i: usize, j: usize| surf[j * (nu + 1) + i];
    (at(i + 1, j) - at(i - 1, j)).cross(at(i, j + 1) - at(i, j - 1)).normalize_or_zero()
}

/// `D_uu + D_vv` of the grid `surf` at inside vertex `(i, j)`.
fn laplacian(surf: &[Vec3], nu: usize, i: usize, j: usize) -> Vec3 {
    let at = |i: usize, j: usize| surf[j * (nu + 1) + i];
    at(i - 1, j) + at(i + 1, j) + at(i, j - 1) + at(i, j + 1) - 4.0 * at(i, j)
}
