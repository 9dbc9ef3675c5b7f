//! reyes-trace: a ray engine over the scene, for the distributed ray tracing of the later
//! stages (soft shadows, glossy reflection, translucency, the Appendix B hider).
//!
//! [`Tracer::new`] turns every surface the dicer would dice into one primitive (a quadric,
//! torus or hyperboloid, a bilinear patch or bilinear patch-mesh sub-patch, each mesh face:
//! quads as their bilinear patch, triangles and the fan triangles of larger polygons as
//! triangles), or, for a bicubic patch-mesh sub-patch or a NURBS span, into the triangles of
//! its tessellation (`tessellate.rs`: vertices and normals on the exact surface, the surface
//! within 1/1000 of the patch's size of its triangles by a proven bound, hits reporting the
//! normals interpolated), or, for a Catmull-Clark subdivision mesh, each limit patch into the
//! triangles of its tessellation (`subdivide.rs`: the same rule, one grid for the whole mesh so
//! that neighbouring patches meet vertex to vertex), and builds a bounding volume hierarchy over them. [`Tracer::intersect`] finds the nearest hit of a [`Ray`] and
//! [`Tracer::occluded`] whether there is any.
//!
//! Layout: this file holds the API; `intake.rs` turns the scene into primitives and their
//! boxes, `bvh.rs` builds the hierarchy over them and `query.rs` traverses it, intersecting
//! each primitive met (`quadric.rs`, `patch.rs`; `placement.rs` carries the ray into the
//! object's space at its time; `poly.rs` solves the polynomials; `tessellate.rs` makes the
//! triangles of bicubic patch meshes and NURBS, `subdivide.rs` those of subdivision meshes).
//!
//! Invariants and conventions:
//!
//! * **Same surfaces as the dicer** (but for the tessellated patches, which are within their
//!   stated bound of it). Quadrics are intersected analytically in object space
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
mod intake;
mod patch;
mod placement;
mod poly;
mod quadric;
mod query;
mod subdivide;
mod tessellate;

use glam::Vec3;
use reyes_scene::Scene;

use crate::intake::{ObjectData, Primitive};

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
    /// more than four vertices fanned into several triangles; for patch meshes and NURBS,
    /// the sub-patch or knot span, row by row; for subdivision meshes, the limit patch in
    /// `reyes_subdiv::limit_patches` order, `(u, v)` the patch's own).
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

/// The ray engine: primitives of a scene under a bounding volume hierarchy.
#[derive(Debug, Clone)]
pub struct Tracer {
    /// Per scene object, in scene order (see `intake.rs`).
    objects: Vec<ObjectData>,
    /// Primitives in hierarchy slot order; the unbounded ones follow the bounded ones.
    prims: Vec<Primitive>,
    /// Number of primitives in the hierarchy (`prims[..bounded]`).
    bounded: usize,
    /// The hierarchy over `prims[..bounded]`, root first.
    nodes: Vec<bvh::Node>,
}

impl Tracer {
    /// Builds the primitives of every object of `scene` and the hierarchy over them.
    pub fn new(scene: &Scene) -> Tracer {
        intake::build(scene)
    }

    /// Number of primitives (quadrics, patches, mesh faces, fan triangles and the triangles
    /// of tessellated patches).
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
        self.exhaustive(ray, t_max).map(|c| self.hit(ray, &c))
    }
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
