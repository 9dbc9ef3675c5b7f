//! The hierarchy changes nothing: for random rays through a scene of a few hundred random
//! primitives of every kind (some moving, some deforming) `intersect` equals testing every
//! primitive, `occluded` agrees with `intersect`, results are deterministic across builds
//! and identical when many threads trace at once.

mod common;

use common::{Rng, object, scene};
use glam::Vec3;
use reyes_scene::{Object, PointsKey, Scene, Shape, Transform, TransformKey};
use reyes_trace::{Ray, Tracer};

fn random_shape(rng: &mut Rng) -> Shape {
    let sweep = |rng: &mut Rng| if rng.unit() < 0.5 { 360.0 } else { rng.range(30.0, 360.0) };
    match rng.below(8) {
        0 => {
            let radius = rng.range(0.3, 1.5);
            let zmin = (rng.unit() < 0.4).then(|| rng.range(-radius, 0.0));
            let zmax = (rng.unit() < 0.4).then(|| rng.range(0.1 * radius, radius));
            Shape::Sphere { radius, zmin, zmax, thetamax: sweep(rng) }
        }
        1 => {
            let zmin = rng.range(-1.0, 0.0);
            Shape::Cylinder {
                radius: rng.range(0.2, 1.0),
                zmin,
                zmax: zmin + rng.range(0.2, 2.0),
                thetamax: sweep(rng),
            }
        }
        2 => {
            let height = rng.range(0.3, 2.0) * if rng.unit() < 0.5 { 1.0 } else { -1.0 };
            Shape::Cone { height, radius: rng.range(0.2, 1.0), thetamax: sweep(rng) }
        }
        3 => Shape::Disk {
            height: rng.range(-0.5, 0.5),
            radius: rng.range(0.2, 1.2),
            thetamax: sweep(rng),
        },
        4 => {
            let major = rng.range(0.5, 1.5);
            let phimin = if rng.unit() < 0.5 { 0.0 } else { rng.range(-180.0, 180.0) };
            let phimax =
                if rng.unit() < 0.5 { phimin + 360.0 } else { phimin + rng.range(30.0, 360.0) };
            Shape::Torus {
                major_radius: major,
                minor_radius: rng.range(0.1, 0.45) * major,
                phimin,
                phimax,
                thetamax: sweep(rng),
            }
        }
        5 => {
            let zmin = if rng.unit() < 0.5 { 0.0 } else { rng.range(0.0, 0.5) };
            Shape::Paraboloid {
                rmax: rng.range(0.2, 1.0),
                zmin,
                zmax: zmin + rng.range(0.2, 1.5),
                thetamax: sweep(rng),
            }
        }
        6 => Shape::BilinearPatch { points: std::array::from_fn(|_| rng.in_cube(1.0).to_array()) },
        _ => {
            // A small grid mesh with a random height field: quads, triangles and a pentagon.
            let n = 3;
            let mut points = Vec::new();
            for j in 0..n {
                for i in 0..n {
                    points.push([i as f32 * 0.6 - 0.6, j as f32 * 0.6 - 0.6, rng.range(-0.3, 0.3)]);
                }
            }
            points.push([0.0, -1.0, 0.1]);
            let at = |i: u32, j: u32| j * n + i;
            let faces = vec![
                vec![at(0, 0), at(1, 0), at(1, 1), at(0, 1)],
                vec![at(1, 0), at(2, 0), at(2, 1)],
                vec![at(1, 0), at(2, 1), at(1, 1)],
                vec![at(0, 1), at(1, 1), at(2, 1), at(2, 2), at(0, 2)],
                vec![at(0, 0), 9, at(2, 0), at(1, 0)],
            ];
            Shape::Mesh { points, faces: faces.into(), colors: None, normals: None, st: None }
        }
    }
}

fn random_transform(rng: &mut Rng, centre: Vec3) -> Vec<Transform> {
    let mut t = Vec::new();
    if rng.unit() < 0.5 {
        t.push(Transform::Scale([rng.range(0.5, 1.5), rng.range(0.5, 1.5), rng.range(0.5, 1.5)]));
    }
    if rng.unit() < 0.7 {
        t.push(Transform::Rotate {
            angle: rng.range(-180.0, 180.0),
            axis: rng.direction().to_array(),
        });
    }
    t.push(Transform::Translate(centre.to_array()));
    t
}

fn random_object(rng: &mut Rng) -> Object {
    let shape = random_shape(rng);
    let centre = rng.in_cube(8.0);
    let mut o = object(shape, random_transform(rng, centre));
    if rng.unit() < 0.2 {
        let mut keys = vec![];
        let mut time = 0.0;
        for _ in 0..2 + rng.below(2) {
            let c = centre + rng.in_cube(1.5);
            keys.push(TransformKey { time, transform: random_transform(rng, c) });
            time += rng.range(0.2, 0.5);
        }
        o.motion = keys;
    }
    let count = match &o.shape {
        Shape::BilinearPatch { .. } => 4,
        Shape::Mesh { points, .. } => points.len(),
        _ => 0,
    };
    if count > 0 && rng.unit() < 0.3 {
        o.deform = (0..2)
            .map(|k| PointsKey {
                time: k as f32,
                points: (0..count).map(|_| rng.in_cube(1.0).to_array()).collect(),
            })
            .collect();
    }
    o
}

fn random_scene(seed: u64, objects: usize) -> Scene {
    let mut rng = Rng::new(seed);
    scene((0..objects).map(|_| random_object(&mut rng)).collect())
}

fn random_ray(rng: &mut Rng) -> (Ray, f32) {
    let origin = rng.in_cube(12.0);
    let dir = if rng.unit() < 0.6 {
        rng.in_cube(8.0) - origin
    } else {
        rng.direction() * rng.range(0.5, 2.0)
    };
    let mut dir = dir;
    if rng.unit() < 0.15 {
        // Parallel to one or two axes: exercises the slab test's parallel case.
        let keep = rng.below(3) as usize;
        let also = (rng.unit() < 0.5).then(|| rng.below(3) as usize);
        for k in 0..3 {
            if k != keep && Some(k) != also {
                dir[k] = 0.0;
            }
        }
    }
    let t_max = if rng.unit() < 0.5 { f32::INFINITY } else { rng.range(0.0, 2.0) };
    (Ray::new(origin, dir, rng.unit()), t_max)
}

#[test]
fn hierarchy_equals_brute_force_and_occluded_agrees() {
    let scene = random_scene(7, 150);
    let tracer = Tracer::new(&scene);
    let prims = tracer.primitive_count();
    assert!((200..=600).contains(&prims), "a few hundred primitives: {prims}");
    let mut rng = Rng::new(99);
    let mut hits = 0;
    let mut kinds = std::collections::HashSet::new();
    for i in 0..10_000 {
        let (ray, t_max) = random_ray(&mut rng);
        let fast = tracer.intersect(&ray, t_max);
        let slow = tracer.intersect_exhaustive(&ray, t_max);
        assert_eq!(fast, slow, "ray {i}: {ray:?} t_max {t_max}");
        assert_eq!(tracer.occluded(&ray, t_max), fast.is_some(), "ray {i}");
        if let Some(h) = fast {
            hits += 1;
            assert!(h.t > 0.0 && h.t < t_max);
            assert!((h.n_world.length() - 1.0).abs() < 1e-4);
            assert!((ray.at(h.t) - h.p_world).length() <= 1e-3 * (1.0 + h.p_world.length()));
            kinds.insert(std::mem::discriminant(&scene.objects[h.object as usize].shape));
        }
    }
    assert!(hits > 2_000, "enough rays hit something: {hits}");
    assert_eq!(kinds.len(), 8, "every shape kind was hit");
}

#[test]
fn builds_are_deterministic_and_threads_agree() {
    let scene = random_scene(11, 120);
    let a = Tracer::new(&scene);
    let b = Tracer::new(&scene);
    let mut rng = Rng::new(5);
    let rays: Vec<(Ray, f32)> = (0..4_000).map(|_| random_ray(&mut rng)).collect();
    let serial: Vec<_> = rays.iter().map(|(r, t)| a.intersect(r, *t)).collect();
    let again: Vec<_> = rays.iter().map(|(r, t)| b.intersect(r, *t)).collect();
    assert_eq!(serial, again);
    let parallel: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = rays
            .chunks(1_000)
            .map(|chunk| {
                s.spawn(|| chunk.iter().map(|(r, t)| a.intersect(r, *t)).collect::<Vec<_>>())
            })
            .collect();
        handles.into_iter().flat_map(|h| h.join().unwrap_or_default()).collect()
    });
    assert_eq!(serial, parallel);
}

#[test]
fn empty_scene_and_degenerate_rays_hit_nothing() {
    let empty = Tracer::new(&scene(vec![]));
    let ray = Ray::new(Vec3::ZERO, Vec3::X, 0.0);
    assert!(empty.intersect(&ray, f32::INFINITY).is_none() && !empty.occluded(&ray, f32::INFINITY));
    let t = Tracer::new(&random_scene(3, 40));
    let mut rng = Rng::new(1);
    for _ in 0..200 {
        let o = rng.in_cube(10.0);
        for (dir, t_max, time) in [
            (Vec3::ZERO, f32::INFINITY, 0.5),
            (Vec3::NAN, f32::INFINITY, 0.5),
            (rng.direction(), 0.0, 0.5),
            (rng.direction(), -1.0, 0.5),
            (rng.direction(), f32::NAN, 0.5),
        ] {
            let r = Ray::new(o, dir, time);
            assert!(t.intersect(&r, t_max).is_none(), "{r:?} {t_max}");
            assert!(!t.occluded(&r, t_max));
        }
        // Times outside [0, 1] and NaN hold the first or last key; no panic, same as brute force.
        for time in [-3.0, 7.0, f32::NAN] {
            let r = Ray::new(o, rng.direction(), time);
            assert_eq!(t.intersect(&r, f32::INFINITY), t.intersect_exhaustive(&r, f32::INFINITY));
        }
    }
}
