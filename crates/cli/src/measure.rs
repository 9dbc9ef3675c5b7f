//! Mass properties by pseudo-random point sampling: patent FIG. 23, where the sampling
//! techniques of the patent "determine a center of mass of an object", and "the pseudo-random
//! nature of this sampling assures that the measurement will be made on the actual object and
//! not some alias image of it".
//!
//! [`measure`] estimates the volume and the centre of mass (uniform density) of one closed
//! object, or one CSG solid, of a scene, as it stands at shutter open (time 0: the first
//! `motion` key and the first `deform` key when there are keys).
//!
//! * **Sampling.** The world-space bounding box is split into `nx x ny x nz` equal cells, as
//!   near cubic as the box allows, each count even, about `samples` in all; each cell gets one
//!   point uniformly distributed in it (stratified, "jittered" sampling, the spatial analogue
//!   of FIG. 6). The jitter of a cell is a hash of the seed and the cell index, and cells are
//!   summed in fixed groups added in a fixed order, so the answer depends only on the scene,
//!   the name, the sample count and the seed, never on threads or scheduling.
//! * **Inside test.** Spheres, cylinders, cones, paraboloids and tori: closed forms in object
//!   space, the world point carried back through the inverse object-to-world matrix.
//!   Cylinders, cones and paraboloids count as closed by their end caps, as they are when used
//!   in a solid. Meshes: parity of the crossings of a ray with the mesh alone (a
//!   [`reyes_trace::Tracer`] over that one object) in a fixed, slightly perturbed direction;
//!   when that ray passes near an edge of a face (where it may count one crossing twice or
//!   none), the majority of three rays in different directions. Solids: the operands'
//!   answers combined by the tree.
//! * **Estimates.** volume = box volume x inside fraction; centre = mean of the inside points.
//! * **Standard errors** come from the strata themselves ("collapsed strata"). With one point
//!   per stratum the variance of a sum `sum y_i` is `sum Var(y_i)`, which one point per stratum
//!   cannot estimate directly; pairing every cell with a neighbour (all counts are even, so the
//!   cells fall into 2 x 2 x 2 blocks) and taking `sum over pairs (y_a - y_b)^2` does: its
//!   expectation is the true variance plus `sum (mu_a - mu_b)^2 >= 0`, the squared differences
//!   of neighbouring strata's means, so it errs on the large side, never the small. For the
//!   volume, `y` is the inside indicator, pairs along x. For centre coordinate k (a ratio
//!   estimate, linearised), `y = inside x (p_k - centre_k)`, paired along another axis (x with
//!   y, y with z, z with x) so that the pair's offset along k does not enter the difference.
//!   This is far tighter than the binomial bound `p (1 - p) / N` of unstratified sampling,
//!   which would ignore that only cells cut by the surface vary at all.

use std::fmt;
use std::path::{Path, PathBuf};

use glam::{DMat4, DVec3, Vec3};
use rayon::prelude::*;
use reyes_sampling::{SplitMix64, unit_f64};
use reyes_scene::object_to_world;
use reyes_scene::{Csg, Object, Scene, Shape};
use reyes_trace::{Ray, Tracer};

/// Default number of sample points.
pub const DEFAULT_SAMPLES: u64 = 1_000_000;
/// Most sample points of one measurement.
pub const MAX_SAMPLES: u64 = 100_000_000_000;

/// What to measure with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeasureOptions {
    /// About how many sample points, from 1 to [`MAX_SAMPLES`] (at least 8 are taken: a
    /// 2 x 2 x 2 grid).
    pub samples: u64,
    /// Seed of the jitter.
    pub seed: u64,
}

impl Default for MeasureOptions {
    fn default() -> Self {
        MeasureOptions { samples: DEFAULT_SAMPLES, seed: 0 }
    }
}

/// What a name resolved to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Target {
    /// `objects[index]`, of shape `shape` (e.g. `"Sphere"`).
    Object {
        /// Index in `Scene::objects`.
        index: usize,
        /// The shape's variant name.
        shape: &'static str,
    },
    /// `solids[index]`.
    Solid {
        /// Index in `Scene::solids`.
        index: usize,
    },
}

/// A centre of mass with its standard errors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Centre {
    /// World-space centre of mass.
    pub at: DVec3,
    /// One standard error per axis.
    pub se: DVec3,
}

/// The result of [`measure`].
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// The name measured.
    pub name: String,
    /// What it names.
    pub target: Target,
    /// The sampled box, world space (`min > max` on some axis when it is empty).
    pub bounds: (DVec3, DVec3),
    /// Cells per axis (one point each).
    pub grid: [u64; 3],
    /// Seed of the jitter.
    pub seed: u64,
    /// Points found inside.
    pub inside: u64,
    /// Estimated volume.
    pub volume: f64,
    /// One standard error of `volume`.
    pub volume_se: f64,
    /// Estimated centre of mass; `None` when no point is inside.
    pub centre: Option<Centre>,
}

impl Measurement {
    /// Number of sample points taken.
    pub fn points(&self) -> u64 {
        if self.box_is_empty() { 0 } else { self.grid.iter().product() }
    }

    fn box_is_empty(&self) -> bool {
        let (lo, hi) = self.bounds;
        !(lo.cmple(hi).all())
    }
}

/// Why a measurement could not be made. Every one displays as one line naming the option
/// at fault, and is a usage error (exit code 2).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MeasureError {
    /// `samples` is 0 or more than [`MAX_SAMPLES`].
    Samples(u64),
    /// No object or solid has the name.
    NotFound {
        /// The name asked for.
        name: String,
        /// The scene file.
        file: PathBuf,
    },
    /// More than one object or solid has the name.
    Ambiguous {
        /// The name asked for.
        name: String,
        /// The first two things named so, e.g. `objects[0]`, `solids[1]`.
        first: String,
        /// See `first`.
        second: String,
    },
    /// The object (or an operand of the solid) bounds no volume.
    NotClosed {
        /// What, e.g. `object "lid"`.
        what: String,
        /// Why, e.g. `Disk`.
        why: String,
    },
    /// The object's transform at shutter open flattens it.
    Degenerate {
        /// What, e.g. `object "lid"`.
        what: String,
        /// Why.
        why: String,
    },
}

impl MeasureError {
    /// Process exit status: 2 (usage).
    pub fn exit_code(&self) -> u8 {
        2
    }
}

impl fmt::Display for MeasureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeasureError::Samples(n) => {
                write!(f, "--samples: must be from 1 to {MAX_SAMPLES}, got {n}")
            }
            MeasureError::NotFound { name, file } => write!(
                f,
                "--object: no object or solid named {} in {}",
                quoted(name),
                one_line(&file.display().to_string())
            ),
            MeasureError::Ambiguous { name, first, second } => write!(
                f,
                "--object: the name {} is ambiguous: {first} and {second} both have it",
                quoted(name)
            ),
            MeasureError::NotClosed { what, why } => write!(
                f,
                "--object: {what} is not closed ({}), so it bounds no volume",
                one_line(why)
            ),
            MeasureError::Degenerate { what, why } => {
                write!(f, "--object: {what} cannot be measured: {}", one_line(why))
            }
        }
    }
}

impl std::error::Error for MeasureError {}

/// A name for a message: quoted, escaped, clipped to 64 characters.
fn quoted(name: &str) -> String {
    let clipped: String = if name.chars().count() > 64 {
        name.chars().take(63).chain(['…']).collect()
    } else {
        name.to_string()
    };
    format!("{clipped:?}")
}

/// `s` with control characters and line separators escaped.
fn one_line(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}') {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Inside tests

/// A closed quadric or torus in object space (full sweep), for the closed-form inside test.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Quadric {
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
    fn contains(&self, p: DVec3) -> bool {
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
    fn bounds(&self) -> (DVec3, DVec3) {
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

/// The shape's variant name.
fn shape_name(shape: &Shape) -> &'static str {
    match shape {
        Shape::Sphere { .. } => "Sphere",
        Shape::Cylinder { .. } => "Cylinder",
        Shape::Cone { .. } => "Cone",
        Shape::Disk { .. } => "Disk",
        Shape::Torus { .. } => "Torus",
        Shape::Paraboloid { .. } => "Paraboloid",
        Shape::BilinearPatch { .. } => "BilinearPatch",
        Shape::Mesh { .. } => "Mesh",
    }
}

/// The closed quadric of a shape, `Ok(None)` for a mesh, or why the shape bounds no volume.
/// Whether it is closed is the scene's own rule ([`reyes_scene::closure`], the one CSG
/// operands obey); a mesh's face orientation does not matter to the parity test.
fn closed_quadric(shape: &Shape) -> Result<Option<Quadric>, String> {
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
        Shape::Mesh { .. } => return Ok(None),
        // `closure` calls these open.
        Shape::Disk { .. } | Shape::BilinearPatch { .. } => return Err(shape_name(shape).into()),
    }))
}

/// Ray directions of the mesh parity test: irrational-ish, far from the axes and each other.
const DIRECTIONS: [Vec3; 3] = [
    Vec3::new(0.5773, 0.5774, 0.5775),
    Vec3::new(-0.6123, 0.2971, 0.7331),
    Vec3::new(0.2234, -0.8862, -0.4057),
];

/// Most crossings counted along one ray (a guard; a closed mesh gives far fewer).
const MAX_CROSSINGS: u32 = 1 << 16;

/// One operand: how to decide whether a world point is inside it.
#[derive(Debug)]
enum Member {
    /// A closed form in object space; `to_object` is world to object.
    Quadric { shape: Quadric, to_object: DMat4 },
    /// Ray parity.
    Mesh(Box<Tracer>),
}

impl Member {
    #[inline]
    fn contains(&self, p: DVec3, key: u64) -> bool {
        match self {
            Member::Quadric { shape, to_object } => shape.contains(to_object.transform_point3(p)),
            Member::Mesh(tracer) => mesh_contains(tracer, p, key),
        }
    }
}

/// Hits this close to a patch or triangle edge (in `u` or `v`) make a ray's count doubtful.
const NEAR_EDGE: f32 = 1e-4;

/// Odd number of crossings along a ray; when that ray passes near an edge of the mesh (where
/// it may count a crossing twice or miss it), the majority of three rays.
fn mesh_contains(tracer: &Tracer, p: DVec3, key: u64) -> bool {
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
fn crossings(tracer: &Tracer, origin: Vec3, dir: Vec3) -> (u32, bool) {
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
enum Node {
    Leaf(usize),
    Union(Vec<Node>),
    Intersection(Vec<Node>),
    Difference(Box<Node>, Box<Node>),
}

impl Node {
    fn contains(&self, members: &[(Member, Aabb)], p: DVec3, key: u64) -> bool {
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
    fn bounds(&self, members: &[(Member, Aabb)]) -> Aabb {
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
struct Aabb {
    min: DVec3,
    max: DVec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb { min: DVec3::INFINITY, max: DVec3::NEG_INFINITY };

    fn union(&self, o: &Aabb) -> Aabb {
        Aabb { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    fn intersect(&self, o: &Aabb) -> Aabb {
        Aabb { min: self.min.max(o.min), max: self.max.min(o.max) }
    }

    fn is_empty(&self) -> bool {
        !self.min.cmple(self.max).all()
    }

    #[inline]
    fn contains(&self, p: DVec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
}

/// The box of `points` under the affine `m`, grown by a few single-precision ulps as the ray
/// engine's boxes are (it holds meshes in `f32`).
fn world_box(m: &DMat4, points: impl Iterator<Item = DVec3>) -> Result<Aabb, String> {
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
fn member(scene: &Scene, index: usize, what: &str) -> Result<(Member, Aabb), MeasureError> {
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
            let Shape::Mesh { points, .. } = &object.shape else {
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
            };
            Ok((Member::Mesh(Box::new(Tracer::new(&alone))), bounds))
        }
    }
}

/// The tree of a solid, its leaves appended to `members`.
fn solid_node(
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

// ---------------------------------------------------------------------------------------------
// Sampling

/// The `n`th uniform number in `[0, 1)` of the stream `key`.
#[inline]
fn draw(key: u64, n: u64) -> f64 {
    unit_f64(SplitMix64::at(key ^ SplitMix64::at(n.wrapping_mul(0xD1B5_4A32_D192_ED03))))
}

/// Cells per axis for about `samples` cells over a box of extents `ext`: as near cubic as
/// possible, every count even and at least 2.
fn grid(ext: DVec3, samples: u64) -> [u64; 3] {
    let e = ext.to_array();
    let mut n = [2u64; 3];
    let mut fixed = [false; 3];
    loop {
        let free: Vec<usize> = (0..3).filter(|&k| !fixed[k]).collect();
        if free.is_empty() {
            return n;
        }
        let taken: f64 = (0..3).filter(|&k| fixed[k]).map(|k| n[k] as f64).product();
        let budget = (samples as f64 / taken).max(1.0);
        let volume: f64 = free.iter().map(|&k| e[k]).product();
        let h = (volume / budget).powf(1.0 / free.len() as f64);
        let thin: Vec<usize> = free.iter().copied().filter(|&k| e[k] / h < 2.0).collect();
        if thin.is_empty() {
            for &k in &free {
                n[k] = 2 * ((e[k] / h / 2.0).round() as u64).max(1);
            }
            return n;
        }
        for k in thin {
            fixed[k] = true;
        }
    }
}

/// Partial sums over some cells (coordinates relative to the box centre).
#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    /// Points inside.
    inside: u64,
    /// Sum of inside points.
    first: DVec3,
    /// Pairs along x whose points differ in being inside.
    vol_pairs: u64,
    /// Per centre coordinate k, over pairs along axis (k + 1) % 3, with
    /// `dx = I_a x_a - I_b x_b` and `di = I_a - I_b`: sums of `dx^2`, `dx di`, `di^2`.
    dxx: [f64; 3],
    dxi: [f64; 3],
    dii: [u64; 3],
}

impl Sums {
    fn add(&mut self, o: &Sums) {
        self.inside += o.inside;
        self.vol_pairs += o.vol_pairs;
        self.first += o.first;
        for k in 0..3 {
            self.dxx[k] += o.dxx[k];
            self.dxi[k] += o.dxi[k];
            self.dii[k] += o.dii[k];
        }
    }
}

/// Rows of 2 x 2 x 2 blocks summed by one task.
const ROWS_PER_TASK: u64 = 16;

/// Samples the box `b` with one jittered point per cell of `n` and sums the statistics.
fn sample(b: &Aabb, n: [u64; 3], seed: u64, inside: &(dyn Fn(DVec3, u64) -> bool + Sync)) -> Sums {
    let ext = b.max - b.min;
    let cell = ext / DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64);
    let centre = (b.min + b.max) * 0.5;
    let seed_key = SplitMix64::at(seed);
    let [bx, by, bz] = n.map(|c| c / 2);
    let rows = by * bz;
    let tasks = rows.div_ceil(ROWS_PER_TASK);
    let parts: Vec<Sums> = (0..tasks)
        .into_par_iter()
        .map(|t| {
            let mut s = Sums::default();
            for row in t * ROWS_PER_TASK..((t + 1) * ROWS_PER_TASK).min(rows) {
                let (j0, k0) = (2 * (row % by), 2 * (row / by));
                for i0 in (0..bx).map(|i| 2 * i) {
                    // The block's 8 cells, indexed by dx + 2 dy + 4 dz.
                    let mut ins = [false; 8];
                    let mut pos = [DVec3::ZERO; 8];
                    for (c, (is, p)) in ins.iter_mut().zip(pos.iter_mut()).enumerate() {
                        let (i, j, k) =
                            (i0 + (c as u64 & 1), j0 + (c as u64 >> 1 & 1), k0 + (c as u64 >> 2));
                        let index = i + n[0] * (j + n[1] * k);
                        let key = SplitMix64::at(seed_key ^ index);
                        let jitter = DVec3::new(draw(key, 0), draw(key, 1), draw(key, 2));
                        let q = b.min + (DVec3::new(i as f64, j as f64, k as f64) + jitter) * cell;
                        *is = inside(q, key);
                        *p = q - centre;
                    }
                    for (p, _) in pos.iter().zip(&ins).filter(|(_, is)| **is) {
                        s.inside += 1;
                        s.first += *p;
                    }
                    // Volume: pairs along x (cells c and c + 1 with dx = 0).
                    for c in [0, 2, 4, 6] {
                        s.vol_pairs += u64::from(ins[c] != ins[c + 1]);
                    }
                    // Centre coordinate k: pairs along axis (k + 1) % 3, i.e. cells `step`
                    // apart in the block's index.
                    for (k, step) in [(0, 2usize), (1, 4), (2, 1)] {
                        let x = |c: usize| if ins[c] { pos[c][k] } else { 0.0 };
                        for a in (0..8).filter(|a| a & step == 0) {
                            let di = i64::from(ins[a]) - i64::from(ins[a + step]);
                            let dx = x(a) - x(a + step);
                            s.dxx[k] += dx * dx;
                            s.dxi[k] += dx * di as f64;
                            s.dii[k] += di.unsigned_abs();
                        }
                    }
                }
            }
            s
        })
        .collect();
    let mut total = Sums::default();
    for p in &parts {
        total.add(p);
    }
    total
}

/// Measures the object or solid named `name` in `scene` (loaded from `file`, which is used in
/// messages only). See the module documentation for the method.
pub fn measure(
    scene: &Scene,
    file: &Path,
    name: &str,
    opts: &MeasureOptions,
) -> Result<Measurement, MeasureError> {
    if opts.samples == 0 || opts.samples > MAX_SAMPLES {
        return Err(MeasureError::Samples(opts.samples));
    }
    let named: Vec<(String, Target)> = if name.is_empty() {
        Vec::new()
    } else {
        let objects =
            scene.objects.iter().enumerate().filter(|(_, o)| o.name == name).map(|(index, o)| {
                (format!("objects[{index}]"), Target::Object { index, shape: shape_name(&o.shape) })
            });
        let solids = scene
            .solids
            .iter()
            .enumerate()
            .filter(|(_, s)| s.name == name)
            .map(|(index, _)| (format!("solids[{index}]"), Target::Solid { index }));
        objects.chain(solids).take(2).collect()
    };
    let target = match named.as_slice() {
        [] => {
            return Err(MeasureError::NotFound {
                name: name.to_string(),
                file: file.to_path_buf(),
            });
        }
        [(first, _), (second, _)] => {
            return Err(MeasureError::Ambiguous {
                name: name.to_string(),
                first: first.clone(),
                second: second.clone(),
            });
        }
        [(_, target), ..] => target.clone(),
    };

    let mut members = Vec::new();
    let tree = match &target {
        Target::Object { index, .. } => {
            members.push(member(scene, *index, &format!("object {}", quoted(name)))?);
            Node::Leaf(0)
        }
        Target::Solid { index } => {
            solid_node(scene, &scene.solids[*index].tree, name, &mut members)?
        }
    };
    let bounds = tree.bounds(&members);
    let mut out = Measurement {
        name: name.to_string(),
        target,
        bounds: (bounds.min, bounds.max),
        grid: [0; 3],
        seed: opts.seed,
        inside: 0,
        volume: 0.0,
        volume_se: 0.0,
        centre: None,
    };
    if bounds.is_empty() {
        return Ok(out);
    }
    let ext = bounds.max - bounds.min;
    let n = grid(ext, opts.samples);
    let inside = |p: DVec3, key: u64| tree.contains(&members, p, key);
    let s = sample(&bounds, n, opts.seed, &inside);

    let total = (n[0] * n[1] * n[2]) as f64;
    let box_volume = ext.x * ext.y * ext.z;
    out.grid = n;
    out.inside = s.inside;
    out.volume = box_volume * s.inside as f64 / total;
    out.volume_se = box_volume / total * (s.vol_pairs as f64).sqrt();
    if s.inside > 0 {
        let count = s.inside as f64;
        let mut at = DVec3::ZERO;
        let mut se = DVec3::ZERO;
        for k in 0..3 {
            let c = s.first[k] / count;
            let var = (s.dxx[k] - 2.0 * c * s.dxi[k] + c * c * s.dii[k] as f64) / (count * count);
            at[k] = c;
            se[k] = var.max(0.0).sqrt();
        }
        out.centre = Some(Centre { at: at + (bounds.min + bounds.max) * 0.5, se });
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Report

/// `x` with `decimals` decimals, without the sign of a negative value that rounds to zero.
fn fixed(x: f64, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => s,
    }
}

/// `value ± se` with the error to two significant figures and the value to match.
fn plus_minus(value: f64, se: f64) -> String {
    if se > 0.0 && se.is_finite() {
        let decimals = (1 - se.log10().floor() as i64).clamp(0, 15) as usize;
        format!("{} ± {se:.decimals$}", fixed(value, decimals))
    } else {
        format!("{} ± 0", significant(value, 7))
    }
}

/// `x` to `digits` significant figures (no exponent).
fn significant(x: f64, digits: i64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let decimals = (digits - 1 - x.abs().log10().floor() as i64).clamp(0, 15) as usize;
    fixed(x, decimals)
}

impl fmt::Display for Measurement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match &self.target {
            Target::Object { index, shape } => format!("objects[{index}], {shape}"),
            Target::Solid { index } => format!("solids[{index}], CSG"),
        };
        writeln!(f, "measure  {} ({what}), at shutter open", quoted(&self.name))?;
        if self.box_is_empty() {
            writeln!(f, "box      empty: the solid's operands do not overlap")?;
            writeln!(f, "volume   0")?;
            return writeln!(f, "centre   none: nothing is inside");
        }
        let (lo, hi) = self.bounds;
        let ext = hi - lo;
        let decimals = (5 - ext.max_element().log10().floor() as i64).clamp(0, 15) as usize;
        let v = |p: DVec3| {
            let [x, y, z] = p.to_array().map(|c| fixed(c, decimals));
            format!("({x}, {y}, {z})")
        };
        writeln!(
            f,
            "box      {} to {}, volume {}",
            v(lo),
            v(hi),
            significant(ext.x * ext.y * ext.z, 7)
        )?;
        let [nx, ny, nz] = self.grid;
        writeln!(
            f,
            "samples  {} points: {nx} x {ny} x {nz} strata, one jittered point each, seed {}",
            self.points(),
            self.seed
        )?;
        writeln!(f, "inside   {} points", self.inside)?;
        writeln!(f, "volume   {}", plus_minus(self.volume, self.volume_se))?;
        match &self.centre {
            Some(c) => writeln!(
                f,
                "centre   ({}, {}, {})",
                plus_minus(c.at.x, c.se.x),
                plus_minus(c.at.y, c.se.y),
                plus_minus(c.at.z, c.se.z)
            )?,
            None => writeln!(f, "centre   none: no sample point is inside")?,
        }
        writeln!(
            f,
            "± is one standard error, estimated from neighbouring strata paired (collapsed \
             strata), which errs on the large side"
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_is_even_and_near_the_sample_count() {
        assert_eq!(grid(DVec3::splat(3.0), 1_000_000), [100, 100, 100]);
        assert_eq!(grid(DVec3::splat(1.0), 1), [2, 2, 2]);
        let n = grid(DVec3::new(1000.0, 1.0, 0.001), 1_000_000);
        assert!(n.iter().all(|c| c % 2 == 0 && *c >= 2), "{n:?}");
        assert_eq!(n[2], 2);
        let total: u64 = n.iter().product();
        assert!((500_000..2_000_000).contains(&total), "{n:?}");
    }

    #[test]
    fn draws_are_uniform_looking_and_in_range() {
        let mean = (0..10_000).map(|i| draw(SplitMix64::at(i), 0)).sum::<f64>() / 10_000.0;
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
        assert!((0..1000).all(|i| (0.0..1.0).contains(&draw(i, i))));
    }

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
            faces: faces.to_vec(),
            colors: None,
        };
        let tetra = vec![vec![0, 1, 2], vec![0, 3, 1], vec![1, 3, 2], vec![2, 3, 0]];
        assert_eq!(closed_quadric(&mesh(&tetra)), Ok(None));
        let why = closed_quadric(&mesh(&tetra[..3])).err().unwrap_or_default();
        assert!(why.contains("belongs to no other face"), "{why}");
    }
}
