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

use glam::{Mat3, Vec3};
use reyes_hider::flags;

use crate::aov::VertexAovs;
use crate::bucket::{BucketRange, Bucketer};
use crate::camera::{CameraSetup, Viewer};
use crate::displace;
use crate::hook::{VertexContext, VertexShader};
use crate::lookdev::{At, Look, Looked};
use crate::motion::{Placement, Pose};
use crate::shade::Shader;
use crate::split::Patch;

mod facing;
mod grid;

pub(crate) use facing::cull_back_faces;
pub(crate) use grid::Grid;
use grid::{EXTRA, Kept, STILL, overlap};

/// A vertex shader from [`crate::DiceOptions`], with where the dicer is.
#[derive(Clone, Copy)]
pub(crate) struct Hook<'a> {
    /// The shader.
    pub shader: &'a dyn VertexShader,
    /// Index of the object in the scene.
    pub object: usize,
    /// Index of the surface being diced (set per grid by [`Emitter::dice`]).
    pub surface: usize,
}

/// One object's shading, flag bits and labels.
#[derive(Clone)]
pub(crate) struct ObjectContext<'a> {
    /// Object to world at shutter open, for normals (inverse transpose up to a positive
    /// factor).
    pub normal_to_world: Mat3,
    /// Shader of the object's material.
    pub shader: Shader,
    /// Labels every micropolygon of the object carries.
    pub labels: Labels,
    /// Shades the vertices instead of `shader` when present.
    pub hook: Option<Hook<'a>>,
    /// Back-facing micropolygons may be dropped: the object is a closed, opaque surface
    /// drawn on its own (not matte, glass or a CSG operand) and the camera is a pinhole, so
    /// a back-facing micropolygon always lies behind a front-facing one of the same object
    /// at every sample that could see it ([`cull_back_faces`]).
    pub cull_back: bool,
    /// The per-vertex AOV layout when the scene writes AOVs, and the object's ids.
    pub aov: Option<(std::sync::Arc<VertexAovs>, [f32; 2])>,
    /// Texture maps, displacement, bump and emission ([`crate::lookdev`]).
    pub look: Option<Look>,
    /// Push crack-free grids' boundary vertices out by [`crate::split::OVERLAP`] (not for CSG operands,
    /// for which a sample seeing a surface twice is as wrong as one seeing it not at all).
    pub overlap: bool,
}

/// What every micropolygon of one object carries besides its geometry and colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Labels {
    /// Flag bits (`OPAQUE`, `MATTE`, `GOURAUD`, `GLASS`).
    pub flags: u32,
    /// CSG tree index and slot id (0, 0 when the object is not a CSG operand).
    pub csg_tree: u16,
    /// See `csg_tree`.
    pub csg_node: u16,
    /// Appendix A `glasshackopacity` (0 unless `GLASS`).
    pub glass_opacity: f32,
}

/// A micropolygon's vertices at one time: raster x, raster y, eye z (x and y NaN where z is
/// not positive).
type Quad = [[f32; 3]; 4];

/// Whether a cell is at the same place at two breakpoints: every coordinate equal, or the
/// same bits (so a vertex that is not finite at both, e.g. projected from behind the eye,
/// counts as not moving, and the cell is classified once rather than once per segment).
#[inline]
fn same(a: &Quad, b: &Quad) -> bool {
    a.iter().flatten().zip(b.iter().flatten()).all(|(x, y)| x == y || x.to_bits() == y.to_bits())
}

/// What shading a vertex at shutter open needs, kept from its evaluation in
/// [`Emitter::dice`] until its grid's cells are decided.
#[derive(Debug, Clone, Copy)]
struct Open {
    /// Object-space position as evaluated, before displacement: where texture maps are
    /// looked up.
    p_lookup: Vec3,
    /// Object-space position, displaced.
    p_object: Vec3,
    /// Colour multiplying the material colour (mesh vertex colours; white otherwise).
    tint: Vec3,
    /// World-space position (displaced) and its camera-space one: the surface point, not
    /// the crack-free corner on a side's polyline.
    p_world: Vec3,
    p_shaded: Vec3,
    /// World-space normal (displaced; not normalised).
    n_world: Vec3,
}

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
                labels: Labels { flags: 0, csg_tree: 0, csg_node: 0, glass_opacity: 0.0 },
                kept: Vec::new(),
                cam: Vec::new(),
                extra: Vec::new(),
                aov: Vec::new(),
                aov_stride: 0,
            },
            ranges: Vec::new(),
            bucketer,
            culled: 0,
            crossing: 0,
            hither,
            yon,
            near,
            quads: Vec::new(),
            moving: 0,
            backfacing: 0,
            escaped: 0,
            cull: None,
            camera: None,
            warp: false,
            shaded: 0,
            shade_all: false,
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
    /// positions. Shading a vertex depends only on its own inputs (the [`VertexShader`]
    /// seam's invariant: the surface point, its grid's rectangle and its `(i, j)`), so each
    /// shaded vertex gets the values it had when every vertex was shaded.
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
        // Look development hook (crate::displace): the grid displaced along its normals at
        // every breakpoint, and its shading normals recomputed, before anything is shaded
        // or projected; the lookups' footprint is the grid's parameter spacing.
        let displaced =
            object.look.as_ref().and_then(|l| displace::grid(l, poses, patch, (nu, nv)));
        self.escaped += displaced.as_ref().map_or(0, |d| d.escaped);
        let boundary = |b: usize, u: f32, v: f32, i: usize, j: usize| {
            patch.sides.as_ref().and_then(|s| s.boundary(b, (u, v), (i, j), (nu, nv)))
        };
        for (b, pose) in poses.iter().enumerate() {
            for j in 0..=nv {
                let v = Patch::at(patch.v, j, nv);
                for i in 0..=nu {
                    let u = Patch::at(patch.u, i, nu);
                    if b == 0 {
                        // Shutter open, where the vertex is shaded (REYES shades once, before
                        // motion): the surface point, displaced, and its normal.
                        let mut sp = pose.surface.eval(u, v);
                        let vertex = j * (nu + 1) + i;
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
                        opens.push(Open {
                            p_lookup,
                            p_object: sp.p,
                            tint: sp.tint,
                            p_world,
                            p_shaded,
                            n_world,
                        });
                    } else {
                        let p_object = match &displaced {
                            Some(d) => d.position(b, j * (nu + 1) + i),
                            None => None,
                        }
                        .or_else(|| boundary(b, u, v, i, j))
                        .unwrap_or_else(|| pose.surface.position(u, v));
                        let p_camera = pose.moment.world_and_camera(p_object).1;
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
        // Camera-space positions are needed only where some vertex comes near the eye.
        if self.grid.cam.iter().all(|p| p.z >= self.near) {
            self.grid.cam = Vec::new();
        } else {
            self.camera = Some(camera.clone());
        }
        let mut quads = std::mem::take(&mut self.quads);
        for cell in 0..(nu * nv) as u32 {
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

    /// Shade, at shutter open (`open`, the first pose), the vertices of the grid that its
    /// kept micropolygons use (every vertex under [`Emitter::shade_all`]): colour and
    /// transmittance (premultiplied, with the object's emission), and the AOVs. `opens` holds
    /// each vertex's surface point, from [`Emitter::dice`].
    // Once per grid, and out of line, so that profiles show shading apart from dicing.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn shade(
        &mut self,
        camera: &CameraSetup,
        object: &ObjectContext<'_>,
        hook: Option<Hook<'_>>,
        open: &Pose<'_>,
        patch: &Patch,
        (nu, nv): (usize, usize),
        opens: &[Open],
    ) {
        let count = opens.len();
        let mut used = vec![self.shade_all; count];
        if !self.shade_all {
            for k in &self.grid.kept {
                for c in self.grid.corners(k.cell) {
                    used[c] = true;
                }
            }
        }
        let world_to_camera = camera.world_to_camera();
        let duv = [(patch.u[1] - patch.u[0]) / nu as f32, (patch.v[1] - patch.v[0]) / nv as f32];
        let g = &mut self.grid;
        let stride = g.aov_stride;
        g.aov.reserve_exact(count * stride);
        g.aov.resize(count * stride, 0.0);
        let mut values = Vec::with_capacity(stride);
        let mut shaded = 0;
        for (vertex, o) in opens.iter().enumerate() {
            if !used[vertex] {
                continue;
            }
            shaded += 1;
            let (i, j) = (vertex % (nu + 1), vertex / (nu + 1));
            let (u, v) = (Patch::at(patch.u, i, nu), Patch::at(patch.v, j, nv));
            let looked = object.look.as_ref().map_or(Looked::NONE, |l| {
                let (uv, duv) = open.surface.st(u, v, duv);
                l.object.looked(&l.system, &At { uv, duv, p_object: o.p_lookup })
            });
            // The shader face-forwards the normal toward the eye (two-sided), which is what
            // CSG needs: where a difference A - B shows B's surface through a hole in A, the
            // eye sees B from B's inside, i.e. the outside of the result, whose outward
            // normal there is B's inward one. The geometric (outward) normal itself is not
            // stored: the orientation survives only in the vertex winding.
            let (mut color, trans) = match &hook {
                None => object.shader.shade_looked(o.p_world, o.n_world, o.tint, &looked),
                Some(hook) => hook.shader.shade(&VertexContext {
                    object: hook.object,
                    surface: hook.surface,
                    patch_u: patch.u,
                    patch_v: patch.v,
                    i: i as u32,
                    j: j as u32,
                    nu: nu as u32,
                    nv: nv as u32,
                    p_world: o.p_world,
                    n_world: o.n_world.normalize_or_zero(),
                    p_object: o.p_object,
                    tint: o.tint * looked.color,
                    looked,
                }),
            };
            if let Some(e) = object.look.as_ref().and_then(|l| l.object.emission) {
                // Emission, premultiplied by the opacity (1 - trans).
                for a in 0..3 {
                    color[a] += e[a] * (1.0 - trans[a]);
                }
            }
            g.color[vertex] = color;
            g.trans[vertex] = trans;
            if let Some((layout, ids)) = &object.aov {
                values.clear();
                let n_camera = world_to_camera.transform_vector3(o.n_world).normalize_or_zero();
                values.extend_from_slice(&n_camera.to_array());
                values.extend_from_slice(&o.p_shaded.to_array());
                values.extend_from_slice(&[u, v, ids[0], ids[1]]);
                for group in &layout.groups {
                    // Local illumination's terms; the ray-traced shader's are not split (the
                    // render refuses component AOVs with it).
                    let terms = match &hook {
                        None => object.shader.components_looked(
                            o.p_world,
                            o.n_world,
                            o.tint,
                            group.as_deref(),
                            &looked,
                        ),
                        Some(_) => [glam::Vec3::ZERO; 3],
                    };
                    for t in terms {
                        values.extend_from_slice(&t.to_array());
                    }
                }
                g.aov[vertex * stride..(vertex + 1) * stride].copy_from_slice(&values);
            }
        }
        self.shaded += shaded;
    }

    /// Emit cell `cell` from its positions at each breakpoint (`(time, quad)`, in time
    /// order): one micropolygon per segment, runs of segments over which it is still merged.
    fn emit_segments(&mut self, cell: u32, quads: &[(f32, Quad)]) {
        let n = quads.len();
        if quads.windows(2).all(|w| same(&w[0].1, &w[1].1)) {
            // Still over the whole shutter (or a single breakpoint).
            if let Some((_, q)) = quads.first() {
                self.emit(cell, (0, q), None, [0.0, 1.0]);
            }
            return;
        }
        let mut a = 0;
        while a + 1 < n {
            let mut b = a + 1;
            let still = same(&quads[a].1, &quads[b].1);
            if still {
                while b + 1 < n && same(&quads[b].1, &quads[b + 1].1) {
                    b += 1;
                }
            }
            let to = (!still).then_some((b as u32, &quads[b].1));
            self.emit(cell, (a as u32, &quads[a].1), to, [quads[a].0, quads[b].0]);
            a = b;
        }
    }

    /// The part of cell `cell`'s motion from breakpoint `from` to breakpoint `to` (over
    /// `time`) during which every vertex is at least `near` in front of the eye: its
    /// positions at the start and end of that part and the part's times, or `None` if there
    /// is no such part (or a position is not finite). Camera-space positions move linearly
    /// between breakpoints, so each vertex is in front of `near` over one interval of the
    /// segment, and all four over the intersection of theirs.
    fn in_front(
        &self,
        cell: u32,
        from: u32,
        to: u32,
        time: [f32; 2],
    ) -> Option<(Quad, Quad, [f32; 2])> {
        let g = &self.grid;
        let count = g.count as usize;
        let corners = g.corners(cell);
        let at = |b: u32| corners.map(|c| g.cam[b as usize * count + c]);
        let (p, q) = (at(from), at(to));
        let (mut lo, mut hi) = (0.0_f32, 1.0_f32);
        for (p, q) in p.iter().zip(&q) {
            if !(p.is_finite() && q.is_finite()) {
                return None;
            }
            match (p.z >= self.near, q.z >= self.near) {
                (true, true) => {}
                (false, false) => return None,
                // Where z(s) = p.z + s (q.z - p.z) reaches `near`.
                (true, false) => hi = hi.min((p.z - self.near) / (p.z - q.z)),
                (false, true) => lo = lo.max((self.near - p.z) / (q.z - p.z)),
            }
        }
        // A part too short to hold a sample time is not worth a record.
        if hi - lo <= 1e-6 || hi.is_nan() || lo.is_nan() {
            return None;
        }
        let project = |s: f32| {
            let mut quad = [[0.0_f32; 3]; 4];
            for (k, (p, q)) in p.iter().zip(&q).enumerate() {
                let c = crate::motion::lerp(*p, *q, s);
                // Rounding may leave a vertex a hair nearer than `near` at the crossing.
                let c = Vec3::new(c.x, c.y, c.z.max(self.near));
                let r = self.camera.as_ref()?.eye_to_raster(c);
                if !r.is_finite() {
                    return None;
                }
                quad[k] = [r.x, r.y, c.z];
            }
            Some(quad)
        };
        let span = time[1] - time[0];
        let t = [time[0] + lo * span, if hi >= 1.0 { time[1] } else { time[0] + hi * span }];
        Some((project(lo)?, project(hi)?, t))
    }

    /// Classify one micropolygon of cell `cell` over its segment `time` (at breakpoint
    /// `from` at the start, at `to` at the end, or at `from` throughout when `to` is `None`)
    /// against the depth limits and buckets, and keep it or drop it.
    #[inline(always)]
    fn emit(&mut self, cell: u32, from: (u32, &Quad), to: Option<(u32, &Quad)>, time: [f32; 2]) {
        let mut usable = true;
        let (mut zmin, mut zmax) = (f32::INFINITY, f32::NEG_INFINITY);
        for q in [Some(from.1), to.map(|t| t.1)].into_iter().flatten() {
            for p in q {
                usable &= p[0].is_finite() && p[1].is_finite() && p[2] >= self.near;
                zmin = zmin.min(p[2]);
                zmax = zmax.max(p[2]);
            }
        }
        usable &= zmax.is_finite();
        if !usable {
            // A moving micropolygon that comes nearer than `near` (or passes behind the
            // eye) during its segment keeps the part of the segment it is in front of it.
            if let Some((to_b, _)) = to
                && from.0 & EXTRA == 0
                && !self.grid.cam.is_empty()
                && let Some((a, b, t)) = self.in_front(cell, from.0, to_b, time)
            {
                let ia = EXTRA | self.grid.extra.len() as u32;
                self.grid.extra.push(a);
                let ib = EXTRA | self.grid.extra.len() as u32;
                self.grid.extra.push(b);
                self.emit(cell, (ia, &a), Some((ib, &b)), t);
                return;
            }
            self.culled += 1;
            return;
        }
        // All in front of hither, or all beyond yon, at both ends.
        if zmax < self.hither || zmin > self.yon {
            self.culled += 1;
            return;
        }
        if let Some(sign) = self.cull
            && Self::backfacing(sign, from.1, to.map(|t| t.1), self.warp)
        {
            self.culled += 1;
            self.backfacing += 1;
            return;
        }
        let crossing = zmin < self.hither || zmax > self.yon;
        let mut flags = self.grid.labels.flags;
        if crossing {
            flags |= flags::HITHER_YON_CROSSING;
        }
        let moves = to.is_some_and(|(_, q)| {
            from.1.iter().zip(q).any(|(p, q)| (0..3).any(|a| q[a] - p[a] != 0.0))
        });
        if moves || time != [0.0, 1.0] {
            flags |= flags::MOVING;
        }
        let kept = Kept { cell, from: from.0, to: to.map_or(STILL, |t| t.0), flags, time };
        let Some(range) = self.bucketer.range(&self.grid.build(&kept)) else {
            self.culled += 1;
            return;
        };
        self.ranges.push(range);
        self.grid.kept.push(kept);
        if crossing {
            self.crossing += 1;
        }
        if flags & flags::MOVING != 0 {
            self.moving += 1;
        }
    }
}

/// Per-object setup: shading (under the object's light set, seen by `viewer`, with the object
/// placed by `open`, its placement at shutter open), flags, and the CSG label `csg`
/// (`(tree index, slot id)` of a CSG operand, from [`crate::CsgSetup::leaf`]).
pub(crate) fn object_context(
    object: &reyes_scene::Object,
    lights: &[reyes_scene::Light],
    viewer: Viewer,
    open: &Placement,
    csg: Option<(u16, u16)>,
) -> ObjectContext<'static> {
    let shader = Shader::for_object(object, lights, viewer);
    let mut flags = 0;
    if shader.opaque() {
        flags |= flags::OPAQUE;
    }
    if object.matte {
        flags |= flags::MATTE;
    }
    if object.interpolation == reyes_scene::Interpolation::Gouraud {
        flags |= flags::GOURAUD;
    }
    let mut glass_opacity = 0.0;
    if let Some(a) = object.glass {
        flags |= flags::GLASS;
        glass_opacity = a;
    }
    let (csg_tree, csg_node) = csg.unwrap_or((0, 0));
    let labels = Labels { flags, csg_tree, csg_node, glass_opacity };
    ObjectContext {
        normal_to_world: open.normal_to_world(),
        shader,
        labels,
        hook: None,
        cull_back: false,
        aov: None,
        look: None,
        overlap: csg.is_none(),
    }
}

#[cfg(test)]
mod tests {
    use crate::lazy::Dicer;
    use crate::{DiceOptions, DiceStats};

    /// A scene file of `scenes/`, 120 pixels across.
    fn scene_file(name: &str) -> reyes_scene::Scene {
        let root = reyes_testkit::golden::workspace_root();
        let mut scene = reyes_scene::load(&root.join(format!("scenes/{name}.ron"))).unwrap();
        let (w, h) = (scene.image.width, scene.image.height);
        scene.image.width = 120;
        scene.image.height = (120 * h / w).max(1);
        scene
    }

    fn dice(scene: &reyes_scene::Scene, all: bool) -> (Vec<crate::lazy::NewGrid>, DiceStats) {
        let frame = reyes_testkit::fixtures::frame_for(scene);
        let options = DiceOptions { shade_every_vertex: all, ..Default::default() };
        let (wave, _, _) = Dicer::new_eager(scene, &frame, &options).unwrap().dice_all();
        (wave.grids, wave.stats)
    }

    /// Every vertex a kept micropolygon uses is shaded and no other: the others keep zero
    /// colour, transmittance and AOVs, and the count is theirs. Shading every vertex instead
    /// gives every kept micropolygon and its AOVs bit for bit.
    #[test]
    fn only_the_corners_of_kept_cells_are_shaded() {
        // Back faces and off-screen cells (spheres), motion (cells kept over part of the
        // shutter), AOVs, displacement and texture maps.
        for name in ["spheres", "motion-blur", "aovs", "lookdev"] {
            let scene = scene_file(name);
            let (grids, stats) = dice(&scene, false);
            let (all_grids, all_stats) = dice(&scene, true);
            let mut shaded = 0u64;
            let mut unused = 0u64;
            for g in grids.iter().map(|g| &g.grid) {
                let st = g.aov_stride;
                let mut used = vec![false; g.count as usize];
                for k in &g.kept {
                    for c in g.corners(k.cell) {
                        used[c] = true;
                    }
                }
                for (c, &u) in used.iter().enumerate() {
                    if u {
                        shaded += 1;
                    } else {
                        unused += 1;
                        assert_eq!((g.color[c], g.trans[c]), ([0.0; 3], [0.0; 3]), "{name}");
                        assert!(g.aov[c * st..(c + 1) * st].iter().all(|&a| a == 0.0), "{name}");
                    }
                }
            }
            assert_eq!(stats.shaded, shaded, "{name}");
            assert!(stats.shaded < stats.vertices, "{name}: every vertex used");
            assert!(unused > 0, "{name}");
            assert_eq!(all_stats.shaded, all_stats.vertices, "{name}");
            assert_eq!(DiceStats { shaded: 0, ..stats }, DiceStats { shaded: 0, ..all_stats });
            assert_eq!(grids.len(), all_grids.len(), "{name}");
            let (mut a, mut b) = (Vec::new(), Vec::new());
            for (g, h) in grids.iter().zip(&all_grids) {
                assert_eq!(g.key, h.key, "{name}");
                assert_eq!(g.grid.len(), h.grid.len(), "{name}");
                for k in 0..g.grid.len() {
                    let (p, q) = (g.grid.micropolygon(k), h.grid.micropolygon(k));
                    assert_eq!(bytemuck::bytes_of(&p), bytemuck::bytes_of(&q), "{name}");
                    a.clear();
                    b.clear();
                    g.grid.micropolygon_aovs(k, &mut a);
                    h.grid.micropolygon_aovs(k, &mut b);
                    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&a), bits(&b), "{name}");
                }
            }
        }
    }
}
