//! reyes-trace: a ray engine over the scene, for the distributed ray tracing of the later
//! stages (soft shadows, glossy reflection, translucency, the Appendix B hider).
//!
//! [`Tracer::new`] turns every surface the dicer would dice into one primitive (a quadric
//! or torus, a bilinear patch, each mesh face: quads as their bilinear patch, triangles and
//! the fan triangles of larger polygons as triangles) and builds a bounding volume
//! hierarchy over them. [`Tracer::intersect`] finds the nearest hit of a [`Ray`] and
//! [`Tracer::occluded`] whether there is any.
//!
//! Invariants and conventions:
//!
//! * **Same surfaces as the dicer.** Quadrics are intersected analytically in object space
//!   (`f64`), with the partial sweeps, z cuts and tube-angle ranges of `reyes_dice`; hits
//!   report the dicer's `(u, v)` and its outward geometric normal, carried to world space
//!   by the inverse transpose. Object-to-world matrices come from
//!   [`reyes_scene::object_to_world`] (transforms in list order).
//! * **Time.** `Ray::time` is normalised over the shutter: 0 at `open`, 1 at `close`. Key
//!   times are normalised the same way; before the first key and after the last the first
//!   or last key holds. With a closed shutter only the first key of each list is used.
//! * **Motion.** Transform keys are interpolated element-wise, which for affine keys moves
//!   every surface point exactly along the straight line between its key positions, as
//!   the dicer's lerp of world positions does (see `placement.rs`); deformation keys are
//!   interpolated point by point. Each primitive's box encloses it over the whole shutter
//!   (the union of its boxes at every pair of transform and deformation keys, which for
//!   affine keys contains every interpolated position).
//! * **Hits** have `0 < t < t_max`, `t` in units of `Ray::dir` (which need not be unit).
//!   The nearest hit wins; equal `t` goes to the primitive created first (scene order,
//!   then the dicer's surface order), so the answer never depends on the hierarchy.
//! * **Deterministic and shareable.** `Tracer` is immutable after construction
//!   (`Send + Sync`); traversal is iterative with a fixed-size stack; no allocation per ray.
//! * Objects whose matrix is singular or not finite are flattened and cannot be hit;
//!   primitives whose box is not finite (a projective matrix sending part of them to
//!   infinity) are tested against every ray instead of being put in the hierarchy.
#![deny(missing_docs)]

mod bvh;
mod patch;
mod placement;
mod poly;
mod quadric;

use glam::{DMat4, DVec3, Vec3};
use reyes_scene::object_to_world;
use reyes_scene::{Object, Scene, Shape, V3};

use crate::bvh::{Aabb, Bvh, NodeKind, STACK};
use crate::placement::{Frame, LocalRay, MatrixKey, Placement, bracket, is_projective};
use crate::quadric::{LocalHit, Quadric};

/// A ray `origin + t dir` at a time within the shutter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// World-space origin.
    pub origin: Vec3,
    /// World-space direction (any non-zero length; `t` is measured in its units).
    pub dir: Vec3,
    /// Time normalised over the shutter: 0 at open, 1 at close.
    pub time: f32,
}

impl Ray {
    /// A ray from its parts.
    pub fn new(origin: Vec3, dir: Vec3, time: f32) -> Ray {
        Ray { origin, dir, time }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// The nearest intersection of a ray with the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter, `0 < t < t_max`.
    pub t: f32,
    /// World-space point `origin + t dir`.
    pub p_world: Vec3,
    /// Unit geometric normal in world space, on the surface's outward side (the dicer's
    /// orientation), whichever side the ray arrived from.
    pub n_world: Vec3,
    /// Surface parameter `u` of the dicer's parametrisation of the hit surface.
    pub u: f32,
    /// Surface parameter `v`.
    pub v: f32,
    /// Index of the object in `Scene::objects`.
    pub object: u32,
    /// Index of the surface within the object, in the dicer's order (0 for quadrics and
    /// patches; for meshes, faces in list order with bad faces skipped and polygons of
    /// more than four vertices fanned into several triangles).
    pub surface: u32,
    /// Index of the mesh face in `Shape::Mesh::faces` (0 for other shapes).
    pub face: u32,
    /// The hit point in the object's own coordinates, before its transform (the dicer's
    /// `SurfacePoint::p`): for a moving object, in the frame at the ray's time; for a
    /// deforming mesh or patch, on the shape as deformed at the ray's time.
    pub p_object: Vec3,
}

impl Hit {
    /// A ray leaving the hit point in direction `dir` at `time`, its origin nudged off the
    /// surface to the side `dir` goes to, so that it does not hit the same surface at
    /// `t ~ 0` through rounding. The nudge is `1e-5 * (1 + max |p|)` along the normal.
    pub fn spawn(&self, dir: Vec3, time: f32) -> Ray {
        Ray::spawn(self.p_world, self.n_world, dir, time)
    }
}

impl Ray {
    /// A ray leaving the surface point `p` (normal `n`, either orientation) in direction
    /// `dir` at `time`, nudged off the surface as [`Hit::spawn`] does: by
    /// `1e-5 * (1 + max |p|)` along the normal, to the side `dir` goes to.
    pub fn spawn(p: Vec3, n: Vec3, dir: Vec3, time: f32) -> Ray {
        let eps = 1e-5 * (1.0 + p.abs().max_element());
        let side = if dir.dot(n) >= 0.0 { n } else { -n };
        Ray { origin: p + side * eps, dir, time }
    }
}

/// The points of a shape at one normalised time.
#[derive(Debug, Clone, PartialEq)]
struct PointKey {
    time: f32,
    points: Vec<Vec3>,
}

/// One primitive's geometry, in its object's placement space (world space when the
/// placement is `Identity`).
#[derive(Debug, Clone, PartialEq)]
enum Geometry {
    /// A quadric or torus.
    Quadric(Quadric),
    /// A bilinear patch, corners in RenderMan order.
    Patch([DVec3; 4]),
    /// A triangle `(a, b, c)`.
    Triangle([Vec3; 3]),
    /// A bilinear patch whose corners are the object's deforming points at these indices.
    DeformingPatch([u32; 4]),
    /// A triangle whose vertices are the object's deforming points at these indices.
    DeformingTriangle([u32; 3]),
}

#[derive(Debug, Clone, PartialEq)]
struct Primitive {
    geometry: Geometry,
    /// Creation order: scene order, then the dicer's surface order. Breaks ties in `t`.
    id: u32,
    object: u32,
    surface: u32,
    face: u32,
}

#[derive(Debug, Clone, PartialEq)]
struct ObjectData {
    placement: Placement,
    /// Deformation keys (two or more) of a deforming mesh or patch; empty otherwise.
    deform: Vec<PointKey>,
    /// World to object for an object whose still, affine transform was baked into its
    /// points (placement `Identity` but not object space), to report `Hit::p_object`.
    unbake: Option<DMat4>,
}

/// A candidate hit: world `t` and what is needed to report it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Candidate {
    t: f64,
    id: u32,
    slot: u32,
    /// World normal, not normalised.
    n: DVec3,
    u: f64,
    v: f64,
    /// The hit point in the primitive's placement space (object space, or world space for
    /// `Identity` placements).
    p: DVec3,
}

impl Candidate {
    /// Is `self` nearer than `best` (ties to the lower id)?
    #[inline]
    fn beats(&self, best: &Option<Candidate>) -> bool {
        match best {
            None => true,
            Some(b) => self.t < b.t || (self.t == b.t && self.id < b.id),
        }
    }
}

/// The frame of the last moving object met during one traversal.
#[derive(Default)]
struct FrameCache {
    object: Option<u32>,
    frame: Option<Frame>,
}

/// Where a primitive's geometry lives for one ray.
enum Space<'a> {
    World,
    Object(&'a Frame),
}

/// The ray engine: primitives of a scene under a bounding volume hierarchy.
#[derive(Debug, Clone)]
pub struct Tracer {
    objects: Vec<ObjectData>,
    /// Primitives in hierarchy slot order; the unbounded ones follow the bounded ones.
    prims: Vec<Primitive>,
    /// Number of primitives in the hierarchy (`prims[..bounded]`).
    bounded: usize,
    nodes: Vec<bvh::Node>,
}

/// Keys with strictly increasing normalised times (later keys at or before an earlier
/// time are dropped; only the first key when the shutter is closed).
fn clean_times<K>(
    keys: &[K],
    time: impl Fn(&K) -> f32,
    norm: impl Fn(f32) -> f32,
    closed: bool,
) -> Vec<(f32, &K)> {
    let mut out: Vec<(f32, &K)> = Vec::with_capacity(keys.len());
    for key in keys {
        let t = norm(time(key));
        if out.last().is_some_and(|(before, _)| t <= *before) {
            continue;
        }
        out.push((t, key));
        if closed {
            break;
        }
    }
    out
}

fn v3(p: &V3) -> Vec3 {
    Vec3::from(*p)
}

/// The box of the points `points` under every matrix of `matrices`, grown by a few ulps;
/// `None` when some image is not finite or the homogeneous `w` changes sign (the
/// primitive reaches infinity).
fn bound_points(matrices: &[DMat4], points: &[DVec3]) -> Option<Aabb> {
    let mut lo = DVec3::INFINITY;
    let mut hi = DVec3::NEG_INFINITY;
    let mut sign = 0.0_f64;
    for m in matrices {
        let projective = is_projective(m);
        for &p in points {
            let world = if projective {
                let h = *m * p.extend(1.0);
                if h.w == 0.0 || h.w.is_nan() || (sign != 0.0 && h.w.signum() != sign) {
                    return None;
                }
                sign = h.w.signum();
                h.truncate() / h.w
            } else {
                m.transform_point3(p)
            };
            lo = lo.min(world);
            hi = hi.max(world);
        }
    }
    if !lo.is_finite() || !hi.is_finite() {
        return None;
    }
    let scale = lo.abs().max(hi.abs()).max_element();
    let pad = scale * 8.0 * f64::from(f32::EPSILON) + f64::from(f32::MIN_POSITIVE);
    let b = Aabb { min: (lo - pad).as_vec3(), max: (hi + pad).as_vec3() };
    b.is_valid().then_some(b)
}

/// The eight corners of a box.
fn corners(lo: DVec3, hi: DVec3) -> [DVec3; 8] {
    std::array::from_fn(|k| {
        DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

/// Primitives being collected, with their boxes (`None`: unbounded).
#[derive(Default)]
struct Builder {
    objects: Vec<ObjectData>,
    prims: Vec<(Primitive, Option<Aabb>)>,
}

impl Builder {
    fn push(
        &mut self,
        geometry: Geometry,
        object: u32,
        surface: u32,
        face: u32,
        bounds: Option<Aabb>,
    ) {
        let id = self.prims.len() as u32;
        self.prims.push((Primitive { geometry, id, object, surface, face }, bounds));
    }

    /// Adds `object` (index `index`): its placement and its primitives.
    fn add(&mut self, index: u32, object: &Object, scene: &Scene) {
        let shutter = scene.camera.shutter;
        let span = shutter.close - shutter.open;
        let closed = !span.is_finite() || span <= 0.0;
        // As the dicer: clamped to [0, 1], NaN as 0, everything at 0 when the shutter is closed.
        let norm = |t: f32| {
            let t = if closed { 0.0 } else { (t - shutter.open) / span };
            if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) }
        };
        let still = object_to_world(&object.transform).as_dmat4();
        let mut keys: Vec<MatrixKey> = clean_times(&object.motion, |k| k.time, norm, closed)
            .into_iter()
            .map(|(time, k)| MatrixKey { time, matrix: object_to_world(&k.transform).as_dmat4() })
            .collect();
        if keys.is_empty() {
            keys.push(MatrixKey { time: 0.0, matrix: still });
        }
        let mut placement = Placement::from_keys(keys);
        let mut unbake = None;
        if placement == Placement::Degenerate {
            return;
        }

        // Points of a mesh or patch, per deformation key (one key when still).
        let own_points: Vec<Vec3> = match &object.shape {
            Shape::BilinearPatch { points } => points.iter().map(v3).collect(),
            Shape::Mesh { points, .. } => points.iter().map(v3).collect(),
            _ => Vec::new(),
        };
        // Deformation keys of a mesh or patch, each with exactly the shape's point count: a
        // missing point is the shape's own, extra points are ignored (as the dicer does).
        let mut point_keys: Vec<PointKey> = if own_points.is_empty() {
            Vec::new()
        } else {
            clean_times(&object.deform, |k| k.time, norm, closed)
                .into_iter()
                .map(|(time, k)| PointKey {
                    time,
                    points: own_points
                        .iter()
                        .enumerate()
                        .map(|(i, own)| k.points.get(i).map_or(*own, v3))
                        .collect(),
                })
                .collect()
        };
        if point_keys.is_empty() {
            point_keys = vec![PointKey { time: 0.0, points: own_points }];
        }
        // A still affine placement is baked into the points (exact: the dicer applies the
        // same matrix to the same points).
        if let Placement::Static(_) = &placement
            && !is_projective(&still)
            && !matches!(
                object.shape,
                Shape::Sphere { .. }
                    | Shape::Cylinder { .. }
                    | Shape::Cone { .. }
                    | Shape::Paraboloid { .. }
                    | Shape::Disk { .. }
                    | Shape::Torus { .. }
            )
        {
            for key in &mut point_keys {
                for p in &mut key.points {
                    *p = still.transform_point3(p.as_dvec3()).as_vec3();
                }
            }
            placement = Placement::Identity;
            // `Static` means invertible; identity matrices need no unbaking.
            if still != DMat4::IDENTITY {
                unbake = still.try_inverse().filter(|m| m.is_finite());
            }
        }
        let matrices = placement.key_matrices();
        let deforming = point_keys.len() > 1;
        let point_sets = |idx: &[u32]| -> Vec<DVec3> {
            point_keys
                .iter()
                .flat_map(|k| {
                    idx.iter().filter_map(|&i| k.points.get(i as usize)).map(|p| p.as_dvec3())
                })
                .collect()
        };
        let first_points = point_keys.first().map_or(&[][..], |k| k.points.as_slice());
        let first = |i: u32| first_points.get(i as usize).copied().unwrap_or(Vec3::ZERO);

        match &object.shape {
            Shape::Sphere { .. }
            | Shape::Cylinder { .. }
            | Shape::Cone { .. }
            | Shape::Paraboloid { .. }
            | Shape::Disk { .. }
            | Shape::Torus { .. } => {
                if let Some(q) = Quadric::from_shape(&object.shape) {
                    let (lo, hi) = q.object_bounds();
                    let b = bound_points(&matrices, &corners(lo, hi));
                    self.push(Geometry::Quadric(q), index, 0, 0, b);
                }
            }
            Shape::BilinearPatch { .. } => {
                let idx = [0, 1, 2, 3];
                let b = bound_points(&matrices, &point_sets(&idx));
                let g = if deforming {
                    Geometry::DeformingPatch(idx)
                } else {
                    Geometry::Patch(idx.map(|i| first(i).as_dvec3()))
                };
                self.push(g, index, 0, 0, b);
            }
            Shape::Mesh { points, faces, .. } => {
                let mut surface = 0u32;
                for (f, face) in faces.iter().enumerate() {
                    if face.iter().any(|&i| i as usize >= points.len()) {
                        continue;
                    }
                    match face.len() {
                        0..=2 => {}
                        4 => {
                            // Around the face a, b, c, d: P0 = a, P1 = b, P2 = d, P3 = c.
                            let idx = [face[0], face[1], face[3], face[2]];
                            let b = bound_points(&matrices, &point_sets(&idx));
                            let g = if deforming {
                                Geometry::DeformingPatch(idx)
                            } else {
                                Geometry::Patch(idx.map(|i| first(i).as_dvec3()))
                            };
                            self.push(g, index, surface, f as u32, b);
                            surface += 1;
                        }
                        n => {
                            for k in 1..n - 1 {
                                let idx = [face[0], face[k], face[k + 1]];
                                let b = bound_points(&matrices, &point_sets(&idx));
                                let g = if deforming {
                                    Geometry::DeformingTriangle(idx)
                                } else {
                                    Geometry::Triangle(idx.map(first))
                                };
                                self.push(g, index, surface, f as u32, b);
                                surface += 1;
                            }
                        }
                    }
                }
            }
        }
        let deform = if deforming { point_keys } else { Vec::new() };
        // Keep `objects[index]` aligned with scene indices.
        while self.objects.len() < index as usize {
            self.objects.push(ObjectData {
                placement: Placement::Degenerate,
                deform: Vec::new(),
                unbake: None,
            });
        }
        self.objects.push(ObjectData { placement, deform, unbake });
    }
}

impl Tracer {
    /// Builds the primitives of every object of `scene` and the hierarchy over them.
    pub fn new(scene: &Scene) -> Tracer {
        let mut builder = Builder::default();
        for (i, object) in scene.objects.iter().enumerate() {
            builder.add(i as u32, object, scene);
        }
        let mut objects = builder.objects;
        while objects.len() < scene.objects.len() {
            objects.push(ObjectData {
                placement: Placement::Degenerate,
                deform: Vec::new(),
                unbake: None,
            });
        }
        let (bounded, unbounded): (Vec<_>, Vec<_>) =
            builder.prims.into_iter().partition(|(_, b)| b.is_some());
        let boxes: Vec<Aabb> = bounded.iter().map(|(_, b)| b.unwrap_or(Aabb::EMPTY)).collect();
        let Bvh { nodes, order } = bvh::build(&boxes);
        let mut slots: Vec<Option<Primitive>> = bounded.into_iter().map(|(p, _)| Some(p)).collect();
        let mut prims: Vec<Primitive> =
            order.iter().filter_map(|&i| slots[i as usize].take()).collect();
        let bounded = prims.len();
        prims.extend(unbounded.into_iter().map(|(p, _)| p));
        Tracer { objects, prims, bounded, nodes }
    }

    /// Number of primitives (quadrics, patches, mesh faces and fan triangles).
    pub fn primitive_count(&self) -> usize {
        self.prims.len()
    }

    /// Number of hierarchy nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The nearest hit with `0 < t < t_max`, if any.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.traverse(ray, t_max, false).map(|c| self.hit(ray, &c))
    }

    /// Is there any hit with `0 < t < t_max`? Agrees with `intersect(ray, t_max).is_some()`.
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.traverse(ray, t_max, true).is_some()
    }

    /// The same answer as [`Tracer::intersect`], found by testing every primitive without
    /// the hierarchy: a reference for tests and measurements.
    pub fn intersect_exhaustive(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        let mut cache = FrameCache::default();
        let mut best: Option<Candidate> = None;
        for slot in 0..self.prims.len() {
            self.consider(slot, ray, t_max, &mut cache, &mut best);
        }
        best.map(|c| self.hit(ray, &c))
    }

    /// Tests slot `slot` and keeps the candidate if it beats `best`.
    #[inline]
    fn consider(
        &self,
        slot: usize,
        ray: &Ray,
        t_max: f32,
        cache: &mut FrameCache,
        best: &mut Option<Candidate>,
    ) {
        if let Some(c) = self.test(slot, ray, cache)
            && c.t < f64::from(t_max)
            && c.beats(best)
        {
            *best = Some(c);
        }
    }

    /// Iterative traversal; with `any`, returns the first hit found.
    fn traverse(&self, ray: &Ray, t_max: f32, any: bool) -> Option<Candidate> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        let mut cache = FrameCache::default();
        let mut best: Option<Candidate> = None;
        for slot in self.bounded..self.prims.len() {
            self.consider(slot, ray, t_max, &mut cache, &mut best);
            if any && best.is_some() {
                return best;
            }
        }
        if self.nodes.is_empty() {
            return best;
        }
        let inv_dir = ray.dir.recip();
        let parallel = !inv_dir.is_finite();
        // Is the box entered before the current limit? Its entry parameter if so.
        let enters = |bounds: &Aabb, limit: f64| {
            let (near, far) = if parallel {
                bounds.slab_parallel(ray.origin, inv_dir)
            } else {
                bounds.slab(ray.origin, inv_dir)
            };
            (near <= far && far >= 0.0 && f64::from(near) <= limit).then_some(near)
        };
        let limit = |best: &Option<Candidate>| best.map_or(f64::from(t_max), |b| b.t);
        // Pending far children with their entry parameters.
        let mut stack = [(0u32, 0.0f32); STACK];
        let mut top = 0usize;
        let mut current = match self.nodes.first() {
            Some(root) if enters(&root.bounds, limit(&best)).is_some() => Some(0usize),
            _ => None,
        };
        loop {
            if let Some(index) = current
                && let Some(node) = self.nodes.get(index)
            {
                current = None;
                match node.kind {
                    NodeKind::Leaf { first, count } => {
                        for slot in first as usize..(first + count) as usize {
                            self.consider(slot, ray, t_max, &mut cache, &mut best);
                            if any && best.is_some() {
                                return best;
                            }
                        }
                    }
                    NodeKind::Interior { right } => {
                        let (left, right) = (index + 1, right as usize);
                        let lim = limit(&best);
                        let hit_left = self.nodes.get(left).and_then(|n| enters(&n.bounds, lim));
                        let hit_right = self.nodes.get(right).and_then(|n| enters(&n.bounds, lim));
                        match (hit_left, hit_right) {
                            (Some(l), Some(r)) => {
                                let (near, far, far_t) =
                                    if r < l { (right, left, l) } else { (left, right, r) };
                                // The tree is at most MAX_DEPTH < STACK deep: there is room.
                                stack[top] = (far as u32, far_t);
                                top += 1;
                                current = Some(near);
                            }
                            (Some(_), None) => current = Some(left),
                            (None, Some(_)) => current = Some(right),
                            (None, None) => {}
                        }
                    }
                }
                if current.is_some() {
                    continue;
                }
            }
            // Pop the next pending node still entered before the limit.
            let lim = limit(&best);
            loop {
                if top == 0 {
                    return best;
                }
                top -= 1;
                let (index, near) = stack[top];
                if f64::from(near) <= lim {
                    current = Some(index as usize);
                    break;
                }
            }
        }
    }

    /// The space primitive geometry of `object` lives in at the ray's time, or `None` when
    /// the object cannot be hit then.
    fn space<'a>(&'a self, object: u32, time: f32, cache: &'a mut FrameCache) -> Option<Space<'a>> {
        match &self.objects.get(object as usize)?.placement {
            Placement::Identity => Some(Space::World),
            Placement::Static(frame) => Some(Space::Object(frame)),
            Placement::Degenerate => None,
            moving @ Placement::Moving(_) => {
                if cache.object != Some(object) {
                    cache.object = Some(object);
                    cache.frame = moving.matrix_at(time).and_then(Frame::new);
                }
                cache.frame.as_ref().map(Space::Object)
            }
        }
    }

    /// The candidate hit of the primitive in `slot`.
    fn test(&self, slot: usize, ray: &Ray, cache: &mut FrameCache) -> Option<Candidate> {
        let prim = self.prims.get(slot)?;
        let space = self.space(prim.object, ray.time, cache)?;
        let make = |t: f64, n: DVec3, u: f64, v: f64, p: DVec3| {
            (t > 0.0 && t.is_finite()).then_some(Candidate {
                t,
                id: prim.id,
                slot: slot as u32,
                n,
                u,
                v,
                p,
            })
        };
        let local_ray = |space: &Space| match space {
            Space::World => Some(LocalRay::world(ray.origin, ray.dir)),
            Space::Object(frame) => frame.localise(ray.origin, ray.dir),
        };
        let from_local = |space: &Space, local: &LocalRay, h: LocalHit| {
            let n = match space {
                Space::World => h.n,
                Space::Object(frame) => frame.normal_to_world(h.p, h.n),
            };
            make(local.world_t(h.s), n, h.u, h.v, h.p)
        };
        let triangle = |tri: &[Vec3; 3]| match &space {
            Space::World => {
                let h = patch::triangle(tri, ray.origin, ray.dir)?;
                let t = f64::from(h.t);
                make(
                    t,
                    patch::triangle_normal(tri).as_dvec3(),
                    f64::from(h.u),
                    f64::from(h.v),
                    ray.origin.as_dvec3() + ray.dir.as_dvec3() * t,
                )
            }
            Space::Object(frame) => {
                let local = frame.localise(ray.origin, ray.dir)?;
                let h = patch::triangle(tri, local.o.as_vec3(), local.d.as_vec3())?;
                let s = f64::from(h.t);
                let p = local.o + local.d * s;
                let n = frame.normal_to_world(p, patch::triangle_normal(tri).as_dvec3());
                make(local.world_t(s), n, f64::from(h.u), f64::from(h.v), p)
            }
        };
        match &prim.geometry {
            Geometry::Triangle(tri) => triangle(tri),
            Geometry::Quadric(q) => {
                let local = local_ray(&space)?;
                from_local(&space, &local, q.intersect(&local)?)
            }
            Geometry::Patch(p) => {
                let local = local_ray(&space)?;
                from_local(&space, &local, patch::bilinear(p, &local)?)
            }
            Geometry::DeformingTriangle(idx) => {
                let keys = &self.objects.get(prim.object as usize)?.deform;
                let tri = deformed(keys, idx, ray.time)?;
                triangle(&tri)
            }
            Geometry::DeformingPatch(idx) => {
                let keys = &self.objects.get(prim.object as usize)?.deform;
                let p = deformed(keys, idx, ray.time)?.map(|p| p.as_dvec3());
                let local = local_ray(&space)?;
                from_local(&space, &local, patch::bilinear(&p, &local)?)
            }
        }
    }

    /// The reported hit of a candidate.
    fn hit(&self, ray: &Ray, c: &Candidate) -> Hit {
        let (object, surface, face) =
            self.prims.get(c.slot as usize).map_or((0, 0, 0), |p| (p.object, p.surface, p.face));
        let p = ray.origin.as_dvec3() + ray.dir.as_dvec3() * c.t;
        let n = c.n.try_normalize().unwrap_or(DVec3::Z);
        let p_object = match self.objects.get(object as usize).and_then(|o| o.unbake) {
            Some(to_object) => to_object.transform_point3(c.p),
            None => c.p,
        };
        Hit {
            t: c.t as f32,
            p_world: p.as_vec3(),
            n_world: n.as_vec3(),
            u: c.u as f32,
            v: c.v as f32,
            object,
            surface,
            face,
            p_object: p_object.as_vec3(),
        }
    }
}

/// The deforming points `idx` at normalised `time`.
fn deformed<const N: usize>(keys: &[PointKey], idx: &[u32; N], time: f32) -> Option<[Vec3; N]> {
    let (i, j, w) = bracket(keys.iter().map(|k| k.time), time);
    let (a, b) = (&keys.get(i)?.points, &keys.get(j)?.points);
    let mut out = [Vec3::ZERO; N];
    for (o, &k) in out.iter_mut().zip(idx) {
        let k = k as usize;
        *o = a.get(k)?.lerp(*b.get(k)?, w);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tracer_is_send_and_sync() {
        fn check<T: Send + Sync>() {}
        check::<Tracer>();
    }
}
