//! Inside tests of FIG. 23's measurement: whether a world-space point lies inside a closed
//! object (closed forms for the quadrics, ray-crossing parity for meshes) or a CSG solid (the
//! operands' answers combined by the tree), and the world-space bounds of each.
//!
//! Invariant: an answer depends only on the point and the key of its cell (which picks the
//! perturbation of a mesh's ray), never on the order of the calls.

use glam::{DMat4, DVec3, Vec3};
use reyes_scene::object_to_world;
use reyes_scene::{Csg, Object, Scene, Shape};
use reyes_trace::{Ray, Tracer};

use crate::estimator::draw;
use crate::{MeasureError, quoted};

/// A closed quadric or torus in object space (full sweep), for the closed-form inside test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Quadric {
    /// `x^2 + y^2 + z^2 <= r^2`.
    Sphere { r2: f64 },
    /// `x^2 + y^2 <= r^2`, `zmin <= z <= zmax` (closed by its end caps).
    Cylinder { r2: f64, zmin: f64, zmax: f64 },
    /// Base of `radius` at z = 0, apex at z = `height` (closed by its base).
    Cone { height: f64, radius: f64 },
    /// `x^2 + y^2 <= k z`, `zmin <= z <= zmax` (closed by its end caps).
    Paraboloid { k: f64, zmin: f64, zmax: f64 },
    /// `(sqrt(x^2 + y^2) - major)^2 + z^2 <= minor^2`.
    Torus { major: f64, minor: f64 },
}

impl Quadric {
    #[inline]
    pub(crate) fn contains(&self, p: DVec3) -> bool {
        let rho2 = p.x * p.x + p.y * p.y;
        match *self {
            Quadric::Sphere { r2 } => rho2 + p.z * p.z <= r2,
            Quadric::Cylinder { r2, zmin, zmax } => rho2 <= r2 && p.z >= zmin && p.z <= zmax,
            Quadric::Cone { height, radius } => {
                let v = p.z / height;
                let r = radius * (1.0 - v);
                (0.0..=1.0).contains(&v) && rho2 <= r * r
            }
            Quadric::Paraboloid { k, zmin, zmax } => p.z >= zmin && p.z <= zmax && rho2 <= k * p.z,
            Quadric::Torus { major, minor } => {
                let d = rho2.sqrt() - major;
                d * d + p.z * p.z <= minor * minor
            }
        }
    }

    /// Object-space box.
    pub(crate) fn bounds(&self) -> (DVec3, DVec3) {
        let column = |r: f64, z0: f64, z1: f64| (DVec3::new(-r, -r, z0), DVec3::new(r, r, z1));
        match *self {
            Quadric::Sphere { r2 } => {
                let r = r2.sqrt();
                column(r, -r, r)
            }
            Quadric::Cylinder { r2, zmin, zmax } => column(r2.sqrt(), zmin, zmax),
            Quadric::Cone { height, radius } => column(radius, height.min(0.0), height.max(0.0)),
            Quadric::Paraboloid { k, zmin, zmax } => column((k * zmax).sqrt(), zmin, zmax),
            Quadric::Torus { major, minor } => column(major + minor, -minor, minor),
        }
    }
}

/// The closed quadric of a shape, `Ok(None)` for a mesh or subdivision mesh, or why the shape bounds no volume.
/// Whether it is closed is the scene's own rule ([`reyes_scene::closure`], the one CSG
/// operands obey); a mesh's face orientation does not matter to the parity test.
pub(crate) fn closed_quadric(shape: &Shape) -> Result<Option<Quadric>, String> {
    if let reyes_scene::Closure::Open(why) = reyes_scene::closure(shape) {
        return Err(why);
    }
    Ok(Some(match *shape {
        Shape::Sphere { radius, .. } => {
            let r = f64::from(radius);
            Quadric::Sphere { r2: r * r }
        }
        Shape::Cylinder { radius, zmin, zmax, .. } => {
            let r = f64::from(radius);
            Quadric::Cylinder { r2: r * r, zmin: f64::from(zmin), zmax: f64::from(zmax) }
        }
        Shape::Cone { height, radius, .. } => {
            Quadric::Cone { height: f64::from(height), radius: f64::from(radius) }
        }
        Shape::Paraboloid { rmax, zmin, zmax, .. } => {
            let (r, z1) = (f64::from(rmax), f64::from(zmax));
            Quadric::Paraboloid { k: r * r / z1, zmin: f64::from(zmin), zmax: z1 }
        }
        Shape::Torus { major_radius, minor_radius, .. } => {
            Quadric::Torus { major: f64::from(major_radius), minor: f64::from(minor_radius) }
        }
        // Ray parity on the ray engine's primitives: a subdivision mesh's are the
        // triangles of its limit surface's tessellation (within 1/1000 of each patch's
        // size of the surface), so its volume is that of the tessellation.
        Shape::Mesh { .. } | Shape::SubdivisionMesh { .. } => return Ok(None),
        // Read into a Mesh when the scene was loaded; closure() calls it open.
        Shape::MeshFile { .. } => return Err("MeshFile (not read)".into()),
        // Not in the ray engine yet, which the parity test needs.
        Shape::Blobby { .. } => return Err("Blobby (not measured yet)".into()),
        // `closure` calls these open.
        Shape::Curves { .. }
        | Shape::Points { .. }
        | Shape::Disk { .. }
        | Shape::BilinearPatch { .. }
        | Shape::Hyperboloid { .. }
        | Shape::PatchMesh { .. }
        | Shape::NuPatch { .. } => return Err(shape.name().into()),
    }))
}

/// Ray directions of the mesh parity test: irrational-ish, far from the axes and each other.
pub(crate) const DIRECTIONS: [Vec3; 3] = [
    Vec3::new(0.5773, 0.5774, 0.5775),
    Vec3::new(-0.6123, 0.2971, 0.7331),
    Vec3::new(0.2234, -0.8862, -0.4057),
];

/// Most crossings counted along one ray (a guard; a closed mesh gives far fewer).
pub(crate) const MAX_CROSSINGS: u32 = 1 << 16;

/// One operand: how to decide whether a world point is inside it.
#[derive(Debug)]
pub(crate) enum Member {
    /// A closed form in object space; `to_object` is world to object.
    Quadric { shape: Quadric, to_object: DMat4 },
    /// Ray parity.
    Mesh(Box<Tracer>),
}

impl Member {
    #[inline]
    pub(crate) fn contains(&self, p: DVec3, key: u64) -> bool {
        match self {
            Member::Quadric { shape, to_object } => shape.contains(to_object.transform_point3(p)),
            Member::Mesh(tracer) => mesh_contains(tracer, p, key),
        }
    }
}

/// Hits this close to a patch or triangle edge (in `u` or `v`) make a ray's count doubtful.
pub(crate) const NEAR_EDGE: f32 = 1e-4;

/// Odd number of crossings along a ray; when that ray passes near an edge of the mesh (where
/// it may count a crossing twice or miss it), the majority of three rays.
pub(crate) fn mesh_contains(tracer: &Tracer, p: DVec3, key: u64) -> bool {
    let origin = p.as_vec3();
    let ray = |k: usize| {
        let n = 16 + 3 * k as u64;
        let wobble = Vec3::new(
            draw(key, n) as f32 - 0.5,
            draw(key, n + 1) as f32 - 0.5,
            draw(key, n + 2) as f32 - 0.5,
        );
        crossings(tracer, origin, DIRECTIONS[k] + wobble * 0.02)
    };
    let (first, doubtful) = ray(0);
    if !doubtful {
        return first % 2 == 1;
    }
    let votes = first % 2 + ray(1).0 % 2;
    match votes {
        0 => false,
        2 => true,
        _ => ray(2).0 % 2 == 1,
    }
}

/// Crossings of the ray from `origin` along `dir` with every surface of `tracer`, and whether
/// any of them was near an edge.
pub(crate) fn crossings(tracer: &Tracer, origin: Vec3, dir: Vec3) -> (u32, bool) {
    let mut ray = Ray::new(origin, dir, 0.0);
    let mut n = 0;
    let mut doubtful = false;
    while n < MAX_CROSSINGS {
        match tracer.intersect(&ray, f32::INFINITY) {
            Some(hit) => {
                n += 1;
                let (u, v) = (hit.u, hit.v);
                doubtful |= u.min(1.0 - u).min(v).min(1.0 - v) < NEAR_EDGE;
                ray = hit.spawn(dir, 0.0);
            }
            None => break,
        }
    }
    (n, doubtful || n >= MAX_CROSSINGS)
}

/// A solid's tree over `Member` indices.
#[derive(Debug)]
pub(crate) enum Node {
    Leaf(usize),
    Union(Vec<Node>),
    Intersection(Vec<Node>),
    Difference(Box<Node>, Box<Node>),
}

impl Node {
    pub(crate) fn contains(&self, members: &[(Member, Aabb)], p: DVec3, key: u64) -> bool {
        match self {
            Node::Leaf(i) => {
                members.get(*i).is_some_and(|(m, b)| b.contains(p) && m.contains(p, key))
            }
            Node::Union(items) => items.iter().any(|n| n.contains(members, p, key)),
            Node::Intersection(items) => items.iter().all(|n| n.contains(members, p, key)),
            Node::Difference(a, b) => a.contains(members, p, key) && !b.contains(members, p, key),
        }
    }

    /// A box holding every point inside.
    pub(crate) fn bounds(&self, members: &[(Member, Aabb)]) -> Aabb {
        match self {
            Node::Leaf(i) => members.get(*i).map_or(Aabb::EMPTY, |(_, b)| *b),
            Node::Union(items) => {
                items.iter().fold(Aabb::EMPTY, |b, n| b.union(&n.bounds(members)))
            }
            Node::Intersection(items) => items
                .iter()
                .map(|n| n.bounds(members))
                .reduce(|a, b| a.intersect(&b))
                .unwrap_or(Aabb::EMPTY),
            Node::Difference(a, _) => a.bounds(members),
        }
    }
}

/// An axis-aligned box (`min > max` on some axis when empty).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Aabb {
    pub(crate) min: DVec3,
    pub(crate) max: DVec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb { min: DVec3::INFINITY, max: DVec3::NEG_INFINITY };

    pub(crate) fn union(&self, o: &Aabb) -> Aabb {
        Aabb { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    pub(crate) fn intersect(&self, o: &Aabb) -> Aabb {
        Aabb { min: self.min.max(o.min), max: self.max.min(o.max) }
    }

    pub(crate) fn is_empty(&self) -> bool {
        !self.min.cmple(self.max).all()
    }

    #[inline]
    pub(crate) fn contains(&self, p: DVec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
}

/// The box of `points` under the affine `m`, grown by a few single-precision ulps as the ray
/// engine's boxes are (it holds meshes in `f32`).
pub(crate) fn world_box(m: &DMat4, points: impl Iterator<Item = DVec3>) -> Result<Aabb, String> {
    let b = points.fold(Aabb::EMPTY, |b, p| {
        let q = m.transform_point3(p);
        Aabb { min: b.min.min(q), max: b.max.max(q) }
    });
    if b.is_empty() || !b.min.is_finite() || !b.max.is_finite() {
        return Err("its points at shutter open are not finite".into());
    }
    let scale = b.min.abs().max(b.max.abs()).max_element();
    let pad = scale * 8.0 * f64::from(f32::EPSILON) + f64::from(f32::MIN_POSITIVE);
    Ok(Aabb { min: b.min - pad, max: b.max + pad })
}

/// The inside test and world box of `scene.objects[index]` at shutter open.
pub(crate) fn member(
    scene: &Scene,
    index: usize,
    what: &str,
) -> Result<(Member, Aabb), MeasureError> {
    let object: &Object = &scene.objects[index];
    let quadric = closed_quadric(&object.shape)
        .map_err(|why| MeasureError::NotClosed { what: what.to_string(), why })?;
    let degenerate = |why: String| MeasureError::Degenerate { what: what.to_string(), why };
    // The first transform key holds at shutter open (the ray engine's and dicer's convention).
    // The scene allows affine transforms only (a last row of (0, 0, 0, 1)).
    let transforms = object.motion.first().map_or(&object.transform, |k| &k.transform);
    let m = object_to_world(transforms).as_dmat4();
    let det = m.determinant();
    if !m.is_finite() || det == 0.0 || !det.is_finite() {
        return Err(degenerate("its transform at shutter open is singular".into()));
    }
    let to_object = m.inverse();
    if !to_object.is_finite() {
        return Err(degenerate("its transform at shutter open is singular".into()));
    }
    match quadric {
        Some(shape) => {
            let (lo, hi) = shape.bounds();
            let corners = (0..8).map(|k| {
                DVec3::new(
                    if k & 1 == 0 { lo.x } else { hi.x },
                    if k & 2 == 0 { lo.y } else { hi.y },
                    if k & 4 == 0 { lo.z } else { hi.z },
                )
            });
            let bounds = world_box(&m, corners).map_err(degenerate)?;
            Ok((Member::Quadric { shape, to_object }, bounds))
        }
        None => {
            // A subdivision mesh's limit surface lies in the hull of its control points
            // (every Catmull-Clark rule, creases included, is a convex combination).
            let (Shape::Mesh { points, .. } | Shape::SubdivisionMesh { points, .. }) =
                &object.shape
            else {
                return Err(degenerate("it is not a mesh".into()));
            };
            // The first deformation key holds at shutter open; a point it lacks is the shape's.
            let first = object.deform.first().map(|k| &k.points);
            let at = |i: usize| {
                let own = points[i];
                let p = first.and_then(|f| f.get(i)).copied().unwrap_or(own);
                DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
            };
            let bounds = world_box(&m, (0..points.len()).map(at)).map_err(degenerate)?;
            let alone = Scene {
                image: scene.image,
                camera: scene.camera.clone(),
                hider: scene.hider.clone(),
                lights: Vec::new(),
                objects: vec![object.clone()],
                solids: Vec::new(),
                raytrace: scene.raytrace,
                outputs: Default::default(),
                texture_cache: scene.texture_cache,
                shader_path: scene.shader_path.clone(),
                shaders: scene.shaders.clone(),
            };
            Ok((Member::Mesh(Box::new(Tracer::new(&alone))), bounds))
        }
    }
}

/// The tree of a solid, its leaves appended to `members`.
pub(crate) fn solid_node(
    scene: &Scene,
    tree: &Csg,
    solid: &str,
    members: &mut Vec<(Member, Aabb)>,
) -> Result<Node, MeasureError> {
    Ok(match tree {
        Csg::Object(name) => {
            let what = format!("operand {} of solid {}", quoted(name), quoted(solid));
            // The scene is validated: an operand's name resolves to exactly one object.
            let index = scene.objects.iter().position(|o| &o.name == name).ok_or_else(|| {
                MeasureError::Degenerate {
                    what: what.clone(),
                    why: "no object has its name".into(),
                }
            })?;
            members.push(member(scene, index, &what)?);
            Node::Leaf(members.len() - 1)
        }
        Csg::Union(items) => Node::Union(
            items.iter().map(|c| solid_node(scene, c, solid, members)).collect::<Result<_, _>>()?,
        ),
        Csg::Intersection(items) => Node::Intersection(
            items.iter().map(|c| solid_node(scene, c, solid, members)).collect::<Result<_, _>>()?,
        ),
        Csg::Difference(a, b) => Node::Difference(
            Box::new(solid_node(scene, a, solid, members)?),
            Box::new(solid_node(scene, b, solid, members)?),
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_forms_match_the_shapes() {
        let cone = Quadric::Cone { height: -2.0, radius: 1.0 };
        assert!(cone.contains(DVec3::new(0.4, 0.0, -0.5)));
        assert!(!cone.contains(DVec3::new(0.0, 0.0, 0.5)));
        assert!(!cone.contains(DVec3::new(0.9, 0.0, -1.0)));
        let torus = Quadric::Torus { major: 2.0, minor: 0.5 };
        assert!(torus.contains(DVec3::new(0.0, 2.3, 0.2)));
        assert!(!torus.contains(DVec3::ZERO));
        let para = Quadric::Paraboloid { k: 1.0, zmin: 1.0, zmax: 4.0 };
        assert!(para.contains(DVec3::new(1.5, 0.0, 3.0)));
        assert!(!para.contains(DVec3::new(0.0, 0.0, 0.5)));
    }

    #[test]
    fn open_meshes_are_named() {
        let mesh = |faces: &[Vec<u32>]| Shape::Mesh {
            points: vec![[0.0; 3]; 4],
            faces: faces.into(),
            colors: None,
            normals: None,
            st: None,
        };
        let tetra = vec![vec![0, 1, 2], vec![0, 3, 1], vec![1, 3, 2], vec![2, 3, 0]];
        assert_eq!(closed_quadric(&mesh(&tetra)), Ok(None));
        let why = closed_quadric(&mesh(&tetra[..3])).err().unwrap_or_default();
        assert!(why.contains("belongs to no other face"), "{why}");
    }
}
