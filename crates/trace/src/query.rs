//! Queries: the traversal of the hierarchy, the intersection of a ray with one primitive
//! in its placement space at the ray's time, and the reported [`Hit`].
//!
//! Invariants: traversal is iterative with a fixed-size stack and allocates nothing; a
//! candidate replaces the best one only when nearer or equally near with a lower id, so
//! the answer never depends on the hierarchy; `t` is compared in world units of
//! `Ray::dir`, in `f64`.

use glam::{DVec3, Vec3};

use crate::bvh::{Aabb, NodeKind, STACK};
use crate::intake::{Geometry, PointKey};
use crate::placement::{Frame, LocalRay, Placement, bracket};
use crate::quadric::LocalHit;
use crate::{Hit, Ray, Tracer, patch, tessellate};

/// A candidate hit: world `t` and what is needed to report it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Candidate {
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

impl Tracer {
    /// The best candidate of all primitives, tested one by one without the hierarchy.
    pub(crate) fn exhaustive(&self, ray: &Ray, t_max: f32) -> Option<Candidate> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        let mut cache = FrameCache::default();
        let mut best: Option<Candidate> = None;
        for slot in 0..self.prims.len() {
            self.consider(slot, ray, t_max, &mut cache, &mut best);
        }
        best
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
    pub(crate) fn traverse(&self, ray: &Ray, t_max: f32, any: bool) -> Option<Candidate> {
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
        // A tessellated patch's triangle: the exact normals and `(u, v)` of its vertices,
        // interpolated (the flat normal where the interpolation vanishes).
        let smooth = |tri: &[Vec3; 3], normals: &[Vec3; 3], uv: &Option<[[f32; 2]; 3]>| {
            let (origin, dir) = match &space {
                Space::World => (ray.origin, ray.dir),
                Space::Object(frame) => {
                    let local = frame.localise(ray.origin, ray.dir)?;
                    (local.o.as_vec3(), local.d.as_vec3())
                }
            };
            let h = patch::triangle(tri, origin, dir)?;
            let (wb, wc) = tessellate::weights(h.u, h.v);
            let wa = 1.0 - wb - wc;
            let flat = patch::triangle_normal(tri);
            let n = tessellate::interpolate_normal(normals, wb, wc).unwrap_or(flat);
            let (u, v, n) = match uv {
                Some(uv) => {
                    let u = wa * uv[0][0] + wb * uv[1][0] + wc * uv[2][0];
                    let v = wa * uv[0][1] + wb * uv[1][1] + wc * uv[2][1];
                    (u, v, n)
                }
                // A mesh triangle: the dicer's (u, v), the normal on the winding's side.
                None => (h.u, h.v, if n.dot(flat) < 0.0 { -n } else { n }),
            };
            let n = n.as_dvec3();
            let s = f64::from(h.t);
            let (u, v) = (f64::from(u), f64::from(v));
            match &space {
                Space::World => make(s, n, u, v, ray.origin.as_dvec3() + ray.dir.as_dvec3() * s),
                Space::Object(frame) => {
                    let local = frame.localise(ray.origin, ray.dir)?;
                    let p = local.o + local.d * s;
                    make(local.world_t(s), frame.normal_to_world(p, n), u, v, p)
                }
            }
        };
        let c = match &prim.geometry {
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
            Geometry::SmoothTriangle { p, n, uv } => smooth(p, n, uv),
            Geometry::DeformingSmoothTriangle { idx, uv } => {
                let keys = &self.objects.get(prim.object as usize)?.deform;
                let (p, n) = deformed_smooth(keys, idx, ray.time)?;
                smooth(&p, &n, uv)
            }
            Geometry::SmoothPatch { p, n } => {
                let local = local_ray(&space)?;
                from_local(&space, &local, smooth_patch(n, patch::bilinear(p, &local)?))
            }
            Geometry::DeformingSmoothPatch(idx) => {
                let keys = &self.objects.get(prim.object as usize)?.deform;
                let (p, n) = deformed_smooth(keys, idx, ray.time)?;
                let p = p.map(|p| p.as_dvec3());
                let local = local_ray(&space)?;
                from_local(&space, &local, smooth_patch(&n, patch::bilinear(&p, &local)?))
            }
            Geometry::DeformingPatch(idx) => {
                let keys = &self.objects.get(prim.object as usize)?.deform;
                let p = deformed(keys, idx, ray.time)?.map(|p| p.as_dvec3());
                let local = local_ray(&space)?;
                from_local(&space, &local, patch::bilinear(&p, &local)?)
            }
        }?;
        // A trimmed NURBS patch has no surface where its trim curves remove it.
        let object = self.objects.get(prim.object as usize)?;
        (!object.trimmed(prim.surface, c.u, c.v)).then_some(c)
    }

    /// The reported hit of a candidate.
    pub(crate) fn hit(&self, ray: &Ray, c: &Candidate) -> Hit {
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
#[inline]
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

/// The deforming points and normals `idx` at normalised `time` (normals lerped, not
/// normalised: the hit normalises them).
#[inline]
fn deformed_smooth<const N: usize>(
    keys: &[PointKey],
    idx: &[u32; N],
    time: f32,
) -> Option<([Vec3; N], [Vec3; N])> {
    let p = deformed(keys, idx, time)?;
    let (i, j, w) = bracket(keys.iter().map(|k| k.time), time);
    let (a, b) = (&keys.get(i)?.normals, &keys.get(j)?.normals);
    let mut n = [Vec3::ZERO; N];
    for (o, &k) in n.iter_mut().zip(idx) {
        let k = k as usize;
        *o = a.get(k)?.lerp(*b.get(k)?, w);
    }
    Some((p, n))
}

/// The hit `h` of a bilinear patch with its corner normals `n` (RenderMan order)
/// interpolated bilinearly at its `(u, v)`, normalised and turned to the side of the patch's
/// own normal (as the dicer's mesh quads); the patch's normal where they cancel.
fn smooth_patch(n: &[Vec3; 4], mut h: LocalHit) -> LocalHit {
    let (u, v) = (h.u as f32, h.v as f32);
    let bottom = n[0].lerp(n[1], u);
    let top = n[2].lerp(n[3], u);
    if let Some(s) = bottom.lerp(top, v).try_normalize() {
        let s = s.as_dvec3();
        h.n = if s.dot(h.n) < 0.0 { -s } else { s };
    }
    h
}
