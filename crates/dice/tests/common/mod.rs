//! Shared helpers for the integration tests: scene builders, raster geometry, brute-force
//! bucket checks and the FNV-1a digest.
#![allow(dead_code)]

use reyes_dice::{Diced, dice_scene};
use reyes_hider::{Frame, Micropolygon};
use reyes_scene::{Camera, Lens, Material, Object, Rgb, Scene, Shape, Transform};
#[allow(unused_imports)]
pub use reyes_testkit::fixtures::{camera, frame_for as frame_of, object, sphere};

/// [`reyes_testkit::fixtures::scene`] drawn two-sided: these tests measure the dicer's
/// geometry (areas, counts, motion segments) of whole surfaces, both halves of a closed one
/// included; culling the back faces is tested on its own (`cull.rs`).
pub fn scene(width: u32, height: u32, camera: Camera, objects: Vec<Object>) -> Scene {
    let mut s = reyes_testkit::fixtures::scene(width, height, camera, objects);
    s.hider.cull_back_faces = false;
    s
}

/// The camera at the origin looking down +z with field of view `fov`, through `lens`.
pub fn camera_ahead(fov: f32, lens: Option<Lens>) -> Camera {
    camera([0.0; 3], [0.0, 0.0, 1.0], fov, lens)
}

/// A `width x height` scene of `objects` seen by the pinhole [`camera_ahead`]`(fov)`.
pub fn scene_ahead(width: u32, height: u32, fov: f32, objects: Vec<Object>) -> Scene {
    scene(width, height, camera_ahead(fov, None), objects)
}

/// The camera of the busy scenes: from `(0, 0.5, -1)` towards `(0, 0, 6)`, fov 50.
pub fn busy_camera(lens: Option<Lens>) -> Camera {
    camera([0.0, 0.5, -1.0], [0.0, 0.0, 6.0], 50.0, lens)
}

/// A 160x120 scene of `objects` seen by `camera`, in 8x8 buckets at shading rate 2 (many
/// buckets, a busy scene's micropolygons in several of them).
pub fn small_buckets_scene(camera: Camera, objects: Vec<Object>) -> Scene {
    let mut s = scene(160, 120, camera, objects);
    s.hider.bucket_size = (8, 8);
    s.hider.shading_rate = 2.0;
    s
}

/// The busy scenes' sphere, torus and cone, seen by [`busy_camera`] partly off screen.
pub fn sphere_torus_cone() -> Vec<Object> {
    vec![
        object(sphere(1.0), vec![Transform::Translate([-1.5, 0.3, 6.0])]),
        tilted_torus(),
        object(
            Shape::Cone { height: 1.5, radius: 0.7, thetamax: 360.0 },
            vec![
                Transform::Rotate { angle: -90.0, axis: [1.0, 0.0, 0.0] },
                Transform::Translate([3.5, 1.0, 5.0]),
            ],
        ),
    ]
}

/// An open torus (300 degrees of it) tilted 60 degrees, centred at `(1.5, -0.5, 7)`.
pub fn tilted_torus() -> Object {
    object(
        Shape::Torus {
            major_radius: 1.0,
            minor_radius: 0.3,
            phimin: 0.0,
            phimax: 360.0,
            thetamax: 300.0,
        },
        vec![
            Transform::Rotate { angle: 60.0, axis: [1.0, 0.2, 0.0] },
            Transform::Translate([1.5, -0.5, 7.0]),
        ],
    )
}

/// An 80x80 floor a little below [`busy_camera`]'s eye, reaching behind it: hither splits,
/// patches with no raster bound, micropolygons crossing hither.
pub fn floor_through_the_eye() -> Object {
    object(
        Shape::BilinearPatch {
            points: [
                [-40.0, -1.0, -40.0],
                [40.0, -1.0, -40.0],
                [-40.0, -1.0, 40.0],
                [40.0, -1.5, 40.0],
            ],
        },
        vec![],
    )
}

/// The points of a quad 0-1-2-3 and a triangle 1-4-2 sharing its edge 1-2, at depths 8 to 9.
pub fn quad_and_triangle() -> Vec<[f32; 3]> {
    vec![[-2.0, -1.0, 8.0], [0.0, -1.0, 8.0], [0.0, 1.0, 9.0], [-2.0, 1.0, 9.0], [2.0, -1.0, 8.0]]
}

/// Plastic of `color` and `roughness`: ambient 1, diffuse and specular 0.5, white highlights.
pub fn plastic(color: Rgb, roughness: f32) -> Material {
    Material::Plastic {
        color,
        opacity: [1.0; 3],
        ka: 1.0,
        kd: 0.5,
        ks: 0.5,
        roughness,
        specular_color: [1.0; 3],
    }
}

/// Dice a scene in its own frame, panicking on error.
pub fn dice(scene: &Scene) -> (Diced, Frame) {
    let frame = frame_of(scene);
    let diced = dice_scene(scene, &frame).expect("dice");
    (diced, frame)
}

/// Signed raster-space area of a micropolygon (shoelace over its cyclic vertices).
pub fn signed_area(mp: &Micropolygon) -> f64 {
    let mut a = 0.0;
    for k in 0..4 {
        let p = mp.v[k];
        let q = mp.v[(k + 1) % 4];
        a += f64::from(p[0]) * f64::from(q[1]) - f64::from(q[0]) * f64::from(p[1]);
    }
    0.5 * a
}

/// Is raster point `(x, y)` inside the micropolygon (as two triangles 0-1-2 and 0-2-3,
/// edges inclusive within `eps`)?
pub fn inside(mp: &Micropolygon, x: f32, y: f32, eps: f32) -> bool {
    let tri = |a: [f32; 3], b: [f32; 3], c: [f32; 3]| {
        let e = |p: [f32; 3], q: [f32; 3]| (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]);
        let (d0, d1, d2) = (e(a, b), e(b, c), e(c, a));
        let scale = 1.0
            + (b[0] - a[0]).abs()
            + (b[1] - a[1]).abs()
            + (c[0] - a[0]).abs()
            + (c[1] - a[1]).abs();
        let tol = eps * scale;
        (d0 >= -tol && d1 >= -tol && d2 >= -tol) || (d0 <= tol && d1 <= tol && d2 <= tol)
    };
    tri(mp.v[0], mp.v[1], mp.v[2]) || tri(mp.v[0], mp.v[2], mp.v[3])
}

/// Does some micropolygon listed in the bucket of raster point `(x, y)` cover it (within
/// 1e-4)?
pub fn covered(d: &Diced, frame: &Frame, x: f32, y: f32) -> bool {
    d.buckets[bucket_of(frame, x, y)].iter().any(|&i| inside(&d.mpolys[i as usize], x, y, 1e-4))
}

/// Brute force: the buckets whose pixels the box `[lo, hi]` reaches (pixel x is reached iff
/// `lo.x < x + 1` and `hi.x >= x`), computed in extended-screen coordinates as the frame does.
pub fn touched_buckets(frame: &Frame, lo: [f32; 3], hi: [f32; 3]) -> Vec<usize> {
    let e = frame.border as f32;
    let touches = |b: usize| {
        let (left, top) = frame.bucket_origin(b);
        let (left, top) = (left as f32 + e, top as f32 + e);
        let (right, bottom) = (left + frame.bucket_w as f32, top + frame.bucket_h as f32);
        lo[0] + e < right && hi[0] + e >= left && lo[1] + e < bottom && hi[1] + e >= top
    };
    (0..frame.bucket_count()).filter(|&b| touches(b)).collect()
}

/// The buckets listing each micropolygon of `d` (its bucket lists inverted), checking that
/// every list is strictly increasing.
pub fn buckets_of_each(d: &Diced) -> Vec<Vec<usize>> {
    let mut listed: Vec<Vec<usize>> = vec![Vec::new(); d.mpolys.len()];
    for (b, list) in d.buckets.iter().enumerate() {
        assert!(list.windows(2).all(|w| w[0] < w[1]), "bucket {b} is not strictly increasing");
        for &i in list {
            listed[i as usize].push(b);
        }
    }
    listed
}

/// 64-bit FNV-1a over the bytes it is fed, in order.
pub struct Fnv(pub u64);

impl Default for Fnv {
    fn default() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    /// Feed `bytes`.
    pub fn eat(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
}

/// Bucket number of the bucket holding raster pixel `(x, y)`.
pub fn bucket_of(frame: &Frame, x: f32, y: f32) -> usize {
    let bx = ((x + frame.border as f32).floor() as u32 / frame.bucket_w).min(frame.buckets_x - 1);
    let by = ((y + frame.border as f32).floor() as u32 / frame.bucket_h).min(frame.buckets_y - 1);
    (by * frame.buckets_x + bx) as usize
}

/// The grid the documented rule (docs/geometry.md, "Dicing to the shading rate") gives a
/// flat patch without crack-free floors or flatness counts whose sides ask for `q_u` and
/// `q_v` micropolygons (a side's mean raster length over the micropolygon side, which for
/// an unsheared parallelogram is its side's length): of `floor` and `ceil` of each (at least
/// 1), the pair whose area is nearest `q_u * q_v` in ratio, then nearest the aspect
/// `q_u / q_v`, then the one with more along u. Written out independently of
/// the dicer, in f64. The dicer works in f32, so a case where two pairs of different area
/// are within 1e-3 of each other in that ratio tests rounding, not the rule, and is refused.
pub fn rate_grid(q_u: f64, q_v: f64) -> (u64, u64) {
    let sides = |q: f64| [(q.floor() as u64).max(1), (q.ceil() as u64).max(1)];
    let mut pairs: Vec<(f64, f64, u64, u64)> = Vec::new();
    for nu in sides(q_u) {
        for nv in sides(q_v) {
            let area = ((nu * nv) as f64 / (q_u * q_v)).ln().abs();
            let aspect = ((nu as f64 / q_u) / (nv as f64 / q_v)).ln().abs();
            pairs.push((area, aspect, nu, nv));
        }
    }
    // Ties within f32 rounding of the dicer are ties here too.
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-9;
    pairs.sort_by(|a, b| {
        if !near(a.0, b.0) {
            a.0.total_cmp(&b.0)
        } else if !near(a.1, b.1) {
            a.1.total_cmp(&b.1)
        } else {
            b.2.cmp(&a.2)
        }
    });
    let best = pairs[0];
    for p in &pairs[1..] {
        if p.2 * p.3 != best.2 * best.3 {
            assert!(p.0 - best.0 > 1e-3, "{q_u} x {q_v}: too near a tie to tell");
            break;
        }
    }
    (best.2, best.3)
}
