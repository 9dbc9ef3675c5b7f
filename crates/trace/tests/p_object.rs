//! `Hit::p_object`: the hit point in the object's own coordinates (before its transform),
//! for every kind of placement: quadrics in object space, baked static meshes and patches,
//! moving objects (the frame at the ray's time) and deforming meshes.

mod common;

use common::{ball, close_v, deforming, moving, object, placed, scene, slide};
use glam::Vec3;
use reyes_scene::object_to_world;
use reyes_scene::{Faces, Shape, Transform};
use reyes_trace::Tracer;

fn shoot(t: &Tracer, origin: Vec3, dir: Vec3, time: f32) -> reyes_trace::Hit {
    match common::shoot(t, origin, dir, time) {
        Some(h) => h,
        None => panic!("ray from {origin} along {dir} at {time} misses"),
    }
}

fn turned() -> Vec<Transform> {
    placed([2.0, 1.0, 1.5], 30.0, [1.0, 1.0, 0.0], [0.5, -0.25, 3.0])
}

#[test]
fn p_object_undoes_the_static_transform() {
    let quad = Shape::Mesh {
        points: vec![[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]],
        faces: Faces::from(vec![vec![0, 1, 2, 3]]),
        colors: None,
        normals: None,
        st: None,
    };
    let patch = Shape::BilinearPatch {
        points: [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
    };
    for shape in [ball(), quad, patch] {
        let t = Tracer::new(&scene(vec![object(shape.clone(), turned())]));
        let to_object = object_to_world(&turned()).inverse();
        let origin = Vec3::new(0.4, -0.1, -10.0);
        let h =
            shoot(&t, origin, Vec3::new(0.0, 0.0, 13.0) - origin + Vec3::new(0.1, 0.0, 0.0), 0.0);
        let want = to_object.transform_point3(h.p_world);
        assert!(close_v(h.p_object, want, 1e-4), "{shape:?}: {} vs {want}", h.p_object);
        if !matches!(shape, Shape::Sphere { .. }) {
            assert!(h.p_object.z.abs() < 1e-4, "on the object's plane z = 0: {}", h.p_object);
        } else {
            assert!((h.p_object.length() - 1.0).abs() < 1e-4, "on the unit ball: {}", h.p_object);
        }
    }
}

#[test]
fn p_object_of_moving_and_deforming_objects() {
    // A ball moving along x by 2: at time 1/2 the hit's object point is the world point
    // less 1 in x.
    let t = Tracer::new(&scene(vec![moving(ball(), slide(0.0, 1.0))]));
    let h = shoot(&t, Vec3::new(1.3, 0.2, -10.0), Vec3::Z, 0.5);
    assert!(close_v(h.p_object, h.p_world - Vec3::X, 1e-5), "{} vs {}", h.p_object, h.p_world);

    // A deforming quad, flat at z = 0 then at z = 2: the object point is on the deformed
    // shape (the untransformed one: no transform here).
    let flat = |z: f32| vec![[-1.0, -1.0, z], [1.0, -1.0, z], [1.0, 1.0, z], [-1.0, 1.0, z]];
    let quad = Shape::Mesh {
        points: flat(0.0),
        faces: Faces::from(vec![vec![0, 1, 2, 3]]),
        colors: None,
        normals: None,
        st: None,
    };
    let t = Tracer::new(&scene(vec![deforming(quad, vec![(0.0, flat(0.0)), (1.0, flat(2.0))])]));
    let h = shoot(&t, Vec3::new(0.2, 0.3, -10.0), Vec3::Z, 0.25);
    assert!(close_v(h.p_object, Vec3::new(0.2, 0.3, 0.5), 1e-5), "{}", h.p_object);
}
