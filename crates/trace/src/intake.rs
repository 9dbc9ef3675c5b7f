//! The intake of the scene: every object's placement (transform and motion keys), its
//! deformation keys and its primitives, with their boxes, collected into a [`Tracer`].
//!
//! Invariants: `Tracer::objects[i]` is the data of `Scene::objects[i]` (a degenerate
//! placement for objects that cannot be hit); primitive ids follow creation order (scene
//! order, then the dicer's surface order); key times are normalised over the shutter and
//! strictly increasing; a still affine transform of a mesh or patch is baked into its
//! points exactly as the dicer applies it; every primitive's box encloses it over the
//! whole shutter, or is `None` when the primitive reaches infinity.

use glam::{DMat4, DVec3, Vec3};
use reyes_scene::object_to_world;
use reyes_scene::patches;
use reyes_scene::patches::trim::TrimRegion;
use reyes_scene::{Object, PatchType, Scene, Shape, V3};

use crate::Tracer;
use crate::bvh::{self, Aabb, Bvh};
use crate::placement::{MatrixKey, Placement, is_projective};
use crate::quadric::Quadric;
use crate::{subdivide, tessellate};

/// The points of a shape at one normalised time (and, for a tessellated patch mesh or
/// NURBS, the exact surface normal at each of its vertices; empty otherwise).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PointKey {
    pub(crate) time: f32,
    pub(crate) points: Vec<Vec3>,
    pub(crate) normals: Vec<Vec3>,
}

/// One primitive's geometry, in its object's placement space (world space when the
/// placement is `Identity`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Geometry {
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
    /// A triangle of a tessellated patch: vertices, their exact surface normals and their
    /// `(u, v)` on the patch.
    /// `None` for a mesh triangle with vertex normals, whose hit keeps the triangle's own
    /// `(u, v)` (the dicer's convention) and whose normal is turned to the winding's side.
    SmoothTriangle { p: [Vec3; 3], n: [Vec3; 3], uv: Option<[[f32; 2]; 3]> },
    /// A deforming [`Geometry::SmoothTriangle`]: vertices and normals are the object's
    /// deforming points and normals at these indices.
    DeformingSmoothTriangle { idx: [u32; 3], uv: Option<[[f32; 2]; 3]> },
    /// A mesh quad with vertex normals (corners in RenderMan order): hit as the bilinear
    /// patch, shaded with the corners' normals interpolated bilinearly at the hit's `(u, v)`
    /// and turned to the side of the patch's own normal, as the dicer shades it.
    SmoothPatch { p: [DVec3; 4], n: [Vec3; 4] },
    /// A deforming [`Geometry::SmoothPatch`]: corners and normals are the object's deforming
    /// points and normals at these indices.
    DeformingSmoothPatch([u32; 4]),
}

/// One primitive and what a hit on it reports.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Primitive {
    pub(crate) geometry: Geometry,
    /// Creation order: scene order, then the dicer's surface order. Breaks ties in `t`.
    pub(crate) id: u32,
    pub(crate) object: u32,
    pub(crate) surface: u32,
    pub(crate) face: u32,
}

/// What the queries need of one scene object, whatever its primitives.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ObjectData {
    pub(crate) placement: Placement,
    /// Deformation keys (two or more) of a deforming mesh or patch; empty otherwise.
    pub(crate) deform: Vec<PointKey>,
    /// World to object for an object whose still, affine transform was baked into its
    /// points (placement `Identity` but not object space), to report `Hit::p_object`.
    pub(crate) unbake: Option<DMat4>,
    /// A trimmed NURBS patch's trim region and the parameter rectangle of each span: a hit
    /// on a span at its own `(s, t)` is dropped where the patch's `(u, v)` is trimmed away.
    pub(crate) trim: Option<Box<(TrimRegion, Vec<[f64; 4]>)>>,
}

impl ObjectData {
    /// Whether the hit at `(s, t)` of surface `surface` lies in the trimmed region.
    pub(crate) fn trimmed(&self, surface: u32, s: f64, t: f64) -> bool {
        let Some(trim) = &self.trim else { return false };
        let (region, spans) = &**trim;
        match spans.get(surface as usize) {
            Some([u0, u1, v0, v1]) => region.removes(u0 + s * (u1 - u0), v0 + t * (v1 - v0)),
            None => false,
        }
    }
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

    /// Adds the primitives of `object` (index `index`) and returns its data.
    fn add(&mut self, index: u32, object: &Object, scene: &Scene) -> ObjectData {
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
            return ObjectData { placement, deform: Vec::new(), unbake: None, trim: None };
        }

        // Points of a mesh or patch, per deformation key (one key when still).
        let subdivided = matches!(object.shape, Shape::SubdivisionMesh { .. });
        let tessellated = patches::is_bezier_shape(&object.shape) || subdivided;
        let own_points: Vec<Vec3> = match &object.shape {
            Shape::BilinearPatch { points } => points.iter().map(v3).collect(),
            Shape::Mesh { points, .. } => points.iter().map(v3).collect(),
            Shape::PatchMesh { kind: PatchType::Bilinear, points, .. } => {
                points.iter().map(v3).collect()
            }
            Shape::SubdivisionMesh { points, .. } => points.iter().map(v3).collect(),
            _ if tessellated => tessellate::own_positions(&object.shape),
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
                    normals: Vec::new(),
                })
                .collect()
        };
        if point_keys.is_empty() {
            point_keys = vec![PointKey { time: 0.0, points: own_points, normals: Vec::new() }];
        }
        // A mesh's vertex normals, the same at every key (they are not keyed).
        let mesh_normals = match &object.shape {
            Shape::Mesh { normals: Some(n), points, .. } if n.len() == points.len() => {
                let n: Vec<Vec3> = n.iter().map(v3).collect();
                for key in &mut point_keys {
                    key.normals.clone_from(&n);
                }
                true
            }
            _ => false,
        };
        // A still affine placement of a mesh or patch is baked into its points (exact: the
        // dicer applies the same matrix to the same points); a tessellated patch's into its
        // vertices and normals once they are made.
        let mut bake = None;
        if let Placement::Static(_) = &placement
            && !is_projective(&still)
            && (matches!(
                object.shape,
                Shape::BilinearPatch { .. }
                    | Shape::Mesh { .. }
                    | Shape::PatchMesh { kind: PatchType::Bilinear, .. }
            ) || tessellated)
        {
            if tessellated {
                bake = Some(still);
            } else {
                // Normals go by the inverse transpose (`Static` means invertible).
                let normal_matrix = still.inverse().transpose();
                for key in &mut point_keys {
                    for p in &mut key.points {
                        *p = still.transform_point3(p.as_dvec3()).as_vec3();
                    }
                    for n in &mut key.normals {
                        *n = normal_matrix.transform_vector3(n.as_dvec3()).as_vec3();
                    }
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
        if tessellated {
            let t = if subdivided {
                subdivide::tessellate(&object.shape, &point_keys, bake.as_ref())
            } else {
                tessellate::tessellate(&object.shape, &point_keys, bake.as_ref())
            };
            point_keys = t.keys;
            self.add_tessellated(index, &t.tris, &point_keys, &matrices, deforming);
        }
        // The box of the points `idx` at every deformation key under every transform key.
        let bound = |idx: &[u32]| {
            let points: Vec<DVec3> = point_keys
                .iter()
                .flat_map(|k| {
                    idx.iter().filter_map(|&i| k.points.get(i as usize)).map(|p| p.as_dvec3())
                })
                .collect();
            bound_points(&matrices, &points)
        };
        let first_points = point_keys.first().map_or(&[][..], |k| k.points.as_slice());
        let first = |i: u32| first_points.get(i as usize).copied().unwrap_or(Vec3::ZERO);
        let first_normals = point_keys.first().map_or(&[][..], |k| k.normals.as_slice());
        let first_normal = |i: u32| first_normals.get(i as usize).copied().unwrap_or(Vec3::Z);
        // The bilinear patch with corners `idx`, RenderMan order.
        let patch = |idx: [u32; 4]| {
            if deforming {
                Geometry::DeformingPatch(idx)
            } else {
                Geometry::Patch(idx.map(|i| first(i).as_dvec3()))
            }
        };

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
                self.push(patch(idx), index, 0, 0, bound(&idx));
            }
            Shape::Hyperboloid { .. } => {
                if let Some(q) = Quadric::from_shape(&object.shape) {
                    let (lo, hi) = q.object_bounds();
                    let b = bound_points(&matrices, &corners(lo, hi));
                    self.push(Geometry::Quadric(q), index, 0, 0, b);
                }
            }
            Shape::PatchMesh { kind: PatchType::Bilinear, .. } => {
                for (k, idx) in patches::bilinear_corners(&object.shape).into_iter().enumerate() {
                    self.push(patch(idx), index, k as u32, 0, bound(&idx));
                }
            }
            // Tessellated above.
            Shape::PatchMesh { .. } | Shape::NuPatch { .. } | Shape::SubdivisionMesh { .. } => {}
            // Read into a Mesh when the scene was loaded.
            Shape::MeshFile { .. } => {}
            // Not in the ray engine yet (docs/geometry.md, "Curves, points and blobbies").
            Shape::Curves { .. } | Shape::Points { .. } | Shape::Blobby { .. } => {}
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
                            let g = match (mesh_normals, deforming) {
                                (false, _) => patch(idx),
                                (true, true) => Geometry::DeformingSmoothPatch(idx),
                                (true, false) => Geometry::SmoothPatch {
                                    p: idx.map(|i| first(i).as_dvec3()),
                                    n: idx.map(first_normal),
                                },
                            };
                            self.push(g, index, surface, f as u32, bound(&idx));
                            surface += 1;
                        }
                        n => {
                            for k in 1..n - 1 {
                                let idx = [face[0], face[k], face[k + 1]];
                                let b = bound(&idx);
                                let g = match (mesh_normals, deforming) {
                                    (false, true) => Geometry::DeformingTriangle(idx),
                                    (false, false) => Geometry::Triangle(idx.map(first)),
                                    (true, true) => {
                                        Geometry::DeformingSmoothTriangle { idx, uv: None }
                                    }
                                    (true, false) => Geometry::SmoothTriangle {
                                        p: idx.map(first),
                                        n: idx.map(first_normal),
                                        uv: None,
                                    },
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
        let trim = TrimRegion::of(&object.shape)
            .map(|r| Box::new((r, reyes_scene::patches::trim::span_domains(&object.shape))));
        ObjectData { placement, deform, unbake, trim }
    }
}

impl Builder {
    /// Adds the triangles of a tessellated patch mesh, NURBS or subdivision mesh, whose vertices and normals
    /// at every key are `keys` (boxes over every key under every matrix).
    fn add_tessellated(
        &mut self,
        index: u32,
        tris: &[tessellate::Tri],
        keys: &[PointKey],
        matrices: &[DMat4],
        deforming: bool,
    ) {
        let first = keys.first();
        for tri in tris {
            let at = |k: &PointKey, i: u32| k.points.get(i as usize).copied();
            let points: Vec<DVec3> = keys
                .iter()
                .flat_map(|k| tri.idx.iter().filter_map(move |&i| at(k, i)))
                .map(|p| p.as_dvec3())
                .collect();
            let b = bound_points(matrices, &points);
            let g = if deforming {
                Geometry::DeformingSmoothTriangle { idx: tri.idx, uv: Some(tri.uv) }
            } else {
                let Some(k) = first else { continue };
                let p = tri.idx.map(|i| at(k, i).unwrap_or(Vec3::ZERO));
                let n = tri.idx.map(|i| k.normals.get(i as usize).copied().unwrap_or(Vec3::Z));
                Geometry::SmoothTriangle { p, n, uv: Some(tri.uv) }
            };
            self.push(g, index, tri.surface, 0, b);
        }
    }
}

/// Builds the primitives of every object of `scene` and the hierarchy over them.
pub(crate) fn build(scene: &Scene) -> Tracer {
    let mut builder = Builder::default();
    // One entry per scene object, so that `objects[i]` is `scene.objects[i]`.
    let objects: Vec<ObjectData> = scene
        .objects
        .iter()
        .enumerate()
        .map(|(i, object)| builder.add(i as u32, object, scene))
        .collect();
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
